"""Tests of TabulatedPolar (the smooth C_l, C_d surrogate) and the built-in airfoil registry."""
import time
import warnings

import numpy as np
import pytest

from bild_mdo.airfoil import AnalyticPolar, TabulatedPolar, naca4412
from bild_mdo.airfoil.sources import PolarData, load_builtin_polars, write_polar_table

TABLE_RE = np.array([5e4, 1e5, 3e5, 1e6, 2e6])
DATA_ALPHA = np.arange(-10.0, 20.01, 0.5)


def _table(re, noise=0.0, seed=0):
    """Data of an analytic polar whose drag scales with Re^-0.2 (the surrogate's input)."""
    p = AnalyticPolar(reynolds_exponent=0.2)
    v = p.evaluate(np.radians(DATA_ALPHA), re)
    rng = np.random.default_rng(seed)
    return PolarData(re, 0.0, DATA_ALPHA, v.cl + noise * rng.standard_normal(DATA_ALPHA.size),
                     v.cd, f"analytic Re={re:g}")


@pytest.fixture(scope="module")
def surrogate():
    return TabulatedPolar([_table(re) for re in TABLE_RE], name="synthetic")


@pytest.fixture
def fresh_surrogate():
    # Warnings are issued once per object: tests of the warning need their own object.
    return TabulatedPolar([_table(re) for re in TABLE_RE[:3]], name="fresh")


