"""Several airfoils along the span: the C^2 blend in r/R, per-station evaluation and max-L/D points."""
import numpy as np
import pytest

from bild_mdo.airfoil import AnalyticPolar, CompressiblePolar, SpanwisePolar, StationMaxLiftToDrag, spanwise_polar
from bild_mdo.airfoil.spanwise import smooth_step

H = 1e-30
ROOT = AnalyticPolar(cl0=0.3, cd0=0.011, k=0.012, reynolds_exponent=0.2)   # a thicker root section
TIP = AnalyticPolar(reynolds_exponent=0.2)
FRACTIONS = (0.3, 0.8)


@pytest.fixture
def polar():
    return SpanwisePolar([ROOT, TIP], FRACTIONS)


def test_smooth_step_by_hand():
    # s(t) = 10 t^3 - 15 t^4 + 6 t^5: s(0) = 0, s(1) = 1, s(1/2) = 1/2; s'(t) = 30 t^2 (1 - t)^2
    # vanishes at both ends (so the blend is flat at every station) and is 15/8 at t = 1/2.
    s, ds = smooth_step(np.array([0.0, 0.5, 1.0, -0.3, 1.7]))
    np.testing.assert_allclose(s, [0.0, 0.5, 1.0, 0.0, 1.0], atol=1e-15)
    np.testing.assert_allclose(ds, [0.0, 1.875, 0.0, 0.0, 0.0], atol=1e-15)


def test_at_each_station_the_polar_is_that_airfoil(polar):
    alpha = np.radians(np.linspace(-30, 40, 71))
    for x, member in zip(FRACTIONS, (ROOT, TIP)):
        v = polar.evaluate(alpha, 7e5, radial_fraction=x)
        for got, want in zip(v[:6], member.evaluate(alpha, 7e5)):
            np.testing.assert_array_equal(got, want)
        np.testing.assert_array_equal(v.dcl_dradial_fraction, 0.0)
    # Inboard of the first and outboard of the last station: those airfoils.
    np.testing.assert_array_equal(polar.evaluate(alpha, 7e5, radial_fraction=0.1).cl, ROOT.evaluate(alpha, 7e5).cl)
    np.testing.assert_array_equal(polar.evaluate(alpha, 7e5, radial_fraction=1.0).cd, TIP.evaluate(alpha, 7e5).cd)


def test_radial_derivatives_by_complex_step(polar):
    rng = np.random.default_rng(11)
    alpha = rng.uniform(-0.2, 0.3, 20)
    reynolds = rng.uniform(1e5, 2e6, 20)
    x = rng.uniform(0.0, 1.0, 20)
    v = polar.evaluate(alpha, reynolds, radial_fraction=x)
    s = polar.second_derivatives(alpha, reynolds, radial_fraction=x)
    # The blend (1 - s) c_root + s c_tip is complex-step safe in x through its weights.
    _, w, dw = polar.weights(x)
    _, w_c, _ = polar.weights(x + 1j * H)
    np.testing.assert_allclose(np.imag(w_c) / H, dw, rtol=1e-12, atol=1e-15)
    root, tip = ROOT.evaluate(alpha, reynolds), TIP.evaluate(alpha, reynolds)
    for field, d1, d2 in (("cl", "dcl_dradial_fraction", "d2cl_dalpha_dradial_fraction"),
                          ("cd", "dcd_dradial_fraction", "d2cd_dalpha_dradial_fraction")):
        blend = (1 - w_c) * getattr(root, field) + w_c * getattr(tip, field)
        np.testing.assert_allclose(np.imag(blend) / H, getattr(v, d1), rtol=1e-12, atol=1e-15)
        slope = "dcl_dalpha" if field == "cl" else "dcd_dalpha"
        blend_a = (1 - w_c) * getattr(root, slope) + w_c * getattr(tip, slope)
        np.testing.assert_allclose(np.imag(blend_a) / H, getattr(s, d2), rtol=1e-12, atol=1e-15)


def test_second_reynolds_derivatives_by_complex_step(polar):
    # c = (1 - s) c_root + s c_tip: d2c/dRe2 is the same blend of the airfoils' (AnalyticPolar._all is
    # complex-step safe, so the complex step of the blended dc/dRe checks it).
    rng = np.random.default_rng(12)
    alpha = rng.uniform(-0.2, 0.3, 20)
    reynolds = rng.uniform(1e5, 2e6, 20)
    x = rng.uniform(0.0, 1.0, 20)
    s = polar.second_derivatives(alpha, reynolds, radial_fraction=x)
    _, w, _ = polar.weights(x)
    root, tip = (p._all(alpha + 0j, reynolds + 1j * H)[0] for p in (ROOT, TIP))
    for k, field in ((3, "d2cl_dre2"), (5, "d2cd_dre2")):
        blend = (1 - w) * root[k] + w * tip[k]
        np.testing.assert_allclose(np.imag(blend) / H, getattr(s, field), rtol=1e-12, atol=1e-30)
    assert np.max(np.abs(s.d2cd_dre2 * reynolds**2)) > 1e-4


