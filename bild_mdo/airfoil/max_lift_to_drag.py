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

The same holds for any other parameter ``p`` of the polar, the Mach number
and the station's ``r/R`` (``g_p`` with ``p`` for ``Re``), so the point at
given ``(Re, M, r/R)`` comes with its derivatives with respect to all three.

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


_STATION_FIELDS = MaxLiftToDrag._fields + ("dalpha_dmach", "dcl_dmach", "dcd_dmach", "dalpha_dradial_fraction",
                                           "dcl_dradial_fraction", "dcd_dradial_fraction")
StationMaxLiftToDrag = NamedTuple("StationMaxLiftToDrag", [(f, np.ndarray) for f in _STATION_FIELDS])
StationMaxLiftToDrag.__doc__ = """The maximum-L/D point at given ``(Re, M, r/R)`` with derivatives with respect to all three.

Fields: those of :class:`MaxLiftToDrag`, then ``dalpha_dmach, dcl_dmach, dcd_dmach,
dalpha_dradial_fraction, dcl_dradial_fraction, dcd_dradial_fraction``.  Returned when
``mach`` or ``radial_fraction`` is given; the derivatives with respect to an argument
that was not given are zero.
"""


def _polar_name(polar):
    return getattr(polar, "name", type(polar).__name__)


def _listed(reynolds):
    return f"{reynolds[:5].tolist()}{' ...' if reynolds.size > 5 else ''}"


def _extra_args(extra, idx=None):
    """Keyword arguments ``mach``/``radial_fraction`` of the polar calls, restricted to rows ``idx``."""
    return {k: (v if idx is None else v[idx]) for k, v in extra.items()}


def max_lift_to_drag(polar, reynolds, alpha_range=None, mach=None, radial_fraction=None):
    """Angle of attack, lift and drag of maximum ``cl/cd`` at each Reynolds number.

    Parameters
    ----------
    polar : Polar
        Any polar that provides first and second derivatives (its
        ``evaluate`` and ``second_derivatives`` methods are used).
    reynolds : array_like
        Chord Reynolds numbers, any shape.  Complex values (complex step) are
        evaluated at the real part and the imaginary part is carried to first
        order with the exact derivatives, like :meth:`Polar.evaluate`
        (likewise for complex ``mach`` and ``radial_fraction``).
    alpha_range : tuple of float, optional
        ``(low, high)`` angles of attack (rad) in which the maximum is sought.
        Default: the polar's ``alpha_scan_range`` attribute if it has one
        (the attached-flow range), else -10 deg to 25 deg.
    mach : array_like, optional
        Mach numbers, broadcast against ``reynolds``.
    radial_fraction : array_like, optional
        ``r/R`` of each point (per-station point of a spanwise polar), broadcast.

    Returns
    -------
    MaxLiftToDrag or StationMaxLiftToDrag
        ``alpha`` (rad), ``cl``, ``cd`` and their derivatives, each with the
        broadcast shape of the inputs; :class:`StationMaxLiftToDrag` when
        ``mach`` or ``radial_fraction`` is given.

    Raises
    ------
    ValueError
        If ``cl/cd`` has no interior local maximum with ``cl > 0`` in the
        range (the polar is not a lifting airfoil there, or the range is too
        small), if a Reynolds number is not finite, or if the Newton solve
        does not converge (the message names the Reynolds numbers).
    """
    given = {"mach": mach, "radial_fraction": radial_fraction}
    given = {k: np.asarray(v) for k, v in given.items() if v is not None}
    inputs = np.broadcast_arrays(np.asarray(reynolds), *given.values())
    reynolds = inputs[0]
    re_real = np.asarray(np.real(reynolds), dtype=float)
    if not np.all(np.isfinite(re_real)):
        raise ValueError("max_lift_to_drag: Reynolds numbers must be finite")
    shape = re_real.shape
    re_flat = re_real.ravel()
    extra = {k: np.asarray(np.real(v), dtype=float).ravel() for k, v in zip(given, inputs[1:])}
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
    v = polar.evaluate(a2, r2, **{k: x[:, None] for k, x in extra.items()})
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
        kw = _extra_args(extra, idx)
        v = polar.evaluate(alpha, re_flat[idx], **kw)
        s = polar.second_derivatives(alpha, re_flat[idx], **kw)
        g_a = v.dcl_dalpha * v.cd - v.cl * v.dcd_dalpha
        dg_a = s.d2cl_dalpha2 * v.cd - v.cl * s.d2cd_dalpha2
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
    v = polar.evaluate(alpha, re_flat, **extra)
    s = polar.second_derivatives(alpha, re_flat, **extra)
    return point_from_polar_values(alpha, v, s, inputs, list(extra), shape)


