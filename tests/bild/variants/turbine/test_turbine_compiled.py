"""The compiled turbine solve against its whole-array definition (bild_mdo.bild.variants.turbine.compiled).

The compiled residual is the whole-array ``_bracketed`` written for one station, and its solver is the
whole-array bracketed Newton solver step for step: the roots must agree to round-off (a hand-checkable
invariant: both solve the same equation to the same tolerance), including where the compiled solve
begins at a prediction from the stations inward.
"""
import math

import numpy as np
import pytest

from bild_mdo.bem.prandtl import EXPONENT_MAX, EXPONENT_MIN
from bild_mdo.bild.variants.turbine import kernel
from bild_mdo.bild.variants.turbine.compiled import turbine_value
from bild_mdo.utils.newton import bracketed_newton

B = 3


def _stations(loss_model, mu):
    """Three designs of 12 stations (hub 5 % R), flat, as the inflow component passes them."""
    radius = np.repeat([40.0, 63.0, 20.0], 12)
    r = radius * np.tile(0.05 + 0.95 * (np.arange(12) + 0.5) / 12, 3)
    v_axial = np.repeat([10.0, 11.4, 6.0], 12)
    v_theta = np.repeat([7.0, 9.0, 4.0], 12) * v_axial * r / radius
    ratio = np.repeat([0.01, 0.006, 0.03], 12)
    hub = 0.05 * radius
    return (np.full(r.size, mu), v_axial, v_theta, ratio, r, radius, hub, B, loss_model)


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip", "none"])
def test_compiled_residual_is_the_whole_array_one(loss_model):
    # At 40 angles from below a = 1/2 (the solve's bracket end) to the unloaded angle, so that the barrier past
    # the maximum of the annulus thrust is met too.
    args = _stations(loss_model, 0.5)
    lo = kernel.half_induction_angle(args[1], args[2], args[3])
    hi = kernel.unloaded_angle(args[1], args[2])
    fractions = np.linspace(-0.9, 1.0, 40)[:, None]
    rest = tuple(np.broadcast_to(a, (40, a.size)).ravel() if np.ndim(a) else a for a in args[1:])
    mu = np.broadcast_to(args[0], (40, args[0].size)).ravel()
    phi = (lo + fractions * (hi - lo)).ravel()
    value, slope, scale = kernel._bracketed(phi, mu, rest)
    assert np.any(value == kernel.BARRIER)
    codes = {"none": 0, "tip": 1, "tip_hub": 2}[loss_model]
    for i in range(phi.size):
        v, x, s, r, radius, hub = (a[i] for a in rest[:6])
        k_hub = 0.5 * B * (r - hub) / hub if codes == 2 else 1.0
        params = (v, x, s, 0.5 * B * (radius - r) / r, k_hub, float(codes), mu[i], kernel.BARRIER)
        one = turbine_value(phi[i], np.zeros(1), params)
        np.testing.assert_allclose(one, (value[i], slope[i], scale[i]), rtol=1e-12, atol=1e-12 * scale[i])


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip", "none"])
@pytest.mark.parametrize("mu", [0.0, 1.5])
def test_compiled_roots_are_the_whole_array_roots(loss_model, mu):
    args = _stations(loss_model, mu)
    phi, status = kernel.solve_loading(*args)
    hi = kernel.unloaded_angle(args[1], args[2])
    lo = kernel.half_induction_angle(args[1], args[2], args[3])
    f_hi = kernel._bracketed(hi, args[0], args[1:])[0]
    loaded = f_hi > 0.0
    np.testing.assert_array_equal(status, np.where(loaded, kernel.LOADED, kernel.UNLOADED))
    assert loaded.sum() >= 30
    at = np.flatnonzero(loaded)
    reference = bracketed_newton(lambda x, idx: kernel._bracketed(x, args[0][at[idx]],
                                                                  tuple(a[at[idx]] if np.ndim(a) else a
                                                                        for a in args[1:])),
                                 lo[at], hi[at], np.full(at.size, -1.0), quadratic_stop=True)
    assert np.all(reference.converged)
    np.testing.assert_allclose(phi[at], reference.x, rtol=0.0, atol=1e-12)
    np.testing.assert_array_equal(phi[~loaded], hi[~loaded])


def _factor_reference(f, cot):
    """Prandtl's factor of exponent ``f`` and its phi derivatives, accurate at every ``f``: ``g = exp(-f)`` and
    ``1 - g**2 = -expm1(-2 f)`` each to round-off (the clips of :mod:`bild_mdo.bem.prandtl`)."""
    fc = min(max(f, EXPONENT_MIN), EXPONENT_MAX)
    g, q = math.exp(-fc), -math.expm1(-2.0 * fc)
    value = 2.0 / math.pi * math.atan2(math.sqrt(q), g)
    if not EXPONENT_MIN < f < EXPONENT_MAX:
        return value, 0.0, 0.0
    a1 = 2.0 / math.pi * g / math.sqrt(q)
    f1 = -f * cot
    return value, a1 * f1, -a1 / q * f1 * f1 + a1 * f * (1.0 + 2.0 * cot * cot)


