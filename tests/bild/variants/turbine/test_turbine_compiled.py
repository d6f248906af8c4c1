"""The compiled turbine solve against its whole-array definition (bild_mdo.bild.variants.turbine.compiled).

The compiled residual is the whole-array ``_bracketed`` written for one station, and its solver is the
whole-array bracketed Newton solver step for step: the roots must agree to round-off (a hand-checkable
invariant: both solve the same equation to the same tolerance), including where the compiled solve
begins at a prediction from the stations inward.
"""
import numpy as np
import pytest

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
