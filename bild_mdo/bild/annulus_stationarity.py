"""The exact ideal loading: each annulus makes its energy loss minus lambda times its thrust stationary.

The paper's ideal loading (Sec. 3, Eq. (22)) equalises the marginal energy
loss per marginal thrust of the annuli, but differentiates the annulus loads
without the Prandtl loss factor ``F``.  With ``F`` kept, the condition is exact
for the blade-element/momentum model the design is analysed in.  Along the
BEM curve of a station at a fixed profile-loss ratio ``s = C_d*/C_l*`` every
quantity is explicit in the inflow angle ``phi``::

    C_x = cos(phi) - s sin(phi),  C_theta = sin(phi) + s cos(phi)
    A   = V_x C_theta + V_theta C_x
    u_axial = A sin(phi),  w = V_theta - u_theta/2 = A cos(phi) = eta2 V_theta
    t = u_axial (u_axial - V_x)             (thrust:  dT/dr = 4 pi rho r F t)
    q = u_axial (V_theta - w)               (torque:  dQ/dr = 4 pi rho r**2 F q)
    e = V_theta q - V_x t                   (energy loss: dE/dr = 4 pi rho r F e)

(at ``phi0 = atan(V_x/V_theta)`` the station is unloaded: ``u_axial = V_x``,
``w = V_theta``).  The ideal loading minimises ``E - lambda T`` annulus by
annulus: with ``' = d/dphi``::

    R(phi) = (F e)' - lambda (F t)' = 0,   i.e.  lambda = G(phi) = (F e)'/(F t)'

at every station, ``lambda`` being ``G(phi_ref)`` of the reference station's
BEM inflow angle (so the chord at ``r_ref`` is ``c_ref``).  ``lambda`` keeps
its meaning (m/s): the marginal energy loss per marginal thrust, the same at
every station.  Equivalently ``V_theta (F q)' - (lambda + V_x) (F t)' = 0``.

On ``[phi0, phi(eta2 = 1/2)]`` the thrust ``F t`` rises to a maximum (a pole of
``G``) where the annulus is overloaded; the root sought lies below it, where
``G`` increases from its unloaded value.  The solve brackets ``G - lambda`` on
``[phi0, phi(eta2 = 1/2)]`` with a barrier (a large positive value) past the
maximum of ``F t``; the partials use ``R``, which is smooth through the root
(``dR/dphi = (F t)' dG/dphi > 0`` there).

All functions are vectorised, real or complex (complex step), and broadcast.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from bild_mdo.bem.prandtl import prandtl_loss_jet
from bild_mdo.utils.newton import bracketed_newton

#: Ideal loadings of BILDGroup: the paper's Eq. (22) (without dF/dphi) or the exact condition of this module.
IDEAL_LOADINGS = ("paper", "exact")
#: Value of the bracketed function past the maximum of the annulus thrust (m/s): positive, finite, large.
BARRIER = 1.0e6
#: Lower end of the bracket in hover (rad): ``phi0 = 0`` is unloaded and ``(F t)' = 0`` there.
HOVER_PHI_MIN = 1.0e-6
_MAX_ITERATIONS = 100


class Annulus(NamedTuple):
    """Normalised annulus loads on the BEM curve and their ``phi`` derivatives (up to the second).

    ``t, e`` are the thrust and energy-loss terms of the module docstring
    (``t1 = dt/dphi``, ``t2 = d2t/dphi2``, ...); ``w = A cos(phi)`` and ``dw = dw/dphi``.
    """

    t: np.ndarray
    t1: np.ndarray
    t2: np.ndarray
    e: np.ndarray
    e1: np.ndarray
    e2: np.ndarray
    w: np.ndarray
    dw: np.ndarray


def _curve(phi, v_axial, v_theta, drag_to_lift):
    sn, cs = np.sin(phi), np.cos(phi)
    c_x, c_t = cs - drag_to_lift * sn, sn + drag_to_lift * cs
    a = v_axial * c_t + v_theta * c_x
    a1 = v_axial * c_x - v_theta * c_t  # dA/dphi (and d2A/dphi2 = -A)
    u = a * sn
    w = a * cs
    u1 = a1 * sn + w
    w1 = a1 * cs - u
    return sn, cs, a, a1, u, w, u1, w1


def annulus(phi, v_axial, v_theta, drag_to_lift):
    """:class:`Annulus` at inflow angle ``phi`` (V_x, V_theta in m/s, ``drag_to_lift = C_d*/C_l*``)."""
    _, _, _, _, u, w, u1, w1 = _curve(phi, v_axial, v_theta, drag_to_lift)
    u2, w2 = 2.0 * w1, -2.0 * u1  # from A'' = -A
    slope = 2.0 * u - v_axial
    gap = v_theta - w
    t, t1, t2 = u * (u - v_axial), u1 * slope, u2 * slope + 2.0 * u1 * u1
    q, q1, q2 = u * gap, u1 * gap - u * w1, u2 * gap - 2.0 * u1 * w1 - u * w2
    e, e1, e2 = v_theta * q - v_axial * t, v_theta * q1 - v_axial * t1, v_theta * q2 - v_axial * t2
    return Annulus(t, t1, t2, e, e1, e2, w, w1)


def annulus_tangent(phi, v_axial, v_theta, drag_to_lift, d_axial, d_theta, d_ratio):
    """Derivative of ``(t, t', e, e', w)`` at fixed ``phi`` along ``(dV_x, dV_theta, ds)``."""
    sn, cs, a, a1, u, w, u1, w1 = _curve(phi, v_axial, v_theta, drag_to_lift)
    c_x, c_t = cs - drag_to_lift * sn, sn + drag_to_lift * cs
    da = d_axial * c_t + d_theta * c_x + d_ratio * (v_axial * cs - v_theta * sn)
    da1 = d_axial * c_x - d_theta * c_t - d_ratio * (v_axial * sn + v_theta * cs)
    du, dw = da * sn, da * cs
    du1, dw1 = da1 * sn + dw, da1 * cs - du
    slope, gap = 2.0 * u - v_axial, v_theta - w
    t, t1 = u * (u - v_axial), u1 * slope
    q, q1 = u * gap, u1 * gap - u * w1
    dt = du * slope - d_axial * u
    dt1 = du1 * slope + u1 * (2.0 * du - d_axial)
    dq = du * gap + u * (d_theta - dw)
    dq1 = du1 * gap + u1 * (d_theta - dw) - du * w1 - u * dw1
    de = d_theta * q + v_theta * dq - d_axial * t - v_axial * dt
    de1 = d_theta * q1 + v_theta * dq1 - d_axial * t1 - v_axial * dt1
    return dt, dt1, de, de1, dw


class Stationarity(NamedTuple):
    """``(F e)' = N``, ``(F t)' = D`` and their ``phi`` derivatives at one point, with the pieces for partials."""

    N: np.ndarray
    D: np.ndarray
    N1: np.ndarray
    D1: np.ndarray
    ring: Annulus
    loss: object


def stationarity(phi, v_axial, v_theta, drag_to_lift, r, radius, hub_radius, num_blades, loss_model):
    """:class:`Stationarity` terms at ``phi``: ``G = N/D`` and ``R = N - lambda D``."""
    ring = annulus(phi, v_axial, v_theta, drag_to_lift)
    loss = prandtl_loss_jet(phi, r, radius, hub_radius, num_blades, loss_model)
    f, f1, f2 = loss.F, loss.dF_dphi, loss.d2F_dphi2
    n = f1 * ring.e + f * ring.e1
    d = f1 * ring.t + f * ring.t1
    n1 = f2 * ring.e + 2.0 * f1 * ring.e1 + f * ring.e2
    d1 = f2 * ring.t + 2.0 * f1 * ring.t1 + f * ring.t2
    return Stationarity(n, d, n1, d1, ring, loss)


def residual_partials(phi, lam, v_axial, v_theta, drag_to_lift, r, radius, hub_radius, num_blades, loss_model):
    """Partials of ``R = (F e)' - lam (F t)'`` and of ``eta2 = w / V_theta`` at fixed ``phi``.

    Returns
    -------
    terms : Stationarity
    d_residual : dict
        ``dR/dx`` for x in ``phi, lam, v_axial, v_theta, drag_to_lift, r, radius, hub_radius``.
    d_eta2 : dict
        ``d eta2/dx`` at fixed ``phi`` for x in ``phi, v_axial, v_theta, drag_to_lift``.
    """
    terms = stationarity(phi, v_axial, v_theta, drag_to_lift, r, radius, hub_radius, num_blades, loss_model)
    ring, loss = terms.ring, terms.loss
    d_residual = {"phi": terms.N1 - lam * terms.D1, "lam": -terms.D}
    eta2 = ring.w / v_theta
    d_eta2 = {"phi": ring.dw / v_theta}
    zero = np.zeros_like(ring.t)
    for name, direction in (("v_axial", (1.0, 0.0, 0.0)), ("v_theta", (0.0, 1.0, 0.0)),
                            ("drag_to_lift", (0.0, 0.0, 1.0))):
        dt, dt1, de, de1, dw = annulus_tangent(phi, v_axial, v_theta, drag_to_lift,
                                               *(zero + value for value in direction))
        d_residual[name] = loss.dF_dphi * (de - lam * dt) + loss.F * (de1 - lam * dt1)
        d_eta2[name] = (dw - eta2 * direction[1]) / v_theta
    for name, f_x, f1_x in (("r", loss.dF_dr, loss.d2F_dphi_dr), ("radius", loss.dF_dradius, loss.d2F_dphi_dradius),
                            ("hub_radius", loss.dF_dhub_radius, loss.d2F_dphi_dhub_radius)):
        d_residual[name] = f1_x * (ring.e - lam * ring.t) + f_x * (ring.e1 - lam * ring.t1)
    return terms, d_residual, d_eta2


def unloaded_angle(v_axial, v_theta):
    """``phi0 = atan(V_x / V_theta)``, where the station carries no load (0 in hover)."""
    return np.arctan2(v_axial, v_theta)


def overloaded_angle(v_axial, v_theta, drag_to_lift):
    """Inflow angle at ``eta2 = 1/2`` (``u_theta = V_theta``), with ``u_axial`` from Eq. (26)."""
    b = 0.5 * (v_axial - v_theta * drag_to_lift)
    c = 0.5 * v_theta * (0.5 * v_theta + v_axial * drag_to_lift)
    return np.arctan2(b + np.sqrt(b * b + c), 0.5 * v_theta)


def _bracketed(phi, lam, args):
    """``(G - lam, dG/dphi, scale)`` below the maximum of ``F t``, the barrier past it."""
    terms = stationarity(phi, *args)
    below = terms.D > 0.0
    d = np.where(below, terms.D, 1.0)
    g = terms.N / d
    value = np.where(below, g - lam, BARRIER)
    slope = np.where(below, (terms.N1 - g * terms.D1) / d, 1.0)
    return value, slope, np.abs(g) + np.abs(lam)


def solve_stationarity(lam, v_axial, v_theta, drag_to_lift, r, radius, hub_radius, num_blades, loss_model):
    """Inflow angle of the exact ideal loading at every station (1-D arrays of one length, real).

    Returns
    -------
    phi : ndarray
        The root; ``phi0`` (0 in hover) at unloaded stations.
    status : ndarray of int
        0 loaded (converged); 1 unloaded: ``lam <= G(phi0)``, the energy per thrust of the lightest load
        already exceeds lambda, so the optimum (with a chord >= 0) carries no load there; 3 ``lam`` beyond
        the largest annulus thrust before ``eta2 = 1/2``; 4 an input outside its domain
        (``V_x >= 0``; ``V_theta, lam, r > 0``; ``s >= 0``), not finite, or not converged.
    """
    hover = v_axial == 0.0
    lo = np.where(hover, HOVER_PHI_MIN, unloaded_angle(v_axial, v_theta))
    hi = overloaded_angle(v_axial, v_theta, drag_to_lift)
    args = (v_axial, v_theta, drag_to_lift, r, radius, hub_radius, num_blades, loss_model)
    f_lo = _bracketed(lo, lam, args)[0]
    f_hi = _bracketed(hi, lam, args)[0]
    with np.errstate(invalid="ignore"):
        domain = (v_axial >= 0.0) & (v_theta > 0.0) & (lam > 0.0) & (drag_to_lift >= 0.0) & (r > 0.0)
    status = np.where(~(domain & np.isfinite(f_lo + f_hi)), 4,
                      np.where(f_lo >= 0.0, 1, np.where(f_hi <= 0.0, 3, 0)))
    phi = np.where(hover, 0.0, lo)
    active = np.flatnonzero(status == 0)
    if active.size:
        def function(x, idx):
            at = active[idx]
            return _bracketed(x, lam[at], tuple(a[at] if np.ndim(a) else a for a in args))

        result = bracketed_newton(function, lo[active], hi[active], f_lo[active], max_iter=_MAX_ITERATIONS,
                                  quadratic_stop=True)
        phi[active] = result.x
        status[active] = np.where(result.converged, 0, 4)
    return phi, status