def _points(n=500, seed=0, re_range=(5.5e4, 1.8e6)):
    rng = np.random.default_rng(seed)
    alpha = rng.uniform(-np.pi, np.pi, n)
    alpha[: n // 2] = rng.uniform(np.radians(-15.0), np.radians(20.0), n // 2)
    reynolds = np.exp(rng.uniform(*np.log(re_range), n))
    return alpha, reynolds


def test_reproduces_the_extended_tables(surrogate):
    # An interpolating spline: exact at the table Reynolds numbers and grid angles.
    for e in surrogate.extended:
        v = surrogate.evaluate(e.alpha[:-1], e.reynolds)
        np.testing.assert_allclose(v.cl, e.cl[:-1], atol=1e-12)
        np.testing.assert_allclose(v.cd, e.cd[:-1], atol=1e-12)


def test_close_to_the_polar_the_data_came_from(surrogate):
    # Between table Reynolds numbers and angles, in attached flow, the surrogate
    # follows the analytic polar that generated the data (interpolation + smoothing error).
    alpha = np.radians(np.linspace(-6.0, 9.0, 61))
    for re in (7e4, 5e5, 1.5e6):
        v = surrogate.evaluate(alpha, re)
        exact = AnalyticPolar(reynolds_exponent=0.2).evaluate(alpha, re)
        np.testing.assert_allclose(v.cl, exact.cl, atol=2e-3)
        np.testing.assert_allclose(v.cd, exact.cd, rtol=1e-2)


def test_first_derivatives_match_central_differences(surrogate):
    alpha, reynolds = _points()
    v = surrogate.evaluate(alpha, reynolds)
    h = 1e-6
    vp, vm = surrogate.evaluate(alpha + h, reynolds), surrogate.evaluate(alpha - h, reynolds)
    np.testing.assert_allclose((vp.cl - vm.cl) / (2 * h), v.dcl_dalpha, atol=1e-7)
    np.testing.assert_allclose((vp.cd - vm.cd) / (2 * h), v.dcd_dalpha, atol=1e-7)
    hr = 1e-6 * reynolds
    vp, vm = surrogate.evaluate(alpha, reynolds + hr), surrogate.evaluate(alpha, reynolds - hr)
    # Compared per unit log(Re): Re * d/dRe.
    np.testing.assert_allclose((vp.cl - vm.cl) / (2 * hr) * reynolds, v.dcl_dre * reynolds, atol=1e-7)
    np.testing.assert_allclose((vp.cd - vm.cd) / (2 * hr) * reynolds, v.dcd_dre * reynolds, atol=1e-7)
    assert np.max(np.abs(v.dcd_dre * reynolds)) > 1e-3  # the Re dependence is really there


def test_second_derivatives_match_central_differences(surrogate):
    alpha, reynolds = _points(seed=1)
    s = surrogate.second_derivatives(alpha, reynolds)
    h = 1e-6
    vp, vm = surrogate.evaluate(alpha + h, reynolds), surrogate.evaluate(alpha - h, reynolds)
    np.testing.assert_allclose((vp.dcl_dalpha - vm.dcl_dalpha) / (2 * h), s.d2cl_dalpha2, atol=1e-5)
    np.testing.assert_allclose((vp.dcd_dalpha - vm.dcd_dalpha) / (2 * h), s.d2cd_dalpha2, atol=1e-5)
    hr = 1e-6 * reynolds
    vp, vm = surrogate.evaluate(alpha, reynolds + hr), surrogate.evaluate(alpha, reynolds - hr)
    np.testing.assert_allclose((vp.dcl_dalpha - vm.dcl_dalpha) / (2 * hr) * reynolds,
                               s.d2cl_dalpha_dre * reynolds, atol=1e-6)
    np.testing.assert_allclose((vp.dcd_dalpha - vm.dcd_dalpha) / (2 * hr) * reynolds,
                               s.d2cd_dalpha_dre * reynolds, atol=1e-6)


def test_c1_across_cell_boundaries_and_the_wrap(surrogate):
    # Knots of the spline: alpha grid points (stall blends included), the table Reynolds
    # numbers, and the +-180 deg wrap.  Left and right limits of values and slopes agree.
    d = 1e-9
    grid = surrogate.extended[0].alpha
    a_knots = np.concatenate([grid[::40], [np.pi]])
    for re in (1.5e5, 1e6):
        vl = surrogate.evaluate(a_knots - d, re)
        vr = surrogate.evaluate(a_knots + d, re)
        for x, y in [(vl.cl, vr.cl), (vl.cd, vr.cd), (vl.dcl_dalpha, vr.dcl_dalpha),
                     (vl.dcd_dalpha, vr.dcd_dalpha), (vl.dcl_dre * re, vr.dcl_dre * re)]:
            np.testing.assert_allclose(x, y, atol=1e-6)
    alpha = np.radians(np.array([-8.0, 3.0, 12.0, 40.0]))
    for re in TABLE_RE[1:-1]:
        vl = surrogate.evaluate(alpha, re * (1 - 1e-10))
        vr = surrogate.evaluate(alpha, re * (1 + 1e-10))
        for x, y in [(vl.cl, vr.cl), (vl.cd, vr.cd), (vl.dcl_dalpha, vr.dcl_dalpha),
                     (vl.dcl_dre * re, vr.dcl_dre * re), (vl.dcd_dre * re, vr.dcd_dre * re)]:
            np.testing.assert_allclose(x, y, atol=1e-6)


def test_periodic_in_alpha(surrogate):
    alpha, reynolds = _points(50, seed=2)
    a = surrogate.evaluate(alpha, reynolds)
    b = surrogate.evaluate(alpha - 4.0 * np.pi, reynolds)
    for x, y in zip(a, b):
        np.testing.assert_allclose(x, y, rtol=1e-9, atol=1e-11)


def test_broadcasting_and_shapes(surrogate):
    alpha = np.linspace(-0.2, 0.3, 21).reshape(3, 7)
    reynolds = np.geomspace(1e5, 1e6, 7)
    v = surrogate.evaluate(alpha, reynolds)
    s = surrogate.second_derivatives(alpha, reynolds)
    for x in (*v, *s):
        assert x.shape == (3, 7)
    flat = surrogate.evaluate(alpha.ravel(), np.tile(reynolds, 3))
    np.testing.assert_array_equal(v.cl.ravel(), flat.cl)


def test_complex_step_through_evaluate(surrogate):
    h = 1e-30
    v = surrogate.evaluate(np.array([0.07]), np.array([2e5 + 1j * h]))
    assert v.cd.imag[0] / h == pytest.approx(v.dcd_dre[0], rel=1e-13)


def test_extrapolates_reynolds_and_warns_once(fresh_surrogate):
    # Past the table the polar is continued from the edge (formula and its checks:
    # tests/airfoil/test_reynolds_extrapolation.py), not clamped; one warning per polar says so.
    alpha = np.radians([2.0, 5.0])
    lo, hi = fresh_surrogate.reynolds[0], fresh_surrogate.reynolds[-1]
    with pytest.warns(UserWarning, match="outside the tabulated range .* are extrapolated") as record:
        below = fresh_surrogate.evaluate(alpha, 0.2 * lo)
        above = fresh_surrogate.evaluate(alpha, 5.0 * hi)
        fresh_surrogate.second_derivatives(alpha, 5.0 * hi)
    assert len(record) == 1
    assert f"{lo:.4g}" in str(record[0].message) and f"{hi:.4g}" in str(record[0].message)
    # The data's drag falls with Re (Re^-0.2): above the table it keeps falling, below it keeps rising.
    assert np.all(above.cd < fresh_surrogate.evaluate(alpha, hi).cd)
    assert np.all(below.cd > fresh_surrogate.evaluate(alpha, lo).cd)
    assert np.all(below.dcd_dre < 0.0) and np.all(above.dcd_dre < 0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fresh_surrogate.evaluate(alpha, 10.0 * hi)   # no second warning


def test_invalid_reynolds_raises(surrogate):
    with pytest.raises(ValueError, match="Reynolds"):
        surrogate.evaluate(0.1, 0.0)
    with pytest.raises(ValueError, match="finite"):
        surrogate.evaluate(np.nan, 1e5)


def test_single_table_is_reynolds_independent():
    p = TabulatedPolar([_table(3e5)])
    a = np.radians([0.0, 5.0])
    with pytest.warns(UserWarning):
        v = p.evaluate(a, 1e6)
    np.testing.assert_array_equal(v.cl, p.evaluate(a, 3e5).cl)
    assert np.all(v.dcl_dre == 0.0)


def test_duplicate_reynolds_rejected():
    with pytest.raises(ValueError, match="distinct"):
        TabulatedPolar([_table(3e5), _table(3e5)])


def test_builders_from_files_tables_and_arrays(tmp_path):
    tables = [_table(re) for re in (1e5, 1e6)]
    xfoil_paths, table_paths = [], []
    for t in tables:
        # XFOIL PACC layout (columns alpha CL CD CDp CM Top_Xtr Bot_Xtr), Re in the header.
        rows = "\n".join(f"  {a:7.3f}  {cl:7.4f}  {cd:8.5f}  {cd:8.5f}  -0.1000   0.5000   1.0000"
                         for a, cl, cd in zip(t.alpha_deg, t.cl, t.cd))
        text = ("\n       XFOIL         Version 6.99\n\n Calculated polar for: test\n\n"
                " 1 1 Reynolds number fixed          Mach number fixed\n\n"
                " xtrf =   1.000 (top)        1.000 (bottom)\n"
                f" Mach =   0.000     Re =     {t.reynolds / 1e6:.3f} e 6     Ncrit =   9.000\n\n"
                "   alpha    CL        CD       CDp       CM     Top_Xtr  Bot_Xtr\n"
                "  ------ -------- --------- --------- -------- -------- --------\n" + rows + "\n")
        path = tmp_path / f"xfoil_{t.reynolds:g}.pol"
        path.write_text(text)
        xfoil_paths.append(path)
        table_path = tmp_path / f"table_{t.reynolds:g}.txt"
        write_polar_table(table_path, t)
        table_paths.append(table_path)
    from_xfoil = TabulatedPolar.from_files(xfoil_paths)
    from_tables = TabulatedPolar.from_tables(table_paths)
    from_arrays = TabulatedPolar.from_arrays([t.reynolds for t in tables],
                                             [t.alpha_deg for t in tables],
                                             [t.cl for t in tables], [t.cd for t in tables])
    np.testing.assert_array_equal(from_xfoil.reynolds, [1e5, 1e6])
    a = np.radians(np.linspace(-5, 10, 7))
    ref = from_arrays.evaluate(a, 3e5)
    # Files round the data to XFOIL's printed digits (4 decimals for cl, 5 for cd).
    for p in (from_xfoil, from_tables):
        v = p.evaluate(a, 3e5)
        np.testing.assert_allclose(v.cl, ref.cl, atol=2e-3)
        np.testing.assert_allclose(v.cd, ref.cd, rtol=2e-2)


def test_evaluation_speed_is_reported(surrogate, capsys):
    # Not asserted (timing depends on the machine); printed for the record with -s.
    rng = np.random.default_rng(0)
    alpha = rng.uniform(-np.pi, np.pi, 300_000)
    reynolds = np.exp(rng.uniform(np.log(6e4), np.log(1.9e6), alpha.size))
    best = np.inf
    for _ in range(3):
        t0 = time.perf_counter()
        v = surrogate.evaluate(alpha, reynolds)
        best = min(best, time.perf_counter() - t0)
    assert v.cl.shape == (300_000,) and np.all(np.isfinite(v.cl))
    print(f"TabulatedPolar.evaluate, 300,000 points: {best * 1e3:.1f} ms")


# ----------------------------------------------------------------- built-in data
@pytest.fixture(scope="module")
def naca():
    return naca4412()


def test_naca4412_max_lift_to_drag_matches_xfoil_at_re_1e6(naca):
    # XFOIL's own data (bild_mdo/airfoil/data/naca4412_re1000000.txt): max cl/cd 132.8 at
    # 5.5 deg.  The smoothed surrogate must agree to a few per cent, at 4-6 deg.
    data = [p for p in load_builtin_polars("naca4412") if p.reynolds == 1e6][0]
    xfoil_max = np.max(data.cl / data.cd)
    m = naca.max_lift_to_drag(1e6)
    ld = float(m.cl / m.cd)
    assert 130.0 < ld < 150.0
    assert ld == pytest.approx(xfoil_max, rel=0.03)
    assert 4.0 < np.degrees(m.alpha) < 6.0


def test_naca4412_max_lift_to_drag_tracks_xfoil_at_every_table_reynolds(naca):
    # Above Re = 1e5 the XFOIL data have no jumps; the surrogate keeps their L/D maximum
    # within 3 %.  (At 5e4 XFOIL jumps between two laminar-bubble solutions at 10 deg,
    # which any smooth fit must cut off.)
    for data in load_builtin_polars("naca4412"):
        if data.reynolds < 1e5:
            continue
        m = naca.max_lift_to_drag(data.reynolds)
        assert float(m.cl / m.cd) == pytest.approx(np.max(data.cl / data.cd), rel=0.03)


def test_naca4412_drag_positive_everywhere(naca):
    alpha, reynolds = np.meshgrid(np.linspace(-np.pi, np.pi, 1441), np.geomspace(5e4, 2e6, 60))
    assert np.all(naca.evaluate(alpha, reynolds).cd > 0.0)



@pytest.mark.parametrize("polar_kind", ["surrogate", "analytic"])
def test_values_with_second_derivatives_are_the_two_calls(surrogate, polar_kind):
    # One spline evaluation for both (TabulatedPolar) or the two calls (the base class default): the same numbers,
    # inside the table and past both of its edges (the C1 continuation), in the broadcast shape.
    polar = surrogate if polar_kind == "surrogate" else AnalyticPolar()
    assert polar.shares_second_derivatives == (polar_kind == "surrogate")
    alpha = np.radians(np.linspace(-8.0, 16.0, 12)).reshape(3, 4)
    reynolds = np.array([[2e4], [4e5], [5e6]])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # Reynolds numbers past the table
        values, second = polar.evaluate_with_second_derivatives(alpha, reynolds)
        alone, second_alone = polar.evaluate(alpha, reynolds), polar.second_derivatives(alpha, reynolds)
    for got, expected in zip((*values, *second), (*alone, *second_alone)):
        assert got.shape == (3, 4)
        np.testing.assert_array_equal(got, expected)
