"""Elementary functions that accept plain arrays or :class:`~bild_mdo.utils.jet.Jet` values alike.

BPM's fits are written once with these helpers: called with arrays (real or complex) they return arrays,
called with jets they return jets whose partials are the exact first derivatives.  Everything is
complex-safe: no ``abs``/``maximum`` of differentiated values; piecewise fits switch on the real part
(:func:`where`) and every branch keeps its own derivative.
"""
from __future__ import annotations

import numpy as np

from bild_mdo.utils.jet import Jet

_LN10 = np.log(10.0)


def value(x):
    """The value of ``x`` (a jet's value, or ``x`` itself)."""
    return x.v if isinstance(x, Jet) else x


def real_value(x):
    """The real part of the value of ``x``: what the piecewise fits switch on."""
    return np.real(value(x))


def _chain(x, fx, dfx):
    """``f(x)`` with the partials of ``x`` times ``f'(x)`` (``x`` a jet) or just ``f(x)``."""
    if isinstance(x, Jet):
        return Jet(fx, {k: d * dfx for k, d in x.d.items()})
    return fx


#: The one seed of :func:`univariate`'s inner evaluation (a name no caller uses).
_UNIVARIATE_SEED = "__univariate__"


def univariate(function, x):
    """``function(x)`` for an elementwise function of ``x`` alone, with the partials of ``x`` chained once.

    With a jet ``x`` of many partials, ``function`` runs on its value with a single seed and its derivative
    multiplies each partial of ``x`` once: the same value and partials as ``function(x)``, without carrying
    every partial through every operation of ``function``.
    """
    if not isinstance(x, Jet):
        return function(x)
    inner = function(Jet(x.v, {_UNIVARIATE_SEED: 1.0}))
    if not isinstance(inner, Jet):
        return inner
    return _chain(x, inner.v, inner.partial(_UNIVARIATE_SEED))


def log10(x):
    """``log10(x)`` for ``x > 0``."""
    v = value(x)
    return _chain(x, np.log10(v), 1.0 / (v * _LN10) if isinstance(x, Jet) else None)


def cos(x):
    """``cos(x)``."""
    v = value(x)
    return _chain(x, np.cos(v), -np.sin(v) if isinstance(x, Jet) else None)


def sin(x):
    """``sin(x)``."""
    v = value(x)
    return _chain(x, np.sin(v), np.cos(v) if isinstance(x, Jet) else None)


def pow10(x):
    """``10**x``."""
    fx = 10.0 ** value(x)
    return _chain(x, fx, fx * _LN10)


def sqrt(x):
    """``sqrt(x)`` for ``x > 0``."""
    fx = np.sqrt(value(x))
    return _chain(x, fx, 0.5 / fx if isinstance(x, Jet) else None)


def power(x, exponent):
    """``x**exponent`` for a constant (real) exponent and ``x > 0``."""
    v = value(x)
    return _chain(x, v ** exponent, exponent * v ** (exponent - 1.0) if isinstance(x, Jet) else None)


def square(x):
    """``x**2``."""
    return x * x


def sign_abs(x):
    """``|x|`` as ``sign(Re x) * x``: complex-safe, derivative ``sign(Re x)`` (the kink at 0 is BPM's own)."""
    return x * np.where(real_value(x) < 0.0, -1.0, 1.0)


def where(condition, a, b):
    """``a`` where ``condition`` (a real boolean array), else ``b``; values and partials selected alike."""
    va, vb = value(a), value(b)
    result = np.where(condition, va, vb)
    if not isinstance(a, Jet) and not isinstance(b, Jet):
        return result
    da = a.d if isinstance(a, Jet) else {}
    db = b.d if isinstance(b, Jet) else {}
    return Jet(result, {k: np.where(condition, da.get(k, 0.0), db.get(k, 0.0)) for k in set(da) | set(db)})


def piecewise(x, edges, branches, pure=False):
    """Evaluate a piecewise fit of ``x``: ``branches[i]`` on ``edges[i-1] < Re x <= edges[i]``.

    Each branch is evaluated on ``x`` replaced, outside its own interval, by a point inside it (the
    midpoint of a bounded interval, else its finite edge), so branches with a restricted domain (square
    roots) never see a value outside it; the result is assembled with :func:`where`.  A NaN argument gives
    NaN (the value and the partials of the argument's own seeds), never a branch's number; -inf belongs to
    the first branch, +inf to the last.

    Parameters
    ----------
    x : array or Jet
        The switching variable.
    edges : sequence of float or real arrays
        ``len(branches) - 1`` increasing breakpoints (broadcastable against ``x``); a point on an edge
        belongs to the lower branch.
    branches : sequence of callable
        ``branch(x) -> array or Jet``.
    pure : bool
        Every branch is a function of ``x`` alone, elementwise (no other array inside): for an array ``x``
        (not a jet) each branch is then evaluated only at the points of its own interval.
    """
    xr = real_value(x)
    edges = [np.real(e) for e in edges]
    lower = [-np.inf] + edges
    upper = edges + [np.inf]
    if pure and not isinstance(x, Jet) and len(branches) > 1 and all(np.ndim(e) == 0 for e in edges):
        return _piecewise_points(x, xr, lower, upper, branches)
    result = None
    for i, (lo, hi, branch) in enumerate(zip(lower, upper, branches)):
        inside = (xr <= hi) if i == 0 else (xr > lo) & (xr <= hi)  # -inf belongs to the first branch
        if len(branches) == 1:
            out = branch(x)
        else:
            fill = hi if i == 0 else (lo if i == len(branches) - 1 else 0.5 * (lo + hi))
            out = branch(where(inside, x, fill))
        result = out if result is None else where(inside, out, result)
    nan = np.isnan(xr)
    return where(nan, x * np.nan, result) if nan.any() else result


def _piecewise_points(x, xr, lower, upper, branches):
    """:func:`piecewise` of an array ``x`` with pure branches: each evaluated at its own points only (the same
    values, elementwise); a NaN argument gives NaN, as there."""
    x = np.asarray(x)
    out = np.empty(x.shape, dtype=np.result_type(x, float))
    covered = np.zeros(x.shape, dtype=bool)
    for i, (lo, hi, branch) in enumerate(zip(lower, upper, branches)):
        inside = (xr <= hi) if i == 0 else (xr > lo) & (xr <= hi)
        if inside.any():
            out[inside] = branch(x[inside])
            covered |= inside
    out[~covered] = np.nan
    return out
