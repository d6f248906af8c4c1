"""Compiled per-station pieces of the local-section-point model: sheet lookups, one trial, the station set-up.

The same model as :mod:`~bild_mdo.bild.variants.local_point.load_path_model`
(whose docstring derives it), written for one station at a time so that the
solves of :mod:`~bild_mdo.bild.variants.reynolds_exact.kernel` can decide per
station (:mod:`bild_mdo.utils.compiled`).  :func:`trial_one` returns, to
round-off, what :func:`~bild_mdo.bild.variants.local_point.load_path_model.trial`
returns for that station (``tests/bild/variants/test_local_stations.py`` compares
them); the components' partials come from the compiled tangent model of
:mod:`~bild_mdo.bild.variants.local_point.partials_kernel`, their complex-step
path from the whole-array jets.

A table is passed as the tuple of :func:`table_arrays`.  Prandtl's factor is in
:mod:`~bild_mdo.bild.variants.local_point.prandtl_kernels` (:func:`prandtl_one` and :func:`prandtl_value_one`
are imported here for the kernels that use them).
"""
from __future__ import annotations

import math

import numpy as np

from bild_mdo.airfoil.load_path_table import X_STEP
from bild_mdo.bild.annulus_stationarity import HOVER_PHI_MIN
from bild_mdo.bild.variants.local_point.prandtl_kernels import prandtl_one, prandtl_value_one  # noqa: F401
from bild_mdo.utils.compiled import kernel

#: Newton steps on R2 in x0 per trial at most, and the step (in x0 = ln Re + ln cl) after which no more is taken:
#: a trial's residual is then that of a state on R2 = 0 to round-off, so the angle solve converges
#: quadratically also from a poor x0 (a warm start, a probe); nor where the steps so far predict the next one
#: (``|d|**3 / |d_before|**2``, quadratic convergence) below X0_ROUNDOFF, the round-off of x0 (about 10).
X0_PASSES, X0_TOL, X0_ROUNDOFF = 4, 1e-9, 1e-15
_INV_STEP = 1.0 / X_STEP
#: Codes of the loss models in the kernels.
LOSS_CODES = {"none": 0, "tip": 1, "tip_hub": 2}
_NAN = math.nan


def table_arrays(table):
    """The arrays of a :class:`~bild_mdo.airfoil.load_path_table.LoadPathTable` that the kernels read (kept on
    the table): ``(coef_s, slots, cover_first, cover_last, offset, kind, end_x0, end_label, end_inward, grid,
    coef_ell, coef_alpha)`` with ``grid = (x_first, nx, x_last)``, the cubics' coefficients ``[rows, 4]`` and
    ``slots[nx, SLOTS, 6]`` the table's node slots (:meth:`~bild_mdo.airfoil.load_path_table.LoadPathTable.
    node_slots`) with the fields of one slot side by side and the sheets of a node first, in their order."""
    arrays = getattr(table, "_kernel_arrays", None)
    if arrays is None:
        ends = table.sheet_ends()
        arrays = (np.ascontiguousarray(table.coef[0].T), _packed_slots(table.node_slots()),
                  table.cover_first.astype(np.int64), table.cover_last.astype(np.int64),
                  (table.row0 - table.first).astype(np.int64), table.kind.astype(float), ends[0],
                  ends[1].astype(np.int64), ends[2], np.array([table.x_first, table.nx, table.x_last]),
                  np.ascontiguousarray(table.coef[1].T), np.ascontiguousarray(table.coef[2].T))
        table._kernel_arrays = arrays
    return arrays


def _packed_slots(slots):
    """``[nx, SLOTS, 6]``: the slots of each node with a sheet first (stable), one slot's fields contiguous."""
    fields = slots.transpose(0, 2, 1)
    order = np.argsort(fields[:, :, 0] < 0.0, axis=1, kind="stable")
    return np.ascontiguousarray(np.take_along_axis(fields, order[:, :, None], axis=1))


