"""Flow states of the BEM analysis: classification, physical roots, zero-loading fallback, on_invalid, partials.

Sources of the asserted numbers: annular momentum theory with Prandtl's factor and the mass flux
rho |u_x| (dT/dr = 4 pi rho r F |u_x| (u_x - V_x), the form CCBlade.jl and AeroDyn use), the
mirror symmetry of hover momentum theory for a symmetric section, the energy balance of an
annulus (Omega dQ - V_x dT >= 0) and hand derivations written next to each case.
"""
import warnings

import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.airfoil import get_polar
from bild_mdo.airfoil.polar import Polar, PolarValues
from bild_mdo.bem import analyze_rotor, station_radii
from bild_mdo.bem.bem_group import BEMAnalysisGroup
from bild_mdo.bem.flow_states import (INVALID_STATES, MIRROR_ROOT, NO_SOLUTION, PROPELLER, PROPELLER_BRAKE,
                                      TURBULENT_WAKE, WINDMILL, BEMStateWarning, classify)
from bild_mdo.bem.inflow import InflowComp
from bild_mdo.bem.loads import BladeElementLoadsComp
from bild_mdo.utils.testing import check_component_partials, check_group_totals

NN, NR, B = 3, 7, 3
OMEGA_PER_RPM = np.pi / 30.0


