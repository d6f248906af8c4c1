"""Buhl's high-induction correction (``high_induction='buhl'``): the thrust at the root, the limits, partials.

Sources: Buhl, "A New Empirical Relationship between Thrust Coefficient and Induction Factor for the
Turbulent Windmill State", NREL/TP-500-36834 (2005): with Prandtl's factor the local thrust coefficient
is ``C_T = 8/9 + (4 F - 40/9) a + (50/9 - 4 F) a^2`` for ``a > 0.4`` and momentum theory's
``4 F a (1 - a)`` below; the torque balance ``dQ/dr = 2 pi r^2 rho F u_axial u_theta`` (momentum theory,
unchanged by the correction).  The test turbine (5 m, analytic NACA 4412-like polar) runs at tip-speed
ratios 9 and 12, where momentum theory alone puts its tip annuli past a = 1 (the vortex-ring state).
"""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.bem import analyze_rotor
from bild_mdo.bem.analyze import station_radii
from bild_mdo.bem.attached_branch import high_induction_candidates
from bild_mdo.bem.bem_group import BEMAnalysisGroup
from bild_mdo.bem.blade_element import residual_function
from bild_mdo.bem.flow_states import PROPELLER_BRAKE, TURBULENT_WAKE, WINDMILL
from bild_mdo.bem.inflow import InflowComp
from bild_mdo.bem.inflow_residual import (buhl_residual_term, induced_velocities, inflow_residual,
                                          inflow_residual_value)
from bild_mdo.bem.loads import BladeElementLoadsComp
from bild_mdo.bem.turbine_polar import TurbinePolar
from bild_mdo.utils.testing import check_component_partials, check_group_totals

R, HUB, B, WIND, RHO = 5.0, 0.5, 3, 8.0, 1.225
NN, NR = 2, 5
POLAR = AnalyticPolar(reynolds_exponent=0.2)


def _blade(nr=NR):
    x = np.linspace(0.0, 1.0, nr)
    return 0.5 * (1.0 - 0.6 * x) + 0.05, np.radians(12.0 - 12.0 * x)


def _rpm(tip_speed_ratio):
    return np.asarray(tip_speed_ratio) * WIND / R * 30.0 / np.pi


def _analyze(high_induction, tip_speed_ratio=(9.0, 12.0), nr=NR):
    chord, twist = _blade(nr)
    tsr = np.asarray(tip_speed_ratio)
    return analyze_rotor(np.tile(chord, (tsr.size, 1)), np.tile(twist, (tsr.size, 1)), np.full(tsr.size, R),
                         np.full(tsr.size, HUB), _rpm(tsr), np.full(tsr.size, WIND), B, POLAR,
                         rho=np.full(tsr.size, RHO), mu=np.full(tsr.size, 1.81e-5), rotor_type="turbine",
                         high_induction=high_induction, on_invalid="ignore")


def test_thrust_at_the_root_is_buhls_and_torque_is_momentum_theorys():
    res = _analyze("buhl", nr=12)
    shape = res.radii.shape  # the section outputs have an azimuth axis (one sector)
    a = 1.0 - np.reshape(res.u_axial, shape) / WIND
    F, u_theta = np.reshape(res.loss_factor, shape), np.reshape(res.u_theta, shape)
    # The blade element's thrust (turbine-signed) over 1/2 rho V^2 2 pi r, against Buhl's or momentum's C_T.
    c_t = res.dthrust_dr / (0.5 * RHO * WIND**2 * 2.0 * np.pi * res.radii)
    buhl = 8.0 / 9.0 + (4.0 * F - 40.0 / 9.0) * a + (50.0 / 9.0 - 4.0 * F) * a**2
    expected = np.where(a > 0.4, buhl, 4.0 * F * a * (1.0 - a))
    np.testing.assert_allclose(c_t, expected, rtol=1e-9)
    # (turbine-signed torque; u_theta is the kernel's, propeller-signed: the wake swirls against the rotation)
    np.testing.assert_allclose(res.dtorque_dr, -2.0 * np.pi * res.radii**2 * RHO * F * (1.0 - a) * WIND * u_theta,
                               rtol=1e-9)
    # Both sides of a = 0.4 are met, and no annulus is flagged: windmills (the tip at TSR 12 a propeller brake,
    # its drag absorbing power) below a = 1.
    assert np.count_nonzero(a > 0.4) >= 6 and np.count_nonzero(a < 0.4) >= 6
    assert np.all(a < 1.0) and np.all(np.isin(res.flow_state, [WINDMILL, PROPELLER_BRAKE]))
    # Without the correction the same rotor has annuli past a = 1 (flagged): the correction is what acts.
    plain = _analyze("none", nr=12)
    assert np.any(1.0 - plain.u_axial / WIND > 1.0) and np.any(plain.flow_state == TURBULENT_WAKE)


