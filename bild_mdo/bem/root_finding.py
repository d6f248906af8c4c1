"""Vectorised, guaranteed-bracket solve of the BEM residual for the inflow angle.

Follows Ning (2014), "A simple solution method for the blade element momentum
equations with guaranteed convergence", Wind Energy 17(9): the residual is a
function of the single unknown ``phi``, so a bracket guarantees convergence.
The bracket is searched region by region, each station taking the first region
whose end points have opposite signs:

1. ``[eps, pi/2]``        (normal operation: thrust-producing propeller/rotor),
2. ``[-pi/4, -eps]``      (windmill / propeller-brake with negative inflow angle),
3. ``[pi/2, pi - eps]``   (propeller-brake with reversed tangential flow),

and, as a last resort, a scan of ``[-pi/2, pi - eps]`` for any sign change.
Inside the bracket a safeguarded Newton iteration (a bisection step whenever
Newton leaves the bracket or fails to halve ``|R|``) converges to round-off.

The solver does not know the physics: it calls ``residual(phi, idx)`` where
``idx`` is an integer array of flat station indices and ``phi`` holds the
trial angles at those stations, and which returns ``(R, dR_dphi)`` (total
derivative along the station's own ``phi``).  Evaluating only the stations
still iterating keeps large batches cheap.  The BEM inflow component passes
a residual that evaluates the polar; the BILD reference-station solve passes
one with fixed ``cl, cd``.
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

#: Distance of the search intervals from phi = 0 and phi = pi (rad), as in Ning (2014).
BRACKET_EPS = 1e-6
#: Residual magnitude accepted as converged.
RESIDUAL_TOL = 1e-13
#: Safeguarded Newton iterations before giving up (bisection alone needs ~55).
MAX_ITER = 200

_REGIONS = (
    (BRACKET_EPS, 0.5 * np.pi),
    (-0.25 * np.pi, -BRACKET_EPS),
    (0.5 * np.pi, np.pi - BRACKET_EPS),
)
_SCAN = np.concatenate([np.linspace(-0.5 * np.pi, -BRACKET_EPS, 19),
                        np.linspace(BRACKET_EPS, np.pi - BRACKET_EPS, 37)])


def _default_describe(shape):
    def describe(flat_index):
        if len(shape) == 2:
            node, station = np.unravel_index(flat_index, shape)
            return f"design/node {node}, station {station}"
        return f"station {flat_index}"
    return describe


def find_brackets(residual, size, describe=None, shape=None):
    """Find ``[lo, hi]`` with a sign change of the residual at every station.

    Parameters
    ----------
    residual : callable
        ``residual(phi, idx) -> (R, dR_dphi)`` on flat index arrays.
    size : int
        Number of stations.
    describe : callable, optional
        ``describe(flat_index) -> str`` naming a station in error messages.
    shape : tuple, optional
        ``(num_nodes, num_radial)``, used by the default ``describe``.

    Returns
    -------
    lo, hi, r_lo, r_hi : ndarray
        Bracket end points (rad) and residuals there, shape ``(size,)``.

    Raises
    ------
    openmdao.api.AnalysisError
        If a station has no sign change anywhere in ``[-pi/2, pi)``.
    """
    describe = describe or _default_describe(shape or (size,))
    lo = np.full(size, np.nan)
    hi = np.full(size, np.nan)
    r_lo = np.full(size, np.nan)
    r_hi = np.full(size, np.nan)
    todo = np.arange(size)
    # R(pi/2) ends region 1 and starts region 3: evaluate it once per station.
    r_half = np.full(size, np.nan)
    for a, b in _REGIONS:
        if todo.size == 0:
            break
        if a == 0.5 * np.pi:
            ra = r_half[todo]
        else:
            ra = residual(np.full(todo.size, a), todo)[0]
        rb = residual(np.full(todo.size, b), todo)[0]
        if b == 0.5 * np.pi:
            r_half[todo] = rb
        _check_finite(ra, todo, a, describe)
        _check_finite(rb, todo, b, describe)
        ok = ra * rb <= 0.0
        idx = todo[ok]
        lo[idx], hi[idx], r_lo[idx], r_hi[idx] = a, b, ra[ok], rb[ok]
        todo = todo[~ok]
    if todo.size:
        lo, hi, r_lo, r_hi = _scan(residual, todo, lo, hi, r_lo, r_hi, describe)
    return lo, hi, r_lo, r_hi


def _scan(residual, todo, lo, hi, r_lo, r_hi, describe):
    """Fallback: first sign change on a grid over [-pi/2, pi - eps]."""
    n = todo.size
    grid = np.broadcast_to(_SCAN, (n, _SCAN.size))
    stations = np.repeat(todo, _SCAN.size)
    values = residual(grid.ravel(), stations)[0]
    _check_finite(values, stations, grid.ravel(), describe)
    values = values.reshape(n, _SCAN.size)
    change = values[:, :-1] * values[:, 1:] <= 0.0
    found = change.any(axis=1)
    if not np.all(found):
        bad = todo[~found][0]
        raise om.AnalysisError(
            f"BEM inflow solve: no inflow angle phi in [-pi/2, pi) makes the residual change "
            f"sign at {describe(bad)} ({np.count_nonzero(~found)} station(s) in all). "
            "The operating point or blade geometry is outside the range the momentum "
            "model can represent (check twist, chord, rpm and v_axial).")
    first = np.argmax(change, axis=1)
    rows = np.arange(n)
    lo[todo] = _SCAN[first]
    hi[todo] = _SCAN[first + 1]
    r_lo[todo] = values[rows, first]
    r_hi[todo] = values[rows, first + 1]
    return lo, hi, r_lo, r_hi


def _check_finite(values, idx, phi, describe):
    bad = ~np.isfinite(values)
    if np.any(bad):
        first = np.argmax(bad)
        phi_bad = np.broadcast_to(phi, values.shape)[first]
        raise om.AnalysisError(
            f"BEM inflow solve: the residual is not finite at phi = {phi_bad:.6g} rad at "
            f"{describe(idx[first])}; check the inputs (chord, radii, rpm) and the polar.")


def solve_bracketed(residual, size, describe=None, shape=None, tol=RESIDUAL_TOL, max_iter=MAX_ITER,
                    initial_guess=None):
    """Solve ``R(phi) = 0`` at every station with a bracketed, safeguarded Newton method.

    Parameters
    ----------
    residual : callable
        ``residual(phi, idx) -> (R, dR_dphi)``: residual and its total derivative with
        respect to phi at the flat station indices ``idx`` (real arrays).
    size : int
        Number of stations (the flat length of phi).
    describe : callable, optional
        ``describe(flat_index) -> str`` naming a station in error messages.
    shape : tuple, optional
        ``(num_nodes, num_radial)``; names stations as (design/node, station) by default.
    tol : float
        Converged when ``|R| <= tol``, when the Newton step is below round-off of
        phi, or when the bracket has shrunk to round-off.
    max_iter : int
        Iteration limit (bisection alone needs ~55 iterations from a width of pi).
    initial_guess : array_like, optional
        First Newton iterate (rad), used at stations where it lies strictly inside the
        bracket found; elsewhere (and by default) the false-position point of the bracket.
        A good guess saves iterations; it cannot change which bracket is searched.

    Returns
    -------
    phi : ndarray
        Inflow angles (rad), shape ``(size,)``.

    Raises
    ------
    openmdao.api.AnalysisError
        No bracket at some station, a non-finite residual, or no convergence.
    """
    describe = describe or _default_describe(shape or (size,))
    lo, hi, r_lo, r_hi = find_brackets(residual, size, describe=describe)

    # False position as the first iterate: strictly inside a strict bracket.
    denom = r_hi - r_lo
    with np.errstate(invalid="ignore", divide="ignore"):
        x = np.where(denom != 0.0, lo - r_lo * (hi - lo) / denom, 0.5 * (lo + hi))
    x = np.clip(x, lo, hi)
    if initial_guess is not None:
        guess = np.broadcast_to(np.asarray(initial_guess, dtype=float), (size,))
        inside = (guess - lo) * (guess - hi) < 0.0
        x = np.where(inside, guess, x)
    r, dr = residual(x, np.arange(size))
    r = np.array(r, dtype=float)
    dr = np.array(dr, dtype=float)
    r_prev = np.full(size, np.inf)

    active = np.arange(size)
    for _ in range(max_iter):
        ra, da, xa = r[active], dr[active], x[active]
        _check_finite(ra, active, xa, describe)
        # Keep the bracket: replace the end point whose residual has the sign of R(x).
        same_lo = np.sign(ra) == np.sign(r_lo[active])
        lo[active] = np.where(same_lo, xa, lo[active])
        r_lo[active] = np.where(same_lo, ra, r_lo[active])
        hi[active] = np.where(same_lo, hi[active], xa)
        r_hi[active] = np.where(same_lo, r_hi[active], ra)

        with np.errstate(invalid="ignore", divide="ignore"):
            step = ra / da
        width = np.abs(hi[active] - lo[active])
        roundoff = 4.0 * np.finfo(float).eps * np.maximum(np.abs(xa), 1e-3)
        done = (np.abs(ra) <= tol) | (np.abs(step) <= roundoff) | (width <= roundoff)
        active = active[~done]
        if active.size == 0:
            return x
        ra, xa, step = ra[~done], xa[~done], step[~done]
        lo_a, hi_a = np.minimum(lo[active], hi[active]), np.maximum(lo[active], hi[active])
        newton = xa - step
        bisect = (~np.isfinite(newton) | (newton <= lo_a) | (newton >= hi_a)
                  | (np.abs(ra) > 0.5 * r_prev[active]))
        x_new = np.where(bisect, 0.5 * (lo_a + hi_a), newton)
        r_prev[active] = np.abs(ra)
        x[active] = x_new
        r_new, dr_new = residual(x_new, active)
        r[active] = r_new
        dr[active] = dr_new

    raise om.AnalysisError(
        f"BEM inflow solve did not converge in {max_iter} iterations at {describe(active[0])} "
        f"({active.size} station(s) in all); |R| = {np.abs(r[active[0]]):.3e}.")


def complex_newton_update(phi_real, residual_complex, dresidual_dphi_real):
    """One Newton update in complex arithmetic after a real solve (complex-step totals).

    With ``phi_real`` the converged real root, ``residual_complex`` the residual
    evaluated at ``phi_real`` with the complex-perturbed inputs, and
    ``dresidual_dphi_real`` the real total derivative dR/dphi, the update
    ``phi = phi_real - R / R'`` has an imaginary part equal to
    ``-(dR/dx h) / R'`` = ``(dphi/dx) h``: the exact implicit derivative.

    Returns
    -------
    ndarray
        Complex inflow angle.
    """
    return phi_real - residual_complex / dresidual_dphi_real
