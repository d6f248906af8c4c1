"""The local section point (section_point='local'): stationarity, the lower of two minima, exact derivatives."""
import warnings

import numpy as np
import pytest

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.airfoil.polar import PolarValues
from bild_mdo.bild.local_section_point import (
    _first_terms,
    _gradient,
    force_factors,
    point_derivatives,
    solve_local_point,
)
from bild_mdo.bild.local_section_point_comp import (
    LoadReynoldsComp,
    LocalSectionPointComp,
    ReferenceReynoldsComp,
    ReferenceSectionPointComp,
)
from bild_mdo.bild.local_section_point_reference import solve_reference_point
from bild_mdo.bild.reference_airfoil import default_polar
from bild_mdo.utils.testing import check_component_partials
from tests.bild.conftest import NN, NR, state

# Inflow angles and load Reynolds numbers Q = Re C of stations of the paper's rotors (Re 1e5..1e6).
PHI = np.array([0.05, 0.12, 0.15, 0.2, 0.35, 0.5])
LOAD = np.array([8e4, 1.2e5, 1.6e5, 2.5e5, 5e5, 1e6])
# A station whose point (torque form, NACA 4412 surrogate) lies 7.5e-6 in ln Re past the table's top edge
# Re = 2e6, where the second Reynolds derivatives jump (the continuation past the table is C^1): a central
# difference in ln Re of half step 1e-4 (the former way to get them) straddled the jump.
EDGE_PHI, EDGE_LOAD = 0.4066844281780629, 755377.8671370973
H = 1e-30


class _ComplexSafe:
    """Test only: the polar's first derivatives at complex ``(alpha, Re)`` (``evaluate`` carries only ``cl, cd``)."""

    def __init__(self, polar):
        self.polar = polar

    def evaluate(self, alpha, reynolds):
        alpha, reynolds = np.broadcast_arrays(np.asarray(alpha, dtype=complex), np.asarray(reynolds, dtype=complex))
        if isinstance(self.polar, AnalyticPolar):
            return PolarValues(*self.polar._all(alpha, reynolds)[0])
        (cl, cl_a, cl_re), (cd, cd_a, cd_re) = self.polar._compute(alpha, reynolds, second=False)
        return PolarValues(cl, cd, cl_a, cl_re, cd_a, cd_re)


def _residuals(polar, alpha, reynolds, phi, load, chord_form):
    """``(G, h)`` of the module docstring, complex-step safe in every argument (through :class:`_ComplexSafe`)."""
    p, q = force_factors(phi, chord_form)
    t = _first_terms(_ComplexSafe(polar), alpha, reynolds, p, q)
    return t.g, reynolds * t.force - load


@pytest.fixture(autouse=True)
def _quiet():
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*Reynolds numbers outside the tabulated range")
        yield


def _path(polar, phi, load, alpha, chord_form="thrust"):
    """Brute force (test only): Re on the path of fixed load, Re C(alpha, Re) = Q, and cd/cl along it."""
    p, q = force_factors(phi, chord_form)
    re = np.full(alpha.shape, load)
    ok = np.ones(alpha.shape, dtype=bool)
    for _ in range(60):  # fixed point Re = Q / C(alpha, Re): a contraction (d ln C / d ln Re << 1)
        v = polar.evaluate(alpha, re)
        force = p * v.cl + q * v.cd
        ok &= force > 0.0
        re = np.where(ok, load / np.where(ok, force, 1.0), load)
    re = np.where(ok, re, np.nan)
    v = polar.evaluate(alpha, np.where(np.isfinite(re), re, 1e6))
    ratio = np.where(np.isfinite(re) & (v.cl > 0.0), v.cd / v.cl, np.inf)
    return ratio


