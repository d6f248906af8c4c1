"""Eta2Comp / solve_eta2: the physical root of the BILD quartic (Eq. (27)) and its derivatives."""
import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials
from scipy.optimize import brentq

from bild_mdo.bild.variants.paper import quartic as qc
from bild_mdo.bild.variants.paper.eta2 import Eta2Comp, solve_eta2
from bild_mdo.bild.variants.paper.ideal_loading import IdealLoadingComp
from bild_mdo.utils.testing import assert_totals_match, check_component_partials

from tests.bild.conftest import NN, NR, state
from tests.bild.variants.paper.test_quartic import eq22_lambda, random_domain


def lift_coefficients(n, seed):
    return np.random.default_rng(seed).uniform(0.3, 1.5, n)


def test_acceptance_random_domain():
    # 100,000 random points of the valid domain: every root in (0.5, 1) and Eq. (22) (with
    # Eqs. (24), (26)) reproduced to 1e-10 relative.  Hover points satisfy lambda > V_theta/(2 L/D).
    v_x, v_t, lam, s = random_domain(100_000, seed=11)
    cl = lift_coefficients(v_x.size, seed=12)
    cd = s * cl
    eta = solve_eta2(v_x, v_t, lam, cl, cd)
    assert np.all((eta > 0.5) & (eta < 1.0))
    error = np.abs(eq22_lambda(eta, v_x, v_t, cd / cl) - lam) / lam
    assert error.max() <= 1e-10


def test_root_is_rounded_to_within_two_ulps_for_extreme_lambda():
    # lambda log-uniform over five decades: roots come within 1e-8 of eta = 1, where Eq. (22) amplifies eta's
    # rounding by |dlambda/deta| (up to ~1e-8 relative per ulp), so the check is that the exact root of Eq. (22)
    # lies within 2 ulps of the returned eta (lambda is bracketed by Eq. (22) at eta -+ 2 ulps).
    rng = np.random.default_rng(13)
    v_x, v_t, _, s = random_domain(50_000, seed=13)
    lam = np.exp(rng.uniform(np.log(1e-2), np.log(1e3), v_x.size))
    hover = v_x == 0.0
    lam[hover] = np.maximum(lam[hover], 0.5 * s[hover] * v_t[hover] * 1.001)
    eta = solve_eta2(v_x, v_t, lam, 1.0, s)
    assert np.all((eta > 0.5) & (eta < 1.0))
    two_ulps = 2 * np.spacing(eta)
    below = eq22_lambda(eta - two_ulps, v_x, v_t, s) - lam
    above = eq22_lambda(eta + two_ulps, v_x, v_t, s) - lam
    close = np.abs(eq22_lambda(eta, v_x, v_t, s) - lam) <= 1e-10 * lam
    assert np.all(close | (below * above <= 0))


def test_root_is_unique_on_a_fine_grid():
    # Uniqueness in (0.5, 1): the physical factor h changes sign exactly once on a 1001-point grid, and the solve's
    # root lies in the grid cell where it does.  In hover h(1) = 0, so the left limit of sign(h) at 1 is used:
    # sign(V_theta s - 2 lambda) (hand derivation of h near eta = 1, V_x = 0).
    v_x, v_t, lam, s = random_domain(20_000, seed=14)
    grid = np.linspace(0.5, 1.0, 1001)
    eta = solve_eta2(v_x, v_t, lam, 1.0, s)
    changes = np.zeros(v_x.size, dtype=int)
    cell = np.full(v_x.size, -1)
    previous = np.sign(qc.physical_factor(grid[0], v_x, v_t, lam, s)[0])
    for j, value in enumerate(grid[1:], start=1):
        sign = np.sign(qc.physical_factor(value, v_x, v_t, lam, s)[0])
        if j == grid.size - 1:
            sign = np.where(v_x == 0.0, np.sign(v_t * s - 2 * lam), sign)
        flipped = sign != previous
        changes += flipped
        cell[flipped] = j
        previous = sign
    assert np.all(changes == 1)
    assert np.all((grid[cell - 1] <= eta) & (eta <= grid[cell]))