def test_nothing_changes_below_critical_induction(make_blade):
    # A propeller (a < 0) and a lightly loaded turbine (a < 0.4 everywhere): the same numbers (the solver's
    # iterates may pass a = 0.4 on the way, so to its tolerance, not bit for bit).
    blade = make_blade(3, 6)
    args = [blade[k] for k in ("chord", "twist", "radius", "hub_radius", "rpm", "v_axial")] + [B, POLAR]
    for kw in ({}, {"rotor_type": "turbine"}):
        if kw:
            chord, twist = _blade()
            args = [chord, twist, R, HUB, float(_rpm(4.0)), WIND, B, POLAR]
        plain, buhl = (analyze_rotor(*args, high_induction=h, on_invalid="ignore", **kw) for h in ("none", "buhl"))
        # a = 1 - u_axial / V_x < 0.4 (without a division: the propeller's first design hovers)
        assert np.all(np.asarray(plain.u_axial) > 0.6 * np.asarray(args[5])[..., None])
        for name in ("phi", "dthrust_dr", "dtorque_dr", "u_axial", "thrust", "power"):
            np.testing.assert_allclose(getattr(buhl, name), getattr(plain, name), rtol=1e-12, atol=0.0)


def _point(a_target, phi=0.3, v_theta=40.0, sigma=0.05, cl=-0.8, cd=0.02, F=0.9):
    """Residual arguments whose torque-and-geometry induction ``1 - 4 F s^2 V_theta / (V_x D)`` is ``a_target``."""
    s, c = np.sin(phi), np.cos(phi)
    d = 4.0 * F * s * c + sigma * (cl * s + cd * c)
    v_axial = 4.0 * F * s * s * v_theta / (d * (1.0 - a_target))
    return phi, v_axial, v_theta, sigma, cl, cd, F


def test_correction_starts_at_critical_induction_with_zero_value_and_slope():
    # Delta R = (2/9) (3 E - 5 s)^2 = (2/9) E^2 (5 a - 2)^2: zero up to a = 0.4, then quadratic in a - 0.4.
    below = [buhl_residual_term(*_point(a)) for a in (-0.5, 0.0, 0.2, 0.39999)]
    assert below == [0.0] * 4
    args = [_point(0.4 + h) for h in (1e-3, 2e-3)]
    values = [buhl_residual_term(*p) for p in args]
    np.testing.assert_allclose(values[1] / values[0], 4.0, rtol=1e-2)  # quadratic onset: C1 at a = 0.4
    # The closed form (2/9) E^2 (5 a - 2)^2 with E = s / (1 - a).
    phi = args[0][0]
    np.testing.assert_allclose(values[0], 2.0 / 9.0 * (np.sin(phi) / (1.0 - 0.401)) ** 2 * (5 * 0.401 - 2) ** 2,
                               rtol=1e-9)


@pytest.mark.parametrize("a_target", [0.45, 0.7, 0.95])
def test_explicit_partials_against_complex_step(a_target):
    point = _point(a_target)
    res = inflow_residual(*point, high_induction="buhl")
    ind = induced_velocities(*point, high_induction="buhl")
    names = ("phi", "v_axial", "v_theta", "sigma", "cl", "cd", "F")
    for k, name in enumerate(names):
        shifted = list(point)
        shifted[k] = point[k] + 1e-30j
        d_res = np.imag(inflow_residual_value(*shifted, high_induction="buhl")) / 1e-30
        d_ux = np.imag(induced_velocities(*shifted, high_induction="buhl").u_axial) / 1e-30
        np.testing.assert_allclose(getattr(res, f"dR_d{name}"), d_res, rtol=1e-10, atol=1e-14, err_msg=name)
        np.testing.assert_allclose(getattr(ind, f"du_axial_d{name}"), d_ux, rtol=1e-10, atol=1e-14, err_msg=name)
    # The correction acts at these points (the residual differs from momentum theory's).
    assert inflow_residual_value(*point, high_induction="buhl") > inflow_residual_value(*point)


