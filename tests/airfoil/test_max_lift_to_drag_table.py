"""Tests of the warm-started maximum-L/D point (per-polar table of alpha*(ln Re), exact Newton finish)."""
import warnings

import numpy as np
import pytest

from bild_mdo.airfoil import AnalyticPolar, MaxLiftToDrag, TabulatedPolar, max_lift_to_drag
from bild_mdo.airfoil.max_lift_to_drag_table import max_lift_to_drag_tabulated
from bild_mdo.airfoil.sources import PolarData


@pytest.fixture(scope="module")
def analytic():
    return AnalyticPolar(reynolds_exponent=0.2)


@pytest.fixture()
def surrogate():
    # A fresh polar per test: its table starts empty.  Data of an analytic polar at five Reynolds
    # numbers, as in test_max_lift_to_drag.py (the surrogate's Re dependence enters cl and cd).
    src = AnalyticPolar(reynolds_exponent=0.2, cl0=0.35)
    alpha = np.arange(-10.0, 20.01, 0.5)
    tables = []
    for re in (5e4, 1e5, 3e5, 1e6, 2e6):
        v = src.evaluate(np.radians(alpha), re)
        tables.append(PolarData(re, 0.0, alpha, v.cl, v.cd, f"analytic {re:g}"))
    return TabulatedPolar(tables)


def test_matches_closed_form_of_analytic_polar(analytic):
    # Hand derivation (AnalyticPolar docstring and test_max_lift_to_drag.py): the closed-form maximum.
    reynolds = np.array([[1e5, 4e5, 1e6], [2e6, 5e6, 1e7]])
    m = max_lift_to_drag_tabulated(analytic, reynolds)
    assert isinstance(m, MaxLiftToDrag) and m.alpha.shape == reynolds.shape
    alpha, cl, cd = analytic.max_lift_to_drag_closed_form(reynolds)
    np.testing.assert_allclose(m.alpha, alpha, rtol=1e-12)
    np.testing.assert_allclose(m.cl, cl, rtol=1e-13)
    np.testing.assert_allclose(m.cd, cd, rtol=1e-13)


def test_same_root_and_derivatives_as_the_scan_solver(surrogate):
    # The exact solver (scan bracket, then Newton) is the definition of the point; the warm start
    # must land on the same root of g = cl_a cd - cl cd_a to round-off, with the same derivatives.
    reynolds = np.exp(np.random.default_rng(4).uniform(np.log(5.2e4), np.log(1.9e6), 3000))
    exact = max_lift_to_drag(surrogate, reynolds)
    warm = max_lift_to_drag_tabulated(surrogate, reynolds)
    np.testing.assert_allclose(warm.alpha, exact.alpha, rtol=1e-12)
    np.testing.assert_allclose(warm.cl, exact.cl, rtol=1e-12)
    np.testing.assert_allclose(warm.cd, exact.cd, rtol=1e-12)
    for name in ("dalpha_dre", "dcl_dre", "dcd_dre"):
        scale = np.max(np.abs(getattr(exact, name)))
        np.testing.assert_allclose(getattr(warm, name), getattr(exact, name), rtol=1e-7, atol=1e-9 * scale)
    # A second query is served by the same table and gives the same values.
    again = max_lift_to_drag_tabulated(surrogate, reynolds[:7])
    np.testing.assert_array_equal(again.alpha, warm.alpha[:7])


def test_result_does_not_depend_on_the_other_queries(surrogate):
    # A design's point is the same alone or in a batch (BILDGroup: nodes do not interact).
    reynolds = np.geomspace(6e4, 1.5e6, 50)
    batch = max_lift_to_drag_tabulated(surrogate, reynolds)
    alone = [max_lift_to_drag_tabulated(surrogate, reynolds[[k]]).alpha[0] for k in (0, 17, 49)]
    np.testing.assert_array_equal(alone, batch.alpha[[0, 17, 49]])


def test_complex_reynolds_carries_the_derivative(analytic):
    h = 1e-30
    m = max_lift_to_drag_tabulated(analytic, np.array([3e5 + 1j * h, 3e6 + 1j * h]))
    assert np.iscomplexobj(m.alpha)
    np.testing.assert_allclose(m.alpha.imag / h, m.dalpha_dre, rtol=1e-14)
    np.testing.assert_allclose(m.cl.imag / h, m.dcl_dre, rtol=1e-14)
    np.testing.assert_allclose(m.cd.imag / h, m.dcd_dre, rtol=1e-14)


def test_errors_and_other_polars_go_to_the_exact_solver(analytic):
    with pytest.raises(ValueError, match="finite"):
        max_lift_to_drag_tabulated(analytic, np.array([1e6, np.nan]))
    # A polar that varies with Mach number is solved by the exact solver itself.
    mach_polar = AnalyticPolar(reynolds_exponent=0.2)
    mach_polar.varies_with_mach = True
    reynolds = np.array([2e5, 8e5])
    np.testing.assert_array_equal(max_lift_to_drag_tabulated(mach_polar, reynolds).alpha,
                                  max_lift_to_drag(mach_polar, reynolds).alpha)


def test_out_of_range_warning_comes_from_the_query(surrogate):
    # The table's nodes are solved silently; a Reynolds number outside the data still warns once.
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        max_lift_to_drag_tabulated(surrogate, np.array([3e5]))
    assert not [w for w in caught if "Reynolds" in str(w.message)]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        max_lift_to_drag_tabulated(surrogate, np.array([2e4]))
    assert [w for w in caught if "2e+04" in str(w.message)]


def test_point_without_derivatives_is_the_same_root_with_lazy_derivatives(surrogate):
    # derivatives=False: the first Newton pass without second derivatives (table curvature) lands on the
    # exact solver's root to round-off, and the derivatives evaluated on first use are the full result's.
    reynolds = np.exp(np.random.default_rng(5).uniform(np.log(5.2e4), np.log(1.9e6), 2000))
    exact = max_lift_to_drag(surrogate, reynolds)
    lazy = max_lift_to_drag_tabulated(surrogate, reynolds, derivatives=False)
    full = max_lift_to_drag_tabulated(surrogate, reynolds)
    np.testing.assert_allclose(lazy.alpha, exact.alpha, rtol=1e-12)
    np.testing.assert_allclose(lazy.cl, exact.cl, rtol=1e-12)
    np.testing.assert_allclose(lazy.cd, exact.cd, rtol=1e-12)
    for name in ("dalpha_dre", "dcl_dre", "dcd_dre"):
        np.testing.assert_allclose(getattr(lazy, name), getattr(full, name), rtol=1e-9)
    np.testing.assert_array_equal(lazy.full().alpha, lazy.alpha)
