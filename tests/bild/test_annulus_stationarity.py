"""The exact ideal loading's per-annulus condition: Prandtl jets, the residual, its partials and its root."""
import numpy as np
import pytest

from bild_mdo.bem.prandtl import LOSS_MODELS, prandtl_loss, prandtl_loss_jet
from bild_mdo.bild import annulus_stationarity as stat

H = 1e-30
NUM_BLADES = 3


def _stations(seed=1, n=40, hover_share=0.3):
    rng = np.random.default_rng(seed)
    v_x = np.where(rng.uniform(size=n) < hover_share, 0.0, rng.uniform(1.0, 30.0, n))
    r = rng.uniform(0.35, 1.45, n)
    s = rng.uniform(0.01, 0.03, n)
    v_t = 84.0 * r
    lo = np.where(v_x == 0.0, 1e-3, stat.unloaded_angle(v_x, v_t))
    phi = lo + rng.uniform(0.1, 0.5, n) * (stat.overloaded_angle(v_x, v_t, s) - lo)
    return dict(phi=phi, lam=rng.uniform(5.0, 20.0, n), v_axial=v_x, v_theta=v_t, drag_to_lift=s, r=r,
                radius=np.full(n, 1.5), hub_radius=np.full(n, 0.3))


def _args(p, loss_model="tip_hub"):
    return (p["v_axial"], p["v_theta"], p["drag_to_lift"], p["r"], p["radius"], p["hub_radius"], NUM_BLADES,
            loss_model)


@pytest.mark.parametrize("loss_model", LOSS_MODELS)
def test_prandtl_jet_matches_prandtl_loss_and_complex_step(loss_model):
    p = _stations()
    phi, r, radius, hub = p["phi"], p["r"], p["radius"], p["hub_radius"]
    jet = prandtl_loss_jet(phi, r, radius, hub, NUM_BLADES, loss_model)
    loss = prandtl_loss(phi, r, radius, hub, NUM_BLADES, loss_model)
    np.testing.assert_array_equal(jet.F, loss.F)  # the same F as the BEM analysis, bit for bit
    np.testing.assert_allclose(jet.dF_dphi, loss.dF_dphi, rtol=1e-13, atol=1e-15)
    perturbed = prandtl_loss_jet(phi + 1j * H, r, radius, hub, NUM_BLADES, loss_model)
    np.testing.assert_allclose(jet.d2F_dphi2, perturbed.dF_dphi.imag / H, rtol=1e-12, atol=1e-13)
    for name, args in (("r", (phi, r + 1j * H, radius, hub)), ("radius", (phi, r, radius + 1j * H, hub)),
                       ("hub_radius", (phi, r, radius, hub + 1j * H))):
        perturbed = prandtl_loss_jet(*args, NUM_BLADES, loss_model)
        np.testing.assert_allclose(getattr(jet, f"dF_d{name}"), perturbed.F.imag / H, rtol=1e-12, atol=1e-13)
        np.testing.assert_allclose(getattr(jet, f"d2F_dphi_d{name}"), perturbed.dF_dphi.imag / H, rtol=1e-12,
                                   atol=1e-12)
        np.testing.assert_allclose(getattr(jet, f"dF_d{name}"), getattr(loss, f"dF_d{name}"), rtol=1e-12,
                                   atol=1e-13)


def _direct_loads(phi, p, loss_model="tip_hub"):
    """F t and F e from the BEM curve written as w = (V_x + k V_theta)/(tan phi + k), k = C_x/C_theta.

    The prototype's form (``/tmp/h7/proto.py``), independent of :func:`annulus`; with
    ``u_theta = 2 (V_theta - w)``: dT/dr = 4 pi rho r F u_a (u_a - V_x), dQ/dr = 2 pi rho r**2 F u_a u_theta.
    """
    v_x, v_t, s = p["v_axial"], p["v_theta"], p["drag_to_lift"]
    k = (np.cos(phi) - s * np.sin(phi)) / (np.sin(phi) + s * np.cos(phi))
    w = (v_x + k * v_t) / (np.tan(phi) + k)
    u_a = w * np.tan(phi)
    f = prandtl_loss_jet(phi, p["r"], p["radius"], p["hub_radius"], NUM_BLADES, loss_model).F
    thrust = f * u_a * (u_a - v_x)
    torque = f * u_a * 2.0 * (v_t - w) / 2.0
    return thrust, v_t * torque - v_x * thrust, torque


