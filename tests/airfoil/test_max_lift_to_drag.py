"""Tests of the exact maximum-L/D point and its Reynolds derivatives."""
import importlib
import warnings

import numpy as np
import pytest

from bild_mdo.airfoil import AnalyticPolar, MaxLiftToDrag, TabulatedPolar, max_lift_to_drag
from bild_mdo.airfoil.sources import PolarData

# The package re-exports the function under the module's name; this is the module.
MAX_LIFT_TO_DRAG_MODULE = importlib.import_module("bild_mdo.airfoil.max_lift_to_drag")


@pytest.fixture(scope="module")
def analytic():
    return AnalyticPolar(reynolds_exponent=0.2)


@pytest.fixture(scope="module")
def surrogate():
    # Data of an analytic polar at five Reynolds numbers; the surrogate's Re dependence
    # then also enters cl (through the stall blend) and the cross derivatives.
    src = AnalyticPolar(reynolds_exponent=0.2, cl0=0.35)
    alpha = np.arange(-10.0, 20.01, 0.5)
    tables = []
    for re in (5e4, 1e5, 3e5, 1e6, 2e6):
        v = src.evaluate(np.radians(alpha), re)
        tables.append(PolarData(re, 0.0, alpha, v.cl, v.cd, f"analytic {re:g}"))
    return TabulatedPolar(tables)


def test_matches_closed_form_of_analytic_polar(analytic):
    # Hand derivation (AnalyticPolar docstring): cl* = sqrt(cl_cd_min^2 + cd0 f / k),
    # f = (Re/1e6)^-0.2, so dcl*/dRe = cd0 f'(Re) / (2 k cl*).
    reynolds = np.array([[1e5, 4e5, 1e6], [2e6, 5e6, 1e7]])
    m = max_lift_to_drag(analytic, reynolds)
    assert isinstance(m, MaxLiftToDrag)
    alpha, cl, cd = analytic.max_lift_to_drag_closed_form(reynolds)
    np.testing.assert_allclose(m.alpha, alpha, rtol=1e-12)
    np.testing.assert_allclose(m.cl, cl, rtol=1e-13)
    np.testing.assert_allclose(m.cd, cd, rtol=1e-13)
    f_prime = -0.2 * (reynolds / 1e6) ** -0.2 / reynolds
    dcl = 0.008 * f_prime / (2.0 * 0.01 * cl)
    np.testing.assert_allclose(m.dcl_dre, dcl, rtol=1e-9)
    np.testing.assert_allclose(m.dalpha_dre, dcl / analytic.cl_alpha, rtol=1e-9)
    # cd* = 2 k cl* (cl* - cl_cd_min)  ->  dcd*/dRe = 2 k (2 cl* - cl_cd_min) dcl*/dRe.
    np.testing.assert_allclose(m.dcd_dre, 2 * 0.01 * (2 * cl - 0.4) * dcl, rtol=1e-9)
    assert m.alpha.shape == reynolds.shape


def test_solves_to_round_off(surrogate):
    reynolds = np.geomspace(6e4, 1.9e6, 40)
    m = surrogate.max_lift_to_drag(reynolds)
    v = surrogate.evaluate(m.alpha, reynolds)
    g = v.dcl_dalpha * v.cd - v.cl * v.dcd_dalpha
    # g ~ cl_a cd ~ 6 * 0.01, so round-off is ~1e-17; a 0.25 deg grid scan would leave ~1e-4.
    assert np.max(np.abs(g)) < 1e-13
    # And it is a maximum: L/D at +-0.1 deg is lower.
    for d in (-np.radians(0.1), np.radians(0.1)):
        w = surrogate.evaluate(m.alpha + d, reynolds)
        assert np.all(w.cl / w.cd < m.cl / m.cd)


def test_reynolds_derivatives_match_differences_of_the_maximum(surrogate):
    reynolds = np.geomspace(6e4, 1.8e6, 25)
    m = surrogate.max_lift_to_drag(reynolds)
    h = 1e-5 * reynolds
    mp = surrogate.max_lift_to_drag(reynolds + h)
    mm = surrogate.max_lift_to_drag(reynolds - h)
    for name in ("alpha", "cl", "cd"):
        fd = (getattr(mp, name) - getattr(mm, name)) / (2 * h) * reynolds
        an = getattr(m, f"d{name}_dre") * reynolds
        np.testing.assert_allclose(an, fd, rtol=1e-5, atol=1e-8 * np.max(np.abs(an)))
    # The implicit-function derivative is not trivially zero here.
    assert np.min(np.abs(m.dalpha_dre * reynolds)) > 1e-3