@pytest.mark.parametrize("polar", [default_polar(), AnalyticPolar(reynolds_exponent=0.2)], ids=["naca4412", "analytic"])
@pytest.mark.parametrize("chord_form", ["thrust", "torque"])
def test_stationarity_and_brute_force_minimum(polar, chord_form):
    # Hand derivation (module docstring): at the solution ds/dalpha along the path is 0 and d2s/dalpha2 > 0;
    # the point is the global minimum of cd/cl along the path (checked here by a fine scan, test only).
    point = solve_local_point(polar, PHI, LOAD, chord_form)
    derivs = point_derivatives(polar, point, PHI, chord_form)
    assert np.all(derivs.curvature > 0.0)
    h = 1e-5
    for i in range(PHI.size):
        s = _path(polar, PHI[i], LOAD[i], point.alpha[i] + np.array([-h, 0.0, h]), chord_form)
        slope = (s[2] - s[0]) / (2.0 * h)
        # Central difference: truncation ~h**2 s''' and round-off ~eps s / h, both << the curvature scale.
        assert abs(slope) < 1e-6 * max(derivs.curvature[i], 1.0)
        assert s[1] == pytest.approx(point.cd[i] / point.cl[i], rel=1e-10)
        grid = np.radians(np.linspace(-5.0, 15.0, 20001))
        brute = _path(polar, PHI[i], LOAD[i], grid, chord_form)
        k = np.argmin(brute)
        assert point.alpha[i] == pytest.approx(grid[k], abs=np.radians(2e-3))
        assert point.cd[i] / point.cl[i] <= brute[k] * (1.0 + 1e-9)
    # On the path: Re C(alpha, Re) = Q.
    p, q = force_factors(PHI, chord_form)
    np.testing.assert_allclose(point.reynolds * (p * point.cl + q * point.cd), LOAD, rtol=1e-12)


def test_two_nearly_equal_minima_take_the_lower():
    # Issue 12: near Re 1e5-3e5 the NACA 4412 surrogate's cd/cl along a fixed-load path has two nearly equal
    # minima (one near 2.5-4.5 deg, one near 7.5-8 deg).  Find such paths by brute force and check the solver
    # returns the lower one.
    polar = default_polar()
    grid = np.radians(np.linspace(-2.0, 12.0, 7001))
    cases = []
    for load in np.geomspace(8e4, 3e5, 40):
        s = _path(polar, 0.15, load, grid)
        interior = (s[1:-1] < s[:-2]) & (s[1:-1] <= s[2:])
        minima = np.flatnonzero(interior) + 1
        if minima.size >= 2:
            best = minima[np.argsort(s[minima])[:2]]
            if abs(s[best[0]] / s[best[1]] - 1.0) < 0.05:
                cases.append((load, grid[best[0]], grid[best[1]]))
    assert cases, "the surrogate has no path with two nearly equal minima near Re 1e5-3e5"
    loads = np.array([c[0] for c in cases])
    point = solve_local_point(polar, np.full(loads.size, 0.15), loads)
    for (load, lower, other), alpha in zip(cases, point.alpha):
        assert abs(np.degrees(lower - other)) > 2.0
        assert alpha == pytest.approx(lower, abs=np.radians(5e-3))
    # both=True also gives the other minimum (the Reynolds-aware exact loading follows both branches).
    again, runner = solve_local_point(polar, np.full(loads.size, 0.15), loads, both=True)
    np.testing.assert_array_equal(again.alpha, point.alpha)
    np.testing.assert_allclose(runner.alpha, [c[2] for c in cases], atol=np.radians(5e-3))


def test_implicit_function_derivatives_match_a_re_solve():
    # The implicit-function theorem on (G, h) = 0 against central differences of the full solve (test only).
    polar = default_polar()
    point = solve_local_point(polar, PHI, LOAD)
    derivs = point_derivatives(polar, point, PHI)
    h = 1e-6
    up, down = solve_local_point(polar, PHI + h, LOAD), solve_local_point(polar, PHI - h, LOAD)
    np.testing.assert_allclose(derivs.dalpha_dphi, (up.alpha - down.alpha) / (2 * h), rtol=1e-5, atol=1e-9)
    np.testing.assert_allclose(derivs.dcd_dphi, (up.cd - down.cd) / (2 * h), rtol=1e-5, atol=1e-10)
    up, down = solve_local_point(polar, PHI, LOAD * (1 + h)), solve_local_point(polar, PHI, LOAD * (1 - h))
    np.testing.assert_allclose(derivs.dalpha_dq * LOAD, (up.alpha - down.alpha) / (2 * h), rtol=1e-5, atol=1e-9)
    np.testing.assert_allclose(derivs.dre_dq * LOAD, (up.reynolds - down.reynolds) / (2 * h), rtol=1e-5)