@pytest.mark.parametrize("lam_excess", [1e-3, 1e-4, 1e-5])
@pytest.mark.parametrize("v_x", [1e-3, 1e-5, 1e-7])
def test_near_hover_near_tip_other_root_is_never_returned(v_x, lam_excess):
    # Tip of a hovering rotor (V_theta = 250 m/s, L/D = 20) loaded just above the hover threshold
    # lambda = V_theta/(2 L/D): the other root of P lies just above 1, within 1e-4 of the physical one.
    v_t, cl, cd = 250.0, 1.0, 0.05
    s = cd / cl
    lam = 0.5 * s * v_t * (1 + lam_excess)
    eta = float(solve_eta2(v_x, v_t, lam, cl, cd))
    other = brentq(lambda e: qc.quartic(e, v_x, v_t, lam, s), 1.0, 1.5, xtol=1e-16, rtol=1e-15)
    assert 0.5 < eta < 1.0 < other
    assert other - eta < 1e-4
    assert abs(eq22_lambda(eta, v_x, v_t, s) - lam) <= 1e-10 * lam


def test_unloaded_hover_stations():
    # Hover with lambda <= V_theta/(2 L/D): no root in (0.5, 1), the station is unloaded, eta2 = 1 exactly.
    v_t = np.array([100.0, 200.0, 300.0])
    s = 0.05
    threshold = 0.5 * s * v_t
    np.testing.assert_array_equal(solve_eta2(0.0, v_t, threshold, 1.0, s), 1.0)
    np.testing.assert_array_equal(solve_eta2(0.0, v_t, 0.5 * threshold, 1.0, s), 1.0)
    assert np.all(solve_eta2(0.0, v_t, 1.01 * threshold, 1.0, s) < 1.0)
    # Continuity as V_x -> 0+: 1 - eta ~ V_x lambda s / (V_theta (s V_theta - 2 lambda)), from h(1) = -lambda V_x
    # and dh/deta(1) = -(V_theta/s)(s V_theta - 2 lambda) at V_x = 0 (hand derivation).
    lam = 0.5 * threshold
    slope = lam * s / (v_t * (s * v_t - 2 * lam))
    for v_x in (1e-4, 1e-6):
        eta = solve_eta2(v_x, v_t, lam, 1.0, s)
        np.testing.assert_allclose((1 - eta) / v_x, slope, rtol=1e-3)


def component_values(kind):
    values = state(kind)
    # Hover: node 0's lambda lies below the loading threshold at its outer stations (unloaded, eta2 = 1).
    values["ideal_loading_constant"] = np.array([0.4, 8.0, 12.0]) if kind == "hover" else np.array([5.0, 8.0, 12.0])
    return values


def test_partials(kind):
    prob = check_component_partials(Eta2Comp(num_nodes=NN, num_radial=NR), component_values(kind))
    eta = prob.get_val("eta2")
    assert np.all((eta > 0.5) & (eta <= 1.0))
    if kind == "hover":
        unloaded = component_values(kind)["ideal_loading_constant"][:, None] <= 0.5 * 0.01 * state(kind)["v_theta"]
        assert np.any(eta == 1.0)
        # eta2 = 1 exactly where lambda <= V_theta C_d/(2 C_l) (with C_d/C_l = 0.011/1.1 = 0.01 at node 0).
        np.testing.assert_array_equal(eta[0] == 1.0, unloaded[0])
    # The scaled residual P/(V_theta**2 + V_x**2 + lambda**2)**2 is zero to round-off at the solution.
    values = component_values(kind)
    v_x, lam = values["v_axial"][:, None], values["ideal_loading_constant"][:, None]
    s = (values["cd_star"] / values["cl_star"])[:, None]
    residual = qc.quartic(eta, v_x, values["v_theta"], lam, s) / (values["v_theta"] ** 2 + v_x**2 + lam**2) ** 2
    assert np.max(np.abs(residual)) < 1e-13