@kernel
def form_one(sn, cs, torque):
    """``ln p, tau`` of the chord form (``p = sin, tau = cot`` for the torque form, else ``cos, -tan``)."""
    if torque:
        return math.log(sn), cs / sn
    return math.log(cs), -sn / cs


@kernel
def lookup(coef, x_first, low, high, offset, x0):
    """``(covered, u, c0, c1, c2, c3)``: the cubic of a sheet (its cover ``[low, high)`` and row ``offset``) in
    the cell of ``x0`` and the local coordinate there (``coef[rows, 4]``: one cell's coefficients side by side,
    one memory access)."""
    t = (x0 - x_first) * _INV_STEP
    if not (t == t):
        return False, 0.0, 0.0, 0.0, 0.0, 0.0
    i = math.floor(t)
    if i < low or i >= high:
        return False, 0.0, 0.0, 0.0, 0.0, 0.0
    row = int(offset + i)
    return True, t - i, coef[row, 0], coef[row, 1], coef[row, 2], coef[row, 3]


@kernel
def sheet_s(coef, x_first, low, high, offset, x0):
    """``(covered, s, ds/dx0)`` of a sheet at ``x0``."""
    covered, u, c0, c1, c2, c3 = lookup(coef, x_first, low, high, offset, x0)
    if not covered:
        return False, _NAN, _NAN
    return True, c0 + u * (c1 + u * (c2 + u * c3)), (c1 + u * (2.0 * c2 + 3.0 * u * c3)) * _INV_STEP


@kernel
def _load_terms(sn, cs, s, vx, vt, torque):
    """``(A, dA/ds, load, dload/ds)`` at ``(phi, s)``: :func:`light_load` before its logarithm and divisions."""
    a = vx * (sn + s * cs) + vt * (cs - s * sn)
    a_s = vx * cs - vt * sn
    u, u_s = a * sn, a_s * sn
    if torque:
        w, w_s = a * cs, a_s * cs
        return a, a_s, u * (vt - w), u_s * (vt - w) - u * w_s
    return a, a_s, u * (u - vx), u_s * (2.0 * u - vx)


@kernel
def light_load(log_k, f, sn, cs, s, vx, vt, torque, log_p):
    """``x_m``, ``dx_m/ds`` at ``(phi, s)`` (as ``load_path_model._light_log_load``)."""
    a, a_s, load, load_s = _load_terms(sn, cs, s, vx, vt, torque)
    return log_k + math.log(f * load / (a * a)) - log_p, load_s / load - 2.0 * a_s / a


