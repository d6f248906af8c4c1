"""Compressibility corrections of lift: Prandtl-Glauert and Karman-Tsien, against hand derivations and XFOIL."""
from pathlib import Path

import numpy as np
import pytest

from bild_mdo.airfoil import AnalyticPolar, CompressiblePolar, resolve_polar
from bild_mdo.airfoil.compressibility import MACH_LIMIT, karman_tsien, prandtl_glauert
from bild_mdo.airfoil.sources.readers import read_polar_table

DATA = Path(__file__).parent / "data"
H = 1e-30


def test_prandtl_glauert_lift_slope_scales_with_one_over_beta():
    # Hand derivation: cl = (cl0 + a alpha) / sqrt(1 - M^2), so dcl/dalpha = a / beta;
    # at M = 0.6, beta = 0.8 and the slope is 1.25 a.
    base = AnalyticPolar()
    polar = CompressiblePolar(base, "prandtl-glauert")
    alpha = np.radians([-4.0, 0.0, 3.0, 6.0])
    v = polar.evaluate(alpha, 1e6, mach=0.6)
    assert np.allclose(v.dcl_dalpha, 1.25 * base.cl_alpha, rtol=1e-14)
    assert np.allclose(v.cl, 1.25 * base.evaluate(alpha, 1e6).cl, rtol=1e-14)
    # Drag is left unchanged (module docstring: no wave drag below the critical Mach number).
    np.testing.assert_array_equal(v.cd, base.evaluate(alpha, 1e6).cd)
    np.testing.assert_array_equal(v.dcd_dmach, 0.0)
    # dcl/dM = cl0 M / beta^3 (differentiating cl0 (1 - M^2)^(-1/2)).
    assert np.allclose(v.dcl_dmach, base.evaluate(alpha, 1e6).cl * 0.6 / 0.8**3, rtol=1e-14)


def test_karman_tsien_reduces_to_prandtl_glauert_at_zero_lift():
    # cl = cl0 / (beta + k cl0): at cl0 = 0, dcl/dcl0 = 1/beta, the Prandtl-Glauert slope.
    for mach in (0.3, 0.5, 0.7):
        _, slope, _, _, _ = karman_tsien(0.0, mach)
        assert slope == pytest.approx(1.0 / np.sqrt(1.0 - mach**2), rel=1e-14)


@pytest.mark.parametrize("rule", [prandtl_glauert, karman_tsien])
def test_corrections_return_the_data_at_the_reference_mach(rule):
    cl = np.linspace(-0.8, 1.4, 12)
    value, *_ = rule(cl, 0.2, reference_mach=0.2)
    np.testing.assert_allclose(value, cl, rtol=1e-13, atol=1e-15)


@pytest.mark.parametrize("rule", [prandtl_glauert, karman_tsien])
@pytest.mark.parametrize("reference_mach", [0.0, 0.15])
def test_rule_derivatives_by_complex_step(rule, reference_mach):
    cl = np.linspace(-0.8, 1.4, 12)
    mach = np.linspace(0.05, 0.85, 12)
    f, f_c, f_cc, f_m, f_cm = rule(cl, mach, reference_mach)
    np.testing.assert_allclose(np.imag(rule(cl, mach + 1j * H, reference_mach)[0]) / H, f_m, rtol=1e-12)
    np.testing.assert_allclose(np.imag(rule(cl + 1j * H, mach, reference_mach)[0]) / H, f_c, rtol=1e-12)
    np.testing.assert_allclose(np.imag(rule(cl + 1j * H, mach, reference_mach)[1]) / H, f_cc, rtol=1e-12,
                               atol=1e-14)
    np.testing.assert_allclose(np.imag(rule(cl, mach + 1j * H, reference_mach)[1]) / H, f_cm, rtol=1e-12)


@pytest.mark.parametrize("correction", ["prandtl-glauert", "karman-tsien"])
def test_polar_mach_derivatives_by_complex_step(correction):
    base = AnalyticPolar(reynolds_exponent=0.2)
    polar = CompressiblePolar(base, correction)
    rng = np.random.default_rng(3)
    alpha = rng.uniform(-0.2, 0.25, (3, 4))
    reynolds = rng.uniform(2e5, 2e6, (3, 4))
    mach = rng.uniform(0.05, 0.7, (3, 4))
    v = polar.evaluate(alpha, reynolds, mach=mach)
    rule = prandtl_glauert if correction == "prandtl-glauert" else karman_tsien
    b = base.evaluate(alpha, reynolds)
    np.testing.assert_allclose(np.imag(rule(b.cl, mach + 1j * H)[0]) / H, v.dcl_dmach, rtol=1e-12)
    # alpha-Mach cross derivative of the max-L/D implicit derivative, by complex step of dcl/dalpha.
    s = polar.second_derivatives(alpha, reynolds, mach=mach)
    _, f_c, _, _, _ = rule(b.cl, mach + 1j * H)
    np.testing.assert_allclose(np.imag(f_c) / H * b.dcl_dalpha, s.d2cl_dalpha_dmach, rtol=1e-12)
    # Complex Mach through evaluate carries d/dM (what OpenMDAO's check_partials(method='cs') sees).
    vc = polar.evaluate(alpha, reynolds, mach=mach + 1j * H)
    np.testing.assert_allclose(np.imag(vc.cl) / H, v.dcl_dmach, rtol=1e-14)