def _component_values():
    chord, twist = _blade()
    radii = station_radii(np.full(NN, R), np.full(NN, HUB), NR)
    return {"v_axial": np.full(NN, WIND), "rpm": _rpm([9.0, 12.0]), "radius": np.full(NN, R),
            "hub_radius": np.full(NN, HUB), "radii": radii, "chord": np.tile(chord, (NN, 1)),
            "twist": np.tile(twist, (NN, 1)), "rho": np.full(NN, RHO), "mu": np.full(NN, 1.81e-5)}


def test_component_partials_on_both_sides_of_critical_induction():
    options = dict(num_nodes=NN, num_radial=NR, num_blades=B, polar=TurbinePolar(POLAR), high_induction="buhl",
                   on_invalid="raise")
    prob = check_component_partials(InflowComp(**options), _component_values(), atol=1e-9, rtol=1e-9)
    phi = prob.get_val("phi")
    values = dict(_component_values(), phi=phi, flow_state=prob.get_val("flow_state"))
    loads = check_component_partials(BladeElementLoadsComp(**{k: v for k, v in options.items() if k != "on_invalid"}),
                                     values, atol=1e-9, rtol=1e-9)
    a = 1.0 - loads.get_val("u_axial") / WIND
    assert np.any(a > 0.45) and np.any(a < 0.35)


def test_totals_through_the_bem_group():
    values = _component_values()
    values = {k: v for k, v in values.items() if k not in ("radii", "rho", "mu")}
    check_group_totals(lambda: BEMAnalysisGroup(num_nodes=NN, num_radial=NR, num_blades=B,
                                                polar=TurbinePolar(POLAR), high_induction="buhl"),
                       of=["thrust", "torque", "power"], wrt=["v_axial", "rpm", "radius", "hub_radius", "chord",
                                                            "twist"], values=values)


def _station(twist_deg, chord_over_r, r_over_r, tsr):
    """Flat inputs of one turbine station (the kernels of ``InflowComp.solve_nonlinear``)."""
    r = r_over_r * R
    return dict(v_axial=np.array([WIND]), rpm=np.array([float(_rpm(tsr))]), radii=np.array([r]),
                chord=np.array([chord_over_r * r]), twist=np.array([np.radians(twist_deg)]), rho=np.array([RHO]),
                mu=np.array([1.8e-5]), radius=np.array([R]), hub_radius=np.array([HUB]), num_blades=B,
                polar=TurbinePolar(POLAR), loss_model="tip_hub", speed_of_sound=np.array([340.0]),
                collective_pitch=np.array([0.0]))


def _inflow_problem(nn, nr, warm_start):
    """A set-up problem of the turbine's InflowComp with Buhl's correction."""
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("inflow", InflowComp(num_nodes=nn, num_radial=nr, num_blades=B, polar=TurbinePolar(POLAR),
                                                  high_induction="buhl", on_invalid="ignore", warm_start=warm_start),
                             promotes=["*"])
    prob.setup()
    return prob


