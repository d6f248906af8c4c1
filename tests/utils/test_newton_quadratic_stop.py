"""bracketed_newton(quadratic_stop=True): one evaluation less, the root as accurate."""
import decimal

import numpy as np

from bild_mdo.utils.newton import bracketed_newton


def _cube_minus(c):
    def function(x, idx):
        return x ** 3 - c[idx], 3.0 * x ** 2
    return function


def test_root_within_half_an_ulp_with_fewer_evaluations():
    # Hand derivation: the root of x**3 - c is the cube root of c.
    c = np.linspace(1.0, 8.0, 200)
    lo, hi = np.zeros(c.size), np.full(c.size, 3.0)
    start = np.cbrt(c) * (1.0 + 1e-3)
    plain = bracketed_newton(_cube_minus(c), lo, hi, -c, start)
    quick = bracketed_newton(_cube_minus(c), lo, hi, -c, start, quadratic_stop=True)
    assert np.all(quick.converged)
    # As accurate as without the option: within one ulp (the rounding of f itself limits both) of the cube
    # root rounded from 50-digit decimal arithmetic (np.cbrt is not correctly rounded everywhere: SIMD
    # builds of numpy differ from it by up to 2 ulp).
    with decimal.localcontext() as context:
        context.prec = 50
        exact = np.array([float(decimal.Decimal(x) ** (decimal.Decimal(1) / 3)) for x in c])
    assert np.all(np.abs(quick.x - exact) <= np.spacing(exact))
    assert np.all(np.abs(plain.x - exact) <= np.spacing(exact))
    assert np.all(quick.iterations <= plain.iterations) and quick.iterations.sum() < plain.iterations.sum()


def test_default_is_unchanged_by_the_option():
    # Without the option every element still needs the confirming evaluation (its last step below round-off).
    c = np.array([2.0, 5.0])
    result = bracketed_newton(_cube_minus(c), np.zeros(2), np.full(2, 3.0), -c, np.cbrt(c) * 1.01)
    assert np.all(result.converged)
    np.testing.assert_allclose(result.x, np.cbrt(c), rtol=2e-16)
