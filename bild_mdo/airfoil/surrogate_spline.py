"""The spline of :class:`~bild_mdo.airfoil.surrogate.TabulatedPolar` in ``log10 Re``: its end conditions, its
optional split, and the bounds of the continuation below the lowest table (the class docstring explains them)."""
from __future__ import annotations

import numpy as np

#: Below the lowest table the continuation saturates (class docstring): lift changes by less than
#: ``LOW_REYNOLDS_LIFT_CHANGE`` and drag by less than a factor ``LOW_REYNOLDS_DRAG_FACTOR`` from the edge's values,
#: however low the Reynolds number.  The drag factor is that of the laminar skin-friction law Re^-1/2 over one
#: decade (10**0.5 = 3.2, rounded to 3).
LOW_REYNOLDS_LIFT_CHANGE = 0.2
LOW_REYNOLDS_DRAG_FACTOR = 3.0
LOW_REYNOLDS_BOUNDS = (LOW_REYNOLDS_LIFT_CHANGE, float(np.log(LOW_REYNOLDS_DRAG_FACTOR)))
#: End conditions of the spline in log Re at the lowest table (``TabulatedPolar(low_end=...)``).
LOW_ENDS = ("not-a-knot", "physical")


def split_index(reynolds, split_reynolds):
    """Index of ``split_reynolds`` in the increasing ``reynolds`` (None without a split); ValueError unless it is
    one of the tables other than the first and the last."""
    if split_reynolds is None:
        return None
    split = float(split_reynolds)
    hit = np.flatnonzero(np.isclose(reynolds, split, rtol=1e-9, atol=0.0))
    if hit.size != 1 or hit[0] in (0, reynolds.size - 1):
        raise ValueError(f"TabulatedPolar: split_reynolds={split:g} must be one of the tabulated Reynolds numbers "
                         f"other than the first and the last, {reynolds.tolist()}")
    return int(hit[0])


def physical_low_slope(grid, values, log_re):
    """Slopes ``d/dlog10 Re`` at the lowest table for ``low_end='physical'``, as the alpha-cell coefficients of
    the periodic cubic spline of their values on ``grid``, shape ``(4, cells, 2)``.

    Lift flat.  Drag ``d(log cd)/dlog10 Re = m0 cos(alpha)**2``: ``m0`` the median over 0..8 deg (attached
    flow) of the ``log cd`` secant of the two lowest tables, at most 0 (drag never rising with Re); the
    ``cos**2`` leaves the flat plate's drag at 90 deg unchanged (pressure drag, not friction).  One smooth
    law for every angle, so the spline of the slope has one sign (secants angle by angle jump where XFOIL's
    data jump, and their spline rings to the wrong sign between the angles).
    """
    from scipy.interpolate import CubicSpline

    cd0, cd1 = values[:, 0, 1], values[:, 1, 1]
    attached = (grid >= 0.0) & (grid <= np.radians(8.0) + 1e-12)
    secant = np.log(cd1[attached] / cd0[attached]) / (log_re[1] - log_re[0])
    m0 = min(float(np.median(secant)), 0.0)
    slope = np.stack([np.zeros_like(cd0), m0 * np.cos(grid) ** 2 * cd0], axis=-1)
    slope[-1] = slope[0]
    return CubicSpline(grid, slope, axis=0, bc_type="periodic").c


def reynolds_spline(log_re, values, split, low_slope=None):
    """Coefficients ``c[k, j, ...]`` (power ``3 - k`` of ``log10 Re - log_re[j]``) of the cubic spline through
    ``values`` (Reynolds along axis 2) in ``log10 Re`` (class docstring: ``split_reynolds``, ``low_end``).

    Without a split: one spline.  With a split at ``log_re[split]``: the tables from there up get their own
    not-a-knot spline, and the tables below one that takes the upper spline's slope at the split (C^1 there).
    The lowest table's end is not-a-knot, or with ``low_slope`` (coefficients of the slope in alpha) clamped.
    """
    from scipy.interpolate import CubicSpline

    low = "not-a-knot" if low_slope is None else (1, low_slope)
    if split is None:
        return CubicSpline(log_re, values, axis=2, bc_type=(low, "not-a-knot")).c
    upper = CubicSpline(log_re[split:], values[:, :, split:], axis=2, bc_type="not-a-knot")
    slope = upper.derivative()(log_re[split])
    lower = CubicSpline(log_re[:split + 1], values[:, :, :split + 1], axis=2, bc_type=(low, (1, slope)))
    return np.concatenate([lower.c, upper.c], axis=1)