CASES = [("naca4412", "thrust", PHI, LOAD), ("naca4412", "torque", PHI, LOAD),
         ("naca4412", "torque", np.array([EDGE_PHI]), np.array([EDGE_LOAD])),
         ("analytic", "thrust", PHI, LOAD), ("analytic", "torque", PHI, LOAD)]


@pytest.mark.parametrize("name, chord_form, phi, load", CASES, ids=[f"{c[0]}-{c[1]}-{c[2].size}" for c in CASES])
def test_implicit_function_derivatives_by_complex_step(name, chord_form, phi, load):
    # Hand-checkable identity: the Jacobian of (G, h) in (alpha, Re, phi, Q) by complex step of the polar's first
    # derivatives (no second derivative of the polar is used), then d(alpha, Re)/dp = -J**-1 (G_p, h_p).  It must
    # equal the exact _gradient terms (the polar's second derivatives, d2/dRe2 included) and point_derivatives.
    polar = default_polar() if name == "naca4412" else AnalyticPolar(reynolds_exponent=0.2)
    point = solve_local_point(polar, phi, load, chord_form)
    derivs = point_derivatives(polar, point, phi, chord_form)
    alpha, re = point.alpha, point.reynolds
    steps = {"alpha": (H, 0, 0, 0), "re": (0, H * re, 0, 0), "phi": (0, 0, H, 0), "q": (0, 0, 0, H * load)}
    jac = {}
    for key, (da, dr, dphi, dq) in steps.items():
        g, h = _residuals(polar, alpha + 1j * da, re + 1j * dr, phi + 1j * dphi, load + 1j * dq, chord_form)
        unit = {"re": re, "q": load}.get(key, 1.0)   # relative steps in Re and Q; derivatives per unit Re, Q
        jac[key] = (g.imag / H / unit, h.imag / H / unit)
    p, q = force_factors(phi, chord_form)
    g_a, g_r, g_phi, _ = _gradient(polar, alpha, re, p, q, _first_terms(polar, alpha, re, p, q))
    tol = dict(rtol=1e-12, atol=1e-14 * np.max(np.abs(g_a)))
    np.testing.assert_allclose(g_a, jac["alpha"][0], **tol)
    np.testing.assert_allclose(g_r * re, jac["re"][0] * re, **tol)
    np.testing.assert_allclose(g_phi, jac["phi"][0], **tol)
    for k in range(phi.size):
        j = np.array([[jac["alpha"][0][k], jac["re"][0][k]], [jac["alpha"][1][k], jac["re"][1][k]]])
        for param, (d_alpha, d_re) in (("phi", (derivs.dalpha_dphi, derivs.dre_dphi)),
                                       ("q", (derivs.dalpha_dq, derivs.dre_dq))):
            want = -np.linalg.solve(j, [jac[param][0][k], jac[param][1][k]])
            # Exact second derivatives: agreement to ~1e-14; the former central difference in ln Re was off by
            # 1e-11 inside the table and by 25 % at the edge case.
            assert d_alpha[k] == pytest.approx(want[0], rel=1e-12)
            assert d_re[k] == pytest.approx(want[1], rel=1e-12)