def test_the_least_induced_of_several_roots_is_taken():
    # A heavily loaded station (found by a random search) whose residual has three roots in region 1 with the
    # correction (a = 0.60, 0.54, 0.34, by a dense scan) and one below a = 0.4 without it.  The solve returns
    # the least induced (the largest phi), momentum theory's root, from any start and in a warm start.
    kernels = _station(-3.352936777823533, 0.22994006537465947, 0.2125, 11.987381458610637)
    grid = np.linspace(1e-6, 0.5 * np.pi, 200001)
    roots = {}
    for h in ("none", "buhl"):
        value = residual_function(**kernels, high_induction=h)(grid, np.zeros(grid.size, int))[0]
        roots[h] = grid[np.flatnonzero(np.sign(value[:-1]) != np.sign(value[1:]))]
    assert roots["buhl"].size == 3 and roots["buhl"][-1] == pytest.approx(roots["none"][-1], abs=1e-4)
    values = {name: np.full((NN,) + kernels[name].shape, kernels[name][0])
              for name in ("v_axial", "rpm", "radius", "hub_radius", "rho", "mu")}
    values.update({name: np.full((NN, NR), kernels[name][0]) for name in ("chord", "twist")})
    values["radii"] = np.tile(np.linspace(0.9, 1.1, NR) * kernels["radii"][0], (NN, 1))
    values["radii"][:, 2] = kernels["radii"][0]
    for warm in (False, True):
        prob = _inflow_problem(NN, NR, warm)
        for name, value in values.items():
            prob.set_val(name, value)
        for start in (0.1497, 0.2508) if warm else (None,):
            if start is not None:
                prob.model.inflow._previous_phi = np.full(NN * NR, start)
            prob.run_model()
            np.testing.assert_allclose(prob.get_val("phi")[:, 2], roots["buhl"][-1], atol=1e-4)


def test_warm_and_cold_solves_agree_with_the_correction():
    # Random turbine blades and twist steps (the warm start's use, a driver moving the design): the warm solve
    # returns the cold solve's roots, with the rule above where the correction allows several roots.  (A turbine's
    # stalled triple of roots below a = 0.4 is not covered by either rule, with or without the correction: about
    # 1 station in 20,000 of such random blades; this seed has none.)
    rng = np.random.default_rng(1)
    nn, nr = 100, 12
    radii = station_radii(np.full(nn, R), np.full(nn, HUB), nr)
    values = dict(v_axial=np.full(nn, WIND), rpm=_rpm(rng.uniform(3.0, 16.0, nn)), radius=np.full(nn, R),
                  hub_radius=np.full(nn, HUB), radii=radii, chord=rng.uniform(0.02, 0.3, (nn, nr)) * radii,
                  twist=np.radians(rng.uniform(-5.0, 25.0, (nn, nr))), rho=np.full(nn, RHO), mu=np.full(nn, 1.8e-5))
    probs = [_inflow_problem(nn, nr, warm) for warm in (True, False)]
    heavy = 0
    for step in range(4):
        values["twist"] = values["twist"] + np.radians(rng.normal(0.0, 0.3, (nn, nr)))
        for prob in probs:
            for name, value in values.items():
                prob.set_val(name, value)
            prob.run_model()
        np.testing.assert_allclose(probs[0].get_val("phi"), probs[1].get_val("phi"), atol=1e-10, rtol=0.0)
        flat = {name: np.broadcast_to(np.asarray(value).reshape(nn, -1), (nn, nr)).ravel()
                for name, value in values.items()}
        kernels = dict(flat, num_blades=B, polar=TurbinePolar(POLAR), loss_model="tip_hub",
                       speed_of_sound=np.full(nn * nr, 340.0), collective_pitch=np.zeros(nn * nr))
        phi = probs[1].get_val("phi").ravel()
        heavy += high_induction_candidates(phi, np.ones(phi.size, dtype=bool), kernels, "buhl").size
    assert heavy > 100  # roots past a = 0.4, where the rule runs


def test_the_degenerate_end_of_buhls_relation_is_flagged():
    # A propeller with negative pitch near hover (V_x = 0.03 m/s at 5000 rpm): with the correction the only root
    # in region 1 lies at a -> 1 (W -> 0), the end of Buhl's relation, and is flagged, as momentum theory's
    # mirror root is without it (bild_mdo.bem.flow_states.BUHL_MAX_INDUCTION).
    args = (np.full(3, 0.05), np.radians([-12.0, -10.0, -8.0]), 0.5, 0.1, 5000.0, 0.03, 2, POLAR)
    for h in ("none", "buhl"):
        res = analyze_rotor(*args, high_induction=h, on_invalid="ignore")
        assert np.all(res.flow_state == TURBULENT_WAKE), h
    res = analyze_rotor(*args, high_induction="buhl", on_invalid="ignore")
    assert np.all(1.0 - res.u_axial / 0.03 > 0.95)