def test_complex_reynolds_carries_the_derivative(analytic):
    h = 1e-30
    m = max_lift_to_drag(analytic, np.array([3e5 + 1j * h, 3e6 + 1j * h]))
    assert np.iscomplexobj(m.alpha)
    np.testing.assert_allclose(m.alpha.imag / h, m.dalpha_dre, rtol=1e-14)
    np.testing.assert_allclose(m.cl.imag / h, m.dcl_dre, rtol=1e-14)
    np.testing.assert_allclose(m.cd.imag / h, m.dcd_dre, rtol=1e-14)
    real = max_lift_to_drag(analytic, np.array([3e5, 3e6]))
    np.testing.assert_array_equal(m.alpha.real, real.alpha)


def test_polar_method_delegates(analytic):
    a = analytic.max_lift_to_drag(7e5)
    b = max_lift_to_drag(analytic, 7e5)
    assert a == b


def test_scalar_reynolds_gives_zero_dimensional_results(analytic):
    m = max_lift_to_drag(analytic, 1e6)
    assert np.shape(m.alpha) == () and np.shape(m.dcd_dre) == ()


def test_no_interior_maximum_raises(analytic):
    # In 0..2 deg the analytic L/D still rises (alpha* = 5.9 deg): no interior maximum.
    with pytest.raises(ValueError, match="no interior maximum"):
        max_lift_to_drag(analytic, 1e6, alpha_range=(0.0, np.radians(2.0)))
    # A polar that never lifts positively has no maximum either.
    upside_down = AnalyticPolar(cl0=-0.4, cl_cd_min=-0.4)
    with pytest.raises(ValueError, match="no interior maximum"):
        max_lift_to_drag(upside_down, 1e6, alpha_range=(np.radians(-10.0), np.radians(-2.0)))


def test_rejects_nonfinite_reynolds(analytic):
    with pytest.raises(ValueError, match="finite"):
        max_lift_to_drag(analytic, np.array([1e6, np.nan]))


class _PolarWithHole(AnalyticPolar):
    """An analytic polar that is undefined (NaN) within 1e-4 rad of a given angle."""

    hole = 0.0

    def _evaluate_real(self, alpha, reynolds):
        values = super()._evaluate_real(alpha, reynolds)
        inside = np.abs(alpha - self.hole) < 1e-4
        return type(values)(*(np.where(inside, np.nan, v) for v in values))


def test_non_convergence_is_reported_with_the_reynolds_numbers():
    # The hole sits on the exact optimum of the second Reynolds number, between the
    # 0.25 deg scan points, so the scan brackets it and the iterates fall into it.
    polar = _PolarWithHole(reynolds_exponent=0.2)
    reynolds = np.array([2e5, 7e5])
    alpha_star, _, _ = polar.max_lift_to_drag_closed_form(reynolds)
    polar.hole = alpha_star[1]
    assert abs(alpha_star[1] - alpha_star[0]) > 1e-3
    with pytest.raises(ValueError, match=r"did not converge .* at Re = \[700000\.0\]"):
        max_lift_to_drag(polar, reynolds)


def test_iteration_limit_is_reported(analytic, monkeypatch):
    monkeypatch.setattr(MAX_LIFT_TO_DRAG_MODULE, "_MAX_ITERATIONS", 1)
    with pytest.raises(ValueError, match=r"did not converge in 1 Newton iterations at Re = "
                                         r"\[300000\.0, 3000000\.0\]"):
        max_lift_to_drag(analytic, np.array([3e5, 3e6]))


def test_reynolds_derivative_is_continuous_past_the_table_edge(surrogate):
    # Past the table the polar is extrapolated C1 in log Re (airfoil/surrogate.py), so the max-L/D point's
    # Reynolds derivatives continue the edge's (continuity of value and slope) instead of dropping to zero.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        edge = surrogate.max_lift_to_drag(np.array([2e6]))
        past = surrogate.max_lift_to_drag(np.array([2e6 * (1.0 + 1e-9)]))
    np.testing.assert_allclose(past.dcl_dre * 2e6, edge.dcl_dre * 2e6, rtol=1e-5)
    assert past.dcd_dre[0] != 0.0