@kernel
def on_sheet(coef, x_first, low, high, offset, log_k, f, sn, cs, vx, vt, torque, log_p, tau, x0):
    """The state on a sheet at ``phi`` from the prediction ``x0``: Newton steps on ``R2`` in ``x0`` (one where the
    prediction was good, at most :data:`X0_PASSES`), the cubic moved with ``x0`` exactly inside its cell.

    Returns ``(where, x0, s, s', s'', x_m, dx_m/ds, s_before)``: ``where`` 2 on the sheet, 1 left by the correction
    (``x0`` the corrected one), 0 off it at the prediction; ``x_m`` and its slope at ``s_before``, the last ``s``."""
    nan = _NAN
    covered, u, c0, c1, c2, c3 = lookup(coef, x_first, low, high, offset, x0)
    if not covered:
        return 0, nan, nan, nan, nan, nan, nan, nan
    sv = c0 + u * (c1 + u * (c2 + u * c3))
    s1 = (c1 + u * (2.0 * c2 + 3.0 * u * c3)) * _INV_STEP
    s2 = (2.0 * c2 + 6.0 * u * c3) * _INV_STEP * _INV_STEP
    s3 = 6.0 * c3 * _INV_STEP ** 3
    a, a_s, load, load_s, s_start = nan, nan, nan, nan, sv
    log_base = log_k - log_p
    d_before = 0.0  # no step before the first
    for _ in range(X0_PASSES):
        s_start = sv
        a, a_s, load, load_s = _load_terms(sn, cs, sv, vx, vt, torque)
        # R2 = x_m - x0 - ln(1 + tau s), dR2/dx0 = s' (load_s / load - 2 A_s / A - tau / (1 + tau s)) - 1: one
        # logarithm and one division (by the product of the three).
        ratio = 1.0 + tau * sv
        below = load * a * ratio
        above = (load_s * a - 2.0 * a_s * load) * ratio - tau * load * a
        d = -(log_base + math.log(f * load / (a * a * ratio)) - x0) * below / (s1 * above - below)
        x0 = x0 + d
        moved = u + d * _INV_STEP
        if 0.0 <= moved <= 1.0:
            u = moved
            sv = sv + d * (s1 + d * (0.5 * s2 + d * (s3 / 6.0)))
            s1, s2 = s1 + d * (s2 + 0.5 * d * s3), s2 + d * s3
        else:
            covered, u, c0, c1, c2, c3 = lookup(coef, x_first, low, high, offset, x0)
            if not covered:
                return 1, x0, nan, nan, nan, nan, nan, nan
            sv = c0 + u * (c1 + u * (c2 + u * c3))
            s1 = (c1 + u * (2.0 * c2 + 3.0 * u * c3)) * _INV_STEP
            s2 = (2.0 * c2 + 6.0 * u * c3) * _INV_STEP * _INV_STEP
            s3 = 6.0 * c3 * _INV_STEP ** 3
        size = abs(d)
        if not (size > X0_TOL and (d_before == 0.0 or size * size * size > X0_ROUNDOFF * d_before * d_before)):
            break
        d_before = size
    return 2, x0, sv, s1, s2, log_base + math.log(f * load / (a * a)), load_s / load - 2.0 * a_s / a, s_start


