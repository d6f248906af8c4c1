"""BPM's spectral-shape and amplitude functions against the report's curves (NASA RP-1218, 1989).

Data: figures 77 (K_1 against R_c), 78 (A and B at R_c = 9.5e4 and 8.58e5, i.e. the A_min/A_max and
B_min/B_max limits), 80 (St_2 against alpha* at M = 0.093, 0.209), 82 (K_2 - K_1 against alpha* at
M = 0.093 ... 0.209), 85 (G_1), 86 (St'_1 against R_c), 88 (G_2 + G_3 against R_c at alpha* = 0 and
6 deg) and 89 (G_2), digitized by the AcousticAnalogies.jl project (data/bpm/README.md).  Levels (dB)
are asserted within 1 dB wherever the report's curve is not vertical; the exceptions are named below with
their measured errors.
"""
from pathlib import Path

import numpy as np
import pytest

from bild_mdo.acoustics import bpm

DATA = Path(__file__).resolve().parent / "data" / "bpm"


def load(name):
    return np.loadtxt(DATA / f"19890016302-{name}.csv", delimiter=",", ndmin=2).T


def test_k1_figure77():
    """Figure 77, Eq. (47): measured max 0.11 dB."""
    re, k1 = load("figure77")
    assert np.max(np.abs(bpm.amplitude_k1(re) - k1)) < 1.0


@pytest.mark.parametrize("name, measured", [("A_min", 0.85), ("A_max", 0.54), ("B_min", 1.16), ("B_max", 0.42)])
def test_spectral_shapes_figure78(name, measured):
    """Figure 78: the limiting shapes A_min, A_max (Eqs. 35-36) and B_min, B_max (Eqs. 41-42) of a = |log St/St_peak|.

    Within 1 dB everywhere except the last digitized points of B_min beyond St_s/St_2 = 1.7, where the curve
    falls by about 25 dB per 0.1 of the ratio (measured 1.16 dB at 1.78); those are held to 1.2 dB.
    """
    ratio, level = load(f"figure78-{name}")
    func = {"A_min": bpm.shape_a_min, "A_max": bpm.shape_a_max, "B_min": bpm.shape_b_min, "B_max": bpm.shape_b_max}
    err = np.abs(func[name](np.abs(np.log10(ratio))) - level)
    assert np.max(err) < measured + 0.05
    steep = (name == "B_min") & (ratio > 1.7)
    assert np.max(err[~steep]) < 1.0
    assert np.max(err) < 1.2


def test_spectral_shapes_between_limits():
    """Eqs. (38)-(40), (44)-(46): A and B are -20 dB at a = a_0(R_c), b = b_0(R_c) (the definition of A_R, B_R),
    0 dB at the peak, and equal A_min/B_min-based limits outside the Reynolds-number blend."""
    for re, a0, b0 in ((5e4, 0.57, 0.30), (2e6, 1.13, 0.56)):
        np.testing.assert_allclose(bpm.spectral_shape_a(np.array([10 ** a0, 10 ** -a0]), re), -20.0, atol=1e-9)
        np.testing.assert_allclose(bpm.spectral_shape_b(np.array([10 ** b0, 10 ** -b0]), re), -20.0, atol=1e-9)
        np.testing.assert_allclose([bpm.spectral_shape_a(1.0, re), bpm.spectral_shape_b(1.0, re)],
                                   [np.sqrt(67.552) - 8.219, np.sqrt(16.888) - 4.109], atol=1e-12)


@pytest.mark.parametrize("mach", ["0.093", "0.209"])
def test_st2_figure80(mach):
    """Figure 80, Eqs. (31), (33): St_2 against alpha*, measured max 2.1 % (reading error of the plot)."""
    alpha, st2 = load(f"figure80-M{mach}")
    assert np.max(np.abs(bpm.peak_strouhal_2(float(mach), alpha) / st2 - 1.0)) < 0.025


@pytest.mark.parametrize("mach", ["0.093", "0.116", "0.163", "0.209"])
def test_k2_minus_k1_figure82(mach):
    """Figure 82, Eqs. (49)-(50): within 1 dB except on the report's vertical drops at gamma_0 -+ gamma.

    The digitized points that lie on those vertical lines (within 0.4 deg of the edges, where the curve
    changes by 10-1000 dB per degree) are left out; the rest agree to 1 dB (measured max 0.9 dB)."""
    m = float(mach)
    alpha, level = load(f"figure82-M{mach}")
    gamma, gamma0 = 27.094 * m + 3.31, 23.43 * m + 4.651
    away = (np.abs(alpha - (gamma0 - gamma)) > 0.4) & (np.abs(alpha - (gamma0 + gamma)) > 0.4)
    assert np.count_nonzero(away) > 0.8 * alpha.size
    assert np.max(np.abs(bpm.amplitude_k2_minus_k1(m, alpha) - level)[away]) < 1.0