def test_derivatives_just_past_the_table_edge_match_a_re_solve():
    # The point of EDGE_PHI, EDGE_LOAD lies just past Re = 2e6; steps of 1e-7 in phi move Re by about 0.5,
    # so the re-solves stay on its side of the edge (test only).
    polar = default_polar()
    phi, load = np.array([EDGE_PHI]), np.array([EDGE_LOAD])
    point = solve_local_point(polar, phi, load, "torque")
    assert 0.0 < point.reynolds[0] / polar.reynolds[-1] - 1.0 < 1e-4
    derivs = point_derivatives(polar, point, phi, "torque")
    h = 1e-7
    up, down = solve_local_point(polar, phi + h, load, "torque"), solve_local_point(polar, phi - h, load, "torque")
    assert np.all(down.reynolds > polar.reynolds[-1])
    np.testing.assert_allclose(derivs.dalpha_dphi, (up.alpha - down.alpha) / (2 * h), rtol=1e-6)
    np.testing.assert_allclose(derivs.dcl_dphi, (up.cl - down.cl) / (2 * h), rtol=1e-6)
    np.testing.assert_allclose(derivs.dre_dphi, (up.reynolds - down.reynolds) / (2 * h), rtol=1e-6)


def test_reynolds_independent_polar_gives_the_maximum_lift_to_drag_point():
    # With no Re dependence (D = 0, C_Re = 0) the condition is A = 0: the max-L/D point (module docstring).
    polar = AnalyticPolar()
    point = solve_local_point(polar, PHI, LOAD)
    best = polar.max_lift_to_drag(np.full(PHI.size, 1e6))
    np.testing.assert_allclose(point.alpha, best.alpha, atol=1e-12)


def test_invalid_load_is_one_line():
    with pytest.raises(ValueError, match="load Reynolds number"):
        solve_local_point(default_polar(), [0.1], [-1.0])


def test_section_point_partials():
    # The component carries complex inputs with its own implicit-function derivatives (the solve is not
    # complex-capable), so complex step checks the wiring here (rows, columns, the (nn, nr) layout, the floor of
    # unloaded stations); their values are checked by test_implicit_function_derivatives_by_complex_step.
    rng = np.random.default_rng(3)
    values = {"phi": 0.05 + 0.4 * rng.random((NN, NR)),
              "load_reynolds": np.exp(np.log(1e5) + 2.3 * rng.random((NN, NR)))}
    check_component_partials(LocalSectionPointComp(num_nodes=NN, num_radial=NR, polar=default_polar()), values,
                             atol=1e-12, rtol=1e-12)


@pytest.mark.parametrize("chord_form", ["thrust", "torque"])
def test_reference_section_point_partials(chord_form):
    values = {"phi_ref": np.array([0.1, 0.3, 0.5]), "reynolds_ref": np.array([4e5, 8e5, 1.5e6])}
    check_component_partials(ReferenceSectionPointComp(num_nodes=NN, polar=default_polar(), chord_form=chord_form),
                             values, atol=1e-12, rtol=1e-12)


def test_reference_point_is_a_minimum_of_its_own_path():
    # Module docstring of local_section_point_reference: at (alpha, Re_ref) the path of fixed load through the
    # point is stationary and the point is a minimum along it (checked by brute force along that path, test only).
    polar = default_polar()
    phi, reynolds = np.array([0.1, 0.3, 0.5]), np.array([4e5, 8e5, 1.5e6])
    point = solve_reference_point(polar, phi, reynolds)
    p, q = force_factors(phi, "thrust")
    load = reynolds * (p * point.cl + q * point.cd)
    h = np.radians(0.05)
    for i in range(phi.size):
        s = _path(polar, phi[i], load[i], point.alpha[i] + np.array([-h, 0.0, h]))
        assert s[1] == pytest.approx(point.cd[i] / point.cl[i], rel=1e-9)
        assert s[1] < s[0] and s[1] < s[2]
    # Where that minimum is also the lowest of the path, the station rule returns the same point (chord c_ref).
    station = solve_local_point(polar, phi, load)
    np.testing.assert_allclose(station.alpha, point.alpha, atol=1e-9)
    np.testing.assert_allclose(station.reynolds, reynolds, rtol=1e-9)


