"""One bracketed solve of one station on one sheet of the load-path table, compiled (both local-point variants).

:func:`sheet_solve` is :func:`~bild_mdo.utils.compiled.bracketed_newton_for` of
:func:`sheet_value`, the loading residual of the station on that sheet as a
function of the inflow angle: the Reynolds-aware exact loading's ``f = N_tot /
D_tot - lambda`` (:func:`~bild_mdo.bild.variants.local_point.kernels.trial_one`)
or the paper loading's physical factor ``h`` of the quartic
(:func:`~bild_mdo.bild.variants.local_point.kernels.paper_trial_one`), with the
sheet coordinate ``x0`` carried along from trial to trial.  Off the sheet the
residual is continued linearly from the last trial on it (so the solver steps
back to a root on the sheet, or converges quickly to one beyond its edge,
which is no candidate), before any trial on it as -1 on the lighter side and
the barrier on the heavier side; past the largest annulus thrust (exact
loading) or ``eta2 < 1/2`` (paper loading) it is the barrier.  One array
``st`` goes through the solver: its first slots record the last trials
(``_X0`` ... below), the others hold the station and the sheet (``_LOG_K`` ...),
so that a trial passes no tuple of arrays.
"""
from __future__ import annotations

import math

from bild_mdo.airfoil.load_path_table import X_STEP
from bild_mdo.bild.variants.local_point.kernels import trial_one
from bild_mdo.bild.variants.local_point.paper_kernels import paper_trial_one
from bild_mdo.utils.compiled import bracketed_newton_for, kernel

# Slots of a sheet solve's state: the coordinate, its two rates and the angle of the last trial on the sheet, f
# and its slope there, whether there was one; the last trial's x, Phi, whether it was on the sheet, D_tot, f and
# slope.
_X0, _RATE, _RATE1, _ON, _F_ON, _SLOPE_ON, _SEEN, _X, _OBJECTIVE, _COVERED, _D_TOT, _F, _SLOPE = range(13)
_STATE_SIZE = 13
# Slots of a sheet solve's constants, after the state in the same array, and the size of the array.
_LOG_K, _K_TIP, _K_HUB, _VX, _VT, _LAM, _LOW, _HIGH, _OFFSET, _KIND, _X_FIRST, _TORQUE, _LOSS, _PAPER, _BARRIER = \
    range(_STATE_SIZE, _STATE_SIZE + 15)
_SOLVE_SIZE = _STATE_SIZE + 15


@kernel
def _move(x0, rate, rate1, step):
    bend = 0.5 * step * rate1
    return x0 + step * (rate + bend if abs(bend) <= 0.5 * abs(rate) else rate)


@kernel
def sheet_value(phi, st, coef):
    """``(f, slope, scale)`` of one sheet at ``phi`` (module docstring)."""
    barrier = st[_BARRIER]
    step = phi - st[_ON]
    predicted = _move(st[_X0], st[_RATE], st[_RATE1], step)
    paper = st[_PAPER] > 0.0
    if paper:
        x0, s, x, f, slope, d_tot, rate, rate1, objective, minimum = paper_trial_one(
            coef, st[_X_FIRST], st[_LOW], st[_HIGH], st[_OFFSET], st[_KIND], st[_LOG_K], st[_K_TIP], st[_K_HUB],
            st[_VX], st[_VT], st[_LAM], phi, predicted, st[_TORQUE] > 0.0, int(st[_LOSS]))
    else:
        x0, s, x, f, slope, d_tot, rate, rate1, objective, minimum = trial_one(
            coef, st[_X_FIRST], st[_LOW], st[_HIGH], st[_OFFSET], st[_KIND], st[_LOG_K], st[_K_TIP], st[_K_HUB],
            st[_VX], st[_VT], st[_LAM], phi, predicted, st[_TORQUE] > 0.0, int(st[_LOSS]))
    good = minimum and math.isfinite(f) and math.isfinite(slope)
    if good:
        st[_X0], st[_RATE], st[_RATE1], st[_ON] = x0, rate, rate1, phi
        st[_F_ON], st[_SLOPE_ON], st[_SEEN] = f, slope, 1.0
    st[_X], st[_OBJECTIVE], st[_COVERED], st[_D_TOT], st[_F], st[_SLOPE] = x, objective, 1.0 if good else 0.0, \
        d_tot, f, slope
    where = x0 if math.isfinite(x0) else predicted
    top = st[_X_FIRST] + X_STEP * st[_HIGH]
    heavier = where >= top
    seen = st[_SEEN] > 0.0
    continued = st[_F_ON] + st[_SLOPE_ON] * (phi - st[_ON])
    scale = d_tot if paper else abs(f + st[_LAM]) + abs(st[_LAM])
    if good:
        if not d_tot > 0.0:
            return barrier, (st[_SLOPE_ON] if seen else 1.0), scale
        return f, slope, scale
    slope_off = st[_SLOPE_ON] if seen else 1.0
    if seen:
        lighter = where <= st[_X_FIRST] + X_STEP * st[_LOW]
        if (lighter and continued > 0.0) or (heavier and continued < 0.0):
            return math.nan, slope_off, scale
        return continued, slope_off, scale
    return (barrier if heavier else -1.0), slope_off, scale


_newton = bracketed_newton_for(sheet_value)


@kernel
def _set_sheet(st, slots_table, label):
    cover_first, cover_last, offset, kind = slots_table
    st[_LOW], st[_HIGH], st[_OFFSET], st[_KIND] = cover_first[label], cover_last[label], offset[label], kind[label]


@kernel
def _fresh(st, x0):
    for k in range(_STATE_SIZE):  # the state only: the constants follow it
        st[k] = 0.0
    st[_X0] = x0
    st[_X], st[_OBJECTIVE] = math.nan, math.nan


@kernel
def sheet_solve(coef, sheets, st, label, lo, hi, f_lo, start, x0, grid, settings):
    """One bracketed solve on sheet ``label``: ``(phi, x0, objective, valid, converged, residual)``; the objective
    (``Phi = F (e - lambda t)`` of the exact loading, ``cd/cl`` of the paper loading's) is infinite where the
    root is not valid: not converged, off the sheet, at a jump of the residual (neither it nor its last Newton
    step small) or below the table."""
    max_iter, angle_tol, root_step = settings  # the barrier is st[_BARRIER] (set once per kernel call)
    _set_sheet(st, sheets, label)
    _fresh(st, x0)
    x, converged, residual, slope, _ = _newton(st, coef, lo, hi, f_lo, start, int(max_iter), angle_tol)
    x0_c = _move(st[_X0], st[_RATE], st[_RATE1], x - st[_ON])
    small = abs(residual) <= 1e-6 * abs(st[_LAM]) or abs(residual / slope) <= root_step
    valid = converged and st[_COVERED] > 0.0 and small and x0_c >= grid[0] + X_STEP
    return x, x0_c, (st[_OBJECTIVE] if valid else math.inf), valid, converged, residual


@kernel
def _sign(value):
    return 1.0 if value > 0.0 else (-1.0 if value < 0.0 else value)
