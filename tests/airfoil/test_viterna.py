"""Tests of the Viterna-Corrigan extrapolation and the Eq. (33) stall smoothing."""
import numpy as np
import pytest

from bild_mdo.airfoil.sources import PolarData
from bild_mdo.airfoil.viterna import (STALL_BLEND_HALF_WIDTH, cd_max_from_aspect_ratio,
                                      default_alpha_grid, detect_stall, extend_arrays,
                                      extend_polar, hermite_blend, post_stall,
                                      viterna_coefficients)

H = 1e-30
STALL = (np.radians(14.0), 1.45, 0.03)        # a NACA-4412-like stall point
STALL_NEG = (np.radians(-11.0), -0.75, 0.02)


def synthetic_polar(stall_deg=14.0, alpha_deg=None, noise=0.0, seed=0):
    """Linear lift rounding over into stall, quadratic drag: (alpha_deg, cl, cd).

    Lift is 0.4 + 5.5 alpha up to alpha_stall - 0.1 rad, then a parabola with the same
    slope there that peaks at alpha_stall.  Drag is quadratic in lift, plus a rise
    past stall.  Noise is Gaussian, absolute on cl, relative on cd.
    """
    a = np.arange(-10.0, 20.01, 0.5) if alpha_deg is None else np.asarray(alpha_deg, float)
    x = np.radians(a)
    x0 = np.radians(stall_deg) - 0.1
    cl = np.where(x < x0, 0.4 + 5.5 * x, 0.4 + 5.5 * x - 27.5 * (x - x0) ** 2)
    cd = 0.007 + 0.012 * (5.5 * x) ** 2 + np.where(x > x0 + 0.1, 2.0 * (x - x0 - 0.1) ** 2, 0.0)
    rng = np.random.default_rng(seed)
    return a, cl + noise * rng.standard_normal(a.size), cd * (1 + noise * rng.standard_normal(a.size))


def test_cd_max_from_aspect_ratio():
    # Viterna & Corrigan (1982): cd_max = 1.11 + 0.018 AR, AR capped at 50.
    assert cd_max_from_aspect_ratio(10.0) == pytest.approx(1.29)
    assert cd_max_from_aspect_ratio(80.0) == pytest.approx(2.01)
    with pytest.raises(ValueError):
        cd_max_from_aspect_ratio(0.0)


@pytest.mark.parametrize("stall", [STALL, STALL_NEG])
def test_post_stall_passes_through_the_stall_point(stall):
    # Definition of A, B (Viterna & Corrigan): the extrapolation matches the stall point.
    a_s, cl_s, cd_s = stall
    cl, cd = post_stall(np.array([a_s]), a_s, cl_s, cd_s, cd_max=1.8, cd_reverse=0.04)
    assert cl.value[0] == pytest.approx(cl_s, rel=1e-13)
    assert cd.value[0] == pytest.approx(cd_s, rel=1e-13)
    a_coef, b_coef = viterna_coefficients(a_s, cl_s, cd_s, 1.8)
    # Hand evaluation of the Viterna formula at 40 deg on the stall side.
    x = np.sign(a_s) * np.radians(40.0)
    cl, cd = post_stall(np.array([x]), a_s, cl_s, cd_s, cd_max=1.8, cd_reverse=0.04)
    assert cl.value[0] == pytest.approx(0.9 * np.sin(2 * x) + a_coef * np.cos(x) ** 2 / np.sin(x))
    assert cd.value[0] == pytest.approx(1.8 * np.sin(x) ** 2 + b_coef * np.cos(x))