def test_unloaded_station_linearization_matches_one_sided_difference():
    # At an unloaded hover station eta2 = 1 for every small change of V_theta, lambda, C_l, C_d (zero partials)
    # and for V_x -> 0+ the root moves as 1 - eta ~ slope V_x: the totals must be finite and equal that.
    values = component_values("hover")
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("eta2", Eta2Comp(num_nodes=NN, num_radial=NR), promotes=["*"])
    prob.setup()
    for name in ("v_axial", "v_theta", "ideal_loading_constant", "cl_star", "cd_star"):
        prob.set_val(name, values[name])
    prob.run_model()
    unloaded = prob.get_val("eta2")[0] == 1.0
    wrt = ["v_axial", "v_theta", "ideal_loading_constant", "cl_star", "cd_star"]
    totals = prob.compute_totals(of=["eta2"], wrt=wrt)
    for name in wrt:
        assert np.all(np.isfinite(totals["eta2", name]))
    d_vx = totals["eta2", "v_axial"][:NR, 0]
    args = (values["v_theta"][0], values["ideal_loading_constant"][0], values["cl_star"][0], values["cd_star"][0])

    def one_sided(step):
        return (solve_eta2(step, *args) - solve_eta2(0.0, *args)) / step

    # Hand derivation: at V_x = 0, eta = 1, h = 0 with dh/dV_x = -lambda, dh/deta = -(V_theta/s)(s V_theta - 2 lambda).
    lam, s = values["ideal_loading_constant"][0], values["cd_star"][0] / values["cl_star"][0]
    v_t = values["v_theta"][0]
    np.testing.assert_allclose(d_vx[unloaded], (-lam * s / (v_t * (s * v_t - 2 * lam)))[unloaded], rtol=1e-12)
    # Richardson-extrapolated one-sided differences (V_x >= 0); stations 3 and 4 sit within 11 % of the loading
    # threshold, where eta2(V_x) bends sharply, hence the loose tolerance of this secondary check.
    step = 1e-5
    np.testing.assert_allclose(d_vx, 2 * one_sided(step / 2) - one_sided(step), rtol=1e-4)
    assert np.all(d_vx[unloaded] < 0)
    np.testing.assert_array_equal(totals["eta2", "ideal_loading_constant"][:NR, 0][unloaded], 0.0)
    np.testing.assert_array_equal(totals["eta2", "v_theta"][:NR, :NR][np.ix_(unloaded, unloaded)], 0.0)


def reference_chain(kind):
    """IdealLoadingComp -> Eta2Comp with reference-station values consistent with Eqs. (24), (26) at eta_ref."""
    values = state(kind)
    eta_ref = np.array([0.985, 0.99, 0.975])
    s = values["cd_star"] / values["cl_star"]
    v_x, v_t = values["v_axial"], values["v_theta_ref"]
    b = (v_x - v_t * s) / 2
    u_axial = b + np.sqrt(b**2 + eta_ref * v_t**2 * (1 - eta_ref + v_x / v_t * s))  # Eq. (26)
    u_t = 2 * v_t * (1 - eta_ref)  # Eq. (24)
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("ideal_loading", IdealLoadingComp(num_nodes=NN), promotes=["*"])
    prob.model.add_subsystem("eta2", Eta2Comp(num_nodes=NN, num_radial=NR), promotes=["*"])
    prob.setup(force_alloc_complex=True)
    v_theta = values["v_theta"].copy()
    v_theta[:, 2] = v_t  # station 2 is the reference station
    for name, value in dict(u_axial_ref=u_axial, u_theta_ref=u_t, v_axial=v_x, v_theta_ref=v_t, v_theta=v_theta,
                            cl_star=values["cl_star"], cd_star=values["cd_star"]).items():
        prob.set_val(name, value)
    prob.run_model()
    return prob, eta_ref


def test_reference_station_round_trip(kind):
    # Alg. 1: lambda from the reference station (Eq. (22)), then the quartic at the reference station must give
    # back the reference station's own eta2 (physical invariant of the method).
    prob, eta_ref = reference_chain(kind)
    np.testing.assert_allclose(prob.get_val("eta2")[:, 2], eta_ref, rtol=1e-13)


def test_totals_through_ideal_loading_and_eta2(kind):
    # Complex-step totals exercise the complex Newton update in Eta2Comp.solve_nonlinear.
    prob, _ = reference_chain(kind)
    wrt = ["u_axial_ref", "u_theta_ref", "v_axial", "v_theta_ref", "v_theta", "cl_star", "cd_star"]
    data = prob.check_totals(of=["eta2"], wrt=wrt, method="cs", out_stream=None)
    assert_totals_match(data, atol=1e-9, rtol=1e-9)
    assert_no_approx_partials(prob.model)