def test_values_and_radial_slope_are_continuous_at_the_stations(polar):
    for x in FRACTIONS:
        left = polar.evaluate(0.08, 5e5, radial_fraction=x - 1e-9)
        right = polar.evaluate(0.08, 5e5, radial_fraction=x + 1e-9)
        assert left.cl == pytest.approx(right.cl, abs=1e-12)
        assert abs(left.dcl_dradial_fraction) < 1e-12 and abs(right.dcl_dradial_fraction) < 1e-12


def test_station_max_lift_to_drag(polar):
    # BILD's per-station point: Re per design (nn, 1), r/R per station (1, nr) -> (nn, nr).
    reynolds = np.array([[3e5], [1.5e6]])
    x = np.array([[0.1, 0.3, 0.45, 0.6, 0.8, 0.95]])
    point = polar.max_lift_to_drag(reynolds, radial_fraction=x)
    assert isinstance(point, StationMaxLiftToDrag) and point.alpha.shape == (2, 6)
    # At and beyond the stations: the closed form of each airfoil (AnalyticPolar docstring).
    for cols, member in (((0, 1), ROOT), ((4, 5), TIP)):
        alpha, cl, cd = member.max_lift_to_drag_closed_form(reynolds)
        for c in cols:
            np.testing.assert_allclose(point.alpha[:, c:c + 1], alpha, rtol=1e-10)
            np.testing.assert_allclose(point.cl[:, c:c + 1], cl, rtol=1e-10)
            np.testing.assert_allclose(point.cd[:, c:c + 1], cd, rtol=1e-10)
    step = 1e-6
    up = polar.max_lift_to_drag(reynolds, radial_fraction=x + step)
    down = polar.max_lift_to_drag(reynolds, radial_fraction=x - step)
    for name in ("alpha", "cl", "cd"):
        np.testing.assert_allclose(getattr(point, f"d{name}_dradial_fraction"),
                                   (getattr(up, name) - getattr(down, name)) / (2 * step), rtol=1e-5, atol=1e-8)
    np.testing.assert_array_equal(point.dalpha_dmach, 0.0)


def test_mach_dependent_members_pass_their_mach_derivatives_through():
    root = CompressiblePolar(ROOT, "prandtl-glauert")
    tip = CompressiblePolar(TIP, "karman-tsien")
    polar = SpanwisePolar([root, tip], FRACTIONS)
    assert polar.varies_with_mach
    v = polar.evaluate(0.05, 1e6, mach=0.5, radial_fraction=[0.2, 0.9])
    assert v.dcl_dmach[0] == root.evaluate(0.05, 1e6, mach=0.5).dcl_dmach
    assert v.dcl_dmach[1] == tip.evaluate(0.05, 1e6, mach=0.5).dcl_dmach
    point = polar.max_lift_to_drag([1e6, 1e6], mach=[0.3, 0.6], radial_fraction=0.55)
    step = 1e-6
    up = polar.max_lift_to_drag([1e6, 1e6], mach=[0.3 + step, 0.6 + step], radial_fraction=0.55)
    down = polar.max_lift_to_drag([1e6, 1e6], mach=[0.3 - step, 0.6 - step], radial_fraction=0.55)
    np.testing.assert_allclose(point.dcl_dmach, (up.cl - down.cl) / (2 * step), rtol=1e-5)


def test_a_spanwise_polar_needs_the_station(polar):
    with pytest.raises(ValueError, match="varies along the span; pass radial_fraction"):
        polar.evaluate(0.1, 1e6)
    with pytest.raises(ValueError, match="pass radial_fraction"):
        polar.max_lift_to_drag(1e6)
    with pytest.raises(ValueError, match="radial_fraction .* must be finite"):
        polar.evaluate(0.1, 1e6, radial_fraction=np.nan)


def test_uniform_polars_accept_and_ignore_the_station():
    v = TIP.evaluate(0.1, 1e6, radial_fraction=0.4)
    assert v.cl == TIP.evaluate(0.1, 1e6).cl and v.dcl_dradial_fraction == 0.0


@pytest.mark.parametrize("polars, fractions, pattern", [
    ([ROOT, TIP], [0.8, 0.3], "increase strictly"),
    ([ROOT, TIP], [0.3], "one radial fraction per polar"),
    ([ROOT, TIP], [0.3, 1.2], "within"),
])
def test_invalid_stations(polars, fractions, pattern):
    with pytest.raises(ValueError, match=pattern):
        SpanwisePolar(polars, fractions)


def test_spanwise_polar_from_airfoil_arguments():
    polar = spanwise_polar({1.0: TIP, 0.25: "analytic"})
    np.testing.assert_array_equal(polar.radial_fractions, [0.25, 1.0])
    assert polar.polars[1] is TIP
    with pytest.raises(ValueError, match="unknown airfoil 'clark-y'"):
        spanwise_polar([(0.2, "clark-y")])