def point_from_polar_values(alpha, v, s, inputs, given, shape, correction=None):
    """The maximum-L/D point from the polar's values at its angle of attack (flat, real arrays).

    Parameters
    ----------
    alpha : ndarray
        Angle of maximum L/D (rad), flat, real.
    v, s : PolarValues, PolarSecondDerivatives (or their Mach / station forms)
        ``polar.evaluate`` and ``polar.second_derivatives`` at ``alpha`` (flat).
    inputs : list of array_like
        The broadcast arguments ``[reynolds, *given values]`` (complex under complex step).
    given : list of str
        Names of the optional arguments given, ``'mach'`` and/or ``'radial_fraction'``, in order.
    shape : tuple
        Shape of the result.
    correction : ndarray, optional
        A last Newton correction ``delta`` (rad) below 1e-10 rad to apply: ``alpha + delta`` with
        ``cl, cd`` carried to first order (their error is ``O(delta**2)``, far below round-off); the
        derivatives stay those at ``alpha`` (relative change ``O(delta)``).

    Returns
    -------
    MaxLiftToDrag or StationMaxLiftToDrag
    """
    # The second-order term g_alpha: the cl_a cd_a terms cancel (module docstring).
    dg_a = s.d2cl_dalpha2 * v.cd - v.cl * s.d2cd_dalpha2
    derivatives = []
    for p in ("re", "mach", "radial_fraction") if given else ("re",):
        if p != "re" and p not in given:
            zero = np.zeros_like(alpha)
            derivatives.append((zero, zero, zero))
            continue
        cl_p, cd_p = getattr(v, f"dcl_d{p}"), getattr(v, f"dcd_d{p}")
        cl_ap, cd_ap = getattr(s, f"d2cl_dalpha_d{p}"), getattr(s, f"d2cd_dalpha_d{p}")
        # Implicit function theorem on g(alpha*, p) = 0 (module docstring).
        g_p = cl_ap * v.cd + v.dcl_dalpha * cd_p - cl_p * v.dcd_dalpha - v.cl * cd_ap
        dalpha = -g_p / dg_a
        derivatives.append((dalpha, v.dcl_dalpha * dalpha + cl_p, v.dcd_dalpha * dalpha + cd_p))
    cl, cd = v.cl, v.cd
    if correction is not None:
        alpha = alpha + correction
        cl = cl + v.dcl_dalpha * correction
        cd = cd + v.dcd_dalpha * correction
    if any(np.iscomplexobj(x) for x in inputs):
        imag = [np.imag(x).ravel() for x in inputs]
        slopes = [derivatives[0]] + [derivatives[1 if k == "mach" else 2] for k in given]
        alpha = alpha + 1j * sum(h * d[0] for h, d in zip(imag, slopes))
        cl = cl + 1j * sum(h * d[1] for h, d in zip(imag, slopes))
        cd = cd + 1j * sum(h * d[2] for h, d in zip(imag, slopes))
    fields = (alpha, cl, cd) + derivatives[0]
    if not given:
        return MaxLiftToDrag(*(np.reshape(x, shape) for x in fields))
    fields += derivatives[1] + derivatives[2]
    return StationMaxLiftToDrag(*(np.reshape(x, shape) for x in fields))
