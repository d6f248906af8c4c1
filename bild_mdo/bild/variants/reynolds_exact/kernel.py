"""The per-station solve of the Reynolds-aware exact loading, compiled (the method of
:mod:`~bild_mdo.bild.variants.reynolds_exact.solve`, whose docstring states it).

:func:`solve_all` runs, for every station in turn, the steps of that
docstring: the sheets its path meets at the first angle, lowest ``cd/cl``
first (on the sheet of the loaded station inward of it in the same design,
the solve begins where the offsets of the two stations inward from their
first angles, extrapolated in ``r``, predict; from the first angle again
where that gives no loaded root); a grid search where none gives a candidate; then the other sheets the
path meets at the solution and the sheets that end at a fold next to it, each
unless its ``cd/cl`` there is far above the solution's or a Newton model of its ``Phi`` shows it cannot
beat the best; finally one
Newton step on ``R2`` at the chosen angle.  Every bracketed solve is
:func:`~bild_mdo.bild.variants.local_point.sheet_solve.sheet_solve` on
:func:`sheet_value` of one sheet, whose ``state`` array records the station's
last trials on it (slots ``_X0`` ... below).
"""
from __future__ import annotations

import math

import numpy as np

from bild_mdo.airfoil.load_path_table import X_STEP
from bild_mdo.bild.variants.local_point.paper_kernels import paper_angle_one
from bild_mdo.bild.variants.local_point.kernels import (
    candidates_one,
    finish_one,
    momentum_one,
    sheet_s,
    station_setup,
    trail_begin,
    trail_prediction,
    trail_record,
)
from bild_mdo.bild.variants.local_point.sheet_solve import (
    _BARRIER,
    _COVERED,
    _D_TOT,
    _F,
    _K_HUB,
    _K_TIP,
    _LAM,
    _LOG_K,
    _LOSS,
    _OBJECTIVE,
    _OFFSET,
    _RATE,
    _SLOPE,
    _SOLVE_SIZE,
    _TORQUE,
    _VT,
    _VX,
    _X,
    _X0,
    _X_FIRST,
    _HIGH,
    _LOW,
    _fresh,
    _set_sheet,
    _sign,
    sheet_solve,
    sheet_value,
)
from bild_mdo.utils.compiled import kernel

