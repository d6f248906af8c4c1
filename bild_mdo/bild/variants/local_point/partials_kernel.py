"""Compiled partials of the load-path model's states: one station at a time, forward mode written out by hand.

The components of the local section point take their partials from the
implicit-function theorem on two residuals of two states ``(phi, x0)``
(:mod:`~bild_mdo.bild.variants.local_point.load_path_model`, whose docstring
derives the model).  The jets there (:class:`~bild_mdo.utils.jet.Jet`) carry
every partial as a dict entry of a whole-array operation, about 300 of them
per call: at one design that is most of a reverse ``compute_totals``.  Here
the same model is evaluated once per station, and its first-order tangent
along each of :data:`DIRECTIONS` in turn (:func:`model_one`): every line of
its tangent block is the derivative of the line of its value block whose name
it carries with a ``d`` (product and quotient rules, Prandtl's factor from its
``f``-derivatives as in :func:`~bild_mdo.bem.prandtl.prandtl_loss_jet`).  Then
the states are eliminated per station with the 2x2 inverse of
``d(residuals)/d(states)`` (:func:`eliminate_all`).

The jets stay the model of record: a component's complex-step path
evaluates them, so the complex-step checks of the components compare these
partials with them (``tests/bild/variants/test_partials_kernel.py`` does too,
station by station).

Quantities (rows of :func:`model_one`'s output), each a function of the
states and the inputs: :data:`QUANTITIES`; ``r_ell = ell(x0) - ln(rho W0 c /
mu)`` is the reference station's second residual, ``lambda_ratio = N_tot /
D_tot`` its lambda.
"""
from __future__ import annotations

import math

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.load_path_table import X_STEP
from bild_mdo.bild.variants.local_point.kernels import lookup
from bild_mdo.bild.variants.local_point.paper_kernels import _quartic_value, paper_eta_one
from bild_mdo.bild.variants.local_point.prandtl_kernels import prandtl_partials_one
from bild_mdo.utils.compiled import kernel

#: Directions of the tangents (columns 1.. of :func:`model_one`'s output) and the rows of the inputs array.
DIRECTIONS = ("phi", "x0", "lam", "v_axial", "v_theta", "r", "radius", "hub_radius", "rho", "mu", "chord")
#: Quantities of the model (rows of :func:`model_one`'s output).
QUANTITIES = ("r1", "r2", "n_tot", "d_tot", "objective", "eta2", "alpha_star", "cl_star", "cd_star", "reynolds",
              "load_reynolds", "r_ell", "phi", "lambda_ratio")
_INV_STEP = 1.0 / X_STEP
_K = len(DIRECTIONS)
_Q = len(QUANTITIES)


@kernel
def _seed(k, j):
    """Component ``j`` of the unit direction ``k``."""
    return 1.0 if k == j else 0.0


@kernel
def _cubic(coef, x_first, low, high, offset, x0):
    """``(f, df/dx0, d2f/dx0**2)`` of a sheet's cubic at ``x0`` (NaN off its cover)."""
    covered, u, c0, c1, c2, c3 = lookup(coef, x_first, low, high, offset, x0)
    if not covered:
        return math.nan, math.nan, math.nan
    return (c0 + u * (c1 + u * (c2 + u * c3)), (c1 + u * (2.0 * c2 + 3.0 * u * c3)) * _INV_STEP,
            (2.0 * c2 + 6.0 * u * c3) * _INV_STEP * _INV_STEP)


