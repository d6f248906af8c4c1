"""Surrogate of tables at several Mach numbers: cardinal-spline weights in M, exact Mach derivatives."""
import warnings

import numpy as np
import pytest

from bild_mdo.airfoil import MachTabulatedPolar, TabulatedPolar, resolve_polar, tabulated_polar
from bild_mdo.airfoil.sources.polar_data import PolarData
from bild_mdo.airfoil.sources.readers import write_polar_table

MACHS = (0.0, 0.4, 0.7)
REYNOLDS = (2e5, 1e6)
H = 1e-30


def _tables():
    # Lift-curve data that follow Prandtl-Glauert exactly, cl = (0.4 + 5.6 alpha)/beta, with a
    # stall near 14 deg and a drag bucket; drag grows with Mach and falls with Re.
    alpha = np.arange(-12.0, 20.01, 0.5)
    rad = np.radians(alpha)
    tables = []
    for m in MACHS:
        beta = np.sqrt(1.0 - m * m)
        for re in REYNOLDS:
            cl = (0.4 + 5.6 * rad - 9.0 * np.maximum(rad - np.radians(10.0), 0.0) ** 2 * 40) / beta
            cd = (0.008 * (re / 1e6) ** -0.2 + 0.01 * (cl * beta - 0.4) ** 2) * (1.0 + 0.3 * m**2)
            tables.append(PolarData(re, m, alpha, cl, cd, source=f"synthetic M={m} Re={re:g}"))
    return tables


@pytest.fixture(scope="module")
def polar():
    return tabulated_polar(_tables(), name="synthetic")


def test_one_surrogate_per_mach_number(polar):
    assert isinstance(polar, MachTabulatedPolar)
    np.testing.assert_array_equal(polar.machs, MACHS)
    assert all(isinstance(m, TabulatedPolar) for m in polar.members)
    assert isinstance(tabulated_polar(_tables()[:2]), TabulatedPolar)


def test_cardinal_weights_interpolate_and_reproduce_polynomials(polar):
    # Cardinal functions of a spline interpolant: w_k(M_j) = delta_kj, and the interpolant of
    # 1, M, M^2 (three Mach numbers: the parabola through them) is the function itself.
    w, _ = polar.mach_weights(np.array(MACHS))
    np.testing.assert_allclose(w, np.eye(3), atol=1e-15)
    mach = np.linspace(0.0, 0.7, 29)
    w, dw = polar.mach_weights(mach)
    nodes = np.array(MACHS)
    for power in range(3):
        np.testing.assert_allclose((nodes[:, None] ** power * w).sum(axis=0), mach**power, atol=1e-14)
    np.testing.assert_allclose(dw.sum(axis=0), 0.0, atol=1e-13)


def test_weight_derivatives_by_complex_step(polar):
    mach = np.linspace(0.01, 0.69, 17)
    _, dw = polar.mach_weights(mach)
    w_c, _ = polar.mach_weights(mach + 1j * H)
    np.testing.assert_allclose(np.imag(w_c) / H, dw, rtol=1e-12, atol=1e-14)


def test_mach_derivatives_by_complex_step(polar):
    rng = np.random.default_rng(5)
    alpha = rng.uniform(-0.15, 0.2, 12)
    reynolds = rng.uniform(2e5, 1e6, 12)
    mach = rng.uniform(0.02, 0.68, 12)
    v = polar.evaluate(alpha, reynolds, mach=mach)
    # c(M + ih) = sum_k w_k(M + ih) c_k: the blend is complex-step safe in M.
    w_c, _ = polar.mach_weights(mach + 1j * H)
    members = [m.evaluate(alpha, reynolds) for m in polar.members]
    cl_c = sum(w * m.cl for w, m in zip(w_c, members))
    cd_c = sum(w * m.cd for w, m in zip(w_c, members))
    np.testing.assert_allclose(np.imag(cl_c) / H, v.dcl_dmach, rtol=1e-12)
    np.testing.assert_allclose(np.imag(cd_c) / H, v.dcd_dmach, rtol=1e-12)
    s = polar.second_derivatives(alpha, reynolds, mach=mach)
    dcl_da_c = sum(w * m.dcl_dalpha for w, m in zip(w_c, members))
    np.testing.assert_allclose(np.imag(dcl_da_c) / H, s.d2cl_dalpha_dmach, rtol=1e-12)


def test_second_reynolds_derivatives_by_complex_step(polar):
    # c(M, Re) = sum_k w_k(M) c_k(Re): d2c/dRe2 is the weighted sum of the members', and each member's
    # TabulatedPolar._compute is complex-step safe in Re, so the complex step of the blended dc/dRe
    # checks it (inside the members' Reynolds range and past it on both sides).
    rng = np.random.default_rng(7)
    alpha = rng.uniform(-0.15, 0.2, 12)
    reynolds = np.concatenate([rng.uniform(2.2e5, 9e5, 6), [1e5, 1.5e5, 3e6], rng.uniform(2e6, 5e6, 3)])
    mach = rng.uniform(0.02, 0.68, 12)
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*Reynolds numbers outside the tabulated range")
        s = polar.second_derivatives(alpha, reynolds, mach=mach)
        w, _ = polar.mach_weights(mach)
        members = [m._compute(alpha, reynolds + 1j * H * reynolds, second=False) for m in polar.members]
    for q, field in ((0, "d2cl_dre2"), (1, "d2cd_dre2")):
        c_re = sum(wk * m[q][2] for wk, m in zip(w, members))
        np.testing.assert_allclose(np.imag(c_re) / H, getattr(s, field) * reynolds, rtol=1e-10, atol=1e-20)
    assert np.max(np.abs(s.d2cd_dre2 * reynolds**2)) > 1e-4