@pytest.mark.parametrize("stall", [STALL, STALL_NEG])
def test_post_stall_derivatives_match_complex_step(stall):
    a_s = stall[0]
    x = np.sign(a_s) * np.linspace(np.abs(a_s), np.pi, 97)
    cl, cd = post_stall(x, *stall)
    clc, cdc = post_stall(x + 1j * H, *stall)
    np.testing.assert_allclose(clc.value.imag / H, cl.slope, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(cdc.value.imag / H, cd.slope, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(clc.slope.imag / H, cl.curvature, rtol=1e-11, atol=1e-11)
    np.testing.assert_allclose(cdc.slope.imag / H, cd.curvature, rtol=1e-11, atol=1e-11)


@pytest.mark.parametrize("stall", [STALL, STALL_NEG])
def test_post_stall_is_c2_at_90_deg(stall):
    # The switch from Viterna's cos^2/sin to the continuation cos^2 sin^3 at 90 deg.
    x = np.sign(stall[0]) * 0.5 * np.pi
    d = 1e-9
    left, right = post_stall(np.array([x - d, x + d]), *stall)
    for curve in (left, right):
        np.testing.assert_allclose(curve.value[0], curve.value[1], atol=1e-7)
        np.testing.assert_allclose(curve.slope[0], curve.slope[1], atol=1e-7)
        np.testing.assert_allclose(curve.curvature[0], curve.curvature[1], atol=1e-6)


def test_two_sides_meet_c2_at_180_deg():
    # Different A, B on the two sides, yet equal value, slope, curvature at +-180 deg.
    up = post_stall(np.array([np.pi]), *STALL, cd_max=2.0, cd_reverse=0.07)
    down = post_stall(np.array([-np.pi]), *STALL_NEG, cd_max=2.0, cd_reverse=0.07)
    for a, b in zip(up, down):
        np.testing.assert_allclose(a.value, b.value, atol=1e-12)
        np.testing.assert_allclose(a.slope, b.slope, atol=1e-12)
        np.testing.assert_allclose(a.curvature, b.curvature, atol=1e-12)
    assert up[1].value[0] == pytest.approx(0.07)     # cd_reverse
    assert up[0].slope[0] == pytest.approx(2.0)      # flat-plate lift slope cd_max


def test_hermite_blend_matches_both_ends():
    v, s = hermite_blend(np.array([0.1, 0.3]), 0.1, 0.3, (1.0, 2.0), (-0.5, 3.0))
    np.testing.assert_allclose(v, [1.0, -0.5], atol=1e-15)
    np.testing.assert_allclose(s, [2.0, 3.0], atol=1e-13)


def test_detect_stall():
    a, cl, _ = synthetic_polar(stall_deg=14.0)
    fine = np.radians(np.linspace(a[0], a[-1], 3001))
    x = np.radians(a)
    a_s, a_n = detect_stall(fine, np.interp(fine, x, cl))
    # The synthetic lift curve peaks at 14 deg; its data start at -10 deg (no negative stall).
    assert np.degrees(a_s) == pytest.approx(14.0, abs=0.05)
    assert np.degrees(a_n) == pytest.approx(-10.0, abs=1e-9)
    with pytest.raises(ValueError, match="negative and positive"):
        detect_stall(fine[fine > 0], cl[:1] * np.ones(np.count_nonzero(fine > 0)))


@pytest.mark.parametrize("pre_stall", ["spline", "polynomial"])
def test_extension_is_c1_at_every_blend_point(pre_stall):
    a, cl, cd = synthetic_polar(noise=1e-3)
    e = extend_arrays(a, cl, cd, 3e5, pre_stall=pre_stall)
    eps = STALL_BLEND_HALF_WIDTH
    d = 1e-10
    for x in (e.alpha_stall - eps, e.alpha_stall + eps, e.alpha_stall_negative + eps,
              e.alpha_stall_negative - eps):
        pair = extend_arrays(a, cl, cd, 3e5, alpha_grid=np.array([x - d, x + d]),
                             pre_stall=pre_stall)
        # Eq. (33) joins its pieces with equal value and slope: left and right limits agree.
        for f in (pair.cl, pair.cd, pair.dcl_dalpha, pair.dcd_dalpha):
            assert abs(f[1] - f[0]) < 1e-6
    assert np.degrees(e.alpha_stall) == pytest.approx(14.0, abs=0.5)


def test_extension_covers_the_circle():
    a, cl, cd = synthetic_polar(noise=1e-3)
    e = extend_arrays(a, cl, cd, 3e5, cd_max=1.9, cd_reverse=0.06)
    np.testing.assert_array_equal(e.alpha, default_alpha_grid())
    assert np.all(e.cd > 0.0)
    # Viterna / flat plate at +-90 deg, construction at +-180 deg.
    at = {deg: int(np.argmin(np.abs(e.alpha - np.radians(deg)))) for deg in (90, -90, 180, -180)}
    for deg in (90, -90):
        assert e.cl[at[deg]] == pytest.approx(0.0, abs=1e-12)
        assert e.cd[at[deg]] == pytest.approx(1.9, rel=1e-12)
    for deg in (180, -180):
        assert e.cd[at[deg]] == pytest.approx(0.06, rel=1e-12)
    # Slopes are the derivative of the values (central differences, step 1e-7 rad).
    x, h = e.alpha[1:-1], 1e-7
    plus = extend_arrays(a, cl, cd, 3e5, cd_max=1.9, cd_reverse=0.06, alpha_grid=x + h)
    minus = extend_arrays(a, cl, cd, 3e5, cd_max=1.9, cd_reverse=0.06, alpha_grid=x - h)
    np.testing.assert_allclose((plus.cl - minus.cl) / (2 * h), e.dcl_dalpha[1:-1], atol=1e-5)
    np.testing.assert_allclose((plus.cd - minus.cd) / (2 * h), e.dcd_dalpha[1:-1], atol=1e-5)


def test_polynomial_pre_stall_reproduces_line_and_quartic():
    # Eq. (33), first lines: data that are exactly a line (lift) and a quartic (drag)
    # are reproduced to round-off by the least-squares fits.
    a = np.arange(-8.0, 12.01, 0.5)
    x = np.radians(a)
    cl = 0.3 + 6.0 * x
    cd = 0.008 + 0.01 * x + 0.3 * x**2 - 0.2 * x**3 + 2.0 * x**4
    grid = np.radians(np.linspace(-6.0, 10.0, 33))
    e = extend_arrays(a, cl, cd, 1e6, alpha_grid=grid, pre_stall="polynomial")
    # Lift never falls, so the stall angles are the ends of the data (module docstring).
    assert np.degrees(e.alpha_stall) == pytest.approx(12.0, abs=0.01)
    assert np.degrees(e.alpha_stall_negative) == pytest.approx(-8.0, abs=0.01)
    np.testing.assert_allclose(e.cl, 0.3 + 6.0 * grid, atol=1e-12)
    np.testing.assert_allclose(e.dcl_dalpha, 6.0, atol=1e-10)
    np.testing.assert_allclose(e.cd, 0.008 + 0.01 * grid + 0.3 * grid**2 - 0.2 * grid**3
                               + 2.0 * grid**4, atol=1e-12)


def test_spline_pre_stall_removes_noise():
    # The smoothing spline must get closer to the noise-free curve than the noisy data are.
    a, cl_true, cd_true = synthetic_polar(alpha_deg=np.arange(-10.0, 20.01, 0.25))
    _, cl, cd = synthetic_polar(alpha_deg=np.arange(-10.0, 20.01, 0.25), noise=5e-3, seed=3)
    inner = (a > -7.0) & (a < 10.0)
    e = extend_arrays(a, cl, cd, 1e6, alpha_grid=np.radians(a[inner]))
    noise_cl = np.sqrt(np.mean((cl[inner] - cl_true[inner]) ** 2))
    err_cl = np.sqrt(np.mean((e.cl - cl_true[inner]) ** 2))
    err_cd = np.sqrt(np.mean((e.cd / cd_true[inner] - 1.0) ** 2))
    noise_cd = np.sqrt(np.mean((cd[inner] / cd_true[inner] - 1.0) ** 2))
    assert err_cl < 0.5 * noise_cl
    assert err_cd < 0.5 * noise_cd


def test_extend_polar_takes_polar_data():
    a, cl, cd = synthetic_polar()
    data = PolarData(2e5, 0.0, a, cl, cd, "synthetic")
    e = extend_polar(data)
    assert e.reynolds == 2e5
    np.testing.assert_array_equal(e.cl, extend_arrays(a, cl, cd, 2e5).cl)


@pytest.mark.parametrize("alpha_deg, message", [
    (np.arange(0.0, 20.0, 0.5), "negative"),
    (np.arange(-1.0, 20.0, 0.5), "stall angles"),
])
def test_extension_rejects_data_without_negative_angles(alpha_deg, message):
    a, cl, cd = synthetic_polar(alpha_deg=alpha_deg)
    with pytest.raises(ValueError, match=message):
        extend_arrays(a, cl, cd, 1e6)


def test_extension_rejects_bad_options():
    a, cl, cd = synthetic_polar()
    with pytest.raises(ValueError, match="pre_stall"):
        extend_arrays(a, cl, cd, pre_stall="rmts")
    with pytest.raises(ValueError, match="increasing"):
        extend_arrays(a[::-1], cl, cd)