@kernel
def _quartic_partials(eta, vx, vt, lam, s):
    """``dP/d(eta, V_x, V_theta, lam, s)`` of the quartic (27) in its product form ``N**2 - 2 b N M - c M**2``
    (the formulas of :func:`bild_mdo.bild.variants.paper.quartic.quartic_and_partials`, for one station)."""
    n_term = 2.0 * s * eta * vx * vt + vx * (2.0 * eta - 1.0) * (lam + vx) + vt * vt * (1.0 - eta) * (4.0 * eta - 1.0)
    m_term = 2.0 * s * vt - vx + (2.0 * eta - 1.0) * (2.0 * lam + 2.0 * vx)
    b = 0.5 * (vx - s * vt)
    c = eta * vt * (s * vx + vt * (1.0 - eta))
    fn, fm, fb, fc = 2.0 * (n_term - b * m_term), -2.0 * (b * n_term + c * m_term), -2.0 * n_term * m_term, \
        -m_term * m_term
    p_eta = fn * (2.0 * s * vx * vt + 2.0 * vx * (lam + vx) + 4.0 * vt * vt * (1.0 - eta) - vt * vt * (4.0 * eta - 1.0)) \
        + fm * (4.0 * lam + 4.0 * vx) + fc * (-eta * vt * vt + vt * (s * vx + vt * (1.0 - eta)))
    p_vx = fn * (2.0 * s * eta * vt + vx * (2.0 * eta - 1.0) + (2.0 * eta - 1.0) * (lam + vx)) \
        + fm * (4.0 * eta - 3.0) + 0.5 * fb + fc * s * eta * vt
    p_vt = fn * (2.0 * s * eta * vx + 2.0 * vt * (1.0 - eta) * (4.0 * eta - 1.0)) + fm * 2.0 * s - 0.5 * fb * s \
        + fc * (eta * vt * (1.0 - eta) + eta * (s * vx + vt * (1.0 - eta)))
    p_lam = fn * vx * (2.0 * eta - 1.0) + fm * (4.0 * eta - 2.0)
    p_s = fn * 2.0 * eta * vx * vt + fm * 2.0 * vt - 0.5 * fb * vt + fc * eta * vx * vt
    return p_eta, p_vx, p_vt, p_lam, p_s


