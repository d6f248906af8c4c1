"""The Reynolds-aware exact ideal loading: each annulus minimises ``E - lambda T`` with its own section point.

The exact ideal loading (:mod:`~bild_mdo.bild.annulus_stationarity`) makes each
annulus' ``F (e - lambda t)`` stationary in its inflow angle ``phi`` at a fixed
profile-loss ratio ``s = cd/cl``.  With a polar that depends on the Reynolds
number ``s`` is not fixed: the chord follows from the load and the Reynolds
number ``Re = rho W0 c / mu`` from the chord.  The local section point
(:mod:`~bild_mdo.bild.local_section_point`) picks ``alpha`` to minimise ``s``
along the path of fixed load, ``h = Re C(alpha, Re, phi) - Q = 0``, with the
load Reynolds number ``Q`` of the annulus.  Here ``Q`` is that of the annulus
itself (not an input), so per station the unknowns are ``(phi, alpha, Re)``
and the design minimises, at a given ``lambda``::

    Phi(phi, alpha) = F(phi) [e(phi, s) - lambda t(phi, s)],   s = cd/cl at (alpha, Re),
    Re from  h = Re C(alpha, Re, phi) - Q(phi, s) = 0,
    Q = 8 pi rho r F L W0 / (mu A**2 B)      (L = t, thrust form; L = q, torque form),

(``t, q, e, A`` as in :mod:`~bild_mdo.bild.annulus_stationarity`: the momentum
thrust, torque and energy-loss terms on the BEM curve and ``W = A``;
``W0 = sqrt(V_x**2 + V_theta**2)``; ``Q = Re C`` is the chord formula
multiplied by ``rho W0 / mu``).  Its stationarity conditions are the three
residuals solved per station:

* ``R2 = G(alpha, Re, phi) = 0``: ``dPhi/dalpha = F (e_s - lambda t_s) ds/dalpha`` along ``h = 0``, and
  ``ds/dalpha = G / (cl**2 (B - Q_s s_Re))`` with the ``G`` of the local section point (the minimum of
  ``cd/cl`` along the path of fixed load: the envelope of the inner problem);
* ``R3 = h = 0``;
* ``R1 = N_tot - lambda D_tot = 0`` with::

      N_tot = (F e)' + kappa F e_s,   D_tot = (F t)' + kappa F t_s,
      kappa = ds/dphi|alpha = s_Re (Q_phi - Re C_phi) / (B - Q_s s_Re)

  (``' = d/dphi`` at fixed ``s``, ``_s = d/ds`` at fixed ``phi``; ``B = C + Re C_Re``).  ``kappa`` is the
  Reynolds feedback: a heavier load gives a larger chord, a higher ``Re`` and a lower ``cd/cl``.  Without it
  (``kappa = 0``) ``R1`` is the exact ideal loading at a fixed ``s``.

``lambda`` is ``N_tot / D_tot`` at the reference station's BEM state with
``c_ref`` (:func:`reference_constant`), so the station at ``r_ref`` has the
chord ``c_ref``.  Every term is written once with :class:`~bild_mdo.utils.jet.Jet`,
which carries its analytic partials; the polar's second derivatives
(:class:`~bild_mdo.airfoil.polar.PolarSecondDerivatives`) and the Prandtl
factor's jet seed them.

The unloaded annulus is always a local minimum of ``Phi`` (as ``Q -> 0`` the
Reynolds number and so ``s`` grow without bound), so a loaded root is kept
only where ``Phi < 0`` there, the value of the unloaded annulus; otherwise the
station is unloaded (zero chord).  The solve is
:func:`bild_mdo.bild.reynolds_ideal_loading_solve.solve_stations`.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from bild_mdo.bem.prandtl import prandtl_loss_jet
from bild_mdo.utils.jet import Jet, variable

#: Names of the partials the residual jets carry: the states, then the inputs.
STATES = ("phi", "alpha", "re")
INPUTS = ("lam", "v_axial", "v_theta", "r", "radius", "hub_radius", "rho", "mu")


class Flow(NamedTuple):
    """Per-station inputs (flat arrays of one length, real or complex) and the options."""

    lam: np.ndarray
    v_axial: np.ndarray
    v_theta: np.ndarray
    r: np.ndarray
    radius: np.ndarray
    hub_radius: np.ndarray
    rho: np.ndarray
    mu: np.ndarray
    num_blades: int
    loss_model: str
    chord_form: str


class Terms(NamedTuple):
    """Jets of the three residuals and of the quantities the components output."""

    r1: Jet
    r2: Jet
    r3: Jet
    n_tot: Jet
    d_tot: Jet
    objective: Jet
    eta2: Jet
    cl: Jet
    cd: Jet
    load_reynolds: Jet


def _polar_jets(polar, alpha, reynolds):
    v = polar.evaluate(alpha, reynolds)
    s = polar.second_derivatives(alpha, reynolds)
    cl = Jet(v.cl, {"alpha": v.dcl_dalpha, "re": v.dcl_dre})
    cd = Jet(v.cd, {"alpha": v.dcd_dalpha, "re": v.dcd_dre})
    cl_a = Jet(v.dcl_dalpha, {"alpha": s.d2cl_dalpha2, "re": s.d2cl_dalpha_dre})
    cl_re = Jet(v.dcl_dre, {"alpha": s.d2cl_dalpha_dre, "re": s.d2cl_dre2})
    cd_a = Jet(v.dcd_dalpha, {"alpha": s.d2cd_dalpha2, "re": s.d2cd_dalpha_dre})
    cd_re = Jet(v.dcd_dre, {"alpha": s.d2cd_dalpha_dre, "re": s.d2cd_dre2})
    return cl, cd, cl_a, cl_re, cd_a, cd_re


def terms(polar, phi, alpha, reynolds, flow):
    """:class:`Terms` at the states ``(phi, alpha, Re)`` (real) for the inputs ``flow`` (module docstring)."""
    re = variable(reynolds, "re")
    sn, cs = Jet(np.sin(phi), {"phi": np.cos(phi)}), Jet(np.cos(phi), {"phi": -np.sin(phi)})
    vx, vt, lam = variable(flow.v_axial, "v_axial"), variable(flow.v_theta, "v_theta"), variable(flow.lam, "lam")
    cl, cd, cl_a, cl_re, cd_a, cd_re = _polar_jets(polar, alpha, reynolds)
    s = cd / cl
    # Annulus on the BEM curve (annulus_stationarity): A, its phi and s derivatives, then t, q, e.
    c_theta, c_x = sn + s * cs, cs - s * sn
    a = vx * c_theta + vt * c_x
    a1 = vx * c_x - vt * c_theta
    a_s = vx * cs - vt * sn
    u, w = a * sn, a * cs
    u1, w1 = a1 * sn + w, a1 * cs - u
    u_s, w_s = a_s * sn, a_s * cs
    slope, gap = 2.0 * u - vx, vt - w
    t, t1, t_s = u * (u - vx), u1 * slope, u_s * slope
    q, q1, q_s = u * gap, u1 * gap - u * w1, u_s * gap - u * w_s
    e, e1, e_s = vt * q - vx * t, vt * q1 - vx * t1, vt * q_s - vx * t_s
    jet = prandtl_loss_jet(phi, flow.r, flow.radius, flow.hub_radius, flow.num_blades, flow.loss_model)
    f = Jet(jet.F, {"phi": jet.dF_dphi, "r": jet.dF_dr, "radius": jet.dF_dradius, "hub_radius": jet.dF_dhub_radius})
    f1 = Jet(jet.dF_dphi, {"phi": jet.d2F_dphi2, "r": jet.d2F_dphi_dr, "radius": jet.d2F_dphi_dradius,
                           "hub_radius": jet.d2F_dphi_dhub_radius})
    n = f1 * e + f * e1
    d = f1 * t + f * t1
    # Load Reynolds number Q of the annulus and its phi and s derivatives.
    w0_value = np.sqrt(flow.v_axial ** 2 + flow.v_theta ** 2)
    w0 = Jet(w0_value, {"v_axial": flow.v_axial / w0_value, "v_theta": flow.v_theta / w0_value})
    factor = (8.0 * np.pi / flow.num_blades) * variable(flow.rho, "rho") * variable(flow.r, "r") * w0 / variable(
        flow.mu, "mu")
    load, load1, load_s = (t, t1, t_s) if flow.chord_form == "thrust" else (q, q1, q_s)
    load_q = factor * f * load / (a * a)
    q_phi = load_q * (f1 / f + load1 / load - 2.0 * a1 / a)
    q_s_ = load_q * (load_s / load - 2.0 * a_s / a)
    # Section point: the force coefficient of the chord formula C = p cl + q cd (dp/dphi = q, dq/dphi = -p).
    p_, qf = (cs, -sn) if flow.chord_form == "thrust" else (sn, cs)
    force = p_ * cl + qf * cd
    force_a = p_ * cl_a + qf * cd_a
    force_re = p_ * cl_re + qf * cd_re
    force_phi = qf * cl - p_ * cd
    b = force + re * force_re
    a_pol = cd_a * cl - cd * cl_a
    d_pol = cd_re * cl - cd * cl_re
    g = a_pol * b - re * d_pol * force_a
    s_re = d_pol / (cl * cl)
    kappa = s_re * (q_phi - re * force_phi) / (b - q_s_ * s_re)
    n_tot = n + kappa * (f * e_s)
    d_tot = d + kappa * (f * t_s)
    return Terms(n_tot - lam * d_tot, g, re * force - load_q, n_tot, d_tot, f * (e - lam * t), w / vt, cl, cd,
                 load_q)


def load_reynolds_value(phi, drag_to_lift, flow):
    """``Q`` of the annulus at ``(phi, s)`` (values only, for the bracketing grid); NaN where it carries no load."""
    sn, cs = np.sin(phi), np.cos(phi)
    a = flow.v_axial * (sn + drag_to_lift * cs) + flow.v_theta * (cs - drag_to_lift * sn)
    u, w = a * sn, a * cs
    load = u * (u - flow.v_axial) if flow.chord_form == "thrust" else u * (flow.v_theta - w)
    f = prandtl_loss_jet(phi, flow.r, flow.radius, flow.hub_radius, flow.num_blades, flow.loss_model).F
    w0 = np.sqrt(flow.v_axial ** 2 + flow.v_theta ** 2)
    value = 8.0 * np.pi * flow.rho * flow.r * w0 * f * load / (flow.mu * flow.num_blades * a * a)
    with np.errstate(invalid="ignore"):
        return np.where(value > 0.0, value, np.nan)


def subset(item, keep):
    """The elements ``keep`` of every jet of a :class:`Terms`."""
    def cut(jet):
        return Jet(jet.v[keep], {k: (x[keep] if np.ndim(x) else x) for k, x in jet.d.items()})
    return Terms(*(cut(jet) for jet in item))


def take(flow, idx):
    """The elements ``idx`` of every array of a :class:`Flow`."""
    return flow._replace(**{name: getattr(flow, name)[idx] for name in Flow._fields[:8]})


def jacobian(item, names):
    """``d item[i] / d names[j]`` stacked as ``(n, len(item), len(names))``."""
    return np.stack([np.stack([np.broadcast_to(r.partial(k), r.v.shape) for k in names], axis=-1)
                     for r in item], axis=-2)


def reference_constant(polar, phi_ref, alpha_ref, reynolds_ref, flow):
    """``lambda = N_tot / D_tot`` at the reference station's state, as a :class:`Jet` (``flow.lam`` unused)."""
    item = terms(polar, phi_ref, alpha_ref, reynolds_ref, flow._replace(lam=np.ones_like(np.real(phi_ref))))
    return item.n_tot / item.d_tot, item


def state_sensitivities(item, names, where):
    """``d(phi, alpha, Re)/dx = -J^-1 R_x`` for x in ``names`` (arrays ``(n, 3)`` per name) and ``J``.

    Only the elements ``where`` (a bool mask) are solved; the others get zeros (and ``J`` the identity).
    """
    jac = jacobian((item.r1, item.r2, item.r3), STATES)
    jac[~where] = np.eye(3)
    rhs = np.stack([jacobian((item.r1, item.r2, item.r3), (name,))[..., 0] for name in names], axis=-1)
    rhs[~where] = 0.0
    with np.errstate(all="ignore"):
        sol = -np.linalg.solve(jac, rhs)
    return {name: sol[..., j] for j, name in enumerate(names)}, jac