@pytest.mark.parametrize("chord_form", ["thrust", "torque"])
def test_reference_point_derivatives_by_complex_step(chord_form):
    # At fixed Re the reference point solves G(alpha, Re; phi) = 0: dalpha/dp = -G_p / G_alpha, with G's
    # Jacobian here by complex step of the polar's first derivatives (hand-checkable identity).  Reynolds
    # numbers inside the NACA 4412 table, at its top edge 2e6 and past both edges.
    polar = default_polar()
    phi = np.array([0.1, 0.3, 0.5, 0.2, 0.25, 0.15])
    reynolds = np.array([4e5, 8e5, 1.5e6, 2e6, 2e6 * (1 + 1e-6), 3e4])
    point = solve_reference_point(polar, phi, reynolds, chord_form)
    load = np.zeros_like(phi)  # h is not used at fixed Re
    g_a = _residuals(polar, point.alpha + 1j * H, reynolds, phi, load, chord_form)[0].imag / H
    g_r = _residuals(polar, point.alpha, reynolds + 1j * H * reynolds, phi, load, chord_form)[0].imag / H
    g_phi = _residuals(polar, point.alpha, reynolds, phi + 1j * H, load, chord_form)[0].imag / H
    np.testing.assert_allclose(point.dalpha_dre * reynolds, -g_r / g_a, rtol=1e-12)
    # G = C E(alpha, Re) (expand A B - Re D C_alpha with C = p cl + q cd): at fixed Re the root does not move
    # with phi, so both sides are round-off.
    np.testing.assert_allclose(point.dalpha_dphi, -g_phi / g_a, atol=1e-13)
    assert np.min(np.abs(point.dalpha_dre * reynolds)) > 1e-4


def test_reference_reynolds_in_the_band_between_two_branches():
    # Documented limitation: with the NACA 4412 surrogate, Re_ref = 2.02e5 at phi = 0.51 is the optimum of no path
    # (brute force over many loads, test only): the point returned is then stationary but not a minimum along its
    # path, and a station with its load chooses another Reynolds number (a chord other than c_ref).
    polar = default_polar()
    phi, reynolds = 0.5115, 2.019e5
    point = solve_reference_point(polar, [phi], [reynolds])
    loads = np.geomspace(8e4, 4e5, 200)
    optima = solve_local_point(polar, np.full(loads.size, phi), loads)
    assert not np.any(np.abs(optima.reynolds / reynolds - 1.0) < 0.02)
    p, q = force_factors(phi, "thrust")
    load = reynolds * (p * point.cl[0] + q * point.cd[0])
    h = np.radians(0.05)
    s = _path(polar, phi, load, point.alpha[0] + np.array([-h, 0.0, h]))
    assert s[1] > s[0] and s[1] > s[2]


@pytest.mark.parametrize("chord_form", ["thrust", "torque"])
def test_load_reynolds_partials(kind, chord_form):
    values = state(kind)
    values.update(dthrust_dr=np.full((NN, NR), 300.0), dtorque_dr=np.full((NN, NR), 50.0),
                  inflow_speed=values["v_theta"] * 1.02)
    check_component_partials(LoadReynoldsComp(num_nodes=NN, num_radial=NR, chord_form=chord_form), values)
    check_component_partials(ReferenceReynoldsComp(num_nodes=NN), values)


def test_load_reynolds_is_reynolds_times_force_coefficient():
    # Hand derivation: with c = 2 dT/dr / (C rho W**2 B) (Eq. (31)), Re C = rho W0 c C / mu = 2 dT/dr W0 / (mu W**2 B).
    values = state("cruise")
    values.update(dthrust_dr=np.full((NN, NR), 300.0), inflow_speed=values["v_theta"] * 1.02)
    prob = check_component_partials(LoadReynoldsComp(num_nodes=NN, num_radial=NR), values)
    w0 = np.sqrt(values["v_axial"][:, None] ** 2 + values["v_theta"] ** 2)
    chord = 2.0 * 300.0 / (1.0 * values["rho"][:, None] * values["inflow_speed"] ** 2 * 3)  # C = 1
    reynolds = values["rho"][:, None] * w0 * chord / values["mu"][:, None]
    np.testing.assert_allclose(prob.get_val("load_reynolds"), reynolds, rtol=1e-13)