@kernel
def model_one(coef_s, coef_ell, coef_alpha, x_first, low, high, offset, point, num_blades, torque, loss, paper,
              scratch, out):
    """``out[q, 0]`` the value of quantity ``q`` (:data:`QUANTITIES`) of one station at ``point`` (its
    :data:`DIRECTIONS` values), ``out[q, 1 + k]`` its partial along direction ``k``.

    ``paper``: the local point with the paper's loading (``local_paper.solve.paper_jets``): ``phi`` is not a
    state but the paper loading's angle at ``s(x0)`` (``point[0]`` unused, its column zero), and ``eta2`` that
    of the quartic (27); ``scratch``: a float array of one element."""
    x0, lam, vx, vt, r, radius, hub, rho, mu, chord = (point[1], point[2], point[3], point[4], point[5], point[6],
                                                       point[7], point[8], point[9], point[10])
    # ---- values (load_path_model.annulus_jets, loading_jets, section_jets, gap._reynolds_jet)
    s, s1, s2 = _cubic(coef_s, x_first, low, high, offset, x0)
    ell, ell1, _ = _cubic(coef_ell, x_first, low, high, offset, x0)
    alpha, alpha1, _ = _cubic(coef_alpha, x_first, low, high, offset, x0)
    phi, eta, u_p, b_p, c_p, root_p = point[0], math.nan, math.nan, math.nan, math.nan, math.nan
    p_eta, p_vx, p_vt, p_lam, p_s = math.nan, math.nan, math.nan, math.nan, math.nan
    if paper:  # local_paper.solve.loading: eta2 to round-off (two Newton steps from the solve's 1e-10), Eq. (26)
        eta = paper_eta_one(scratch, vx, vt, lam, s)
        for _ in range(2):
            value, slope, _ = _quartic_value(eta, scratch, (vx, vt, lam, s))
            eta = eta - value / slope
        p_eta, p_vx, p_vt, p_lam, p_s = _quartic_partials(eta, vx, vt, lam, s)
        b_p = 0.5 * (vx - vt * s)
        c_p = eta * vt * (vt * (1.0 - eta) + vx * s)
        root_p = math.sqrt(b_p * b_p + c_p)
        u_p = b_p + root_p if b_p >= 0.0 else c_p / (root_p - b_p)
        phi = math.atan2(u_p, eta * vt)
    sn, cs = math.sin(phi), math.cos(phi)
    f, f1, f2, f_r, f1_r, f_big, f1_big, f_h, f1_h = prandtl_partials_one(sn, cs, r, radius, hub, num_blades, loss)
    c_th, c_x = sn + s * cs, cs - s * sn
    a = vx * c_th + vt * c_x
    a1 = vx * c_x - vt * c_th
    a_s = vx * cs - vt * sn
    u, w = a * sn, a * cs
    u1, w1, u_s, w_s = a1 * sn + w, a1 * cs - u, a_s * sn, a_s * cs
    slope, gap = 2.0 * u - vx, vt - w
    t, t1, t_s = u * (u - vx), u1 * slope, u_s * slope
    q, q1, q_s = u * gap, u1 * gap - u * w1, u_s * gap - u * w_s
    e, e1, e_s = vt * q - vx * t, vt * q1 - vx * t1, vt * q_s - vx * t_s
    w0sq = vx * vx + vt * vt
    w0 = math.sqrt(w0sq)
    if torque:
        p, p1, tau, tau1 = sn, cs, cs / sn, -1.0 / (sn * sn)
        lo, lo1, lo_s = q, q1, q_s
    else:
        p, p1, tau, tau1 = cs, -sn, -sn / cs, -1.0 / (cs * cs)
        lo, lo1, lo_s = t, t1, t_s
    x = math.log(8.0 * math.pi * rho * r * w0 / (mu * num_blades)) + math.log(f) + math.log(lo) \
        - 2.0 * math.log(a) - math.log(p)
    x1 = f1 / f + lo1 / lo - 2.0 * a1 / a - p1 / p
    x_s = lo_s / lo - 2.0 * a_s / a
    ratio = 1.0 + tau * s
    r2 = x - x0 - math.log(ratio)
    r2_phi = x1 - tau1 * s / ratio
    r2_0 = x_s * s1 - 1.0 - tau * s1 / ratio
    kappa = -s1 * r2_phi / r2_0
    n_tot = f1 * e + f * e1 + kappa * (f * e_s)
    d_tot = f1 * t + f * t1 + kappa * (f * t_s)
    cl = math.exp(x0 - ell)
    big_q = math.exp(x0) * ratio
    values = (n_tot - lam * d_tot, r2, n_tot, d_tot, f * (e - lam * t), eta if paper else w / vt, alpha, cl, cl * s,
              math.exp(ell),
              p * big_q, ell - math.log(rho * w0 * chord / mu), phi, n_tot / d_tot)
    for k in range(_Q):
        out[k, 0] = values[k]
    # ---- tangents along each direction (the line of the same name, differentiated)
    for k in range(_K):
        dphi, dx0, dlam, dvx, dvt, dr, dbig, dh, drho, dmu, dchord = (_seed(k, 0), _seed(k, 1), _seed(k, 2),
                                                                 _seed(k, 3), _seed(k, 4), _seed(k, 5),
                                                                 _seed(k, 6), _seed(k, 7), _seed(k, 8),
                                                                 _seed(k, 9), _seed(k, 10))
        ds, ds1 = s1 * dx0, s2 * dx0
        deta = 0.0
        if paper:  # phi follows s and the inputs through the quartic and Eq. (26)
            deta = -(p_vx * dvx + p_vt * dvt + p_lam * dlam + p_s * ds) / p_eta
            db = 0.5 * (dvx - dvt * s - vt * ds)
            inner = vt * (1.0 - eta) + vx * s
            dc = (deta * vt + eta * dvt) * inner + eta * vt * (dvt * (1.0 - eta) - vt * deta + dvx * s + vx * ds)
            droot = (2.0 * b_p * db + dc) / (2.0 * root_p)
            du = db + droot if b_p >= 0.0 else (dc - u_p * (droot - db)) / (root_p - b_p)
            den = eta * vt
            dphi = (den * du - u_p * (deta * vt + eta * dvt)) / (u_p * u_p + den * den)
        dsn, dcs = cs * dphi, -sn * dphi
        df = f1 * dphi + f_r * dr + f_big * dbig + f_h * dh
        df1 = f2 * dphi + f1_r * dr + f1_big * dbig + f1_h * dh
        dc_th, dc_x = dsn + ds * cs + s * dcs, dcs - ds * sn - s * dsn
        da = dvx * c_th + vx * dc_th + dvt * c_x + vt * dc_x
        da1 = dvx * c_x + vx * dc_x - dvt * c_th - vt * dc_th
        da_s = dvx * cs + vx * dcs - dvt * sn - vt * dsn
        du, dw = da * sn + a * dsn, da * cs + a * dcs
        du1, dw1 = da1 * sn + a1 * dsn + dw, da1 * cs + a1 * dcs - du
        du_s, dw_s = da_s * sn + a_s * dsn, da_s * cs + a_s * dcs
        dslope, dgap = 2.0 * du - dvx, dvt - dw
        dt = du * (u - vx) + u * (du - dvx)
        dt1 = du1 * slope + u1 * dslope
        dt_s = du_s * slope + u_s * dslope
        dq = du * gap + u * dgap
        dq1 = du1 * gap + u1 * dgap - du * w1 - u * dw1
        dq_s = du_s * gap + u_s * dgap - du * w_s - u * dw_s
        de = dvt * q + vt * dq - dvx * t - vx * dt
        de1 = dvt * q1 + vt * dq1 - dvx * t1 - vx * dt1
        de_s = dvt * q_s + vt * dq_s - dvx * t_s - vx * dt_s
        dlog_w0 = (vx * dvx + vt * dvt) / w0sq
        if torque:
            dp, dp1, dtau, dtau1 = dsn, dcs, tau1 * dphi, 2.0 * cs / (sn * sn * sn) * dphi
            dlo, dlo1, dlo_s = dq, dq1, dq_s
        else:
            dp, dp1, dtau, dtau1 = dcs, -dsn, tau1 * dphi, -2.0 * sn / (cs * cs * cs) * dphi
            dlo, dlo1, dlo_s = dt, dt1, dt_s
        dx = drho / rho + dr / r + dlog_w0 - dmu / mu + df / f + dlo / lo - 2.0 * da / a - dp / p
        dx1 = (df1 - f1 * df / f) / f + (dlo1 - lo1 * dlo / lo) / lo - 2.0 * (da1 - a1 * da / a) / a \
            - (dp1 - p1 * dp / p) / p
        dx_s = (dlo_s - lo_s * dlo / lo) / lo - 2.0 * (da_s - a_s * da / a) / a
        dratio = dtau * s + tau * ds
        dr2 = dx - dx0 - dratio / ratio
        dr2_phi = dx1 - (dtau1 * s + tau1 * ds - tau1 * s * dratio / ratio) / ratio
        dr2_0 = dx_s * s1 + x_s * ds1 - (dtau * s1 + tau * ds1 - tau * s1 * dratio / ratio) / ratio
        dkappa = -(ds1 * r2_phi + s1 * dr2_phi - s1 * r2_phi * dr2_0 / r2_0) / r2_0
        dn = df1 * e + f1 * de + df * e1 + f * de1 + dkappa * (f * e_s) + kappa * (df * e_s + f * de_s)
        dd = df1 * t + f1 * dt + df * t1 + f * dt1 + dkappa * (f * t_s) + kappa * (df * t_s + f * dt_s)
        dell = ell1 * dx0
        dcl = cl * (dx0 - dell)
        tangents = (dn - dlam * d_tot - lam * dd, dr2, dn, dd,
                    df * (e - lam * t) + f * (de - dlam * t - lam * dt), deta if paper else (dw - w * dvt / vt) / vt,
                    alpha1 * dx0, dcl, dcl * s + cl * ds, math.exp(ell) * dell,
                    dp * big_q + p * big_q * dx0 + p * math.exp(x0) * dratio,
                    dell - (drho / rho + dlog_w0 + dchord / chord - dmu / mu), dphi, (dn - values[13] * dd) / d_tot)
        for j in range(_Q):
            out[j, 1 + k] = tangents[j]


