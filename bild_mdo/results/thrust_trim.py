"""Trim every point of an off-design sweep to a thrust: the collective pitch or the rotor speed that gives it.

:func:`trim_points` solves, for all points at once, ``T(x) = T*`` in ``x`` =
the collective pitch (rad) or the rotor speed (rpm) of each point, with the
BEM analysis of the fixed blade (:func:`~bild_mdo.bem.analyze_rotor`):

1. a scan of :data:`SCAN_POINTS` values over the search range
   (:data:`PITCH_RANGE` rad, or :data:`RPM_FACTORS` times the point's rotor
   speed) in one vectorised analysis; the bracket is the first interval, from
   the low end, on which ``T - T*`` changes sign from below (thrust rises with
   pitch and speed until the blade stalls, so this is the attached-flow root,
   not the one past stall);
2. the Illinois variant of regula falsi inside each bracket, all points in one
   analysis per step, until ``|T / T* - 1| <= THRUST_RTOL``.

A point whose scan finds no crossing (the thrust is out of reach in the range)
is reported in ``status`` with that reason; it never stops the sweep.
"""
from __future__ import annotations

import numpy as np

#: Collective pitch range searched (rad): -20 ... +40 deg.
PITCH_RANGE = (np.radians(-20.0), np.radians(40.0))
#: Rotor-speed range searched, as factors of each point's rotor speed.
RPM_FACTORS = (0.1, 5.0)
#: Values of the first scan.
SCAN_POINTS = 25
#: Relative thrust tolerance of the trim.
THRUST_RTOL = 1e-10
#: Regula-falsi steps at most.
MAX_STEPS = 60

TRIM_VARIABLES = ("collective_pitch", "rpm")


def trim_points(evaluate, thrust_target, start, trim):
    """``(x, trimmed)``: the trimmed value of every point and whether it reached the target.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(x)`` -> thrust (N) of every point at the values ``x`` (shape ``(n, k)`` gives ``(n, k)``:
        ``k`` values per point, analysed together).
    thrust_target : float
        T* (N), > 0.
    start : ndarray, shape (n,)
        Each point's current pitch (rad) or rotor speed (rpm) (the rpm range is relative to it).
    trim : {'collective_pitch', 'rpm'}
    """
    n = start.size
    if trim == "collective_pitch":
        grid = np.broadcast_to(np.linspace(*PITCH_RANGE, SCAN_POINTS), (n, SCAN_POINTS))
    else:
        grid = start[:, None] * np.geomspace(*RPM_FACTORS, SCAN_POINTS)[None, :]
    g = evaluate(grid) / thrust_target - 1.0
    crossing = (g[:, :-1] < 0.0) & (g[:, 1:] >= 0.0) & np.isfinite(g[:, :-1]) & np.isfinite(g[:, 1:])
    found = np.any(crossing, axis=1)
    first = np.argmax(crossing, axis=1)
    rows = np.arange(n)
    lo, hi = grid[rows, first].copy(), grid[rows, first + 1].copy()
    g_lo, g_hi = g[rows, first].copy(), g[rows, first + 1].copy()
    x = np.where(found, hi, start)
    done = ~found | (np.abs(g_hi) <= THRUST_RTOL)
    side = np.zeros(n, dtype=int)  # Illinois: which end was kept last (+1 hi, -1 lo)
    for _ in range(MAX_STEPS):
        if np.all(done):
            break
        with np.errstate(divide="ignore", invalid="ignore"):
            x_new = np.where(done, x, (lo * g_hi - hi * g_lo) / (g_hi - g_lo))
        x_new = np.where(np.isfinite(x_new) & (x_new > lo) & (x_new < hi), x_new, 0.5 * (lo + hi))
        g_new = np.where(done, 0.0, evaluate(np.where(done, x, x_new)[:, None])[:, 0] / thrust_target - 1.0)
        below = g_new < 0.0
        active = ~done
        # The end kept twice in a row has its residual halved (Illinois), so the bracket closes from both sides.
        g_hi = np.where(active & below & (side == 1), 0.5 * g_hi, g_hi)
        g_lo = np.where(active & ~below & (side == -1), 0.5 * g_lo, g_lo)
        lo, g_lo = np.where(active & below, x_new, lo), np.where(active & below, g_new, g_lo)
        hi, g_hi = np.where(active & ~below, x_new, hi), np.where(active & ~below, g_new, g_hi)
        side = np.where(active, np.where(below, 1, -1), side)
        x = np.where(active, x_new, x)
        done |= active & ((np.abs(g_new) <= THRUST_RTOL) | (hi - lo <= 1e-14 * np.maximum(np.abs(hi), 1.0)))
    return x, found


def out_of_reach(trim, thrust_target):
    """The status text of a point whose thrust target is not reached in the search range."""
    if trim == "collective_pitch":
        where = f"collective pitch {np.degrees(PITCH_RANGE[0]):g} ... {np.degrees(PITCH_RANGE[1]):g} deg"
    else:
        where = f"rotor speed {RPM_FACTORS[0]:g} ... {RPM_FACTORS[1]:g} times the point's"
    return f"thrust {thrust_target:g} N not reached with {where} before the blade stalls"