def test_invalid_inputs_raise_analysis_error_naming_node_and_station():
    values = component_values("cruise")
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("eta2", Eta2Comp(num_nodes=NN, num_radial=NR), promotes=["*"])
    prob.setup()
    for name in ("v_axial", "v_theta", "ideal_loading_constant", "cl_star", "cd_star"):
        prob.set_val(name, values[name])
    v_theta = values["v_theta"].copy()
    v_theta[1, 4] = -3.0
    prob.set_val("v_theta", v_theta)
    with pytest.raises(om.AnalysisError, match=r"v_theta = -3\.0 at node 1, station 4"):
        prob.run_model()
    prob.set_val("v_theta", values["v_theta"])
    prob.set_val("ideal_loading_constant", [5.0, 0.0, 12.0])
    with pytest.raises(om.AnalysisError, match=r"lambda = 0\.0 at node 1, station 0"):
        prob.run_model()


def test_solve_eta2_broadcasts_and_validates():
    eta = solve_eta2(np.array([[0.0], [30.0]]), np.array([50.0, 100.0, 150.0]), 10.0, 1.0, 0.01)
    assert eta.shape == (2, 3)
    assert np.all((eta > 0.5) & (eta < 1.0))
    with pytest.raises(ValueError, match=r"v_axial = -1\.0 at index \(0,\)"):
        solve_eta2(np.array([-1.0, 2.0]), 50.0, 10.0, 1.0, 0.01)
    with pytest.raises(ValueError, match="cd_star"):
        solve_eta2(10.0, 50.0, 10.0, 1.0, 0.0)


def test_taylor_coefficients_expand_the_quartic_about_eta_one():
    # P(1 - t) = lam**4 sum_k q_k t**k (Eq. (27) expanded about eta = 1; the solve's polynomial), checked against
    # the product form of bild_mdo.bild.variants.paper.quartic at t in [0, 1/2] to round-off of P's terms; q0 is P(1) of the
    # closed form (h(1) = -lam V_x, quartic module docstring), zero in hover.
    from bild_mdo.bild.variants.paper.eta2 import _taylor_coefficients

    v_x, v_t, lam, s = random_domain(20_000, seed=15)
    q = _taylor_coefficients(v_x, v_t, lam, s)
    for t in (0.0, 0.05, 0.2, 0.37, 0.5):
        value = lam**4 * sum(coefficient * t**k for k, coefficient in enumerate(q))
        n_term, m_term, b, c = qc.physical_factor_terms(1.0 - t, v_x, v_t, lam, s)
        terms = n_term**2 + np.abs(2 * b * n_term * m_term) + np.abs(c) * m_term**2 + (v_t**2 + v_x**2 + lam**2)**2
        assert np.max(np.abs(value - qc.quartic(1.0 - t, v_x, v_t, lam, s)) / terms) < 1e-12
    p1 = -lam * v_x * (v_x + 2 * s * v_t) * (lam + v_x + s * v_t)
    np.testing.assert_allclose(lam**4 * q[0], p1, rtol=1e-12, atol=0.0)
    assert np.all(q[0][v_x == 0.0] == 0.0)


def test_safeguarded_fallback_finds_the_same_root():
    # Every element solved by the fast path (explicit start, Newton, product-form step) and again by the bracketed
    # fallback alone (_solve_tail from eta = 1/2): the two roots of the same function agree to round-off.
    from bild_mdo.bild.variants.paper.eta2 import _solve, _solve_tail

    v_x, v_t, lam, s = random_domain(20_000, seed=16)
    eta, done = _solve(v_x, v_t, lam, s, v_x.shape)
    again, converged = _solve_tail(np.full(v_x.size, 0.75), np.zeros(v_x.size, dtype=bool), v_x, v_t, lam, s,
                                   v_x.shape)
    assert np.all(done) and np.all(converged)
    np.testing.assert_allclose(eta, again, rtol=0.0, atol=8 * np.finfo(float).eps)
