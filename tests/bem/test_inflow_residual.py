"""BEM residual (Eq. 9 with F) and induced velocities (Eq. 8 with F): partials and consistency."""
import numpy as np
import openmdao.api as om
import pytest
from scipy.optimize import brentq

from bild_mdo.bem.inflow_residual import force_coefficients, induced_velocities, inflow_residual

NAMES = ["phi", "v_axial", "v_theta", "sigma", "cl", "cd", "F"]


def _random_args(n=100, seed=4):
    rng = np.random.default_rng(seed)
    return [rng.uniform(-0.7, 2.8, n), rng.uniform(0.0, 60.0, n), rng.uniform(5.0, 250.0, n),
            rng.uniform(0.01, 0.3, n), rng.uniform(-1.0, 1.6, n), rng.uniform(0.005, 1.2, n),
            rng.uniform(0.2, 1.0, n)]


def test_residual_partials_match_complex_step():
    args = _random_args()
    res = inflow_residual(*args)
    for i, name in enumerate(NAMES):
        perturbed = list(args)
        perturbed[i] = perturbed[i] + 1e-30j
        cs = np.imag(inflow_residual(*perturbed).residual) / 1e-30
        np.testing.assert_allclose(getattr(res, "dR_d" + name), cs, rtol=1e-12, atol=1e-13, err_msg=name)


def test_induced_velocity_partials_match_complex_step():
    args = _random_args(seed=5)
    ind = induced_velocities(*args)
    for i, name in enumerate(NAMES):
        perturbed = list(args)
        perturbed[i] = perturbed[i] + 1e-30j
        c = induced_velocities(*perturbed)
        for field, value in (("du_axial_d", c.u_axial), ("du_theta_d", c.u_theta)):
            np.testing.assert_allclose(getattr(ind, field + name), np.imag(value) / 1e-30,
                                       rtol=1e-11, atol=1e-10, err_msg=field + name)


def test_reduces_to_paper_eq9_without_loss():
    # Eq. (9) with F = 1 and J/pi replaced by the local V_x / V_theta (hand substitution).
    phi, vx, vt, sigma, cl, cd = 0.4, 12.0, 80.0, 0.08, 0.9, 0.02
    s, c = np.sin(phi), np.cos(phi)
    cx, ct = cl * c - cd * s, cl * s + cd * c
    expected = vx / vt * (sigma * ct + 4 * s * c) + (sigma * cx - 4 * s * s)
    assert inflow_residual(phi, vx, vt, sigma, cl, cd, 1.0).residual == pytest.approx(expected, rel=1e-15)


@pytest.mark.parametrize("v_axial", [0.0, 15.0])
def test_root_satisfies_momentum_and_blade_element_balance(v_axial):
    """At R(phi) = 0 the Eq. (8) velocities close the inflow triangle and both momentum balances.

    Physical invariants: tan(phi) = u_axial / (V_theta - u_theta/2); axial momentum
    4 pi rho u_axial (u_axial - V_x) r F = 1/2 rho W^2 B c C_x; angular momentum
    2 pi rho u_axial u_theta r^2 F = 1/2 rho W^2 B c C_theta r.
    """
    B, c, r, rho, F = 3, 0.08, 0.6, 1.2, 0.9
    vt = 120.0
    sigma = B * c / (2 * np.pi * r)
    twist = 0.35

    def coeffs(phi):
        alpha = twist - phi
        return 2 * np.pi * alpha, 0.01 + 0.02 * alpha**2

    phi = brentq(lambda p: inflow_residual(p, v_axial, vt, sigma, *coeffs(p), F).residual, 1e-6, np.pi / 2,
                 xtol=1e-15, rtol=1e-15)
    cl, cd = coeffs(phi)
    ind = induced_velocities(phi, v_axial, vt, sigma, cl, cd, F)
    ux, ut = ind.u_axial, ind.u_theta
    assert np.tan(phi) == pytest.approx(ux / (vt - ut / 2), rel=1e-12)
    w2 = ux**2 + (vt - ut / 2) ** 2
    cx, ctheta = force_coefficients(phi, cl, cd)
    assert 4 * np.pi * rho * ux * (ux - v_axial) * r * F == pytest.approx(0.5 * rho * w2 * B * c * cx, rel=1e-11)
    assert 2 * np.pi * rho * ux * ut * r**2 * F == pytest.approx(0.5 * rho * w2 * B * c * ctheta * r, rel=1e-11)


def test_hover_is_regular():
    # V_x = 0: no division by V_x anywhere (the paper's non-normalised form).
    with np.errstate(all="raise"):
        res = inflow_residual(0.2, 0.0, 100.0, 0.1, 0.8, 0.01, 0.95)
        ind = induced_velocities(0.2, 0.0, 100.0, 0.1, 0.8, 0.01, 0.95)
    assert np.isfinite(res.residual) and np.isfinite(res.dR_dphi)
    assert np.isfinite(ind.u_axial) and ind.u_axial > 0.0


def test_overflow_is_an_analysis_error():
    # V_x / V_theta = 1e302 (rpm ~ 1e-300): the momentum terms exceed the floating-point range.
    with pytest.raises(om.AnalysisError, match="not finite"):
        inflow_residual(0.3, 10.0, 1e-301, 0.1, 1.0, 0.01, 0.9)