def test_compiled_prandtl_factor_forms():
    # The three forms of the compiled factor (series in exp(-f), acos, atan2 with expm1) and the clips, across
    # every boundary between them, against the factor evaluated accurately (a hand-checkable closed form).
    from bild_mdo.bild.variants.local_point.prandtl_kernels import _factor, _factor_value

    for f in np.concatenate([np.geomspace(1e-12, 300.0, 400), [0.1, 4.0, 100.0]]):
        for cot in (0.3, 2.0, 9.0):
            expected = _factor_reference(f, cot)
            # (d2F/dphi2 is a difference of two terms: its tolerance is on their size.)
            np.testing.assert_allclose(_factor(f, cot), expected, rtol=1e-13,
                                       atol=1e-14 * np.max(np.abs(expected[1:]), initial=1e-300))
        np.testing.assert_allclose(_factor_value(f), expected[0], rtol=2e-15)


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip", "none"])
def test_design_solve_is_the_station_solve(loss_model):
    # The solve design by design (the inflow component's) against the flat one, with unloaded stations (where
    # mu >= G(phi0) = x (V - s x) / (x + s V), close to V: the inner ones of the third design) and a failed
    # design (no wind).
    _, v_axial, v_theta, ratio, r, radius, hub = _stations(loss_model, 0.0)[:7]
    mu = np.repeat([0.0, 0.0, 5.7], 12)
    v_axial = np.where(np.repeat([1.0, 0.0, 1.0], 12) > 0.0, v_axial, 0.0)
    flat = kernel.solve_loading(mu, v_axial, v_theta, ratio, r, radius, hub, B, loss_model)
    node = [a.reshape(3, 12)[:, 0] for a in (mu, v_axial, ratio, radius, hub)]
    phi, status = kernel.solve_designs(*node, v_theta.reshape(3, 12), r.reshape(3, 12), B, loss_model)
    np.testing.assert_array_equal(status.ravel(), flat[1])
    assert {kernel.LOADED, kernel.UNLOADED, kernel.FAILED} <= set(status.ravel())
    np.testing.assert_allclose(phi.ravel(), flat[0], rtol=0.0, atol=1e-12)


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip", "none"])
def test_compiled_loads_and_chords_are_the_jets(loss_model):
    args = _stations(loss_model, 0.3)
    phi, status = kernel.solve_loading(*args)
    assert np.all(status == kernel.LOADED)
    shape = (3, 12)
    node = [a.reshape(shape)[:, 0] for a in (args[1], args[3], args[5], args[6])]
    rho = np.array([1.225, 1.1, 1.0])
    out = {name: np.zeros(shape) for name in kernel.LOAD_NAMES}
    kernel.station_loads(phi.reshape(shape), args[2].reshape(shape), args[4].reshape(shape), node[0], node[1],
                         node[2], node[3], rho, B, loss_model, out)
    jets = kernel.station_jets(phi, *args[1:])
    four_pi_rho = 4.0 * np.pi * np.repeat(rho, 12)
    expected = {"axial_induction": 1.0 - jets["u"].v / args[1], "tangential_induction": jets["w"].v / args[2] - 1.0,
                "u_axial": jets["u"].v, "inflow_speed": jets["W"].v, "loss_factor": jets["F"].v,
                "dthrust_dr": four_pi_rho * args[4] * jets["F"].v * jets["t"].v,
                "dtorque_dr": four_pi_rho * args[4] ** 2 * jets["F"].v * jets["q"].v}
    for name, value in expected.items():
        np.testing.assert_allclose(out[name].ravel(), value, rtol=1e-13, atol=1e-13 * np.max(np.abs(value)))
    cl = np.array([1.1, 0.9, 1.3])
    chord = kernel.reference_chord(phi.reshape(shape)[:, 4], node[0], args[2].reshape(shape)[:, 4], node[1],
                                   args[4].reshape(shape)[:, 4], node[2], node[3], cl, B, loss_model)
    expected = kernel.chord_jet(jets, args[4], B, np.repeat(cl, 12)).v.reshape(shape)[:, 4]
    np.testing.assert_allclose(chord, expected, rtol=1e-13)


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip"])
def test_compiled_reference_chord_solve_is_the_whole_array_one(loss_model):
    # The reference station's chord solve (bracketed Newton from the midpoint of [phi_half, phi0]) against the
    # whole-array solver on the jets' chord and slope; then the multiplier G there from the whole-array terms.
    args = [a.reshape(3, 12)[:, 8] for a in _stations(loss_model, 0.0)[1:7]]
    cl = np.array([1.1, 0.9, 1.3])
    lo, hi = kernel.half_induction_angle(*args[:3]), kernel.unloaded_angle(*args[:2])

    def chord(x, idx):
        jets = kernel.station_jets(x, *[a[idx] for a in args], B, loss_model)
        return kernel.chord_jet(jets, args[3][idx], B, cl[idx])

    c_ref = 0.6 * chord(lo, np.arange(3)).v
    phi, mu, c_lo, status = kernel.solve_reference_chord(*args, cl, c_ref, B, loss_model)
    np.testing.assert_array_equal(status, 0)
    np.testing.assert_allclose(c_lo, c_ref / 0.6, rtol=1e-13)
    reference = bracketed_newton(lambda x, idx: (chord(x, idx).v - c_ref[idx], chord(x, idx).partial("phi")),
                                 lo, hi, np.ones(3), quadratic_stop=True)
    np.testing.assert_allclose(phi, reference.x, rtol=0.0, atol=1e-13)
    terms = kernel.turbine_terms(reference.x, *args, B, loss_model)
    np.testing.assert_allclose(mu, terms.power_slope / terms.thrust_slope, rtol=1e-12)
    bad = kernel.solve_reference_chord(*args, cl, np.array([-1.0, c_ref[1], 2.0 * c_lo[2]]), B, loss_model)[3]
    np.testing.assert_array_equal(bad, [1, 0, 1])