@kernel
def solve_all(table, flow, num_blades, guess, first_label, torque, loss, settings, probes, search, begin, end, out):
    """Solve stations ``begin`` to ``end - 1`` (module docstring; ``begin`` the first station of a design).

    ``flow[8, n]``: the stations (:func:`~bild_mdo.bild.variants.local_point.kernels.station_setup`); the first
    angle is the paper loading's at ``start_ratio``; ``guess, first_label[n]``: a warm start (NaN, -1: none; empty
    arrays: none anywhere), the angle where the solve on sheet ``first_label`` begins; ``settings``: ``(barrier,
    max_iter, angle_tol, root_step, start_ratio, prune_factor, fold_window, fold_margin, near_ratio)``; ``probes``: the
    probe steps; ``search``: the fractions of the bracket of the grid search.  Writes ``out[11, n]``: ``phi,
    x0, label, code, Phi`` (code 0 loaded, 1 unloaded, 3 overloaded, 4 outside the domain, 5 loaded past the table's
    top) and, where loaded (NaN elsewhere), the station's values
    (:func:`~bild_mdo.bild.variants.local_point.kernels.finish_one`).
    """
    coef, slots, cover_first, cover_last, offset, kind, end_x0, end_label, end_inward, grid, coef_ell, coef_alpha = table
    sheets = (cover_first, cover_last, offset, kind)
    x_first, nx, x_last = grid[0], int(grid[1]), grid[2]
    barrier, max_iter, angle_tol, root_step, start_ratio, prune, window, margin, near_ratio = settings
    solve_settings = (max_iter, angle_tol, root_step)
    k = slots.shape[1]
    labels, x0s, scores = np.empty(k, dtype=np.int64), np.empty(k), np.empty(k)
    near_label = np.empty(k + end_x0.size, dtype=np.int64)
    near_x0, near_phi = np.empty(k + end_x0.size), np.empty(k + end_x0.size)
    st = np.zeros(_SOLVE_SIZE)  # a solve's state, then the station's and the sheet's constants
    work = np.zeros(1)
    st[_BARRIER] = barrier
    st[_X_FIRST], st[_TORQUE], st[_LOSS] = x_first, 1.0 if torque else 0.0, loss
    trail = np.zeros(6)
    warm_any = guess.size > 0
    for j in range(begin, end):
        row = out[:, j]
        for q in range(5, 11):
            row[q] = math.nan
        trail_begin(trail, flow, j)
        ok, st[_LOG_K], st[_K_TIP], st[_K_HUB], lo_j, hi_j = station_setup(flow, j, num_blades, loss, start_ratio)
        if not ok:
            trail_record(trail, -1, 0.0, 0.0)
            row[0], row[1], row[2], row[3], row[4] = 0.0, math.nan, -1.0, 4.0, math.inf
            continue
        st[_LAM], st[_VX], st[_VT] = flow[0, j], flow[1, j], flow[2, j]
        first = paper_angle_one(work, st[_VX], st[_VT], st[_LAM], start_ratio)
        first = min(max(first, lo_j), hi_j) if math.isfinite(first) else lo_j
        guess_j = guess[j] if warm_any else math.nan
        warm, warm_label = (guess_j, first_label[j]) if math.isfinite(guess_j) else (first, -1)
        trail_label, offset_j = trail_prediction(trail, flow[3, j])
        if trail_label >= 0 and not math.isfinite(guess_j):
            # No warm start: the solve on the sheet of the station inward begins where the offset of the stations
            # inward predicts (it changes where Newton's method begins, not which sheets are tried).
            warm, warm_label = min(max(first + offset_j, lo_j), hi_j), trail_label
        best_phi, best_x0, best_obj, best_label = first, math.nan, math.inf, -1
        best_x, best_rate = math.nan, math.nan
        overloaded, above = False, False
        tried = 0
        x_g, tau_g = momentum_one(st[_LOG_K], st[_K_TIP], st[_K_HUB], st[_VX], st[_VT], first, start_ratio, torque,
                                  loss)
        count = candidates_one(slots, x_first, nx, x_g, tau_g, labels, x0s, scores)
        # The sheet of least cd/cl at the first angle; the next one where it gave no load.
        for _ in range(count):
            if best_obj < 0.0 or overloaded:
                break
            m = 0
            for q in range(1, count):
                if scores[q] < scores[m]:
                    m = q
            if scores[m] == math.inf:
                break
            scores[m] = math.inf
            # A warm start changes only where the solve on the station's last sheet begins, not which sheets are
            # tried: the design stays the one a cold start finds.
            start = warm if labels[m] == warm_label else first
            x, x0_c, obj, valid, converged, residual = sheet_solve(coef, sheets, st, labels[m], lo_j, hi_j, -1.0,
                                                                   start, x0s[m], grid, solve_settings)
            if start != first and not obj < 0.0:
                # The predicted start led to no loaded root: the solve from the first angle, as without it.
                x, x0_c, obj, valid, converged, residual = sheet_solve(coef, sheets, st, labels[m], lo_j, hi_j,
                                                                       -1.0, first, x0s[m], grid, solve_settings)
            if obj < best_obj:
                best_phi, best_x0, best_obj, best_label = x, x0_c, obj, labels[m]
                best_x, best_rate = st[_X], st[_RATE]
            if converged and residual < 0.0 and hi_j - x <= 1e-9:
                overloaded = True
            if valid:
                above = above or st[_X0] > x_last - X_STEP
                tried |= 1 << labels[m]
        # No candidate at the first angle: a search of the angles for a minimum on any sheet.
        if not math.isfinite(best_obj) and not overloaded:
            for fraction in search:
                phi_g = lo_j + fraction * (hi_j - lo_j)
                x_s, tau_s = momentum_one(st[_LOG_K], st[_K_TIP], st[_K_HUB], st[_VX], st[_VT], phi_g, start_ratio,
                                          torque, loss)
                found = candidates_one(slots, x_first, nx, x_s, tau_s, labels, x0s, scores)
                for m in range(found):
                    x, x0_c, obj, valid, _, _ = sheet_solve(coef, sheets, st, labels[m], lo_j, hi_j, -1.0, phi_g,
                                                            x0s[m], grid, solve_settings)
                    if obj < best_obj:
                        best_phi, best_x0, best_obj, best_label = x, x0_c, obj, labels[m]
                        best_x, best_rate = st[_X], st[_RATE]
        # The other sheets next to the solution: those its path meets there, and those that end at a fold within
        # the window of its coordinate (probed where the coordinate reaches them).
        near = 0
        if math.isfinite(best_obj):
            if math.isfinite(best_x):
                tau_b = math.cos(best_phi) / math.sin(best_phi) if torque else -math.tan(best_phi)
                found = candidates_one(slots, x_first, nx, best_x, tau_b, labels, x0s, scores)
                for m in range(found):
                    if not (tried >> labels[m]) & 1 and labels[m] != best_label:
                        near_label[near], near_x0[near], near_phi[near] = labels[m], x0s[m], best_phi
                        near += 1
            if math.isfinite(best_rate) and best_rate != 0.0:
                # The ends are sorted by x0 (LoadPathTable.sheet_ends): those in the window, in that order.
                for e in range(np.searchsorted(end_x0, best_x0 - window), end_x0.size):
                    if end_x0[e] >= best_x0 + window:
                        break
                    label = end_label[e]
                    target = end_x0[e] + end_inward[e] * (margin * X_STEP)
                    phi_p = best_phi + (target - best_x0) / best_rate
                    if not (tried >> label) & 1 and label != best_label and lo_j < phi_p < hi_j:
                        near_label[near], near_x0[near], near_phi[near] = label, target, phi_p
                        near += 1
        best_ref = best_obj
        s_best = math.inf
        if near > 0:
            _set_sheet(st, sheets, best_label)
            covered, s_here, _ = sheet_s(coef, x_first, st[_LOW], st[_HIGH], st[_OFFSET], best_x0)
            if covered and s_here > 0.0:
                s_best = s_here
        for m in range(near):
            phi_m = near_phi[m]
            _set_sheet(st, sheets, near_label[m])
            # A sheet whose cd/cl where it is met exceeds the best's by more than near_ratio is no candidate.
            covered, s_here, _ = sheet_s(coef, x_first, st[_LOW], st[_HIGH], st[_OFFSET], near_x0[m])
            if covered and s_here > near_ratio * s_best:
                continue
            _fresh(st, near_x0[m])
            sheet_value(phi_m, st, coef)
            here, slope, d_tot = st[_F], st[_SLOPE], st[_D_TOT]
            if not (st[_COVERED] > 0.0 and d_tot > 0.0):
                continue
            drop = 0.5 * abs(d_tot) * here * here / abs(slope)
            if not st[_OBJECTIVE] - prune * (drop if math.isfinite(drop) else math.inf) < best_ref:
                continue
            x0_here = st[_X0]
            step = abs(here / slope)
            direction = -1.0 if here > 0.0 else 1.0
            step = min(max(step, 0.001), 0.15) if (math.isfinite(step) and slope > 0.0) else probes[0]
            far = min(max(phi_m + 2.0 * direction * step, lo_j), hi_j)
            f_lo = -_sign(here) if far < phi_m else _sign(here)
            x, x0_c, obj, valid, _, _ = sheet_solve(coef, sheets, st, near_label[m], min(phi_m, far),
                                                    max(phi_m, far), f_lo, phi_m + direction * step, x0_here, grid,
                                                    solve_settings)
            if obj < best_obj:
                best_phi, best_x0, best_obj, best_label = x, x0_c, obj, near_label[m]
            if valid or abs(x - far) > 1e-9:
                continue
            # The root is not within twice the Newton step: probe for a bracket.
            edge = hi_j if direction > 0.0 else lo_j
            for size in probes:
                probe = min(max(phi_m + direction * (size + 2.0 * step), lo_j), hi_j)
                _fresh(st, x0_here)
                value = sheet_value(probe, st, coef)[0]
                if value != -1.0 and _sign(value) != _sign(here):
                    f_lo = -_sign(here) if probe < phi_m else _sign(here)
                    x, x0_c, obj, _, _, _ = sheet_solve(coef, sheets, st, near_label[m], min(phi_m, probe),
                                                        max(phi_m, probe), f_lo, phi_m, x0_here, grid, solve_settings)
                    if obj < best_obj:
                        best_phi, best_x0, best_obj, best_label = x, x0_c, obj, near_label[m]
                    break
                if value == -1.0 or probe == edge:
                    break
        if math.isfinite(best_obj) and best_obj < 0.0:
            _set_sheet(st, sheets, best_label)
            values = finish_one(coef, coef_ell, coef_alpha, x_first, st[_LOW], st[_HIGH], st[_OFFSET], st[_LOG_K],
                                st[_K_TIP], st[_K_HUB], st[_VX], st[_VT], best_phi, best_x0, torque, loss)
            row[1] = values[0]
            row[0], row[2], row[3], row[4] = best_phi, best_label, 5.0 if above else 0.0, best_obj
            for q in range(6):
                row[5 + q] = values[1 + q]
            trail_record(trail, best_label, best_phi - first, flow[3, j])
        else:
            trail_record(trail, -1, 0.0, 0.0)
            row[0], row[1], row[2], row[3], row[4] = lo_j, math.nan, -1.0, 3.0 if overloaded else 1.0, best_obj
