"""The one safeguarded, vectorised Newton solver with a bracket, used by every scalar solve in bild-mdo.

Every implicit quantity in the package is a scalar root per element of a large
batch: the BEM inflow angle phi per station (Ning 2014), the reference-station
inflow angle per design, the annular efficiency eta2 per station (the BILD
quartic) and the angle of attack of maximum L/D per Reynolds number.  Each
caller finds a bracket ``[lo, hi]`` with a sign change from its own physics and
hands it here with ``f(x, idx) -> (f, df/dx[, scale])``, evaluated only at the
flat indices ``idx`` still iterating, so large batches stay cheap.

Inside the bracket every element takes a Newton step, replaced by a bisection
step whenever Newton leaves the bracket, is not finite, or fails to halve
``|f|`` (so the bracket at least halves every other iteration and convergence
is guaranteed for a continuous ``f``).  An element is converged when

* ``|f| <= atol``, or ``|f| <= 4 eps scale`` where ``f`` supplies ``scale``
  (the magnitude of its terms: f is zero to round-off), or
* the Newton correction is below round-off of ``x`` (it is still applied), or
* the bracket has shrunk to round-off of ``x``.

Elements that reach ``max_iter`` or whose ``f`` is not finite are reported as
not converged in :class:`NewtonResult`; the solver never returns a silent
guess, and the caller raises with a message in its own terms.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

_EPS = np.finfo(float).eps


class NewtonResult(NamedTuple):
    """Outcome of :func:`bracketed_newton`, each an array of the batch size.

    Attributes
    ----------
    x : ndarray
        Roots (or the last iterate where ``converged`` is False).  Where the
        last Newton correction was below round-off it has been applied, so
        ``residual`` and ``slope`` belong to the iterate before it.
    converged : ndarray of bool
        True where one of the convergence tests holds.
    residual : ndarray
        ``f`` at the last iterate (NaN or inf where it was not finite).
    slope : ndarray
        ``df/dx`` at the last iterate.
    iterations : ndarray of int
        Evaluations of ``f`` per element, the first one included.
    """

    x: np.ndarray
    converged: np.ndarray
    residual: np.ndarray
    slope: np.ndarray
    iterations: np.ndarray

    def first_failure(self):
        """Flat index of the first element that did not converge, or None."""
        bad = np.flatnonzero(~self.converged)
        return int(bad[0]) if bad.size else None


def false_position(lo, hi, f_lo, f_hi):
    """The false-position point of each bracket (its midpoint where ``f_lo == f_hi``)."""
    lo, hi, f_lo, f_hi = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (lo, hi, f_lo, f_hi)))
    denom = f_hi - f_lo
    with np.errstate(invalid="ignore", divide="ignore"):
        x = np.where(denom != 0.0, lo - f_lo * (hi - lo) / denom, 0.5 * (lo + hi))
    return np.clip(x, np.minimum(lo, hi), np.maximum(lo, hi))


def bracketed_newton(function, lo, hi, f_lo, x0=None, *, atol=0.0, max_iter=100, x_scale=1e-3,
                     quadratic_stop=False, xtol=0.0):
    """Solve ``f(x) = 0`` for every element, with ``x`` kept inside ``[lo, hi]``.

    Parameters
    ----------
    function : callable
        ``function(x, idx)`` returns ``(f, df_dx)`` or ``(f, df_dx, scale)`` at the
        flat indices ``idx`` (an integer array) and trial values ``x`` of the same
        length; ``scale >= 0`` bounds the magnitude of the terms of ``f`` so that
        ``4 eps scale`` is its rounding error.
    lo, hi : array_like
        Bracket end points, shape ``(n,)``; ``f(lo)`` and ``f(hi)`` differ in sign
        (or one is zero).  Either may be the larger.
    f_lo : array_like
        ``f(lo)``, shape ``(n,)``; only its sign is used.
    x0 : array_like, optional
        First iterate; where it lies outside the closed bracket, is not finite
        (or by default) the midpoint is used.  Callers with a cheap good
        estimate (or the false-position point, :func:`false_position`) should
        pass it.
    atol : float
        Absolute residual tolerance.
    max_iter : int
        Iterations after the first evaluation (bisection alone needs ~55 from a
        width of pi).
    x_scale : float
        Floor of ``|x|`` in the round-off tests, for roots at ``x = 0``.
    quadratic_stop : bool
        Also converged (saving the evaluation that would only confirm it) when
        two Newton steps in a row show quadratic convergence that leaves the
        applied correction's predicted error ``|step|**3 / |previous step|**2``
        below ``eps |x| / 4`` (half an ulp); the correction is applied.
        Default False (the behaviour of earlier releases, bit for bit).
    xtol : float
        With ``quadratic_stop``: also converged when that predicted error is
        at most ``xtol`` (absolute, in the units of ``x``; default 0) and the
        correction itself at most ``sqrt(xtol)`` (a step that is small only
        against a large one before it, outside the quadratic regime, does not
        stop the solve).

    Returns
    -------
    NewtonResult
    """
    lo = np.array(lo, dtype=float).ravel()
    hi = np.array(hi, dtype=float).ravel()
    n = lo.size
    sign_lo = np.sign(np.broadcast_to(np.asarray(f_lo, dtype=float).ravel(), (n,)))
    x = 0.5 * (lo + hi)
    if x0 is not None:
        guess = np.broadcast_to(np.asarray(x0, dtype=float).ravel(), (n,))
        inside = (guess - lo) * (guess - hi) <= 0.0
        x = np.where(inside, guess, x)
    f = np.full(n, np.nan)
    slope = np.full(n, np.nan)
    converged = np.zeros(n, dtype=bool)
    iterations = np.zeros(n, dtype=int)

    # Working arrays of the elements still iterating (compacted as they finish).  The loop body is
    # written for small batches too (one design: tens of elements), where each NumPy call costs more
    # than its arithmetic: method calls instead of module functions, no temporary beyond need.
    active = np.arange(n)
    # Ordered brackets lo_w <= hi_w, with the sign of f at lo_w (the sign at the other end is opposite).
    swap = lo > hi
    lo_w, hi_w = np.where(swap, hi, lo), np.where(swap, lo, hi)
    sign_w = np.where(swap, -sign_lo, sign_lo)
    xa = x.copy()
    f_prev = np.full(n, np.inf)
    step_prev = np.zeros(n)  # |previous Newton step|; 0 after a bisection step or at the start
    four_eps = 4.0 * _EPS
    root_xtol = np.sqrt(xtol)
    caller = np.geterr()  # the function runs under the caller's floating-point error handling
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for count in range(1, max_iter + 2):
            with np.errstate(**caller):
                out = function(xa, active)
            fa = np.asarray(out[0], dtype=float)
            da = np.asarray(out[1], dtype=float)
            # Keep the bracket: replace the end point whose f has the sign of f(x).
            same_lo = np.sign(fa) == sign_w
            lo_w = np.where(same_lo, xa, lo_w)
            hi_w = np.where(same_lo, hi_w, xa)

            step = fa / da
            abs_step = np.abs(step)
            roundoff = four_eps * np.maximum(np.abs(xa), x_scale)
            abs_f = np.abs(fa)
            if len(out) > 2:
                at_root = abs_f <= four_eps * out[2]
                if atol > 0.0:
                    at_root |= abs_f <= atol
            else:
                at_root = abs_f <= atol
            small = abs_step <= roundoff
            if quadratic_stop:
                cube = abs_step * abs_step * abs_step
                small |= cube <= 0.0625 * roundoff * step_prev * step_prev
                if xtol > 0.0:
                    small |= (cube <= xtol * step_prev * step_prev) & (abs_step <= root_xtol)
            small_step = small & ~at_root
            finite = np.isfinite(fa)
            done = (at_root | small_step | (hi_w - lo_w <= roundoff)) & finite
            keep = ~done & finite
            if not keep.all():
                # A correction below round-off is still the better estimate: apply it (within the bracket).
                xa_out = np.where(done & small_step, np.minimum(np.maximum(xa - step, lo_w), hi_w), xa)
                gone = ~keep
                idx = active[gone]
                x[idx] = xa_out[gone]
                f[idx] = fa[gone]
                slope[idx] = da[gone]
                iterations[idx] = count
                converged[idx] = done[gone]
                if not keep.any():
                    break
                active, xa, fa, da, step, abs_f = active[keep], xa[keep], fa[keep], da[keep], step[keep], abs_f[keep]
                lo_w, hi_w, sign_w = lo_w[keep], hi_w[keep], sign_w[keep]
                f_prev = f_prev[keep]
                abs_step = abs_step[keep]
            newton = xa - step
            bisect = ~((newton > lo_w) & (newton < hi_w)) | (abs_f > 0.5 * f_prev)
            f_prev = abs_f
            step_prev = np.where(bisect, 0.0, abs_step)
            xa = np.where(bisect, 0.5 * (lo_w + hi_w), newton)
        else:
            # Out of iterations: the elements still active keep their next iterate (not converged).
            x[active], f[active], slope[active], iterations[active] = xa, fa, da, max_iter + 1
    return NewtonResult(x, converged, f, slope, iterations)


def complex_step_update(x_real, residual_complex, slope_real):
    """One Newton update in complex arithmetic after a real solve (complex-step totals).

    With ``x_real`` the converged real root, ``residual_complex`` the residual at
    ``x_real`` with the complex-perturbed inputs, and ``slope_real`` the real
    ``dR/dx``, the imaginary part of ``x_real - R / R'`` is ``(dx/dinput) h``: the
    exact implicit derivative.  Only the imaginary part of the update is kept, so
    the real solution stays bit-identical to the real solve.
    """
    return x_real - 1j * np.imag(residual_complex) / slope_real