def _run(*args, on_invalid="warn", **kwargs):
    """analyze_rotor, returning (result, BEMStateWarnings issued)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("ignore", UserWarning)   # the polar's Reynolds-clamp note
        warnings.simplefilter("always", BEMStateWarning)
        result = analyze_rotor(*args, on_invalid=on_invalid, **kwargs)
    return result, [w for w in caught if issubclass(w.category, BEMStateWarning)]


def _reproducer(v_axial=0.0, **kwargs):
    # The blade of the issue: constant chord, twist 20 deg -> -10 deg, hover at 3000 rpm.
    return _run(0.1 * np.ones(20), np.radians(np.linspace(20, -10, 20)), 1.0, 0.2, 3000.0, v_axial, 3,
                get_polar("naca4412"), **kwargs)


def _momentum_thrust(res, v_axial, rho):
    """Annular momentum thrust per unit span with F and the mass flux rho |u_x| (hand derivation)."""
    return 4.0 * np.pi * rho * res.radii * res.loss_factor * np.abs(res.u_axial) * (res.u_axial - v_axial)


class SymmetricPolar(Polar):
    """Symmetric section: cl odd and cd even in alpha, both Re-dependent (not a real airfoil)."""

    name = "symmetric-test"

    def _evaluate_real(self, alpha, reynolds):
        f, df = (reynolds / 1e6) ** 0.05, 0.05 * (reynolds / 1e6) ** 0.05 / reynolds
        g, dg = (reynolds / 1e6) ** -0.2, -0.2 * (reynolds / 1e6) ** -0.2 / reynolds
        s2 = np.sin(2.0 * alpha)
        return PolarValues(2.0 * f * s2, 0.01 * g + np.sin(alpha) ** 2, 4.0 * f * np.cos(2.0 * alpha),
                           2.0 * s2 * df, s2, 0.01 * dg * np.ones_like(alpha))


class NegativeDragPolar(Polar):
    """cl = 0, cd = -500 (unphysical): a section whose only roots have W <= 0.

    Hand derivation (C_x = 500 sin phi, C_theta = -500 cos phi, k = 500 sigma > 4 >= 4F for sigma > 0.008):
    R = (4F|s| - k)(lam c - s) for s > 0 and (4F s + k)(s - lam c) for s < 0.  In (0, pi/2) the
    roots are tan(phi) = lam with D = c (4F s - k) < 0 (W < 0) and none from 4F s = k > 4F; in
    (-pi/2, 0) and (pi/2, pi) R keeps one sign.  So no admissible root exists at any V_x.
    """

    name = "negative-drag"

    def _evaluate_real(self, alpha, reynolds):
        z = np.zeros_like(alpha)
        return PolarValues(z, np.full_like(alpha, -500.0), z, z, z, z)


def test_classify_from_signs():
    # (C_x, C_theta, V_x, u_x, admissible) -> code, by the definitions of bild_mdo.bem.flow_states.
    cases = [((1.0, 1.0, 10.0, 12.0, True), PROPELLER),
             ((1.0, 1.0, 0.0, 5.0, True), PROPELLER),
             ((-1.0, 1.0, 10.0, 9.0, True), PROPELLER_BRAKE),       # a = 0.1
             ((-1.0, 1.0, 0.0, -5.0, True), TURBULENT_WAKE),        # hover, flow reversed: vortex ring
             ((-1.0, -1.0, 10.0, 7.0, True), WINDMILL),             # a = 0.3
             ((-1.0, -1.0, 10.0, 5.0, True), TURBULENT_WAKE),       # a = 0.5 > 0.4
             ((-1.0, 1.0, 10.0, -2.0, True), TURBULENT_WAKE),       # a = 1.2: vortex ring
             ((-1.0, 1.0, 0.0, 5.0, True), NO_SOLUTION),            # hover, dT < 0 with u_x > 0
             ((1.0, -1.0, 10.0, 12.0, True), NO_SOLUTION),          # dT > 0, dQ < 0 breaks the energy balance
             ((1.0, 1.0, 10.0, 12.0, False), NO_SOLUTION)]          # W < 0
    args = np.array([c[0] for c in cases], dtype=object).T
    codes = classify(*(np.array(a, dtype=float) for a in args[:4]), np.array(args[4], dtype=bool))
    np.testing.assert_array_equal(codes, [c[1] for c in cases])


def test_reproducer_hover_reverse_thrust_is_flagged():
    # The reproducer.  Outboard (negative pitch) the annuli push air upward while the inboard
    # ones drive the wake down: the vortex-ring state, where momentum theory has no streamtube.  They are
    # flagged; the value returned is the mirror momentum root (no 177 deg roots, no FM > 1).
    with pytest.raises(om.AnalysisError, match=r"station 1[5-9].*turbulent wake / vortex ring"):
        _reproducer(on_invalid="raise")
    res, warned = _reproducer()
    assert len(warned) == 1 and "turbulent wake / vortex ring" in str(warned[0].message)
    ring = res.flow_state == TURBULENT_WAKE
    assert ring.sum() >= 1 and np.all(np.isin(res.flow_state, (PROPELLER, TURBULENT_WAKE)))
    # The flagged stations are the outboard ones (twist decreases outboard), each named in the warning.
    assert np.all(np.flatnonzero(ring) > np.flatnonzero(~ring).max())
    for station in np.flatnonzero(ring)[:3]:
        assert f"station {station}" in str(warned[0].message)
    assert np.all(np.abs(res.phi) < np.pi / 2)                     # no 177 deg mirror-image roots
    assert np.all(res.dthrust_dr[ring] < 0) and np.all(res.dtorque_dr[ring] > 0) and np.all(res.u_axial[ring] < 0)
    # The value returned satisfies momentum theory with the mass flux rho |u_x| at every station.
    np.testing.assert_allclose(res.dthrust_dr, _momentum_thrust(res, 0.0, res.rho), rtol=1e-9, atol=1e-9)
    assert np.all(res.dtorque_dr > 0)
    # Momentum-theory bound in hover (Prandtl F <= 1 and a hub only lower it): 0 < FM < 1, P > 0.
    assert res.thrust > 0 and res.power > 0 and 0 < res.figure_of_merit < 1
    quiet, warned = _reproducer(on_invalid="ignore")
    assert not warned and quiet.thrust == res.thrust


def test_hover_mirror_symmetry():
    # Symmetric section in hover: twist -> -twist maps phi -> -phi, dT -> -dT, u_x -> -u_x and keeps dQ
    # (R(-phi; -twist) = -R(phi; twist) with F even in phi and Re independent of phi).
    polar = SymmetricPolar()
    twist = np.radians(np.linspace(25.0, 8.0, NR))
    pos, w1 = _run(np.full(NR, 0.12), twist, 1.1, 0.15, 2200.0, 0.0, B, polar)
    neg, w2 = _run(np.full(NR, 0.12), -twist, 1.1, 0.15, 2200.0, 0.0, B, polar, on_invalid="ignore")
    assert not w1 and not w2
    np.testing.assert_array_equal(pos.flow_state, PROPELLER)
    np.testing.assert_array_equal(neg.flow_state, TURBULENT_WAKE)
    np.testing.assert_allclose(neg.phi, -pos.phi, rtol=1e-10)
    np.testing.assert_allclose(neg.dthrust_dr, -pos.dthrust_dr, rtol=1e-9)
    np.testing.assert_allclose(neg.dtorque_dr, pos.dtorque_dr, rtol=1e-9)
    np.testing.assert_allclose(neg.u_axial, -pos.u_axial, rtol=1e-9)
    # Hover annulus: u_x = sqrt(dT/dr / (4 pi rho r F)) (momentum theory, hand derivation).
    np.testing.assert_allclose(pos.u_axial, np.sqrt(pos.dthrust_dr / (4 * np.pi * pos.rho * pos.radii * pos.loss_factor)),
                               rtol=1e-9)


def test_windmill_state_signs():
    # Fast axial flow on a low-pitch blade: every annulus extracts power (dT < 0, dQ < 0) with the
    # flow slowed but not reversed, 0 < a = 1 - u_x/V_x <= 0.4 (momentum valid), and no annulus
    # extracts more than the flow delivers: Omega dQ - V_x dT >= 0 (energy balance).
    v_axial, rpm = 70.0, 1500.0
    res, warned = _run(np.full(NR, 0.1), np.radians(np.linspace(2.0, -4.0, NR)), 1.2, 0.2, rpm, v_axial, B,
                       SymmetricPolar())
    assert not warned
    np.testing.assert_array_equal(res.flow_state, WINDMILL)
    assert np.all(res.dthrust_dr < 0) and np.all(res.dtorque_dr < 0)
    a = 1.0 - res.u_axial / v_axial
    assert np.all(a > 0) and np.all(a <= 0.4)
    assert np.all(rpm * OMEGA_PER_RPM * res.dtorque_dr - v_axial * res.dthrust_dr >= 0)
    np.testing.assert_allclose(res.dthrust_dr, _momentum_thrust(res, v_axial, res.rho), rtol=1e-9)
    # Efficiency and FM keep the formula's value (here V T / P > 0 with T, P < 0): documented, not reported.
    assert res.thrust < 0 and res.power < 0 and res.efficiency > 0


def test_turbulent_wake_warns_once_raises_or_ignores():
    # The reproducer's blade at V_x = 5 m/s: outboard annuli work against the freestream with
    # a = 1 - u_x / V_x > 0.4 (turbulent wake / vortex ring: momentum theory invalid).
    res, warned = _reproducer(v_axial=5.0)
    a = 1.0 - res.u_axial / 5.0
    wake = (res.dthrust_dr < 0) & (a > 0.4)
    assert wake.sum() >= 1
    np.testing.assert_array_equal(res.flow_state == TURBULENT_WAKE, wake)
    assert len(warned) == 1
    message = str(warned[0].message)
    first = int(np.flatnonzero(wake)[0])
    r_over_r = res.radii[first] / 1.0
    assert f"{wake.sum()} station(s)" in message
    assert f"node 0, station {first} (r/R = {r_over_r:.3f}): turbulent wake / vortex ring" in message
    with pytest.raises(om.AnalysisError, match=rf"node 0, station {first} \(r/R = {r_over_r:.3f}\)"):
        _reproducer(v_axial=5.0, on_invalid="raise")
    _, warned = _reproducer(v_axial=5.0, on_invalid="ignore")
    assert not warned


def _section_problem(polar, values, solve_range="physical", on_invalid="ignore"):
    prob = om.Problem(reports=False)
    kw = dict(num_nodes=NN, num_radial=NR, num_blades=B, polar=polar)
    prob.model.add_subsystem("inflow", InflowComp(**kw, solve_range=solve_range, on_invalid=on_invalid),
                             promotes=["*"])
    prob.model.add_subsystem("loads", BladeElementLoadsComp(**kw), promotes=["*"])
    prob.setup(force_alloc_complex=True)
    for name, value in values.items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


def _values(make_blade, v_axial):
    blade = make_blade(NN, NR)
    values = {k: blade[k] for k in ("rpm", "radius", "hub_radius", "chord", "twist")}
    values.update(v_axial=np.asarray(v_axial, dtype=float),
                  radii=station_radii(blade["radius"], blade["hub_radius"], NR),
                  rho=[1.225, 1.1, 0.95], mu=[1.79e-5, 1.75e-5, 1.7e-5])
    return values


def test_no_momentum_solution_zero_loading(make_blade):
    # NegativeDragPolar has no admissible root anywhere (hand derivation in its docstring).
    values = _values(make_blade, [0.0, 20.0, 35.0])
    prob = _section_problem(NegativeDragPolar(), values)
    np.testing.assert_array_equal(prob.get_val("flow_state"), NO_SOLUTION)
    v_theta = prob.get_val("rpm", units="rad/s")[:, None] * values["radii"]
    v_x = values["v_axial"][:, None]
    # CCBlade's "zero loading assumed": phi = atan2(V_x, V_theta), no induction, no loads.
    np.testing.assert_allclose(prob.get_val("phi"), np.arctan2(v_x, v_theta), rtol=1e-14)
    np.testing.assert_array_equal(prob.get_val("dthrust_dr"), 0.0)
    np.testing.assert_array_equal(prob.get_val("dtorque_dr"), 0.0)
    np.testing.assert_allclose(prob.get_val("u_axial"), np.broadcast_to(v_x, (NN, NR)), rtol=1e-14)
    np.testing.assert_allclose(prob.get_val("inflow_speed"), np.hypot(v_x, v_theta), rtol=1e-14)
    with pytest.raises(om.AnalysisError, match="node 0, station 0 .*no momentum solution"):
        _section_problem(NegativeDragPolar(), values, on_invalid="raise")
    with pytest.warns(BEMStateWarning, match=f"{NN * NR} station"):
        _section_problem(NegativeDragPolar(), values, on_invalid="warn")
    # The full-range solve keeps the first sign change: for V_x > 0 the root tan(phi) = V_x / V_theta
    # (W < 0), flagged as a mirror root.
    full = _section_problem(NegativeDragPolar(), values, solve_range="full")
    state = full.get_val("flow_state")
    np.testing.assert_array_equal(state[1:], MIRROR_ROOT)
    np.testing.assert_allclose(full.get_val("phi")[1:], np.arctan2(v_x, v_theta)[1:], rtol=1e-10)


def test_partials_at_fallback_stations(make_blade):
    values = _values(make_blade, [0.0, 20.0, 35.0])
    check_component_partials(InflowComp(num_nodes=NN, num_radial=NR, num_blades=B, polar=NegativeDragPolar(),
                                        on_invalid="ignore"), values, atol=1e-9, rtol=1e-9)


def _all_states():
    """Three rotors whose stations cover propeller, brake, windmill and turbulent wake (smooth test polar)."""
    x = np.linspace(0.0, 1.0, NR)
    radius, hub = np.array([1.0, 1.2, 0.9]), np.array([0.15, 0.2, 0.12])
    return dict(v_axial=np.array([0.0, 70.0, 20.0]), rpm=np.array([2000.0, 1500.0, 2500.0]), radius=radius,
                hub_radius=hub, chord=np.full((NN, NR), 0.1),
                twist=np.stack([np.radians(25 - 40 * x), np.radians(2 - 6 * x), np.radians(8 - 14 * x)]),
                radii=station_radii(radius, hub, NR), rho=np.array([1.225, 1.1, 0.95]),
                mu=np.array([1.79e-5, 1.75e-5, 1.7e-5]))


def test_partials_in_every_state(smooth_polar):
    values = _all_states()
    prob = check_component_partials(InflowComp(num_nodes=NN, num_radial=NR, num_blades=B, polar=smooth_polar,
                                               on_invalid="ignore"), values, atol=1e-9, rtol=1e-9)
    state = prob.get_val("flow_state")
    for code in (PROPELLER, PROPELLER_BRAKE, WINDMILL, TURBULENT_WAKE):
        assert np.any(state == code), code
    loads_values = dict(values, phi=prob.get_val("phi"), flow_state=state)
    check_component_partials(BladeElementLoadsComp(num_nodes=NN, num_radial=NR, num_blades=B, polar=smooth_polar),
                             loads_values, atol=1e-9, rtol=1e-9)
    # The zero-loading branch of the loads, at stations labelled NO_SOLUTION.
    loads_values["flow_state"] = np.where(np.arange(NR) % 3 == 0, float(NO_SOLUTION), state)
    check_component_partials(BladeElementLoadsComp(num_nodes=NN, num_radial=NR, num_blades=B, polar=smooth_polar),
                             loads_values, atol=1e-9, rtol=1e-9)


def test_group_totals_in_every_state(smooth_polar):
    values = _all_states()
    values.pop("radii")
    values["altitude"] = np.array([0.0, 500.0, 1500.0])
    for name in ("rho", "mu"):
        values.pop(name)
    check_group_totals(lambda: BEMAnalysisGroup(num_nodes=NN, num_radial=NR, num_blades=B, polar=smooth_polar,
                                                on_invalid="ignore"),
                       of=["thrust", "torque", "energy_loss", "phi", "dthrust_dr"],
                       wrt=["chord", "twist", "v_axial", "rpm", "radius", "hub_radius"], values=values)


def test_random_rotors_no_unflagged_unphysical_metric():
    # 500 seeded random rotors (hover, propeller, windmill): no exception, no NaN, and no FM > 1 or
    # eta > 1 (where T > 0 and P > 0) unless the rotor has a flagged station and the analysis warned.
    rng = np.random.default_rng(17)
    n, nr = 500, 20
    x = (np.arange(nr) + 0.5) / nr
    radius = rng.uniform(0.3, 1.5, n)
    chord = radius[:, None] * (rng.uniform(0.03, 0.15, (n, 1)) * (1 - x) + rng.uniform(0.03, 0.15, (n, 1)) * x)
    twist = np.radians(rng.uniform(0, 45, (n, 1)) * (1 - x) + rng.uniform(-15, 20, (n, 1)) * x)
    kind = rng.integers(0, 3, n)
    v_axial = np.where(kind == 0, 0.0, np.where(kind == 1, rng.uniform(2, 40, n), rng.uniform(40, 120, n)))
    res, warned = _run(chord, twist, radius, radius * rng.uniform(0.1, 0.25, n), rng.uniform(1000, 6000, n),
                       v_axial, B, get_polar("naca4412"), altitude=rng.uniform(0, 3000, n))
    for name, value in res.to_dict().items():
        assert np.all(np.isfinite(value)), name
    assert np.all(np.isin(res.flow_state, (PROPELLER, PROPELLER_BRAKE, WINDMILL, TURBULENT_WAKE, NO_SOLUTION)))
    flagged = np.isin(res.flow_state, INVALID_STATES).any(axis=1)
    assert flagged.any() and len(warned) == 1
    ok = (res.thrust > 0) & (res.power > 0)
    hover = v_axial == 0
    unphysical = ok & ((hover & (res.figure_of_merit > 1)) | (~hover & (res.efficiency > 1)))
    assert not np.any(unphysical & ~flagged)
    # Energy balance of every valid annulus: Omega dQ - V_x dT >= 0.
    valid = ~np.isin(res.flow_state, INVALID_STATES)
    omega = res.power / res.torque
    energy = omega[:, None] * res.dtorque_dr - v_axial[:, None] * res.dthrust_dr
    assert np.all(energy[valid] >= -1e-9 * np.abs(omega[:, None] * res.dtorque_dr)[valid])
    # Momentum theory holds at every valid station.
    np.testing.assert_allclose(res.dthrust_dr[valid],
                               _momentum_thrust(res, v_axial[:, None], res.rho[:, None])[valid], rtol=1e-8, atol=1e-6)


def test_options_are_validated():
    with pytest.raises(ValueError, match="on_invalid must be one of warn, raise, ignore"):
        analyze_rotor(np.full(5, 0.1), np.full(5, 0.2), 1.0, 0.2, 2000.0, 0.0, 3, get_polar("analytic"),
                      on_invalid="loud")
    with pytest.raises(ValueError, match="solve_range must be one of physical, full"):
        analyze_rotor(np.full(5, 0.1), np.full(5, 0.2), 1.0, 0.2, 2000.0, 0.0, 3, get_polar("analytic"),
                      solve_range="all")