@kernel
def eliminate_all(coef_s, coef_ell, coef_alpha, grid, cover_first, cover_last, offsets, points, labels, num_blades,
                  torque, loss, paper, residuals, inputs, outputs, totals):
    """``totals[n, o, i]``: the total partial of quantity ``outputs[o]`` with respect to direction ``inputs[i]`` at
    station ``n`` (``points[n]`` its :data:`DIRECTIONS` values, ``labels[n]`` its sheet), the states ``(phi, x0)``
    eliminated through the two ``residuals`` (rows of :data:`QUANTITIES`), or with ``paper`` the state ``x0``
    through the one."""
    x_first = grid[0]
    work = np.empty((_Q, 1 + _K))
    scratch = np.zeros(1)
    for n in range(points.shape[0]):
        label = labels[n]
        model_one(coef_s, coef_ell, coef_alpha, x_first, cover_first[label], cover_last[label], offsets[label],
                  points[n], num_blades, torque, loss, paper, scratch, work)
        if paper:
            ra = residuals[0]
            inv_slope = 1.0 / work[ra, 2]
            for i in range(inputs.shape[0]):
                col = 1 + inputs[i]
                d_x0 = -work[ra, col] * inv_slope
                for o in range(outputs.shape[0]):
                    totals[n, o, i] = work[outputs[o], col] + work[outputs[o], 2] * d_x0
            continue
        ra, rb = residuals[0], residuals[1]
        j11, j12, j21, j22 = work[ra, 1], work[ra, 2], work[rb, 1], work[rb, 2]
        inv_det = 1.0 / (j11 * j22 - j12 * j21)
        for i in range(inputs.shape[0]):
            col = 1 + inputs[i]
            g1, g2 = work[ra, col], work[rb, col]
            d_phi = -(j22 * g1 - j12 * g2) * inv_det
            d_x0 = -(j11 * g2 - j21 * g1) * inv_det
            for o in range(outputs.shape[0]):
                row = outputs[o]
                totals[n, o, i] = work[row, col] + work[row, 1] * d_phi + work[row, 2] * d_x0


