"""Compiled per-station pieces of the local point with the paper's loading: its trial and the first angle.

:func:`paper_trial_one` is :func:`~bild_mdo.bild.variants.local_point.kernels.trial_one` with the paper's
loading as the residual (the physical factor of the quartic (27) at the annulus' ``eta2``); both local
variants start from :func:`paper_angle_one`, the paper loading's inflow angle at a typical ``cd/cl``.
"""
from __future__ import annotations

import math

import numpy as np

from bild_mdo.bild.variants.paper.eta2 import _taylor_coefficients
from bild_mdo.bild.variants.local_point.kernels import _NAN, form_one, on_sheet, prandtl_one
from bild_mdo.utils.compiled import bracketed_newton_for, kernel

#: Tolerance of ``eta2`` in the paper loading's first angle (a start: its error is far below the distance to
#: the solution).
FIRST_TOL = 1e-10
#: Last Newton step on the Taylor polynomial (which is the quartic itself, re-expanded) below which its iterate is
#: the root: Newton's method converges quadratically there, so the next step would be far below FIRST_TOL.
TAYLOR_STEP = 1e-8


@kernel
def paper_trial_one(coef, x_first, low, high, offset, kind, log_k, k_tip, k_hub, vx, vt, lam, phi, x0, torque,
                    loss):
    """One trial of one station with the paper's loading: as
    :func:`~bild_mdo.bild.variants.local_point.kernels.trial_one`, ``(x0, s, x, h, slope, scale,
    rate, 0, s, minimum)`` with ``h = N - u M`` the physical factor of the quartic (27)
    (:mod:`bild_mdo.bild.variants.paper.quartic`) at ``eta2 = w / V_theta`` (``u, w`` of the annulus: Eq. (25) holds on the BEM
    curve), its total slope along ``R2 = 0`` and its rounding scale ``|N| + |u M|``, which is -1 where ``eta2
    < 1/2`` (past the quartic's bracket: the solves read it as the exact loading's largest thrust)."""
    nan = _NAN
    sn, cs = math.sin(phi), math.cos(phi)
    f, f1, _ = prandtl_one(sn, cs, k_tip, k_hub, loss)
    log_p, tau = form_one(sn, cs, torque)
    if torque:
        csc2 = 1.0 / (sn * sn)
        dlogp, tau1 = tau, -csc2
    else:
        sec2 = 1.0 / (cs * cs)
        dlogp, tau1 = tau, -sec2
    where, x0, sv, s1, _, _, _, _ = on_sheet(coef, x_first, low, high, offset, log_k, f, sn, cs, vx, vt, torque,
                                             log_p, tau, x0)
    if where < 2:
        return (x0 if where == 1 else nan), nan, nan, nan, nan, nan, nan, nan, nan, False
    a = vx * (sn + sv * cs) + vt * (cs - sv * sn)
    a1 = vx * (cs - sv * sn) - vt * (sn + sv * cs)
    a_s = vx * cs - vt * sn
    uu, w = a * sn, a * cs
    u1, w1 = a1 * sn + w, a1 * cs - uu
    u_s, w_s = a_s * sn, a_s * cs
    if torque:
        load, load1, load_s = uu * (vt - w), u1 * (vt - w) - uu * w1, u_s * (vt - w) - uu * w_s
    else:
        load, load1, load_s = uu * (uu - vx), u1 * (2.0 * uu - vx), u_s * (2.0 * uu - vx)
    x = log_k + math.log(f * load / (a * a)) - log_p
    x1 = f1 / f + load1 / load - 2.0 * a1 / a - dlogp
    xs = load_s / load - 2.0 * a_s / a
    ratio = 1.0 + tau * sv
    rate = -(x1 - tau1 * sv / ratio) / (xs * s1 - 1.0 - tau * s1 / ratio)
    kappa = s1 * rate
    # The physical factor of the quartic at eta2 = w / V_theta (bild_mdo.bild.variants.paper.quartic.physical_factor_terms).
    eta, eta1, eta_s = w / vt, w1 / vt, w_s / vt
    sum_axial = lam + vx
    n_term = 2.0 * sv * eta * vx * vt + vx * (2.0 * eta - 1.0) * sum_axial + vt * vt * (1.0 - eta) * (4.0 * eta - 1.0)
    n_eta = 2.0 * sv * vx * vt + 2.0 * vx * sum_axial + vt * vt * (5.0 - 8.0 * eta)
    m_term = 2.0 * sv * vt - vx + (2.0 * eta - 1.0) * 2.0 * sum_axial
    m_eta = 4.0 * sum_axial
    h = n_term - uu * m_term
    h_phi = n_eta * eta1 - u1 * m_term - uu * m_eta * eta1
    h_s = n_eta * eta_s + 2.0 * eta * vx * vt - u_s * m_term - uu * (m_eta * eta_s + 2.0 * vt)
    scale = abs(n_term) + abs(uu * m_term) if eta >= 0.5 else -1.0
    minimum = (sv == sv) and (ratio > 0.0) and (kind * (1.0 + tau * s1 / ratio) > 0.0)
    return x0, sv, x, h, h_phi + kappa * h_s, scale, rate, 0.0, sv, minimum





