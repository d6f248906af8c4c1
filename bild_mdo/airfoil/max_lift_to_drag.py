"""The maximum lift-to-drag point of a polar, exact on the polar, with Reynolds derivatives.

BILD (Assumption 2 of the paper) runs every blade element at the angle of
attack of maximum ``cl/cd``.  At that angle

    g(alpha, Re) = cl_alpha cd - cl cd_alpha = 0,

the numerator of ``d(cl/cd)/d(alpha)``.  This module brackets the maximum by a
vectorised scan, solves ``g = 0`` to round-off with the package's safeguarded
Newton solver (:func:`bild_mdo.utils.newton.bracketed_newton`), and
differentiates the solution by the implicit function theorem::

    dalpha*/dRe = -g_Re / g_alpha
    g_alpha = cl_aa cd - cl cd_aa                    (the cl_a cd_a terms cancel)
    g_Re    = cl_aRe cd + cl_a cd_Re - cl_Re cd_a - cl cd_aRe
    dcl*/dRe = cl_a dalpha*/dRe + cl_Re,   dcd*/dRe = cd_a dalpha*/dRe + cd_Re

The solver needs only the polar's ``evaluate`` and ``second_derivatives``
methods, so it sits below :mod:`bild_mdo.airfoil.polar`, whose
:meth:`~bild_mdo.airfoil.polar.Polar.max_lift_to_drag` calls it.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from bild_mdo.utils.newton import bracketed_newton

#: Default scan range of the bracket search (rad) for polars that do not give one.
DEFAULT_SCAN_RANGE = (np.radians(-10.0), np.radians(25.0))

_SCAN_STEP = np.radians(0.25)
_MAX_ITERATIONS = 100


class MaxLiftToDrag(NamedTuple):
    """The maximum-L/D operating point at given Reynolds numbers and its Re derivatives."""

    alpha: np.ndarray
    cl: np.ndarray
    cd: np.ndarray
    dalpha_dre: np.ndarray
    dcl_dre: np.ndarray
    dcd_dre: np.ndarray


def _g_and_slope(polar, alpha, reynolds):
    v = polar.evaluate(alpha, reynolds)
    s = polar.second_derivatives(alpha, reynolds)
    g = v.dcl_dalpha * v.cd - v.cl * v.dcd_dalpha
    dg = s.d2cl_dalpha2 * v.cd - v.cl * s.d2cd_dalpha2
    return g, dg, v, s


def _polar_name(polar):
    return getattr(polar, "name", type(polar).__name__)


def _listed(reynolds):
    return f"{reynolds[:5].tolist()}{' ...' if reynolds.size > 5 else ''}"


def max_lift_to_drag(polar, reynolds, alpha_range=None):
    """Angle of attack, lift and drag of maximum ``cl/cd`` at each Reynolds number.

    Parameters
    ----------
    polar : Polar
        Any polar that provides first and second derivatives (its
        ``evaluate`` and ``second_derivatives`` methods are used).
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
        small), if a Reynolds number is not finite, or if the Newton solve
        does not converge (the message names the Reynolds numbers).
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
    rows = np.arange(re_flat.size)
    missing = ~np.isfinite(score[rows, k])
    if np.any(missing):
        raise ValueError(
            f"{_polar_name(polar)}: cl/cd has no interior maximum with "
            f"cl > 0 for alpha in [{np.degrees(low):g}, {np.degrees(high):g}] deg at Re = "
            f"{_listed(re_flat[missing])}; check the polar or pass a wider alpha_range")

    def residual(alpha, idx):
        g_a, dg_a, v, _ = _g_and_slope(polar, alpha, re_flat[idx])
        # Magnitude of the two terms of g: g is zero to round-off below 4 eps times it.
        scale = np.abs(v.dcl_dalpha * v.cd) + np.abs(v.cl * v.dcd_dalpha)
        return g_a, dg_a, scale

    # g > 0 at the low end of the scan interval, g <= 0 at the high end.
    solution = bracketed_newton(residual, grid[k], grid[k + 1], g[rows, k], max_iter=_MAX_ITERATIONS)
    if not np.all(solution.converged):
        raise ValueError(
            f"{_polar_name(polar)}: the maximum-L/D solve did not converge in {_MAX_ITERATIONS} "
            f"Newton iterations at Re = {_listed(re_flat[~solution.converged])}; check that the "
            "polar and its derivatives are finite near the maximum")
    alpha = solution.x

    _, dg_a, v, s = _g_and_slope(polar, alpha, re_flat)
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
