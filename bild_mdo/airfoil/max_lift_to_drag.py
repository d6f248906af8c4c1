"""The maximum lift-to-drag point of a polar, exact on the polar, with Reynolds derivatives.

BILD (Assumption 2 of the paper) runs every blade element at the angle of
attack of maximum ``cl/cd``.  At that angle

    g(alpha, Re) = cl_alpha cd - cl cd_alpha = 0,

the numerator of ``d(cl/cd)/d(alpha)``.  This module brackets the maximum by a
vectorised scan, solves ``g = 0`` by a safeguarded Newton iteration to
round-off, and differentiates the solution by the implicit function theorem::

    dalpha*/dRe = -g_Re / g_alpha
    g_alpha = cl_aa cd - cl cd_aa                    (the cl_a cd_a terms cancel)
    g_Re    = cl_aRe cd + cl_a cd_Re - cl_Re cd_a - cl cd_aRe
    dcl*/dRe = cl_a dalpha*/dRe + cl_Re,   dcd*/dRe = cd_a dalpha*/dRe + cd_Re
"""
from __future__ import annotations

import numpy as np

from bild_mdo.airfoil.polar import MaxLiftToDrag

#: Default scan range of the bracket search (rad) for polars that do not give one.
DEFAULT_SCAN_RANGE = (np.radians(-10.0), np.radians(25.0))

_SCAN_STEP = np.radians(0.25)
_MAX_ITERATIONS = 100
_ALPHA_TOL = 1e-14


def _g_and_slope(polar, alpha, reynolds):
    v = polar.evaluate(alpha, reynolds)
    s = polar.second_derivatives(alpha, reynolds)
    g = v.dcl_dalpha * v.cd - v.cl * v.dcd_dalpha
    dg = s.d2cl_dalpha2 * v.cd - v.cl * s.d2cd_dalpha2
    return g, dg, v, s


def max_lift_to_drag(polar, reynolds, alpha_range=None):
    """Angle of attack, lift and drag of maximum ``cl/cd`` at each Reynolds number.

    Parameters
    ----------
    polar : Polar
        Any polar that provides first and second derivatives.
    reynolds : array_like
        Chord Reynolds numbers, any shape.  Complex values (complex step) are
        evaluated at the real part and the imaginary part is carried to first
        order with the exact Re derivatives, like :meth:`Polar.evaluate`.
    alpha_range : tuple of float, optional
        ``(low, high)`` angles of attack (rad) in which the maximum is sought.
        Default: the polar's ``alpha_scan_range`` attribute if it has one
        (the attached-flow range), else -10 deg to 25 deg.

    Returns
    -------
    MaxLiftToDrag
        ``alpha`` (rad), ``cl``, ``cd`` and their derivatives with respect to
        ``Re``, each with the shape of ``reynolds``.

    Raises
    ------
    ValueError
        If ``cl/cd`` has no interior local maximum with ``cl > 0`` in the
        range (the polar is not a lifting airfoil there, or the range is too
        small), or if a Reynolds number is not finite.
    """
    reynolds = np.asarray(reynolds)
    is_complex = np.iscomplexobj(reynolds)
    re_real = np.asarray(np.real(reynolds), dtype=float)
    if not np.all(np.isfinite(re_real)):
        raise ValueError("max_lift_to_drag: Reynolds numbers must be finite")
    shape = re_real.shape
    re_flat = re_real.ravel()
    if alpha_range is None:
        alpha_range = getattr(polar, "alpha_scan_range", DEFAULT_SCAN_RANGE)
    low, high = (float(a) for a in alpha_range)
    if not high > low:
        raise ValueError(f"alpha_range must be increasing, got {alpha_range}")

    # Bracket: on a fine grid, the intervals where g changes from + to - hold the
    # local maxima of cl/cd; keep the one with the largest cl/cd (and cl > 0).
    n_scan = max(int(np.ceil((high - low) / _SCAN_STEP)) + 1, 3)
    grid = np.linspace(low, high, n_scan)
    a2, r2 = np.meshgrid(grid, re_flat)
    v = polar.evaluate(a2, r2)
    g = v.dcl_dalpha * v.cd - v.cl * v.dcd_dalpha
    ratio = v.cl / v.cd
    is_max = (g[:, :-1] > 0.0) & (g[:, 1:] <= 0.0) & (v.cl[:, :-1] > 0.0) & (v.cd[:, :-1] > 0.0)
    score = np.where(is_max, np.maximum(ratio[:, :-1], ratio[:, 1:]), -np.inf)
    k = np.argmax(score, axis=1)
    missing = ~np.isfinite(score[np.arange(re_flat.size), k])
    if np.any(missing):
        bad = re_flat[missing]
        raise ValueError(
            f"{getattr(polar, 'name', type(polar).__name__)}: cl/cd has no interior maximum with "
            f"cl > 0 for alpha in [{np.degrees(low):g}, {np.degrees(high):g}] deg at Re = "
            f"{bad[:5].tolist()}{' ...' if bad.size > 5 else ''}; check the polar or pass a "
            "wider alpha_range")
    lo = grid[k].copy()
    hi = grid[k + 1].copy()

    # Safeguarded Newton on g = 0: bisect whenever the Newton step leaves the bracket.
    alpha = 0.5 * (lo + hi)
    active = np.ones(re_flat.size, dtype=bool)
    for _ in range(_MAX_ITERATIONS):
        idx = np.flatnonzero(active)
        if idx.size == 0:
            break
        a, r = alpha[idx], re_flat[idx]
        g_a, dg_a, _, _ = _g_and_slope(polar, a, r)
        pos = g_a > 0.0
        lo[idx] = np.where(pos, a, lo[idx])
        hi[idx] = np.where(pos, hi[idx], a)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = -g_a / dg_a
        new = np.where(g_a == 0.0, a, a + step)
        inside = np.isfinite(new) & (new >= lo[idx]) & (new <= hi[idx])
        new = np.where(inside, new, 0.5 * (lo[idx] + hi[idx]))
        alpha[idx] = new
        done = (np.abs(new - a) <= _ALPHA_TOL * (1.0 + np.abs(a))) \
            | (hi[idx] - lo[idx] <= _ALPHA_TOL)
        active[idx[done]] = False

    g_a, dg_a, v, s = _g_and_slope(polar, alpha, re_flat)
    g_re = (s.d2cl_dalpha_dre * v.cd + v.dcl_dalpha * v.dcd_dre
            - v.dcl_dre * v.dcd_dalpha - v.cl * s.d2cd_dalpha_dre)
    dalpha = -g_re / dg_a
    dcl = v.dcl_dalpha * dalpha + v.dcl_dre
    dcd = v.dcd_dalpha * dalpha + v.dcd_dre
    cl, cd = v.cl, v.cd
    if is_complex:
        ire = np.imag(reynolds).ravel()
        alpha = alpha + 1j * ire * dalpha
        cl = cl + 1j * ire * dcl
        cd = cd + 1j * ire * dcd
    return MaxLiftToDrag(*(np.reshape(x, shape) for x in (alpha, cl, cd, dalpha, dcl, dcd)))