@kernel
def trial_one(coef, x_first, low, high, offset, kind, log_k, k_tip, k_hub, vx, vt, lam, phi, x0, torque, loss):
    """One trial of one station (:func:`~bild_mdo.bild.variants.local_point.load_path_model.trial`):
    ``(x0, s, x, f, slope, d_tot, rate, rate1, objective, minimum)``; NaN and False off the sheet (``x0`` the
    corrected coordinate where the correction left it)."""
    nan = _NAN
    sn, cs = math.sin(phi), math.cos(phi)
    f, f1, f2 = prandtl_one(sn, cs, k_tip, k_hub, loss)
    log_p, tau = form_one(sn, cs, torque)
    if torque:
        csc2 = 1.0 / (sn * sn)
        dlogp, d2logp, tau1, tau2 = tau, -csc2, -csc2, 2.0 * tau * csc2
    else:
        sec2 = 1.0 / (cs * cs)
        dlogp, d2logp, tau1, tau2 = tau, -sec2, -sec2, 2.0 * tau * sec2
    where, x0, sv, s1, s2, x_m, x_s, s_start = on_sheet(coef, x_first, low, high, offset, log_k, f, sn, cs, vx, vt,
                                                        torque, log_p, tau, x0)
    if where < 2:  # off the sheet; where 1, the corrected coordinate tells on which side it was left
        return (x0 if where == 1 else nan), nan, nan, nan, nan, nan, nan, nan, nan, False
    # The annulus on the BEM curve (load_path_model.annulus) and its load coordinate (log_load; its value to
    # first order in the correction of s, as the solves use it only to look for sheets nearby).
    c_theta, c_x = sn + sv * cs, cs - sv * sn
    a = vx * c_theta + vt * c_x
    a1 = vx * c_x - vt * c_theta
    a_s = vx * cs - vt * sn
    a1s = -(vx * sn + vt * cs)
    uu, w = a * sn, a * cs
    u1, w1 = a1 * sn + w, a1 * cs - uu
    u2, w2 = 2.0 * w1, -2.0 * u1
    u_s, w_s = a_s * sn, a_s * cs
    u1s, w1s = a1s * sn + w_s, a1s * cs - u_s
    gradient = 2.0 * uu - vx
    t, t1 = uu * (uu - vx), u1 * gradient
    t2 = u2 * gradient + 2.0 * u1 * u1
    t_s, t1s, t_ss = u_s * gradient, u1s * gradient + 2.0 * u1 * u_s, 2.0 * u_s * u_s
    g = vt - w
    q, q1 = uu * g, u1 * g - uu * w1
    q2 = u2 * g - 2.0 * u1 * w1 - uu * w2
    q_s = u_s * g - uu * w_s
    q1s = u1s * g - u1 * w_s - u_s * w1 - uu * w1s
    q_ss = -2.0 * u_s * w_s
    e, e1, e2 = vt * q - vx * t, vt * q1 - vx * t1, vt * q2 - vx * t2
    e_s, e1s, e_ss = vt * q_s - vx * t_s, vt * q1s - vx * t1s, vt * q_ss - vx * t_ss
    if torque:
        lo, lo1, lo2, lo_s, lo1s, lo_ss = q, q1, q2, q_s, q1s, q_ss
    else:
        lo, lo1, lo2, lo_s, lo1s, lo_ss = t, t1, t2, t_s, t1s, t_ss
    x = x_m + x_s * (sv - s_start)
    inv_f, inv_lo, inv_a = 1.0 / f, 1.0 / lo, 1.0 / a
    rf, rl, ra = f1 * inv_f, lo1 * inv_lo, a1 * inv_a
    rl_s, ra_s = lo_s * inv_lo, a_s * inv_a
    x1 = rf + rl - 2.0 * ra - dlogp
    xs = rl_s - 2.0 * ra_s
    x11 = f2 * inv_f - rf * rf + lo2 * inv_lo - rl * rl + 2.0 * (1.0 + ra * ra) - d2logp
    x1s = lo1s * inv_lo - rl * rl_s - 2.0 * (a1s * inv_a - ra * ra_s)
    x_ss = lo_ss * inv_lo - rl_s * rl_s + 2.0 * ra_s * ra_s
    # The rates of x0 and s along R2 = 0, the loading and its total slope.
    ratio = 1.0 + tau * sv
    inv_ratio = 1.0 / ratio
    bend = tau1 * sv * inv_ratio
    lean = tau * s1 * inv_ratio
    r2_phi = x1 - bend
    inv_r2_0 = 1.0 / (xs * s1 - 1.0 - lean)
    rate = -r2_phi * inv_r2_0
    kappa = s1 * rate
    e_sf, t_sf = f * e_s, f * t_s
    n_tot = f1 * e + f * e1 + kappa * e_sf
    inv_d = 1.0 / (f1 * t + f * t1 + kappa * t_sf)
    d_tot = 1.0 / inv_d
    ratio_g = n_tot * inv_d
    r2_pp = x11 - (tau2 * sv * inv_ratio - bend * bend)
    r2_p0 = x1s * s1 - tau1 * s1 * inv_ratio * inv_ratio
    r2_00 = x_ss * s1 * s1 + xs * s2 - (tau * s2 * inv_ratio - lean * lean)
    rate1 = -(r2_pp + 2.0 * r2_p0 * rate + r2_00 * rate * rate) * inv_r2_0
    kappa1 = s2 * rate * rate + s1 * rate1
    e_s1 = f1 * e_s + f * e1s
    t_s1 = f1 * t_s + f * t1s
    n1 = f2 * e + 2.0 * f1 * e1 + f * e2 + kappa1 * e_sf + kappa * (2.0 * e_s1 + kappa * f * e_ss)
    d1 = f2 * t + 2.0 * f1 * t1 + f * t2 + kappa1 * t_sf + kappa * (2.0 * t_s1 + kappa * f * t_ss)
    slope = (n1 - ratio_g * d1) * inv_d
    minimum = (sv == sv) and (ratio > 0.0) and (kind * (1.0 + lean) > 0.0)
    return x0, sv, x, ratio_g - lam, slope, d_tot, rate, rate1, f * (e - lam * t), minimum