def test_at_a_tabulated_mach_number_the_surrogate_is_that_table(polar):
    alpha = np.radians(np.linspace(-10, 15, 26))
    for m, member in zip(MACHS, polar.members):
        v = polar.evaluate(alpha, 5e5, mach=m)
        np.testing.assert_allclose(v.cl, member.evaluate(alpha, 5e5).cl, rtol=1e-13, atol=1e-15)
    # No Mach number: the lowest table, exactly.
    for got, want in zip(polar.evaluate(alpha, 5e5), polar.members[0].evaluate(alpha, 5e5)):
        np.testing.assert_array_equal(got, want)


def test_between_tables_the_lift_is_the_parabola_through_the_data(polar):
    # The tables scale cl by 1/beta = 1, 1.0911, 1.4003 at M = 0, 0.4, 0.7.  Hand derivation:
    # the parabola through them is 1 - 0.23106 M + 1.14702 M^2, 1.2199 at M = 0.55 (1/beta
    # itself is 1.1974 there: the interpolation error of three tables, 1.9 %).
    inv_beta = 1.0 / np.sqrt(1.0 - np.array(MACHS) ** 2)
    coef = np.polyfit(MACHS, inv_beta, 2)
    assert np.polyval(coef, 0.55) == pytest.approx(1.2199, abs=1e-4)
    alpha = np.radians(np.linspace(-4, 6, 11))
    base = polar.members[0].evaluate(alpha, 5e5).cl
    cl = polar.evaluate(alpha, 5e5, mach=0.55).cl
    np.testing.assert_allclose(cl, base * np.polyval(coef, 0.55), rtol=2e-3, atol=1e-4)


def test_max_lift_to_drag_mach_derivative_by_central_difference(polar):
    reynolds = np.array([3e5, 8e5])
    mach = np.array([0.2, 0.55])
    point = polar.max_lift_to_drag(reynolds, mach=mach)
    step = 1e-6
    up = polar.max_lift_to_drag(reynolds, mach=mach + step)
    down = polar.max_lift_to_drag(reynolds, mach=mach - step)
    np.testing.assert_allclose(point.dalpha_dmach, (up.alpha - down.alpha) / (2 * step), rtol=1e-5, atol=1e-8)
    np.testing.assert_allclose(point.dcl_dmach, (up.cl - down.cl) / (2 * step), rtol=1e-5, atol=1e-8)
    np.testing.assert_allclose(point.dcd_dmach, (up.cd - down.cd) / (2 * step), rtol=1e-5, atol=1e-9)


def test_mach_outside_the_tables_is_clamped_with_a_warning():
    polar = tabulated_polar(_tables(), name="clamped")
    with pytest.warns(RuntimeWarning, match="outside the tabulated range 0...0.7"):
        v = polar.evaluate(0.05, 5e5, mach=0.8)
    assert v.dcl_dmach == 0.0
    assert v.cl == pytest.approx(polar.evaluate(0.05, 5e5, mach=0.7).cl, rel=1e-14)


def test_reynolds_outside_the_tables_is_extrapolated_in_every_member(polar):
    # The tables' drag falls as Re^-0.2 (_tables): past Re = 1e6 each member continues it as a
    # power law from the edge (TabulatedPolar), so the blend keeps falling, continuously, with
    # Re derivatives and Mach derivatives that are the members' blended (complex step in M).
    alpha = np.radians([1.0, 4.0])
    mach = np.array([0.3, 0.6])
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*outside the tabulated range", category=UserWarning)
        edge = polar.evaluate(alpha, 1e6, mach=mach)
        past = polar.evaluate(alpha, 1e6 * (1.0 + 1e-9), mach=mach)
        far = polar.evaluate(alpha, 4e6, mach=mach)
        members = [m.evaluate(alpha, 4e6) for m in polar.members]
    np.testing.assert_allclose(past.cd, edge.cd, rtol=1e-8)
    np.testing.assert_allclose(past.dcd_dre * 1e6, edge.dcd_dre * 1e6, rtol=1e-6)
    assert np.all(far.cd < edge.cd) and np.all(far.dcd_dre < 0.0)
    w_c, _ = polar.mach_weights(mach + 1j * H)
    np.testing.assert_allclose(np.imag(sum(w * m.cd for w, m in zip(w_c, members))) / H, far.dcd_dmach, rtol=1e-12)
    np.testing.assert_allclose(sum(w.real * m.dcd_dre for w, m in zip(w_c, members)), far.dcd_dre, rtol=1e-12)


def test_a_folder_of_tables_at_several_mach_numbers_resolves_to_a_mach_polar(tmp_path):
    for table in _tables():
        write_polar_table(tmp_path / f"syn_re{int(table.reynolds)}_m{table.mach:g}.txt", table)
    polar = resolve_polar(tmp_path)
    assert isinstance(polar, MachTabulatedPolar) and polar.varies_with_mach
    np.testing.assert_array_equal(polar.machs, MACHS)
    assert resolve_polar(str(tmp_path)) is polar