@pytest.mark.parametrize("correction", ["prandtl-glauert", "karman-tsien"])
def test_second_reynolds_derivatives_by_complex_step(correction):
    # cl = F(cl_base(alpha, Re), M): d2cl/dRe2 = F_cc cl_Re**2 + F_c cl_ReRe; the NACA 4412 surrogate's
    # lift depends on Re and its _compute is complex-step safe in Re, so the complex step of
    # dcl/dRe = F_c(cl_base) cl_base_Re checks it.  Drag is the base polar's.
    base = resolve_polar("naca4412")
    polar = CompressiblePolar(base, correction)
    rng = np.random.default_rng(4)
    alpha = rng.uniform(-0.1, 0.2, 10)
    reynolds = np.exp(rng.uniform(np.log(6e4), np.log(1.9e6), 10))
    mach = rng.uniform(0.05, 0.65, 10)
    s = polar.second_derivatives(alpha, reynolds, mach=mach)
    (cl, _, cl_re), (_, _, cd_re) = base._compute(alpha, reynolds + 1j * H * reynolds, second=False)
    rule = prandtl_glauert if correction == "prandtl-glauert" else karman_tsien
    f_c = rule(cl, mach)[1]
    np.testing.assert_allclose(np.imag(f_c * cl_re) / H, s.d2cl_dre2 * reynolds, rtol=1e-10, atol=1e-20)
    np.testing.assert_allclose(np.imag(cd_re) / H, s.d2cd_dre2 * reynolds, rtol=1e-10, atol=1e-20)
    assert np.max(np.abs(s.d2cl_dre2 * reynolds**2)) > 1e-3


def test_no_mach_is_exactly_the_base_polar():
    base = AnalyticPolar()
    polar = CompressiblePolar(base, "karman-tsien")
    alpha = np.radians(np.linspace(-20, 30, 51))
    for got, want in zip(polar.evaluate(alpha, 1e6), base.evaluate(alpha, 1e6)):
        np.testing.assert_array_equal(got, want)


def test_max_lift_to_drag_under_prandtl_glauert():
    # Hand derivation: cl/cd is scaled by 1/beta at every alpha, so alpha* does not move,
    # cl* scales by 1/beta and cd* is unchanged; dcl*/dM = cl*(0) M / beta^3.
    polar = CompressiblePolar(AnalyticPolar(), "prandtl-glauert")
    point = polar.max_lift_to_drag([1e6, 1e6], mach=[0.0, 0.6])
    assert point.alpha[1] == pytest.approx(point.alpha[0], abs=1e-12)
    assert point.cl[1] == pytest.approx(point.cl[0] / 0.8, rel=1e-12)
    assert point.cd[1] == pytest.approx(point.cd[0], rel=1e-12)
    assert point.dcl_dmach[1] == pytest.approx(point.cl[0] * 0.6 / 0.8**3, rel=1e-10)
    assert point.dalpha_dmach == pytest.approx([0.0, 0.0], abs=1e-12)


def test_mach_validity_limits():
    polar = CompressiblePolar(AnalyticPolar(), "prandtl-glauert")
    with pytest.warns(RuntimeWarning, match="beyond the validity"):
        high = polar.evaluate(0.05, 1e6, mach=0.95)
    at_limit = polar.evaluate(0.05, 1e6, mach=MACH_LIMIT)
    assert high.cl == at_limit.cl and high.dcl_dmach == 0.0
    with pytest.raises(ValueError, match="Mach number must be finite and >= 0"):
        polar.evaluate(0.05, 1e6, mach=-0.1)
    with pytest.raises(ValueError, match="unknown compressibility correction 'glauert'"):
        CompressiblePolar(AnalyticPolar(), "glauert")


def test_resolve_polar_switches_the_correction_per_polar():
    polar = resolve_polar("analytic", compressibility="Karman-Tsien")
    assert isinstance(polar, CompressiblePolar) and polar.correction == "karman-tsien"
    assert resolve_polar("analytic", compressibility="none").varies_with_mach is False


def test_prandtl_glauert_against_xfoil_at_mach_half():
    # XFOIL 6.99, NACA 0012, Re = 1e6, Ncrit 9, alpha -2..4 deg, at M = 0 and M = 0.5
    # (XFOIL's MACH command: Karman-Tsien pressures and a compressible boundary layer); files
    # in tests/airfoil/data, made by the command in data/README.md.  At small angles the
    # Prandtl-Glauert-corrected M = 0 lift is within 0.009 (2.1 %) below XFOIL's M = 0.5 lift
    # (XFOIL's lift slope is 1.177 times the M = 0 slope, Prandtl-Glauert's 1/beta = 1.155).
    m0 = read_polar_table(DATA / "naca0012_re1000000_mach0.txt")
    m5 = read_polar_table(DATA / "naca0012_re1000000_mach0.5.txt")
    np.testing.assert_array_equal(m0.alpha_deg, m5.alpha_deg)
    corrected = prandtl_glauert(m0.cl, 0.5)[0]
    assert np.max(np.abs(corrected - m5.cl)) < 0.01
    lifting = m5.alpha_deg != 0.0
    assert np.max(np.abs(corrected[lifting] / m5.cl[lifting] - 1.0)) < 0.025
    slope_ratio = np.polyfit(m5.alpha_deg, m5.cl, 1)[0] / np.polyfit(m0.alpha_deg, m0.cl, 1)[0]
    assert slope_ratio == pytest.approx(1.0 / np.sqrt(0.75), rel=0.025)