@kernel
def momentum_one(log_k, k_tip, k_hub, vx, vt, phi, s, torque, loss):
    """``(x_m, tau)`` of a station at ``phi`` with ``cd/cl = s``."""
    sn, cs = math.sin(phi), math.cos(phi)
    f = prandtl_value_one(sn, k_tip, k_hub, loss)
    log_p, tau = form_one(sn, cs, torque)
    return light_load(log_k, f, sn, cs, s, vx, vt, torque, log_p)[0], tau


@kernel
def candidates_one(slots, x_first, nx, x, tau, labels, x0s, scores):
    """The sheets a path ``(x, tau)`` meets as a minimum of ``cd/cl`` next to the node of ``x`` (as
    :func:`~bild_mdo.bild.variants.reynolds_exact.solve.candidates`), written into ``labels, x0s, scores``;
    returns their number."""
    cell = math.floor((x - x_first) * _INV_STEP)
    if not (cell >= 0.0 and cell <= nx - 2):
        return 0
    node = int(cell)
    count = 0
    for k in range(slots.shape[1]):
        label = slots[node, k, 0]
        if label < 0.0:  # the sheets of a node come first (table_arrays)
            break
        s, s1, kind, low, high = slots[node, k, 1], slots[node, k, 2], slots[node, k, 3], slots[node, k, 4], \
            slots[node, k, 5]
        ratio = 1.0 + tau * s
        if not (ratio > 0.0 and kind * (1.0 + tau * s1 / ratio) > 0.0):
            continue
        x0 = x - math.log(ratio)
        cell0 = math.floor((x0 - x_first) * _INV_STEP)
        if cell0 >= low and cell0 < high:
            labels[count] = int(label)
            x0s[count] = x0
            scores[count] = s
            count += 1
    return count


@kernel
def finish_one(coef, coef_ell, coef_alpha, x_first, low, high, offset, log_k, k_tip, k_hub, vx, vt, phi, x0, torque,
               loss):
    """A chosen state's last step and what the station passes on: ``x0`` after one Newton step on ``R2`` at
    ``phi`` (as :func:`~bild_mdo.bild.variants.reynolds_exact.solve.polish`), then at that ``x0`` (as
    :func:`~bild_mdo.bild.variants.local_point.load_path_model.station_outputs`) ``eta2, alpha, cl, cd, Re,
    Re C``."""
    sn, cs = math.sin(phi), math.cos(phi)
    log_p, tau = form_one(sn, cs, torque)
    covered, s, s1 = sheet_s(coef, x_first, low, high, offset, x0)
    if covered:
        f = prandtl_value_one(sn, k_tip, k_hub, loss)
        x_m, x_s = light_load(log_k, f, sn, cs, s, vx, vt, torque, log_p)
        ratio = 1.0 + tau * s
        step = (x_m - x0 - math.log(ratio)) / (x_s * s1 - 1.0 - tau * s1 / ratio)
        if math.isfinite(step):
            x0 = x0 - step
    covered, u, c0, c1, c2, c3 = lookup(coef, x_first, low, high, offset, x0)
    s = c0 + u * (c1 + u * (c2 + u * c3))
    covered, u, c0, c1, c2, c3 = lookup(coef_ell, x_first, low, high, offset, x0)
    ell = c0 + u * (c1 + u * (c2 + u * c3))
    covered, u, c0, c1, c2, c3 = lookup(coef_alpha, x_first, low, high, offset, x0)
    alpha = c0 + u * (c1 + u * (c2 + u * c3))
    cl = math.exp(x0 - ell)
    w = (vx * (sn + s * cs) + vt * (cs - s * sn)) * cs
    return x0, w / vt, alpha, cl, s * cl, math.exp(ell), math.exp(log_p + x0) * (1.0 + tau * s)