def state_totals(table, points, labels, num_blades, torque, loss, residuals, inputs, outputs, paper=False,
                 required=None):
    """:func:`eliminate_all` by names: ``points[n, len(DIRECTIONS)]``, the names of the residuals (two, or with
    ``paper`` one), of the inputs and of the outputs; returns ``totals[n, outputs, inputs]``.

    Raises om.AnalysisError where a partial of a station is not finite (a state singular in its residuals),
    except at the stations where ``required`` (a boolean mask) is False: the caller replaces those."""
    from bild_mdo.bild.variants.local_point.kernels import LOSS_CODES, table_arrays

    coef, _, cover_first, cover_last, offset, _, _, _, _, grid, coef_ell, coef_alpha = table_arrays(table)
    totals = np.zeros((points.shape[0], len(outputs), len(inputs)))
    index = [np.array([QUANTITIES.index(name) for name in names], dtype=np.int64) for names in (residuals, outputs)]
    directions = np.array([DIRECTIONS.index(name) for name in inputs], dtype=np.int64)
    eliminate_all(coef, coef_ell, coef_alpha, grid, cover_first, cover_last, offset,
                  np.ascontiguousarray(points, dtype=float), np.asarray(labels, dtype=np.int64), num_blades, torque,
                  LOSS_CODES[loss], paper, index[0], directions, index[1], totals)
    bad = ~np.all(np.isfinite(totals), axis=(1, 2))
    if required is not None:
        bad &= required
    if np.any(bad):
        i = int(np.flatnonzero(bad)[0])
        raise om.AnalysisError(f"local section point: the partials of a solved state are not finite ({bad.sum()} of "
                               f"{bad.size} stations, the first on sheet {int(labels[i])} at x0 = {points[i, 1]:.6g}, "
                               f"phi = {points[i, 0]:.6g} rad): its state is singular in the residuals")
    return totals
