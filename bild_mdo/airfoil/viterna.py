"""Viterna-Corrigan post-stall extrapolation and the stall smoothing of Eq. (33).

The paper (Appendix 7.2, Eq. 33) builds, for each Reynolds number, a polar that
covers every angle of attack:

* pre-stall: lift linear in ``alpha`` and drag a 4th-order polynomial, both
  least-squares fits of the XFOIL data (``pre_stall="polynomial"``), or, as an
  option of this module, a smoothing spline of the data (``pre_stall="spline"``);
* a cubic blend within ``+-epsilon`` (1.5 deg) of the stall angle;
* the Viterna-Corrigan flat-plate extrapolation (Viterna & Corrigan 1982) beyond.

Viterna-Corrigan, matched at the stall point ``(alpha_s, cl_s, cd_s)``::

    cl = cd_max/2 sin(2 alpha) + A cos(alpha)^2 / sin(alpha)      (Eq. 33a, third line)
    cd = cd_max sin(alpha)^2   + B cos(alpha)                      (Eq. 33b, third line)
    A  = (cl_s - cd_max sin(alpha_s) cos(alpha_s)) sin(alpha_s) / cos(alpha_s)^2
    B  = (cd_s - cd_max sin(alpha_s)^2) / cos(alpha_s)

is used from the stall angle to ``+-90 deg`` on the same side.  The paper stops
at ``+-90 deg``; a BEM solve can meet any angle, so this module continues to
``+-180 deg`` (reverse flow) with terms chosen so that the result is twice
continuously differentiable at ``+-90 deg`` and periodic and C^2 at ``+-180 deg``::

    cl = cd_max/2 sin(2 alpha) + A cos(alpha)^2 sin(alpha)^3
    cd = cd_max sin(alpha)^2 + B cos + c3 cos^3 + c5 cos^5,
         c3 = -2 B - 2.5 cd_reverse,   c5 = B + 1.5 cd_reverse

so ``cl(+-180 deg) = 0`` with the flat-plate slope ``cd_max``, and
``cd(+-180 deg) = cd_reverse``.  The positive and negative stall sides each get
their own ``A, B`` (matched at their own stall point) and meet at ``+-180 deg``
with equal value, slope and curvature whatever their ``A, B``.

Stall detection
---------------
The lift data are smoothed first (a smoothing spline, as for the
``'spline'`` pre-stall model of :func:`extend_arrays`).  The positive stall
angle is the angle of the largest smoothed ``cl`` at positive angle of attack;
if that largest value is at the last data point (the data never stall), the
last data angle is used, as AirfoilPrep matches Viterna at the end of the data.
The negative stall angle is, symmetrically, the angle of the smallest smoothed
``cl`` at negative angle of attack, or the first data angle.  Data beyond the
stall angles (XFOIL's post-stall points) are discarded in favour of Viterna,
as in the paper.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

#: Half width of the cubic stall blend of Eq. (33), 1.5 deg (paper Appendix 7.2).
STALL_BLEND_HALF_WIDTH = np.radians(1.5)

#: Maximum drag coefficient of a flat plate normal to the flow (infinite aspect ratio).
DEFAULT_CD_MAX = 2.0

#: Drag coefficient at +-180 deg (reverse flow, trailing edge first).
DEFAULT_CD_REVERSE = 0.05


def cd_max_from_aspect_ratio(aspect_ratio):
    """Viterna-Corrigan maximum drag coefficient ``1.11 + 0.018 AR`` (valid for AR <= 50).

    Parameters
    ----------
    aspect_ratio : float
        Blade aspect ratio (radius / mean chord).

    Returns
    -------
    float
        ``cd_max``.
    """
    aspect_ratio = float(aspect_ratio)
    if not aspect_ratio > 0.0:
        raise ValueError(f"aspect_ratio must be positive, got {aspect_ratio}")
    return 1.11 + 0.018 * min(aspect_ratio, 50.0)


def viterna_coefficients(alpha_stall, cl_stall, cd_stall, cd_max):
    """Viterna-Corrigan constants ``A, B`` that put the extrapolation through the stall point.

    Parameters
    ----------
    alpha_stall : float or ndarray
        Stall angle (rad), ``0 < |alpha_stall| < pi/2``; negative for negative stall.
    cl_stall, cd_stall : float or ndarray
        Lift and drag coefficients at the stall angle.
    cd_max : float
        Flat-plate maximum drag coefficient.

    Returns
    -------
    tuple of (float or ndarray)
        ``A`` (multiplies ``cos^2/sin`` in cl) and ``B`` (multiplies ``cos`` in cd).
    """
    s = np.sin(alpha_stall)
    c = np.cos(alpha_stall)
    a_coef = (cl_stall - cd_max * s * c) * s / c**2
    b_coef = (cd_stall - cd_max * s**2) / c
    return a_coef, b_coef


class CurveDerivatives(NamedTuple):
    """A curve of one variable with its first and second derivatives (per rad)."""

    value: np.ndarray
    slope: np.ndarray
    curvature: np.ndarray


def post_stall(alpha, alpha_stall, cl_stall, cd_stall, cd_max=DEFAULT_CD_MAX,
               cd_reverse=DEFAULT_CD_REVERSE):
    """Viterna-Corrigan extrapolation on one side of the polar, continued to ``+-180 deg``.

    Parameters
    ----------
    alpha : ndarray
        Angle of attack (rad), on the side of ``alpha_stall`` (``0 < alpha <= pi``
        for positive stall, ``-pi <= alpha < 0`` for negative stall).  Values on
        the other side are not meaningful (they are computed from a guarded
        ``sin`` and must be masked by the caller).
    alpha_stall : float
        Stall angle the extrapolation is matched at (rad), ``0 < |alpha_stall| < pi/2``.
    cl_stall, cd_stall : float
        Lift and drag coefficients at ``alpha_stall``.
    cd_max : float
        Flat-plate maximum drag coefficient (reached at ``+-90 deg``).
    cd_reverse : float
        Drag coefficient at ``+-180 deg``.

    Returns
    -------
    cl, cd : CurveDerivatives
        Values, first and second derivatives with respect to ``alpha`` (per rad).
    """
    alpha = np.asarray(alpha)
    a_coef, b_coef = viterna_coefficients(alpha_stall, cl_stall, cd_stall, cd_max)
    s = np.sin(alpha)
    c = np.cos(alpha)
    side = 1.0 if alpha_stall > 0 else -1.0
    # Guard the division: the formula is only used strictly on the stall side.  Branch
    # on real parts so that the function is complex-step safe.
    s_safe = np.where(side * np.real(s) > 1e-12, s, side * 1e-12)
    front = np.abs(np.real(alpha)) <= 0.5 * np.pi

    # Flat plate (all angles): cl = cd_max/2 sin 2a, cd = cd_max sin^2 a.
    s2 = 2.0 * s * c                                   # sin 2a
    c2 = c * c - s * s                                 # cos 2a
    cl_fp = 0.5 * cd_max * s2
    dcl_fp = cd_max * c2
    d2cl_fp = -2.0 * cd_max * s2
    cd_fp = cd_max * s**2
    dcd_fp = cd_max * s2
    d2cd_fp = 2.0 * cd_max * c2

    # Viterna lift correction A cos^2/sin (front) and its C^2 continuation A cos^2 sin^3 (back).
    r_front = c**2 / s_safe
    dr_front = -2.0 * c - c**3 / s_safe**2
    d2r_front = 2.0 * s + 3.0 * c**2 / s_safe + 2.0 * c**4 / s_safe**3
    r_back = c**2 * s**3
    dr_back = -2.0 * c * s**4 + 3.0 * c**3 * s**2
    d2r_back = (2.0 * s**5 - 8.0 * c**2 * s**3 - 9.0 * c**2 * s**3 + 6.0 * c**4 * s)
    r = np.where(front, r_front, r_back)
    dr = np.where(front, dr_front, dr_back)
    d2r = np.where(front, d2r_front, d2r_back)

    # Viterna drag correction B cos (front); the back adds c3 cos^3 + c5 cos^5, whose
    # triple zero at 90 deg keeps C^2 there, with c3, c5 fixing cd(180) = cd_reverse and
    # cd''(180) = cd_max * 2 on both sides.
    c5 = b_coef + 1.5 * cd_reverse
    c3 = -2.0 * b_coef - 2.5 * cd_reverse
    back = ~front
    q = b_coef * c + back * (c3 * c**3 + c5 * c**5)
    dq = -b_coef * s + back * (-3.0 * c3 * c**2 * s - 5.0 * c5 * c**4 * s)
    d2q = -b_coef * c + back * (c3 * (6.0 * c * s**2 - 3.0 * c**3)
                                + c5 * (20.0 * c**3 * s**2 - 5.0 * c**5))

    cl = CurveDerivatives(cl_fp + a_coef * r, dcl_fp + a_coef * dr, d2cl_fp + a_coef * d2r)
    cd = CurveDerivatives(cd_fp + q, dcd_fp + dq, d2cd_fp + d2q)
    return cl, cd


def hermite_blend(alpha, x0, x1, left, right):
    """Cubic on ``[x0, x1]`` matching value and slope of two curves at its ends (Eq. 33, middle line).

    Parameters
    ----------
    alpha : ndarray
        Angles (rad) in ``[x0, x1]``.
    x0, x1 : float
        Ends of the blend interval (rad).
    left, right : tuple of float
        ``(value, slope)`` of the curve to the left of ``x0`` and to the right of ``x1``.

    Returns
    -------
    value, slope : ndarray
        The cubic and its derivative (per rad); C^1-continuous with both curves.
    """
    h = x1 - x0
    t = (np.asarray(alpha, dtype=float) - x0) / h
    t2 = t * t
    t3 = t2 * t
    value = ((2 * t3 - 3 * t2 + 1) * left[0] + (t3 - 2 * t2 + t) * h * left[1]
             + (-2 * t3 + 3 * t2) * right[0] + (t3 - t2) * h * right[1])
    slope = ((6 * t2 - 6 * t) * (left[0] - right[0]) / h + (3 * t2 - 4 * t + 1) * left[1]
             + (3 * t2 - 2 * t) * right[1])
    return value, slope


class ExtendedPolar(NamedTuple):
    """One Reynolds number's polar extended to the whole circle by Eq. (33).

    Attributes
    ----------
    alpha : ndarray, shape (n,)
        Angle of attack grid (rad) from -pi to pi.
    cl, cd : ndarray, shape (n,)
        Lift and drag coefficients on the grid.
    dcl_dalpha, dcd_dalpha : ndarray, shape (n,)
        Their slopes (per rad): continuous, since every piece of Eq. (33)
        meets the next with equal value and slope.
    alpha_stall, alpha_stall_negative : float
        Detected positive and negative stall angles (rad); the cubic blends
        cover ``+-epsilon`` around them.
    reynolds : float
        Chord Reynolds number of the data.
    """

    alpha: np.ndarray
    cl: np.ndarray
    cd: np.ndarray
    dcl_dalpha: np.ndarray
    dcd_dalpha: np.ndarray
    alpha_stall: float
    alpha_stall_negative: float
    reynolds: float


def default_alpha_grid(step_deg=0.25):
    """Uniform angle-of-attack grid (rad) from -pi to pi inclusive, ``step_deg`` apart.

    Parameters
    ----------
    step_deg : float
        Spacing (deg); must divide 360.

    Returns
    -------
    ndarray
    """
    n = 360.0 / step_deg
    if not (step_deg > 0 and abs(n - round(n)) < 1e-9):
        raise ValueError(f"alpha step must divide 360 deg, got {step_deg}")
    return np.linspace(-np.pi, np.pi, int(round(n)) + 1)


def _smoothing_spline(alpha, values, lam):
    # A cubic smoothing spline (penalty on the integrated squared second derivative)
    # removes the point-to-point scatter of XFOIL (transition-point jumps) while keeping
    # the lift curve and the drag bucket; lam=None lets generalised cross-validation pick
    # the penalty.  Imported here: scipy.interpolate is only needed to build a
    # surrogate, and a process that loads one from the polar cache does not pay for it.
    from scipy.interpolate import make_smoothing_spline

    return make_smoothing_spline(alpha, values, lam=lam)


def detect_stall(alpha, cl):
    """Positive and negative stall angles of a lift curve (see the module docstring).

    Parameters
    ----------
    alpha : ndarray
        Angles (rad), increasing, dense (a fine evaluation grid of the smoothed data).
    cl : ndarray
        Smoothed lift coefficient on ``alpha``.

    Returns
    -------
    tuple of float
        ``(alpha_stall, alpha_stall_negative)`` (rad).
    """
    pos = alpha > 0.0
    neg = alpha < 0.0
    if not (np.any(pos) and np.any(neg)):
        raise ValueError("polar data must include negative and positive angles of attack")
    alpha_stall = alpha[pos][np.argmax(cl[pos])]
    alpha_stall_negative = alpha[neg][np.argmin(cl[neg])]
    return float(alpha_stall), float(alpha_stall_negative)


def extend_arrays(alpha_deg, cl, cd, reynolds=float("nan"), *, alpha_grid=None,
                  cd_max=DEFAULT_CD_MAX, cd_reverse=DEFAULT_CD_REVERSE,
                  epsilon=STALL_BLEND_HALF_WIDTH, pre_stall="spline", smoothing=None):
    """Extend one polar to ``[-pi, pi]`` with Eq. (33): pre-stall fit, cubic blend, Viterna.

    Parameters
    ----------
    alpha_deg, cl, cd : array_like, shape (n,)
        Data (angle in deg, increasing), e.g. one XFOIL polar.
    reynolds : float
        Reynolds number of the data (only recorded in the result).
    alpha_grid : ndarray, optional
        Output grid (rad), must lie in ``[-pi, pi]``; default
        :func:`default_alpha_grid`.
    cd_max : float
        Flat-plate drag coefficient at 90 deg (see :func:`cd_max_from_aspect_ratio`).
    cd_reverse : float
        Drag coefficient at +-180 deg.
    epsilon : float
        Half width of the cubic stall blends (rad); the paper's 1.5 deg by default.
    pre_stall : {'spline', 'polynomial'}
        Pre-stall model.  ``'polynomial'`` is the paper's (Appendix 7.2): a
        least-squares line for lift and quartic for drag over the data between
        the stall angles.  ``'spline'`` (default) is a cubic smoothing spline of
        the same data, which keeps the curvature of the lift curve and the
        shape of the drag bucket (and so the maximum-L/D point) that a line and
        a quartic cannot follow.
    smoothing : float, optional
        Penalty of the smoothing splines (``lam`` of
        :func:`scipy.interpolate.make_smoothing_spline`, with alpha in rad);
        default: chosen by generalised cross-validation.

    Returns
    -------
    ExtendedPolar
    """
    alpha = np.radians(np.asarray(alpha_deg, dtype=float))
    cl = np.asarray(cl, dtype=float)
    cd = np.asarray(cd, dtype=float)
    if not (alpha.ndim == 1 and alpha.shape == cl.shape == cd.shape and alpha.size >= 6):
        raise ValueError("alpha_deg, cl, cd must be 1-D arrays of equal length >= 6")
    if np.any(np.diff(alpha) <= 0):
        raise ValueError("alpha_deg must be strictly increasing")
    if pre_stall not in ("spline", "polynomial"):
        raise ValueError(f"pre_stall must be 'spline' or 'polynomial', got {pre_stall!r}")
    if not (cd_max > 0 and cd_reverse > 0 and 0 < epsilon < np.radians(10.0)):
        raise ValueError("need cd_max > 0, cd_reverse > 0 and 0 < epsilon < 10 deg")
    grid = default_alpha_grid() if alpha_grid is None else np.asarray(alpha_grid, dtype=float)
    if np.any(np.abs(grid) > np.pi + 1e-12):
        raise ValueError("alpha_grid must lie in [-pi, pi]")

    fine = np.linspace(alpha[0], alpha[-1], 4 * alpha.size + 1)
    a_s, a_n = detect_stall(fine, _smoothing_spline(alpha, cl, smoothing)(fine))
    if not (a_n < -epsilon and a_s > epsilon and a_s - a_n > 4 * epsilon
            and a_s + epsilon < 0.5 * np.pi and a_n - epsilon > -0.5 * np.pi):
        raise ValueError(
            f"Re={reynolds:g}: detected stall angles {np.degrees(a_n):.2f} and "
            f"{np.degrees(a_s):.2f} deg; Eq. (33) needs the data to reach below "
            f"-{np.degrees(epsilon):g} and above +{np.degrees(epsilon):g} deg with stall "
            "within +-90 deg")

    # The pre-stall fit uses only the data between the stall angles: XFOIL's post-stall
    # points are replaced by Viterna, as in the paper.
    inside = (alpha >= a_n - 1e-12) & (alpha <= a_s + 1e-12)
    if np.count_nonzero(inside) < 6:
        raise ValueError(f"Re={reynolds:g}: fewer than 6 data points between the stall angles")
    a_in = alpha[inside]
    if pre_stall == "spline":
        s_cl = _smoothing_spline(a_in, cl[inside], smoothing)
        # Drag is smoothed in log space: its scatter is relative (a few per cent
        # over a tenfold range), and the fit stays positive.
        s_cd = _smoothing_spline(a_in, np.log(cd[inside]), smoothing)
        ds_cl, ds_cd = s_cl.derivative(), s_cd.derivative()

        def model(x):
            cd_x = np.exp(s_cd(x))
            return (s_cl(x), ds_cl(x)), (cd_x, cd_x * ds_cd(x))
    else:
        f_cl = np.polynomial.Polynomial.fit(a_in, cl[inside], 1)   # Eq. (33a), first line
        f_cd = np.polynomial.Polynomial.fit(a_in, cd[inside], 4)   # Eq. (33b), first line
        df_cl, df_cd = f_cl.deriv(), f_cd.deriv()

        def model(x):
            return (f_cl(x), df_cl(x)), (f_cd(x), df_cd(x))

    out = np.empty((4, grid.size))                      # cl, cd, dcl, dcd
    pre = (grid >= a_n + epsilon) & (grid <= a_s - epsilon)
    (m_cl, m_dcl), (m_cd, m_dcd) = model(grid[pre])
    out[:, pre] = m_cl, m_cd, m_dcl, m_dcd
    for side, a_st in ((1.0, a_s), (-1.0, a_n)):
        (cl_st, _), (cd_st, _) = model(a_st)
        # Blend from the pre-stall model at a_st - side*eps to Viterna at a_st + side*eps.
        x_model, x_vit = a_st - side * epsilon, a_st + side * epsilon
        v_cl, v_cd = post_stall(np.array([x_vit]), a_st, cl_st, cd_st, cd_max, cd_reverse)
        ends = {x_model: model(x_model),
                x_vit: ((v_cl.value[0], v_cl.slope[0]), (v_cd.value[0], v_cd.slope[0]))}
        lo, hi = min(x_model, x_vit), max(x_model, x_vit)
        blend = (grid > lo) & (grid < hi)
        b_cl, b_dcl = hermite_blend(grid[blend], lo, hi, ends[lo][0], ends[hi][0])
        b_cd, b_dcd = hermite_blend(grid[blend], lo, hi, ends[lo][1], ends[hi][1])
        out[:, blend] = b_cl, b_cd, b_dcl, b_dcd
        post = side * (grid - x_vit) >= 0.0
        v_cl, v_cd = post_stall(grid[post], a_st, cl_st, cd_st, cd_max, cd_reverse)
        out[:, post] = v_cl.value, v_cd.value, v_cl.slope, v_cd.slope
    if np.any(out[1] <= 0.0):
        raise ValueError(f"Re={reynolds:g}: the extended drag coefficient is not positive "
                         f"everywhere (min {out[1].min():.3g}); check the data, cd_max and "
                         "cd_reverse")
    return ExtendedPolar(grid, out[0], out[1], out[2], out[3], a_s, a_n, float(reynolds))


def extend_polar(data, **kwargs):
    """:func:`extend_arrays` for a :class:`~bild_mdo.airfoil.sources.polar_data.PolarData`.

    Parameters
    ----------
    data : PolarData
        One polar (``alpha_deg``, ``cl``, ``cd``, ``reynolds``).
    **kwargs
        Passed to :func:`extend_arrays`.

    Returns
    -------
    ExtendedPolar
    """
    return extend_arrays(data.alpha_deg, data.cl, data.cd, data.reynolds, **kwargs)