@kernel
def station_setup(flow, j, num_blades, loss, ratio):
    """The constants of station ``j`` of ``flow`` (rows ``lam, V_x, V_theta, r, R, r_hub, rho, mu``, as
    :class:`~bild_mdo.bild.variants.local_point.load_path_model.StationFlow`): ``(ok, ln K, k_tip, k_hub, lo,
    hi)``, ``ok`` False outside the domain; the bracket from the unloaded angle (``HOVER_PHI_MIN`` in hover) to
    ``eta2 = 1/2`` at ``cd/cl = ratio`` (:func:`bild_mdo.bild.annulus_stationarity.overloaded_angle`)."""
    lam, vx, vt, r, radius, hub, rho, mu = (flow[0, j], flow[1, j], flow[2, j], flow[3, j], flow[4, j], flow[5, j],
                                            flow[6, j], flow[7, j])
    if not (vx >= 0.0 and vt > 0.0 and lam > 0.0 and r > 0.0 and rho > 0.0 and mu > 0.0 and r < radius):
        return False, 0.0, 0.0, 0.0, 0.0, 0.0
    half_b = 0.5 * num_blades
    log_k = math.log(8.0 * math.pi * rho * r * math.sqrt(vx * vx + vt * vt) / (mu * num_blades))
    k_hub = half_b * (r - hub) / hub if loss == 2 else 1.0
    lo = HOVER_PHI_MIN if vx == 0.0 else math.atan2(vx, vt)
    b = 0.5 * (vx - vt * ratio)
    c = 0.5 * vt * (0.5 * vt + vx * ratio)
    return True, log_k, half_b * (radius - r) / r, k_hub, lo, math.atan2(b + math.sqrt(b * b + c), 0.5 * vt)


# The trail of a design's stations inward of the one being solved (both local-point solves): ``trail[6]`` holds
# how many loaded stations on one sheet it knows (0, 1, 2), their offsets of the solution from the first angle
# (outermost first), their radii and their sheet.
_KNOWN, _OFF1, _OFF2, _R1, _R2, _LABEL = range(6)


@kernel
def continues_design(flow, j):
    """Whether station ``j`` of ``flow`` continues the design of station ``j - 1`` outward (the same radius,
    lambda and V_x, a larger r)."""
    return (j > 0 and flow[3, j] > flow[3, j - 1] and flow[4, j] == flow[4, j - 1] and flow[0, j] == flow[0, j - 1]
            and flow[1, j] == flow[1, j - 1])


@kernel
def trail_begin(trail, flow, j):
    """Forget the trail unless station ``j`` of ``flow`` continues the design of station ``j - 1`` outward."""
    if not continues_design(flow, j):
        trail[_KNOWN] = 0.0


@kernel
def _first_stations(flow, starts):
    count = 0
    for j in range(flow.shape[1]):
        if not continues_design(flow, j):
            starts[count] = j
            count += 1
    return count


def design_starts(flow):
    """The stations of ``flow`` where :func:`trail_begin` forgets the trail (the first of a design): a solve may
    begin there without changing any station's result (:func:`bild_mdo.utils.compiled.run_in_threads`)."""
    starts = np.empty(flow.shape[1], dtype=np.int64)
    return starts[:_first_stations(flow, starts)]


@kernel
def trail_prediction(trail, r):
    """``(label, offset)`` the trail predicts at radius ``r`` (linear in ``r`` from two stations, constant from
    one); ``(-1, 0)`` where it knows none."""
    if trail[_KNOWN] == 0.0:
        return -1, 0.0
    if trail[_KNOWN] == 1.0:
        return int(trail[_LABEL]), trail[_OFF1]
    slope = (trail[_OFF1] - trail[_OFF2]) / (trail[_R1] - trail[_R2])
    return int(trail[_LABEL]), trail[_OFF1] + slope * (r - trail[_R1])


@kernel
def trail_record(trail, label, offset, r):
    """Add a loaded station (``label`` its sheet, ``offset`` its solution less its first angle); ``label < 0``
    (not loaded) forgets the trail."""
    if label < 0:
        trail[_KNOWN] = 0.0
        return
    if trail[_KNOWN] > 0.0 and label == trail[_LABEL]:
        trail[_KNOWN], trail[_OFF2], trail[_R2] = 2.0, trail[_OFF1], trail[_R1]
    else:
        trail[_KNOWN] = 1.0
    trail[_OFF1], trail[_R1], trail[_LABEL] = offset, r, float(label)
