"""The per-station solve of the paper's loading with the local section point, compiled (the method of
:mod:`~bild_mdo.bild.variants.local_paper.solve`, whose docstring states it).

Per station, in the inflow angle: on every sheet that the station's path meets
as a minimum of ``cd/cl`` at the first angle (the paper loading at a typical
``cd/cl``), the root of the quartic's physical factor ``h(phi)`` with the
section point carried along the sheet
(:func:`~bild_mdo.bild.variants.local_point.sheet_solve.sheet_solve`); of the
roots the one of least ``cd/cl`` is kept.  Where the path of that solution
meets a minimum of lower ``cd/cl`` on another sheet, the station is solved on
that sheet too and takes it where its root has the lower ``cd/cl``
(:data:`~bild_mdo.bild.variants.local_paper.solve.SWITCHES` times at most).
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
    station_setup,
    trail_begin,
    trail_prediction,
    trail_record,
)
from bild_mdo.bild.variants.local_point.sheet_solve import (
    _BARRIER,
    _HIGH,
    _K_HUB,
    _K_TIP,
    _LAM,
    _LOG_K,
    _LOSS,
    _LOW,
    _OFFSET,
    _PAPER,
    _SOLVE_SIZE,
    _TORQUE,
    _VT,
    _VX,
    _X,
    _X_FIRST,
    _set_sheet,
    sheet_solve,
)
from bild_mdo.utils.compiled import kernel


@kernel
def solve_all(table, flow, num_blades, torque, loss, settings, begin, end, out):
    """Solve stations ``begin`` to ``end - 1`` (module docstring; ``begin`` the first station of a design).

    ``flow[8, n]``: the stations (:func:`~bild_mdo.bild.variants.local_point.kernels.station_setup`; the bracket
    ends at ``eta2 = 1/2`` with ``cd/cl = 0``); the first angle is the paper loading's at ``start_ratio``, at
    ``lowest_ratio`` where that leaves the station unloaded;
    ``settings``: ``(barrier, max_iter, angle_tol, root_step, start_ratio, lowest_ratio,
    switches)``.  Writes ``out[10, n]``: ``phi, x0, label, code`` (code 0 loaded, 1 unloaded, 4 outside the domain, 5 loaded past the
    table's top) and, where loaded, the station's values (NaN elsewhere)
    (:func:`~bild_mdo.bild.variants.local_point.kernels.finish_one`).
    """
    coef, slots, cover_first, cover_last, offset, kind, _, _, _, grid, coef_ell, coef_alpha = table
    sheets = (cover_first, cover_last, offset, kind)
    x_first, nx, x_last = grid[0], int(grid[1]), grid[2]
    barrier, max_iter, angle_tol, root_step, start_ratio, lowest_ratio, switches = settings
    solve_settings = (max_iter, angle_tol, root_step)
    k = slots.shape[1]
    labels, x0s, scores = np.empty(k, dtype=np.int64), np.empty(k), np.empty(k)
    st = np.zeros(_SOLVE_SIZE)  # a solve's state, then the station's and the sheet's constants
    work = np.zeros(1)
    st[_BARRIER] = barrier
    st[_X_FIRST], st[_TORQUE], st[_LOSS], st[_PAPER] = x_first, 1.0 if torque else 0.0, loss, 1.0
    trail = np.zeros(6)
    for j in range(begin, end):
        row = out[:, j]
        for q in range(4, 10):
            row[q] = math.nan
        trail_begin(trail, flow, j)
        ok, st[_LOG_K], st[_K_TIP], st[_K_HUB], lo_j, hi_j = station_setup(flow, j, num_blades, loss, 0.0)
        if not ok:
            trail_record(trail, -1, 0.0, 0.0)
            row[0], row[1], row[2], row[3] = 0.0, math.nan, -1.0, 4.0
            continue
        st[_LAM], st[_VX], st[_VT] = flow[0, j], flow[1, j], flow[2, j]
        row[0], row[1], row[2], row[3] = lo_j, math.nan, -1.0, 1.0
        # Hover: the quartic leaves the station unloaded at every cd/cl its path can reach.
        if st[_VX] == 0.0 and st[_LAM] <= 0.5 * lowest_ratio * st[_VT]:
            trail_record(trail, -1, 0.0, 0.0)
            continue
        first = paper_angle_one(work, st[_VX], st[_VT], st[_LAM], start_ratio)
        if not math.isfinite(first):
            first = paper_angle_one(work, st[_VX], st[_VT], st[_LAM], lowest_ratio)
        first = min(max(first, lo_j), hi_j) if math.isfinite(first) else lo_j
        best_phi, best_x0, best_s, best_label, best_x = first, math.nan, math.inf, -1, math.nan
        x_g, tau_g = momentum_one(st[_LOG_K], st[_K_TIP], st[_K_HUB], st[_VX], st[_VT], first, start_ratio, torque,
                                  loss)
        count = candidates_one(slots, x_first, nx, x_g, tau_g, labels, x0s, scores)
        # On the sheet of the loaded station inward, the solve begins where the offsets of the stations inward
        # from their first angles predict (from the first angle again where that gives no root on the sheet).
        trail_label, offset_j = trail_prediction(trail, flow[3, j])
        predicted = min(max(first + offset_j, lo_j), hi_j)
        for m in range(count):
            start = predicted if labels[m] == trail_label else first
            x, x0_c, s, _, _, _ = sheet_solve(coef, sheets, st, labels[m], lo_j, hi_j, -1.0, start, x0s[m],
                                              grid, solve_settings)
            if start != first and not s < math.inf:
                x, x0_c, s, _, _, _ = sheet_solve(coef, sheets, st, labels[m], lo_j, hi_j, -1.0, first, x0s[m],
                                                  grid, solve_settings)
            if s < best_s:
                best_phi, best_x0, best_s, best_label, best_x = x, x0_c, s, labels[m], st[_X]
        # The solution's own path: a lower minimum there is the station's section point instead.
        for _ in range(int(switches)):
            if not (math.isfinite(best_s) and math.isfinite(best_x)):
                break
            tau_b = math.cos(best_phi) / math.sin(best_phi) if torque else -math.tan(best_phi)
            found = candidates_one(slots, x_first, nx, best_x, tau_b, labels, x0s, scores)
            moved = False
            start_phi = best_phi
            for m in range(found):
                if labels[m] == best_label or not scores[m] < best_s * (1.0 - 1e-12):
                    continue
                x, x0_c, s, _, _, _ = sheet_solve(coef, sheets, st, labels[m], lo_j, hi_j, -1.0, start_phi,
                                                  x0s[m], grid, solve_settings)
                if s < best_s:
                    best_phi, best_x0, best_s, best_label, best_x = x, x0_c, s, labels[m], st[_X]
                    moved = True
            if not moved:
                break
        if math.isfinite(best_s):
            _set_sheet(st, sheets, best_label)
            values = finish_one(coef, coef_ell, coef_alpha, x_first, st[_LOW], st[_HIGH], st[_OFFSET], st[_LOG_K],
                                st[_K_TIP], st[_K_HUB], st[_VX], st[_VT], best_phi, best_x0, torque, loss)
            row[1] = values[0]
            row[0], row[2], row[3] = best_phi, best_label, 5.0 if row[1] > x_last - X_STEP else 0.0
            for q in range(6):
                row[4 + q] = values[1 + q]
            trail_record(trail, best_label, best_phi - first, flow[3, j])
        else:
            trail_record(trail, -1, 0.0, 0.0)
