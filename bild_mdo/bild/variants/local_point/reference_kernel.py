"""The reference station of the local-point variants on the load-path table, compiled (the method of
:mod:`~bild_mdo.bild.variants.local_point.reference_solve`, whose docstring states it).

Per design: on every run of a sheet along which ``ln Re`` is monotone and
passes through ``ln Re_ref``, a start by linear interpolation of the nodes,
then Newton's method on ``(R2, Rell)``; of the converged states the lowest
``cd/cl`` of those that are a minimum along their path, else (the Reynolds
gap) the lowest of the maxima.  The exact loading's lambda ``N_tot / D_tot``
at the chosen state comes with it (:func:`~bild_mdo.bild.variants.
local_point.kernels.trial_one`).
"""
from __future__ import annotations

import math

import numpy as np

from bild_mdo.bild.variants.local_point.kernels import form_one, lookup, prandtl_one, sheet_s, trial_one
from bild_mdo.utils.compiled import kernel

_INV_STEP = 1000.0


def reference_arrays(table):
    """``(coef_ell, coef_alpha, run_label, run_start, run_stop, run_x0, run_ell)``: what the reference kernel
    reads besides :func:`~bild_mdo.bild.variants.local_point.kernels.table_arrays` (the runs of every sheet along
    which ``ln Re`` is monotone, their nodes concatenated)."""
    runs = table._reynolds_runs()
    sizes = np.array([xs.size for _, xs, _ in runs], dtype=np.int64)
    stop = np.cumsum(sizes)
    return (np.ascontiguousarray(table.coef[1].T), np.ascontiguousarray(table.coef[2].T),
            np.array([k for k, _, _ in runs], dtype=np.int64), stop - sizes, stop,
            np.concatenate([xs for _, xs, _ in runs]), np.concatenate([ells for _, _, ells in runs]))


@kernel
def _crossing(xs, ells, start, stop, ell):
    """``x0`` where a monotone run of nodes passes ``ell`` (linear interpolation), or NaN."""
    first, last = ells[start], ells[stop - 1]
    if not (min(first, last) <= ell <= max(first, last)):
        return math.nan
    rising = last > first
    lo, hi = start, stop - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if (ells[mid] <= ell) == rising:
            lo = mid
        else:
            hi = mid
    span = ells[hi] - ells[lo]
    weight = (ell - ells[lo]) / span if span != 0.0 else 0.0
    return xs[lo] + weight * (xs[hi] - xs[lo])


@kernel
def reference_newton(coef, coef_ell, x_first, low, high, offset, log_k, k_tip, k_hub, vx, vt, phi, x0, ell_ref,
                     torque, loss, settings):
    """Newton's method on ``(R2, Rell)`` from ``(phi, x0)`` on one sheet: ``(phi, x0, converged)``."""
    passes, tol, phi_step, x_step = settings
    for _ in range(int(passes)):
        sn, cs = math.sin(phi), math.cos(phi)
        f, f1, _ = prandtl_one(sn, cs, k_tip, k_hub, loss)
        log_p, tau = form_one(sn, cs, torque)
        tau1 = -1.0 / (sn * sn) if torque else -1.0 / (cs * cs)
        covered, s, s1 = sheet_s(coef, x_first, low, high, offset, x0)
        covered_ell, ell, ell1 = sheet_s(coef_ell, x_first, low, high, offset, x0)
        if not covered:
            return phi, x0, False
        a = vx * (sn + s * cs) + vt * (cs - s * sn)
        a1 = vx * (cs - s * sn) - vt * (sn + s * cs)
        a_s = vx * cs - vt * sn
        u, w = a * sn, a * cs
        u1, w1 = a1 * sn + w, a1 * cs - u
        u_s, w_s = a_s * sn, a_s * cs
        thrust = u * (u - vx)
        if torque:
            load, load1, load_s = u * (vt - w), u1 * (vt - w) - u * w1, u_s * (vt - w) - u * w_s
        else:
            load, load1, load_s = thrust, u1 * (2.0 * u - vx), u_s * (2.0 * u - vx)
        x = log_k + math.log(f * load / (a * a)) - log_p
        x1 = f1 / f + load1 / load - 2.0 * a1 / a - tau
        xs = load_s / load - 2.0 * a_s / a
        ratio = 1.0 + tau * s
        r2 = x - x0 - math.log(ratio)
        r_ell = ell - ell_ref
        j11 = x1 - tau1 * s / ratio
        j12 = xs * s1 - 1.0 - tau * s1 / ratio
        d_phi = (ell1 * r2 - j12 * r_ell) / (j11 * ell1)
        d_x = r_ell / ell1
        if not (math.isfinite(d_phi) and math.isfinite(d_x) and thrust > 0.0 and ratio > 0.0):
            return phi, x0, False
        d_phi = min(max(d_phi, -phi_step), phi_step)
        d_x = min(max(d_x, -x_step), x_step)
        phi -= d_phi
        x0 -= d_x
        if abs(d_phi) <= tol and abs(d_x) <= tol * max(abs(x0), 1.0):
            return phi, x0, True
    return phi, x0, False


