"""Tests of AnalyticPolar: derivatives, smoothness, closed-form values, input checks."""
import numpy as np
import pytest

from bild_mdo.airfoil import AnalyticPolar, Polar

H = 1e-30  # complex step


@pytest.fixture
def polar():
    return AnalyticPolar(reynolds_exponent=0.2)


def _sample(n=400, seed=0):
    rng = np.random.default_rng(seed)
    # Wider than [-pi, pi] to cover the wrap-around.
    alpha = rng.uniform(-4.0, 4.0, n)
    reynolds = np.exp(rng.uniform(np.log(1e5), np.log(1e7), n))
    return alpha, reynolds


def test_is_a_polar(polar):
    assert isinstance(polar, Polar)


def test_first_and_second_derivatives_match_complex_step(polar):
    # _all is complex-step safe, so complex step gives the exact derivatives of the
    # implemented formulas to round-off.
    alpha, reynolds = _sample()
    (v, s) = polar._all(alpha, reynolds)
    cl, cd, dcl_da, dcl_dre, dcd_da, dcd_dre = v
    d2cl_da2, d2cl_dadre, d2cd_da2, d2cd_dadre, d2cl_dre2, d2cd_dre2 = s
    va, _ = polar._all(alpha + 1j * H, reynolds)
    vr, _ = polar._all(alpha + 0j, reynolds + 1j * H)
    np.testing.assert_allclose(va[0].imag / H, dcl_da, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(va[1].imag / H, dcd_da, rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(va[2].imag / H, d2cl_da2, rtol=1e-11, atol=1e-11)
    np.testing.assert_allclose(va[4].imag / H, d2cd_da2, rtol=1e-11, atol=1e-12)
    np.testing.assert_allclose(vr[0].imag / H, dcl_dre, atol=1e-25)
    np.testing.assert_allclose(vr[1].imag / H, dcd_dre, rtol=1e-12, atol=1e-25)
    np.testing.assert_allclose(vr[4].imag / H, d2cd_dadre, rtol=1e-11, atol=1e-24)
    # Second Reynolds derivatives (the local section point's G_Re): complex step of d/dRe.
    np.testing.assert_allclose(vr[3].imag / H, d2cl_dre2, atol=1e-30)
    np.testing.assert_allclose(vr[5].imag / H, d2cd_dre2, rtol=1e-11, atol=1e-30)
    assert np.all(d2cl_dadre == 0.0) and np.all(d2cl_dre2 == 0.0)
    # The Re terms are not trivially zero: the derivative test above can fail.
    assert np.max(np.abs(dcd_dre)) > 1e-10
    assert np.max(np.abs(d2cd_dadre)) > 1e-9
    assert np.max(np.abs(d2cd_dre2 * reynolds**2)) > 1e-4


def test_second_reynolds_derivative_is_the_power_law_in_attached_flow(polar):
    # Hand derivation: below the stall blend cd = cd0 (Re/Re_ref)^-n + k (cl - cl_cd_min)^2, so
    # d2cd/dRe2 = n (n + 1) cd0 (Re/Re_ref)^-n / Re^2 (n = 0.2), and lift does not depend on Re.
    alpha = np.radians(np.linspace(-5.0, 8.0, 14))
    reynolds = np.geomspace(1e4, 1e8, 14)
    s = polar.second_derivatives(alpha, reynolds)
    want = 0.2 * 1.2 * 0.008 * (reynolds / 1e6) ** -0.2 / reynolds**2
    np.testing.assert_allclose(s.d2cd_dre2, want, rtol=1e-13)
    np.testing.assert_array_equal(s.d2cl_dre2, 0.0)


def test_public_methods_agree_with_internal(polar):
    alpha, reynolds = _sample(50, seed=1)
    v = polar.evaluate(alpha, reynolds)
    s = polar.second_derivatives(alpha, reynolds)
    (vi, si) = polar._all(alpha, reynolds)
    for a, b in zip(v, vi):
        np.testing.assert_array_equal(a, b)
    for a, b in zip(s, si):
        np.testing.assert_array_equal(a, b)
    assert v.cl.shape == alpha.shape


@pytest.mark.parametrize("where", ["upper_blend_start", "upper_blend_end", "lower_blend_start",
                                   "lower_blend_end", "plus_90", "minus_90", "pi"])
def test_c2_continuity_at_every_joint(polar, where):
    # The joints of the piecewise definition: the ends of the two stall blends, the
    # switch of the Viterna continuation at +-90 deg, and the wrap at +-180 deg.
    dw = polar.stall_half_width
    x = {"upper_blend_start": polar.alpha_stall - dw, "upper_blend_end": polar.alpha_stall + dw,
         "lower_blend_start": polar.alpha_stall_negative + dw,
         "lower_blend_end": polar.alpha_stall_negative - dw,
         "plus_90": 0.5 * np.pi, "minus_90": -0.5 * np.pi, "pi": np.pi}[where]
    delta = 1e-9
    left, right = np.array([x - delta]), np.array([x + delta])
    vl, vr = polar.evaluate(left, 5e5), polar.evaluate(right, 5e5)
    sl, sr = polar.second_derivatives(left, 5e5), polar.second_derivatives(right, 5e5)
    # A jump would show up as an O(1) difference; continuity leaves O(delta * next derivative).
    for a, b in [(vl.cl, vr.cl), (vl.cd, vr.cd), (vl.dcl_dalpha, vr.dcl_dalpha),
                 (vl.dcd_dalpha, vr.dcd_dalpha), (vl.dcd_dre, vr.dcd_dre)]:
        np.testing.assert_allclose(a, b, atol=1e-6)
    for a, b in [(sl.d2cl_dalpha2, sr.d2cl_dalpha2), (sl.d2cd_dalpha2, sr.d2cd_dalpha2)]:
        np.testing.assert_allclose(a, b, atol=1e-4)


def test_flat_plate_and_reverse_flow_values(polar):
    # Viterna/flat plate: cl(+-90) = 0, cd(+-90) = cd_max; construction: cl(180) = 0,
    # cd(180) = cd_reverse, slope of cl at 180 deg = cd_max (flat plate cd_max/2 sin 2a).
    v = polar.evaluate(np.array([0.5 * np.pi, -0.5 * np.pi, np.pi, -np.pi]), 1e6)
    np.testing.assert_allclose(v.cl, 0.0, atol=1e-12)
    np.testing.assert_allclose(v.cd, [polar.cd_max, polar.cd_max, polar.cd_reverse,
                                      polar.cd_reverse], rtol=1e-12)
    np.testing.assert_allclose(v.dcl_dalpha[2:], polar.cd_max, rtol=1e-12)


def test_periodic_in_alpha(polar):
    alpha, reynolds = _sample(50, seed=2)
    a = polar.evaluate(alpha, reynolds)
    b = polar.evaluate(alpha + 2.0 * np.pi, reynolds)
    for x, y in zip(a, b):
        np.testing.assert_allclose(x, y, rtol=1e-10, atol=1e-12)


def test_physical_shape(polar):
    alpha = np.linspace(-np.pi, np.pi, 20001)
    v = polar.evaluate(alpha, 1e6)
    assert np.all(v.cd > 0.0)
    # Attached flow (hand value): cl(0) = cl0, cd(0) = cd0 + k (cl0 - cl_cd_min)^2 at Re_ref.
    v0 = polar.evaluate(0.0, 1e6)
    assert v0.cl == pytest.approx(0.4, abs=1e-14)
    assert v0.cd == pytest.approx(0.008, abs=1e-14)
    # The lift maximum lies inside the upper stall blend (13 +- 3 deg).
    a_max = np.degrees(alpha[np.argmax(v.cl)])
    assert 10.0 < a_max < 16.0
    assert 1.3 < v.cl.max() < 1.8


def test_closed_form_max_lift_to_drag_is_the_scan_maximum(polar):
    # Hand derivation (class docstring): k cl*^2 = k cl_cd_min^2 + cd0 f(Re).
    reynolds = np.array([2e5, 1e6, 5e6])
    alpha_star, cl_star, cd_star = polar.max_lift_to_drag_closed_form(reynolds)
    np.testing.assert_allclose(cl_star, np.sqrt(0.16 + 0.8 * (reynolds / 1e6) ** -0.2), rtol=1e-14)
    for re, a_s, ld in zip(reynolds, alpha_star, cl_star / cd_star):
        alpha = np.linspace(-0.3, 0.4, 70001)
        v = polar.evaluate(alpha, re)
        ratio = v.cl / v.cd
        assert ratio.max() == pytest.approx(ld, rel=1e-9)
        assert alpha[np.argmax(ratio)] == pytest.approx(a_s, abs=2e-5)


def test_reynolds_independent_by_default():
    v = AnalyticPolar().evaluate(np.linspace(-3, 3, 11), 3e5)
    assert np.all(v.dcd_dre == 0.0) and np.all(v.dcl_dre == 0.0)
    np.testing.assert_array_equal(v.cd, AnalyticPolar().evaluate(np.linspace(-3, 3, 11), 3e6).cd)


def test_complex_step_through_evaluate(polar):
    # Polar.evaluate carries complex inputs to first order with the analytic derivatives.
    v = polar.evaluate(np.array([0.1 + 1j * H]), np.array([4e5]))
    assert v.cd.imag[0] / H == pytest.approx(v.dcd_dalpha[0], rel=1e-14)


@pytest.mark.parametrize("kwargs", [
    {"cd0": -0.01}, {"k": 0.0}, {"alpha_stall": np.radians(2.0)},
    {"alpha_stall_negative": np.radians(2.0)}, {"alpha_stall": np.radians(89.0)},
])
def test_invalid_parameters_raise(kwargs):
    with pytest.raises(ValueError):
        AnalyticPolar(**kwargs)


def test_nonpositive_reynolds_raises_with_scaling(polar):
    with pytest.raises(ValueError, match="positive Reynolds"):
        polar.evaluate(0.1, -1.0)
