"""Vectorised, guaranteed-bracket solve of the BEM residual for the inflow angle.

Follows Ning (2014), "A simple solution method for the blade element momentum
equations with guaranteed convergence", Wind Energy 17(9): the residual is a
function of the single unknown ``phi``, so a bracket guarantees convergence.
The bracket is searched region by region, each station taking the first region
whose end points have opposite signs:

1. ``[eps, pi/2]``        (normal operation: thrust-producing propeller/rotor),
2. ``[-pi/4, -eps]``      (windmill / propeller-brake with negative inflow angle),
3. ``[pi/2, pi - eps]``   (propeller-brake with reversed tangential flow),

and, as a last resort, a scan of ``[-pi/2, pi - eps]`` for any sign change
(:func:`solve_bracketed`: BILD's reference station, and the BEM analysis with
``solve_range='full'``).  The BEM analysis by default uses :func:`solve_physical`:
CCBlade.jl's region order, accepting only kinematically consistent roots (``W > 0``).
Inside the bracket the package's one safeguarded Newton solver
(:func:`bild_mdo.utils.newton.bracketed_newton`) converges to round-off.

The solver does not know the physics: it calls ``residual(phi, idx)`` where
``idx`` is an integer array of flat station indices and ``phi`` holds the
trial angles at those stations, and which returns ``(R, dR_dphi)`` (total
derivative along the station's own ``phi``).  The BEM inflow component passes
a residual that evaluates the polar; the BILD reference-station solve passes
one with fixed ``lift_coefficient, drag_coefficient`` (``C_l*, C_d*``).
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.utils.newton import bracketed_newton, false_position

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


#: Largest distance (rad) of the cold start from the previous root for which the slopes at both give
#: the curvature of the warm start's Halley step.
_HALLEY_SPAN = 0.1


def warm_region_one(residual, previous, initial_guess=None, tol=RESIDUAL_TOL, max_iter=MAX_ITER, any_root=False):
    """Warm start: region-1 roots re-solved from a previous solve's roots, where they are the cold solve's roots.

    Both cold solves (:func:`solve_physical`, :func:`solve_bracketed`) first test region 1,
    ``[eps, pi/2]``, by the signs at its end points and solve in it when they differ.  Here, in ONE
    pass per station, the residual is evaluated at both end points, at the previous root ``p``, at
    the cold solve's first iterate ``c`` (``initial_guess``, where inside) and at ``m = (p + c)/2``; the bracket
    ``[eps, p]`` or ``[p, pi/2]`` (whichever has the sign change) is handed to
    :func:`~bild_mdo.utils.newton.bracketed_newton`, started at the Halley point from ``p`` (``R''``
    from ``R'`` at ``p`` and ``c``).
    A station is accepted only where the cold solve would search region 1 (strictly opposite
    end-point signs) and where everything evaluated is consistent with ONE simple root ``x`` in
    the region: the slopes at ``x``, ``p``, ``c`` and ``m = (p + c)/2`` have the sign of ``R(pi/2)``,
    and ``p``, ``c`` and ``m`` lie on the side of ``x`` their signs say.  With one root in region 1
    the cold solve returns that root, so the two agree to solver tolerance.  Elsewhere the station
    is solved cold by the caller.  Limitation: three roots in region 1 (deep stall at high
    solidity, about 0.2 % of stations of random rotors with chord/r up to 2, none of the
    propellers of the tests) can lie so close together that none of the samples falls between
    them; there the cold solve's pick depends on its start point and the warm start may return
    another of the three (the BEM inflow component then applies
    :func:`~bild_mdo.bem.attached_branch.attached_branch` to either).

    Parameters
    ----------
    residual : callable
        ``residual(phi, idx) -> (R, dR_dphi)``.
    previous : array_like
        Previous roots (rad), shape ``(size,)``; stations outside ``(eps, pi/2)`` or not finite are
        left to the cold solve.
    initial_guess : ndarray, optional
        The cold solve's ``initial_guess``.
    tol, max_iter
        As in :func:`solve_bracketed`.
    any_root : bool
        Accept every converged root in region 1, one of several too (for a caller that then
        chooses among them: the BEM inflow component's attached-branch rule).

    Returns
    -------
    phi : ndarray
        Roots (rad), NaN where not accepted.
    accepted : ndarray of bool
    """
    a, b = _REGIONS[0]
    previous = np.asarray(previous, dtype=float).ravel()
    size = previous.size
    phi = np.full(size, np.nan)
    accepted = np.zeros(size, dtype=bool)
    idx = np.flatnonzero(np.isfinite(previous) & (previous > a) & (previous < b))
    n = idx.size
    if n == 0:
        return phi, accepted
    p = previous[idx]
    c = p if initial_guess is None else initial_guess[idx]
    c = np.where((c > a) & (c < b), c, p)
    m = 0.5 * (p + c)
    with np.errstate(all="ignore"):
        values, slopes = residual(np.concatenate([np.full(n, a), np.full(n, b), p, c, m]), np.tile(idx, 5))[:2]
    ra, rb, rp, rc, rm = np.reshape(values, (5, n))
    slopes = np.reshape(slopes, (5, n))
    dp, dc = slopes[2:4]
    ok = (((ra > 0.0) & (rb < 0.0)) | ((ra < 0.0) & (rb > 0.0))) & np.isfinite(rp) & np.isfinite(rc) & np.isfinite(rm)
    left = opposite_signs(ra, rp)
    lo, hi, f_lo = np.where(left, a, p), np.where(left, p, b), np.where(left, ra, rp)
    # A Halley step from p (error O(dphi^3) rather than Newton's O(dphi^2): one pass fewer after an optimiser
    # step), with R'' from the slopes at p and c where c is near p; elsewhere a Newton step.
    gap = c - p
    with np.errstate(all="ignore"):
        curvature = np.where((np.abs(gap) > 1e-6) & (np.abs(gap) < _HALLEY_SPAN), (dc - dp) / gap, 0.0)
        x0 = p - 2.0 * rp * dp / (2.0 * dp * dp - rp * curvature)
    x0 = np.where((x0 > lo) & (x0 < hi), x0, false_position(lo, hi, f_lo, np.where(left, rp, rb)))
    sel = np.flatnonzero(ok)
    result = bracketed_newton(lambda x, i: residual(x, idx[sel[i]]), lo[sel], hi[sel], f_lo[sel], x0[sel],
                              atol=tol, max_iter=max_iter)
    x, sign_b = result.x, np.sign(rb[sel])
    good = result.converged
    if not any_root:
        # One simple root x in (a, b): R falls (or rises) through it, with the sign of R(a) left of x and that
        # of R(b) right of it; a slope of the other sign at p, c or m shows a second and a third root.
        good = good & (np.sign(result.slope) == sign_b) & np.all(np.sign(slopes[2:, sel]) == sign_b, axis=0)
        for point, value in ((p[sel], rp[sel]), (c[sel], rc[sel]), (m[sel], rm[sel])):
            good &= (np.abs(value) <= tol) | ((np.sign(value) == sign_b) == (point > x))
    phi[idx[sel[good]]] = x[good]
    accepted[idx[sel[good]]] = True
    return phi, accepted


def _solve_rest(cold, residual, phi, accepted, guess, describe):
    """``(phi, found)``: the accepted warm roots, and ``cold(residual, sub, describe, guess)`` at the others."""
    found = accepted.copy()
    rest = np.flatnonzero(~accepted)
    if rest.size:
        phi_rest, found_rest = cold(lambda x, i: residual(x, rest[i]), rest, lambda i: describe(rest[i]),
                                    None if guess is None else guess[rest])
        phi[rest], found[rest] = phi_rest, found_rest
    return phi, found


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
        ok = opposite_signs(ra, rb)
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
    change = opposite_signs(values[:, :-1], values[:, 1:])
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


def opposite_signs(a, b):
    """``a b <= 0`` without forming the product (which overflows or underflows at extreme residuals)."""
    return ((a <= 0.0) & (b >= 0.0)) | ((a >= 0.0) & (b <= 0.0))


def _check_finite(values, idx, phi, describe):
    bad = ~np.isfinite(values)
    if np.any(bad):
        first = np.argmax(bad)
        phi_bad = np.broadcast_to(phi, values.shape)[first]
        raise om.AnalysisError(
            f"BEM inflow solve: the residual is not finite at phi = {phi_bad:.6g} rad at "
            f"{describe(idx[first])}; check the inputs (chord, radii, rpm) and the polar.")


#: Physical search regions (CCBlade.jl's quadrants for V_x >= 0, Omega > 0, in its order):
#: Q1 (flow through the disk from ahead), Q2 (flow reversed through the disk), Q3 (tangential
#: flow reversed, ``W_theta < 0``; searched only for ``V_x > 0``).
PHYSICAL_REGIONS = ((BRACKET_EPS, 0.5 * np.pi), (-0.5 * np.pi, -BRACKET_EPS), (0.5 * np.pi, np.pi - BRACKET_EPS))


def _solve_in(residual, idx, lo, hi, r_lo, r_hi, guess, describe, tol, max_iter):
    """Safeguarded Newton solve at stations ``idx`` inside brackets ``[lo, hi]``; AnalysisError if not converged."""
    x0 = false_position(lo, hi, r_lo, r_hi)
    if guess is not None:
        g = guess[idx]
        x0 = np.where((g - lo) * (g - hi) < 0.0, g, x0)
    result = bracketed_newton(lambda x, i: residual(x, idx[i]), lo, hi, r_lo, x0, atol=tol, max_iter=max_iter)
    first = result.first_failure()
    if first is not None:
        _check_finite(result.residual, idx, result.x, describe)
        raise om.AnalysisError(
            f"BEM inflow solve did not converge in {max_iter} iterations at {describe(idx[first])} "
            f"({np.count_nonzero(~result.converged)} station(s) in all); |R| = {np.abs(result.residual[first]):.3e}.")
    return result.x


def solve_physical(residual, admissible, forward, describe=None, tol=RESIDUAL_TOL, max_iter=MAX_ITER,
                   initial_guess=None, previous=None, warm_any_root=False):
    """Solve ``R(phi) = 0`` for a physical (admissible) root at every station, in CCBlade.jl's order.

    Regions are tried in the order of :data:`PHYSICAL_REGIONS` (Q3 only where ``forward``), each by
    the signs at its end points; a root is accepted only where ``admissible(phi, idx)`` holds
    (``W > 0``: roots with ``W < 0`` are 180-deg mirror images of a real flow).  In forward
    flight, where Q1 has the same sign at both ends, Q1 is scanned on a grid before Q2 and the
    sign change at the largest phi is taken (the momentum branch with the smaller induction).
    Stations left over are scanned on a grid over the regions for the first sign change with
    admissible end points.  In hover this reduces to Q1 where ``c_l(twist) > 0`` and Q2 otherwise (the
    residual at ``phi -> 0`` is ``sigma c_l(twist)``; at ``-pi/2`` and ``pi/2`` it is
    ``+-(sigma c_d + 4F)``), so a hover station always has a root.

    Parameters
    ----------
    residual : callable
        ``residual(phi, idx) -> (R, dR_dphi)`` (see :func:`solve_bracketed`).
    admissible : callable
        ``admissible(phi, idx) -> bool array``.
    forward : ndarray of bool
        ``V_x > 0`` per station, shape ``(size,)``.
    describe, tol, max_iter, initial_guess, previous, warm_any_root
        As in :func:`solve_bracketed` (``previous``: warm start, see :func:`warm_region_one`; a
        station whose warm root is not admissible is solved cold).

    Returns
    -------
    phi : ndarray
        Inflow angles (rad); NaN where no admissible root exists.
    found : ndarray of bool
        Where an admissible root was found.
    """
    forward = np.asarray(forward, dtype=bool)
    size = forward.size
    describe = describe or _default_describe((size,))
    guess = None if initial_guess is None else np.broadcast_to(np.asarray(initial_guess, dtype=float), (size,))
    if previous is not None:
        phi, warm = warm_region_one(residual, previous, guess, tol=tol, max_iter=max_iter, any_root=warm_any_root)
        sel = np.flatnonzero(warm)
        warm[sel] = admissible(phi[sel], sel)
        return _solve_rest(lambda res, sub, desc, g: solve_physical(res, lambda x, i: admissible(x, sub[i]),
                                                                    forward[sub], desc, tol, max_iter, g),
                           residual, phi, warm, guess, describe)
    phi = np.full(size, np.nan)
    found = np.zeros(size, dtype=bool)
    args = (residual, admissible, phi, found, describe, tol, max_iter)
    for k, (a, b) in enumerate(PHYSICAL_REGIONS):
        todo = np.flatnonzero(~found)
        idx = todo[forward[todo]] if k == 2 else todo
        if idx.size == 0:
            continue
        # Both end points in one pass (the same values as two passes, at half the call overhead).
        ra, rb = residual(np.repeat([a, b], idx.size), np.tile(idx, 2))[0].reshape(2, idx.size)
        _check_finite(ra, idx, a, describe)
        _check_finite(rb, idx, b, describe)
        ok = opposite_signs(ra, rb)
        if np.any(ok):
            sel = idx[ok]
            x = _solve_in(residual, sel, np.full(sel.size, a), np.full(sel.size, b), ra[ok], rb[ok], guess,
                          describe, tol, max_iter)
            good = admissible(x, sel)
            phi[sel[good]] = x[good]
            found[sel[good]] = True
        if k == 0:
            # Same signs at both ends of Q1 in forward flight: an even number of roots there, typically
            # the two momentum branches of an annulus that extracts power (a < 1/2 and a > 1/2 for the
            # same loading).  The largest phi has the smallest induction: the momentum-valid branch.
            todo = np.flatnonzero(~found & forward)
            if todo.size:
                _scan_admissible(*args, todo, _Q1_SCAN, last=True)
    todo = np.flatnonzero(~found)
    if todo.size:
        _scan_admissible(*args, todo, _SCAN, last=False, allowed=forward[todo][:, None] | (_SCAN < 0.5 * np.pi))
    return phi, found


_Q1_SCAN = np.linspace(BRACKET_EPS, 0.5 * np.pi, 31)


def _scan_admissible(residual, admissible, phi, found, describe, tol, max_iter, todo, grid, last, allowed=True):
    """Solve in the first (or last) grid interval with a sign change and admissible end points (in place).

    ``grid`` is one grid for all stations ``todo``, shape ``(k,)``, or one per station, ``(todo.size, k)``.
    """
    n = todo.size
    points = np.broadcast_to(grid, (n, np.shape(grid)[-1]))
    k = points.shape[1]
    stations = np.repeat(todo, k)
    x = points.ravel()
    values = residual(x, stations)[0]
    _check_finite(values, stations, x, describe)
    values = values.reshape(n, k)
    ok_end = admissible(x, stations).reshape(n, k) & allowed
    change = opposite_signs(values[:, :-1], values[:, 1:]) & ok_end[:, :-1] & ok_end[:, 1:]
    change &= np.diff(np.sign(points), axis=1) == 0   # never across phi = 0
    has = change.any(axis=1)
    if not np.any(has):
        return
    rows = np.flatnonzero(has)
    first = (k - 2 - np.argmax(change[:, ::-1], axis=1) if last else np.argmax(change, axis=1))[has]
    sel = todo[has]
    xr = _solve_in(residual, sel, points[rows, first], points[rows, first + 1], values[rows, first],
                   values[rows, first + 1], None, describe, tol, max_iter)
    good = admissible(xr, sel)
    phi[sel[good]] = xr[good]
    found[sel[good]] = True


def solve_bracketed(residual, size, describe=None, shape=None, tol=RESIDUAL_TOL, max_iter=MAX_ITER,
                    initial_guess=None, previous=None, warm_any_root=False):
    """Solve ``R(phi) = 0`` at every station: Ning's bracket search, then the safeguarded Newton solve.

    The Newton solve is :func:`bild_mdo.utils.newton.bracketed_newton`, started at
    the false-position point of each bracket (or at ``initial_guess``).

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
    previous : array_like, optional
        Roots of a previous solve (rad): a warm start (:func:`warm_region_one`), which returns
        the root the cold solve returns; stations it cannot vouch for are solved cold.
        ``warm_any_root=True`` keeps every converged warm root (``any_root``).

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
    if previous is not None:
        guess = None if initial_guess is None else np.broadcast_to(np.asarray(initial_guess, dtype=float), (size,))
        phi, warm = warm_region_one(residual, previous, guess, tol=tol, max_iter=max_iter, any_root=warm_any_root)
        return _solve_rest(lambda res, sub, desc, g: (solve_bracketed(res, sub.size, desc, None, tol, max_iter, g),
                                                      np.ones(sub.size, dtype=bool)),
                           residual, phi, warm, guess, describe)[0]
    lo, hi, r_lo, r_hi = find_brackets(residual, size, describe=describe)
    x0 = false_position(lo, hi, r_lo, r_hi)
    if initial_guess is not None:
        guess = np.broadcast_to(np.asarray(initial_guess, dtype=float), (size,))
        x0 = np.where((guess - lo) * (guess - hi) < 0.0, guess, x0)
    result = bracketed_newton(residual, lo, hi, r_lo, x0, atol=tol, max_iter=max_iter)
    first = result.first_failure()
    if first is not None:
        _check_finite(result.residual, np.arange(size), result.x, describe)
        failed = np.count_nonzero(~result.converged)
        raise om.AnalysisError(
            f"BEM inflow solve did not converge in {max_iter} iterations at {describe(first)} "
            f"({failed} station(s) in all); |R| = {np.abs(result.residual[first]):.3e}.")
    return result.x