@kernel
def reference_all(table, extra, consts, guess, ell_ref, torque, loss, settings, gap_rank, exclude, out):
    """Solve every design's reference station (module docstring).

    ``consts[n, 5]``: ``ln K, k_tip, k_hub, V_x, V_theta``; ``settings``: ``(passes, tol, phi_step, x_step)``;
    ``exclude[n]``: bit ``k`` set, sheet ``k`` is no candidate (0: all are).
    Writes ``out[n, 10]``: ``phi, x0, s, alpha, label, on_table, N_tot, D_tot, slope, Phi`` (``on_table`` 0 where
    no sheet covers ``Re_ref``, or where the table has only maxima there and a sheet passes ``Re_ref`` in the
    cells it leaves out next to a fold: the caller solves those on the polar; ``slope`` the ``d(N_tot/D_tot)/dphi``
    of a station's residual there and ``Phi`` its ``F (e - lambda t)`` at ``lambda = N_tot / D_tot``: the state
    is the ideal load of a station at ``r_ref`` only where ``slope > 0`` and ``Phi < 0``).
    """
    coef, _, cover_first, cover_last, offset, kind, _, _, _, grid, _, _ = table
    coef_ell, coef_alpha, run_label, run_start, run_stop, run_x0, run_ell = extra
    x_first = grid[0]
    for j in range(guess.size):
        log_k, k_tip, k_hub, vx, vt = consts[j, 0], consts[j, 1], consts[j, 2], consts[j, 3], consts[j, 4]
        best_score, best_phi, best_x0, best_label = math.inf, guess[j], math.nan, -1
        near_fold = False
        for m in range(run_label.size):
            start = _crossing(run_x0, run_ell, run_start[m], run_stop[m], ell_ref[j])
            if not math.isfinite(start):
                continue
            label = run_label[m]
            if (exclude[j] >> label) & 1:
                continue
            low, high, off = cover_first[label], cover_last[label], offset[label]
            cell = math.floor((start - x_first) * _INV_STEP)
            if cell < low or cell >= high:
                near_fold = True  # in the cells a sheet leaves out next to its fold
                continue
            phi, x0, ok = reference_newton(coef, coef_ell, x_first, low, high, off, log_k, k_tip, k_hub, vx, vt,
                                           guess[j], start, ell_ref[j], torque, loss, settings)
            if not ok:
                continue
            covered, s, s1 = sheet_s(coef, x_first, low, high, off, x0)
            if not covered:
                continue
            tau = math.cos(phi) / math.sin(phi) if torque else -math.tan(phi)
            ratio = 1.0 + tau * s
            minimum = kind[label] * (1.0 + tau * s1 / ratio) > 0.0
            score = s + (0.0 if minimum else gap_rank)
            if score < best_score:
                best_score, best_phi, best_x0, best_label = score, phi, x0, label
        row = out[j]
        row[0], row[1], row[4], row[5] = best_phi, best_x0, best_label, 0.0
        # No minimum on the table, but a sheet passes Re_ref next to its fold: the polar decides (the gap).
        if best_label < 0 or (near_fold and best_score >= gap_rank):
            continue
        low, high, off = cover_first[best_label], cover_last[best_label], offset[best_label]
        covered, s, _ = sheet_s(coef, x_first, low, high, off, best_x0)
        covered, u, c0, c1, c2, c3 = lookup(coef_alpha, x_first, low, high, off, best_x0)
        row[2], row[3], row[5] = s, c0 + u * (c1 + u * (c2 + u * c3)), 1.0
        tr = trial_one(coef, x_first, low, high, off, kind[best_label], log_k, k_tip, k_hub, vx, vt, 0.0, best_phi,
                       best_x0, torque, loss)
        row[6], row[7] = tr[3] * tr[5], tr[5]
        # The station's own test of a loaded root (f rising through 0, Phi below the unloaded 0) at lambda_ref.
        lam = tr[3]
        tr = trial_one(coef, x_first, low, high, off, kind[best_label], log_k, k_tip, k_hub, vx, vt, lam, best_phi,
                       best_x0, torque, loss)
        row[8], row[9] = tr[4], tr[8]