@pytest.mark.parametrize("loss_model", LOSS_MODELS)
def test_terms_and_partials_against_complex_step(loss_model):
    p = _stations()
    terms = stat.stationarity(p["phi"], *_args(p, loss_model))
    thrust, energy, _ = _direct_loads(p["phi"] + 1j * H, p, loss_model)
    np.testing.assert_allclose(terms.N, energy.imag / H, rtol=1e-12)
    np.testing.assert_allclose(terms.D, thrust.imag / H, rtol=1e-12)
    perturbed = stat.stationarity(p["phi"] + 1j * H, *_args(p, loss_model))
    np.testing.assert_allclose(terms.N1, perturbed.N.imag / H, rtol=1e-11, atol=1e-9)
    np.testing.assert_allclose(terms.D1, perturbed.D.imag / H, rtol=1e-11, atol=1e-9)
    _, d_res, d_eta = stat.residual_partials(p["phi"], p["lam"], *_args(p, loss_model))
    for name in ("phi", "lam", "v_axial", "v_theta", "drag_to_lift", "r", "radius", "hub_radius"):
        q = dict(p, **{name: p[name] + 1j * H})
        t = stat.stationarity(q["phi"], *_args(q, loss_model))
        np.testing.assert_allclose(d_res[name], (t.N - q["lam"] * t.D).imag / H, rtol=1e-11, atol=1e-9,
                                   err_msg=name)
        if name in d_eta:
            np.testing.assert_allclose(d_eta[name], (t.ring.w / q["v_theta"]).imag / H, rtol=1e-11, atol=1e-14,
                                       err_msg=name)


def test_root_makes_marginal_energy_per_thrust_equal_lambda():
    # Hand derivation (module docstring): at the root dE_r/dT_r along the station's BEM curve equals lambda,
    # i.e. V_theta (F q)' - (lambda + V_x) (F t)' = 0; checked with the independent prototype form of the curve.
    p = _stations(seed=3, hover_share=0.5)
    phi, status = stat.solve_stationarity(p["lam"], *_args(p))
    assert np.all(status == 0)
    thrust, energy, torque = _direct_loads(phi + 1j * H, p)
    np.testing.assert_allclose(energy.imag / thrust.imag, p["lam"], rtol=1e-10)
    balance = p["v_theta"] * torque.imag - (p["lam"] + p["v_axial"]) * thrust.imag
    assert np.max(np.abs(balance) / (p["v_theta"] * np.abs(torque.imag))) < 1e-10
    # The root lies on the loaded branch: positive thrust, below the annulus' maximum thrust, eta2 in (1/2, 1).
    terms = stat.stationarity(phi, *_args(p))
    assert np.all(terms.ring.t > 0.0) and np.all(terms.D > 0.0)
    eta2 = terms.ring.w / p["v_theta"]
    assert np.all((eta2 > 0.5) & (eta2 < 1.0))


def test_lambda_from_a_station_is_recovered_at_that_station():
    # lambda = G(phi) at a point; solving the station with that lambda returns the same phi (G is monotone).
    p = _stations(seed=4)
    terms = stat.stationarity(p["phi"], *_args(p))
    lam = terms.N / terms.D
    phi, status = stat.solve_stationarity(lam, *_args(p))
    assert np.all(status == 0)
    np.testing.assert_allclose(phi, p["phi"], rtol=1e-11, atol=1e-13)


def test_hover_zero_load_cost_is_blade_speed_times_drag_to_lift():
    # Hand derivation: near phi = 0 in hover u_axial ~ V_theta phi, t' ~ 2 V_theta**2 phi and
    # (V_theta q)' ~ 2 s V_theta**3 phi (F = 1 to round-off there), so G(0+) = V_theta C_d/C_l.
    p = _stations(seed=6, n=6, hover_share=1.0)
    # G is linear in phi near 0 (plus O(phi**2)): extrapolate from phi = 1e-5 and 2e-5 to 0.
    g1, g2 = (stat.stationarity(np.full(6, phi), *_args(p)) for phi in (1e-5, 2e-5))
    np.testing.assert_allclose(2.0 * g1.N / g1.D - g2.N / g2.D, p["v_theta"] * p["drag_to_lift"], rtol=1e-7)


def test_status_of_unloadable_stations_and_a_huge_lambda():
    p = _stations(seed=5, n=4, hover_share=0.0)
    p["v_axial"] = np.array([0.0, 20.0, 0.0, 20.0])
    # lambda below the zero-load cost G(phi0) (V_theta C_d/C_l in hover): unloaded, at phi0.
    # A huge lambda is reached just below the annulus' maximum thrust, where G = (F e)'/(F t)' has its pole.
    lam = np.array([1e-3, 1e-3, 1e4, 1e4])
    phi, status = stat.solve_stationarity(lam, *_args(p))
    np.testing.assert_array_equal(status, [1, 1, 0, 0])
    assert phi[0] == 0.0
    assert phi[1] == stat.unloaded_angle(p["v_axial"][1], p["v_theta"][1])
    terms = stat.stationarity(phi[2:], *(a[2:] if np.ndim(a) else a for a in _args(p)))
    assert np.all(terms.D > 0.0)
    np.testing.assert_allclose(terms.N / terms.D, lam[2:], rtol=1e-10)


def test_inputs_outside_the_domain_are_reported_not_guessed():
    p = _stations(seed=7, n=4, hover_share=0.0)
    lam = np.array([10.0, -1.0, np.nan, 10.0])
    p["v_axial"] = np.array([-1.0, 10.0, 10.0, 10.0])
    _, status = stat.solve_stationarity(lam, *_args(p))
    np.testing.assert_array_equal(status, [4, 4, 4, 0])