def test_g1_figure85():
    """Figure 85, Eq. (57): measured max 0.83 dB (at the steep flank e = 0.84)."""
    e, g1 = load("figure85-G1")
    assert np.max(np.abs(bpm.shape_g1(e) - g1)) < 1.0


def test_st1_prime_figure86():
    """Figure 86, Eq. (55): St'_1 against R_c within 4 % (the reading error of the plot)."""
    re, st = load("figure86-St_1_prime")
    assert np.max(np.abs(bpm.reference_strouhal(re) / st - 1.0)) < 0.04


@pytest.mark.parametrize("alpha", [0.0, 6.0])
def test_g2_plus_g3_figure88(alpha):
    """Figure 88, Eqs. (58)-(60): the peak level G_2 + G_3 against R_c at alpha* = 0 and 6 deg, within 1 dB."""
    re, level = load(f"figure88-G2-alpha{alpha:.0f}")
    model = bpm.shape_g2(re / bpm.reference_reynolds(alpha)) + bpm.shape_g3(alpha)
    assert np.max(np.abs(model - level)) < 1.0


def test_g2_figure89():
    """Figure 89, Eq. (58): G_2 against R_c / (R_c)_0, within 1 dB except one digitized point on the steep
    flank (measured 1.06 dB at d = 2.07, where G_2 falls 6 dB per 0.1 of d), held to 1.1 dB."""
    d, g2 = load("figure89")
    err = np.abs(bpm.shape_g2(d) - g2)
    assert np.count_nonzero(err > 1.0) <= 1
    assert np.max(err) < 1.1


def test_st1_closed_form():
    """Eq. (31) at the report's four Mach numbers gives the St_1 of its Sec. 5.1.1 (0.081, 0.071, 0.059, 0.051)."""
    np.testing.assert_allclose(bpm.peak_strouhal_1(np.array([0.093, 0.116, 0.163, 0.209])),
                               [0.081, 0.071, 0.059, 0.051], atol=2.5e-3)


@pytest.mark.parametrize("name", ["shape_a_min", "shape_a_max", "shape_b_min", "shape_b_max", "shape_g1",
                                  "shape_g2"])
def test_pure_piecewise_evaluates_each_branch_at_its_own_points_only(name, monkeypatch):
    """The fits whose branches depend on their argument alone (``piecewise(..., pure=True)``) give, for arrays,
    the values of the general path (every branch everywhere, then selected) bit for bit: real and complex
    (complex step), on the edges (the lower branch) and at NaN (NaN on both paths: never a silent number)."""
    from bild_mdo.acoustics.bpm import jet_math, laminar_vortex_shedding, turbulent_trailing_edge

    function = getattr(bpm, name)
    x = np.random.default_rng(3).uniform(1e-3, 5.0, (6, 3, 40))
    x[0, 0, :8] = [np.nan, 0.204, 0.244, 0.13, 0.145, 0.8545, 1.17, 3.0889]
    fast = [function(x), function(x + 1e-30j)]
    general = jet_math.piecewise
    for module in (turbulent_trailing_edge, laminar_vortex_shedding):
        monkeypatch.setattr(module, "piecewise", lambda x, edges, branches, pure=False: general(x, edges, branches))
    for values, argument in zip(fast, (x, x + 1e-30j)):
        np.testing.assert_array_equal(values, function(argument))
        assert values.dtype == argument.dtype and values.shape == x.shape
        assert np.isnan(values[0, 0, 0]) and np.count_nonzero(np.isnan(values)) == 1
    # -inf belongs to the first branch, +inf to the last, on both paths.
    edges, branches = [0.0, 1.0], [lambda v: np.full_like(v, -1.0), np.zeros_like, lambda v: np.full_like(v, 1.0)]
    x = np.array([-np.inf, 0.5, np.inf])
    for pure in (True, False):
        np.testing.assert_array_equal(general(x, edges, branches, pure=pure), [-1.0, 0.0, 1.0])