@kernel
def _quartic_value(eta, st, params):
    """The function of the quartic (27) bracketed on ``[1/2, 1]`` (:func:`bild_mdo.bild.variants.paper.eta2._bracket_function`):
    ``P`` itself, in hover the cubic ``P / (1 - eta)``."""
    vx, vt, lam, s = params
    v2 = vt * vt
    one_minus = 1.0 - eta
    sum_axial = lam + vx
    m_term = 2.0 * s * vt - vx + (2.0 * eta - 1.0) * 2.0 * sum_axial
    dm = 4.0 * sum_axial
    if vx == 0.0:
        sv = s * vt
        q = 4.0 * eta - 1.0
        t0, t1, t2 = v2 * one_minus * q * q, sv * q * m_term, eta * m_term * m_term
        return (v2 * (t0 + t1 - t2), v2 * (v2 * q * (8.0 * one_minus - q) + sv * (4.0 * m_term + q * dm)
                                           - m_term * (m_term + 2.0 * eta * dm)), v2 * (abs(t0) + abs(t1) + abs(t2)))
    sv_x = s * vx
    n_term = 2.0 * sv_x * eta * vt + vx * (2.0 * eta - 1.0) * sum_axial + v2 * one_minus * (4.0 * eta - 1.0)
    dn = 2.0 * sv_x * vt + 2.0 * vx * sum_axial + v2 * (5.0 - 8.0 * eta)
    b = 0.5 * (vx - s * vt)
    inner = vt * (sv_x + vt * one_minus)
    c = eta * inner
    dc = inner - eta * v2
    value = n_term * (n_term - 2.0 * b * m_term) - c * m_term * m_term
    slope = 2.0 * (n_term - b * m_term) * dn - 2.0 * (b * n_term + c * m_term) * dm - m_term * m_term * dc
    return value, slope, n_term * n_term + abs(2.0 * b * n_term * m_term) + abs(c) * m_term * m_term


_quartic_root = bracketed_newton_for(_quartic_value)
_taylor = kernel(_taylor_coefficients)


@kernel
def _taylor_start(vx, vt, lam, s):
    """``(t, step)``: ``t = 1 - eta2`` from the quadratic model and two Newton steps on the Taylor polynomial of
    the quartic about ``eta2 = 1`` (:func:`bild_mdo.bild.variants.paper.eta2._taylor_coefficients`,
    :func:`bild_mdo.bild.variants.paper.eta2._start`; in hover the cubic ``P / t``), and the last of the steps."""
    q0, q1, q2, q3, q4 = _taylor(vx, vt, lam, s)
    if vx == 0.0:
        q0, q1, q2, q3, q4 = q1, q2, q3, q4, 0.0
    a = 4.0 / 3.0  # bild_mdo.bild.variants.paper.eta2._START_SHIFT
    w = q1 + 2.0 * a * q0
    t = -2.0 * q0 / (w + math.sqrt(max(q1 * q1 - 4.0 * q0 * (q2 + a * w), 0.0)))
    step = math.inf
    for _ in range(2):
        step = ((((q4 * t + q3) * t + q2) * t + q1) * t + q0) / ((((4.0 * q4 * t + 3.0 * q3) * t + 2.0 * q2) * t + q1))
        t -= step
    return t, step


@kernel
def paper_angle_one(work, vx, vt, lam, s):
    """The paper loading's inflow angle at ``cd/cl = s`` (``work``: a float array of one element, the caller's,
    so that no call allocates): ``eta2`` of the quartic (27) on ``[1/2, 1]`` (:func:`paper_eta_one`),
    ``u_axial`` from Eq. (26), ``phi = atan2(u_axial, eta2 V_theta)``; NaN where the quartic has no root below 1
    (an unloaded station)."""
    eta = paper_eta_one(work, vx, vt, lam, s)
    if not eta < 1.0:
        return math.nan
    b = 0.5 * (vx - vt * s)
    c = eta * vt * (vt * (1.0 - eta) + vx * s)
    root = math.sqrt(b * b + c)
    u_axial = b + root if b >= 0.0 else c / (root - b)
    return math.atan2(u_axial, eta * vt)


@kernel
def paper_eta_one(work, vx, vt, lam, s):
    """``eta2`` of the quartic (27) on ``[1/2, 1]`` at ``cd/cl = s`` to :data:`FIRST_TOL` (NaN where it has no
    root below 1)."""
    # The bracket ends in closed form (bild_mdo.bild.variants.paper.eta2._solve_tail); the root from the Taylor model of
    # bild_mdo.bild.variants.paper.eta2._solve where its Newton steps have converged, else the bracketed solve from
    # there (by false position where it lies outside the bracket).
    sv = s * vt
    if vx == 0.0:
        f_lo, f_hi = 0.5 * vt * vt * vt * vt, 2.0 * vt * vt * (lam + sv) * (sv - 2.0 * lam)
    else:
        f_lo = 0.25 * vt * (vt * vt + vx * vx) * (vt + 2.0 * s * vx)
        f_hi = -lam * vx * (vx + 2.0 * sv) * (lam + vx + sv)
    if not f_hi < 0.0:
        return math.nan
    t, step = _taylor_start(vx, vt, lam, s)
    eta = 1.0 - t
    if not (0.5 < eta < 1.0 and abs(step) <= TAYLOR_STEP):
        start = eta if 0.5 < eta < 1.0 else min(max(0.5 - 0.5 * f_lo / (f_hi - f_lo), 0.501), 1.0 - 1e-12)
        eta, converged, _, _, _ = _quartic_root(work, (vx, vt, lam, s), 0.5, 1.0, 1.0, start, 100, FIRST_TOL)
        if not converged or eta >= 1.0:
            return math.nan
    return eta
