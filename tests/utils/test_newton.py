"""The one safeguarded Newton solver: hand-derived roots, non-convergence reported, complex-step update."""
import numpy as np

from bild_mdo.utils.newton import bracketed_newton, complex_step_update, false_position


def _cube_minus(c):
    """f(x) = x**3 - c, f' = 3 x**2: the root is the real cube root of c (hand derivation)."""
    def function(x, idx):
        return x**3 - c[idx], 3.0 * x**2
    return function


def test_cube_root_of_two_bracketed():
    c = np.array([2.0, 2.0, 27.0])
    lo, hi = np.array([0.0, 2.0, 0.0]), np.array([2.0, 0.0, 4.0])  # either end may be the larger
    f_lo = lo**3 - c
    result = bracketed_newton(_cube_minus(c), lo, hi, f_lo)
    assert np.all(result.converged)
    np.testing.assert_allclose(result.x, [2.0 ** (1.0 / 3.0), 2.0 ** (1.0 / 3.0), 3.0], rtol=0, atol=4e-16)
    assert result.first_failure() is None


def test_only_iterating_elements_are_evaluated():
    c = np.array([1.0, 8.0, 1000.0])
    sizes = []

    def function(x, idx):
        sizes.append(idx.size)
        return x**3 - c[idx], 3.0 * x**2

    bracketed_newton(function, np.zeros(3), np.full(3, 20.0), -c, x0=np.array([1.0, 1.0, 1.0]))
    # x0 = 1 is the exact root of the first element: it leaves after one evaluation.
    assert sizes[0] == 3 and sizes[1] == 2


def test_non_convergence_is_reported_not_hidden():
    # f = x**3 - 2 with a budget of 2 iterations from the midpoint of [0, 100] cannot converge.
    c = np.array([2.0])
    result = bracketed_newton(_cube_minus(c), np.zeros(1), np.full(1, 100.0), -c, max_iter=2)
    assert not result.converged[0]
    assert result.first_failure() == 0
    assert result.iterations[0] == 3


def test_non_finite_function_is_reported():
    def function(x, idx):
        return np.where(idx == 1, np.nan, x - 0.25), np.ones_like(x)
    result = bracketed_newton(function, np.zeros(2), np.ones(2), -np.ones(2))
    np.testing.assert_array_equal(result.converged, [True, False])
    assert np.isnan(result.residual[1])


def test_scale_based_convergence_stops_at_round_off():
    # f = 1e20 (x - 1/3) is zero to round-off at the double nearest 1/3, where |f| ~ 1e20 eps:
    # no absolute tolerance could accept it, the scale of its terms (1e20) does.
    def function(x, idx):
        return 1e20 * x - 1e20 / 3.0, np.full_like(x, 1e20), np.full_like(x, 1e20)
    result = bracketed_newton(function, np.zeros(1), np.ones(1), -np.ones(1))
    assert result.converged[0]
    assert abs(result.x[0] - 1.0 / 3.0) <= 2 * np.spacing(1.0 / 3.0)
    assert result.iterations[0] <= 3


def test_false_position_point():
    # Chord through (0, -1) and (2, 3) crosses zero at x = 0.5; equal values give the midpoint.
    np.testing.assert_allclose(false_position([0.0, 0.0], [2.0, 2.0], [-1.0, 1.0], [3.0, 1.0]), [0.5, 1.0])


def test_complex_step_update_gives_implicit_derivative():
    # x**3 - c = 0: dx/dc = 1 / (3 x**2) (implicit function theorem).
    c = np.array([2.0, 5.0])
    x = bracketed_newton(_cube_minus(c), np.zeros(2), np.full(2, 3.0), -c).x
    h = 1e-30
    x_c = complex_step_update(x, x**3 - (c + 1j * h), 3.0 * x**2)
    np.testing.assert_array_equal(np.real(x_c), x)
    np.testing.assert_allclose(np.imag(x_c) / h, 1.0 / (3.0 * x**2), rtol=1e-14)
