"""The annulus of a local-section-point station in the coordinates of the load-path table.

A station of the local-section-point variants runs at the minimum of
``s = cd/cl`` along its path of fixed load.  Its load follows from the
momentum balance on the BEM curve at a given inflow angle ``phi`` and ratio
``s`` (:mod:`~bild_mdo.bild.annulus_stationarity`: ``A = V_x C_theta +
V_theta C_x``, ``u = A sin(phi)``, ``w = A cos(phi)``, ``t = u (u - V_x)``,
``q = u (V_theta - w)``, ``e = V_theta q - V_x t``), with the momentum load
coordinate::

    x_m = ln(Q / p) = ln K + ln F + ln L - 2 ln A - ln p,
    K = 8 pi rho r W0 / (mu B),   L = t (thrust form) or q (torque form),

(``(p, q_f) = (cos, -sin)`` or ``(sin, cos)`` of ``phi``, ``tau = q_f / p``;
``W0 = sqrt(V_x**2 + V_theta**2)``; ``F`` Prandtl's factor).  Its section point
lies on a sheet of the polar's load-path table
(:mod:`bild_mdo.airfoil.load_path_table`) at the sheet's coordinate ``x0``,
where ``s = s(x0)``, ``ln Re = ell(x0)``, ``alpha = alpha(x0)`` and ``ln cl = x0 -
ell(x0)``.  The blade element carries the momentum load where::

    R2 = x_m(phi, s(x0)) - x0 - ln(1 + tau s(x0)) = 0,

so the state of a station is ``(phi, x0)`` on a sheet.  Along ``R2 = 0``, ``x0``
and ``s`` move with ``phi`` at the rates ``y = dx0/dphi = -R2_phi / R2_x0`` and
``kappa = ds/dphi = s' y`` (the Reynolds feedback: a heavier load gives a
larger chord, a higher Reynolds number and a lower ``cd/cl``), and the Reynolds-aware exact
loading is ``R1 = N_tot - lambda D_tot = 0`` with ``N_tot = (F e)' + kappa F
e_s``, ``D_tot = (F t)' + kappa F t_s`` (``'`` = d/dphi at fixed ``s``, ``_s`` =
d/ds at fixed ``phi``).  The point is a minimum of ``cd/cl`` along the path
where ``kind (1 + tau s' / (1 + tau s)) > 0`` (:mod:`bild_mdo.airfoil.load_path`).

The solves evaluate this model station by station, compiled
(:func:`~bild_mdo.bild.variants.local_point.kernels.trial_one`);
:func:`station_jets` writes the same quantities with
:class:`~bild_mdo.utils.jet.Jet`, whose partials with respect to the states and
every input are exact, for the partials of the components (and, with complex
inputs, their complex step).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from bild_mdo.bem.prandtl import prandtl_loss_jet
from bild_mdo.utils.jet import Jet, variable


class StationFlow(NamedTuple):
    """Per-station inputs (flat arrays of one length) and the options of a local-point station."""

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


FLOW_ARRAYS = StationFlow._fields[:8]


def take(flow, idx):
    """The elements ``idx`` of every array of a :class:`StationFlow`."""
    return flow._replace(**{name: getattr(flow, name)[idx] for name in FLOW_ARRAYS})


class Constants(NamedTuple):
    """What a trial angle needs of the inputs: ``ln K``, the Prandtl exponents' numerators, ``V_x, V_theta``."""

    log_k: np.ndarray
    k_tip: np.ndarray
    k_hub: np.ndarray
    v_axial: np.ndarray
    v_theta: np.ndarray
    lam: np.ndarray


def constants(flow):
    """:class:`Constants` of a :class:`StationFlow` (real)."""
    w0 = np.sqrt(flow.v_axial ** 2 + flow.v_theta ** 2)
    half_b = 0.5 * flow.num_blades
    with np.errstate(divide="ignore"):
        log_k = np.log(8.0 * np.pi * flow.rho * flow.r * w0 / (flow.mu * flow.num_blades))
    k_tip = half_b * (flow.radius - flow.r) / flow.r
    k_hub = half_b * (flow.r - flow.hub_radius) / flow.hub_radius if flow.loss_model == "tip_hub" else None
    return Constants(log_k, k_tip, k_hub, flow.v_axial, flow.v_theta, flow.lam)


#: Value of ``f`` past the largest annulus thrust (m/s): positive, finite, large (as the exact loading's).
BARRIER = 1.0e6


# ------------------------------------------------------------------------------------------------ jets
#: Names of the partials the jets carry: the states, then the inputs (as in :class:`StationFlow`).
STATES = ("phi", "x0")
INPUTS = ("lam", "v_axial", "v_theta", "r", "radius", "hub_radius", "rho", "mu")


class StationJets(NamedTuple):
    """Jets of the residuals ``R1`` (Reynolds-aware exact loading), ``R2`` (the blade element carries the momentum
    load) and of the outputs of a station, and whether the sheet covered its point."""

    r1: Jet
    r2: Jet
    n_tot: Jet
    d_tot: Jet
    objective: Jet
    eta2: Jet
    alpha: Jet
    cl: Jet
    cd: Jet
    reynolds: Jet
    load_reynolds: Jet
    covered: np.ndarray


def _log(jet):
    return Jet(np.log(jet.v), {k: x / jet.v for k, x in jet.d.items()})


def _exp(jet):
    value = np.exp(jet.v)
    return Jet(value, {k: x * value for k, x in jet.d.items()})


def _curve_jets(values, x0):
    """Jets of a sheet quantity and of its slope ``d/dx0`` at the jet ``x0``."""
    value = Jet(values.f, {k: values.f1 * d for k, d in x0.d.items()})
    return value, Jet(values.f1, {k: values.f2 * d for k, d in x0.d.items()})


class AnnulusJets(NamedTuple):
    """Jets of the annulus at ``(phi, s)``: Prandtl's ``F`` and ``dF/dphi``, ``w``, the loads ``t, e`` with their
    ``phi`` and ``s`` slopes, ``x_m`` with its slopes, ``tau`` and ``p`` of ``phi``."""

    f: Jet
    f1: Jet
    w: Jet
    t: Jet
    t1: Jet
    t_s: Jet
    e: Jet
    e1: Jet
    e_s: Jet
    x: Jet
    x1: Jet
    x_s: Jet
    tau: Jet
    tau1: Jet
    p: Jet


def annulus_jets(flow, phi, s, seed=True):
    """:class:`AnnulusJets` at the jets ``phi`` and ``s`` (the momentum balance of :func:`annulus`, first order);
    ``seed=False``: the inputs of ``flow`` are constants (no partials with respect to them)."""
    torque = flow.chord_form == "torque"
    var = variable if seed else (lambda value, name: value)
    vx, vt = var(flow.v_axial, "v_axial"), var(flow.v_theta, "v_theta")
    sn = Jet(np.sin(phi.v), {k: np.cos(phi.v) * d for k, d in phi.d.items()})
    cs = Jet(np.cos(phi.v), {k: -np.sin(phi.v) * d for k, d in phi.d.items()})
    jet = prandtl_loss_jet(phi.v, flow.r, flow.radius, flow.hub_radius, flow.num_blades, flow.loss_model)
    radii = {"r": (jet.dF_dr, jet.d2F_dphi_dr), "radius": (jet.dF_dradius, jet.d2F_dphi_dradius),
             "hub_radius": (jet.dF_dhub_radius, jet.d2F_dphi_dhub_radius)} if seed else {}
    f = Jet(jet.F, {k: jet.dF_dphi * d for k, d in phi.d.items()}) + Jet(0.0, {k: v[0] for k, v in radii.items()})
    f1 = Jet(jet.dF_dphi, {k: jet.d2F_dphi2 * d for k, d in phi.d.items()}) + Jet(0.0, {k: v[1] for k, v in
                                                                                       radii.items()})
    a = vx * (sn + s * cs) + vt * (cs - s * sn)
    a1 = vx * (cs - s * sn) - vt * (sn + s * cs)
    a_s = vx * cs - vt * sn
    u, w = a * sn, a * cs
    u1, w1, u_s, w_s = a1 * sn + w, a1 * cs - u, a_s * sn, a_s * cs
    slope, gap = 2.0 * u - vx, vt - w
    t, t1, t_s = u * (u - vx), u1 * slope, u_s * slope
    q, q1, q_s = u * gap, u1 * gap - u * w1, u_s * gap - u * w_s
    e, e1, e_s = vt * q - vx * t, vt * q1 - vx * t1, vt * q_s - vx * t_s
    load, load1, load_s = (q, q1, q_s) if torque else (t, t1, t_s)
    w0 = np.sqrt(flow.v_axial ** 2 + flow.v_theta ** 2)
    log_k = Jet(np.log(8.0 * np.pi * flow.rho * flow.r * w0 / (flow.mu * flow.num_blades)),
                {"rho": 1.0 / flow.rho, "r": 1.0 / flow.r, "mu": -1.0 / flow.mu, "v_axial": flow.v_axial / w0 ** 2,
                 "v_theta": flow.v_theta / w0 ** 2} if seed else {})
    p, p1 = (sn, cs) if torque else (cs, -1.0 * sn)
    tau, tau1 = (cs / sn, -1.0 / (sn * sn)) if torque else (-1.0 * sn / cs, -1.0 / (cs * cs))
    x = log_k + _log(f) + _log(load) - 2.0 * _log(a) - _log(p)
    x1 = f1 / f + load1 / load - 2.0 * a1 / a - p1 / p
    x_s = load_s / load - 2.0 * a_s / a
    return AnnulusJets(f, f1, w, t, t1, t_s, e, e1, e_s, x, x1, x_s, tau, tau1, p)


def loading_jets(ring, x0, s, s1):
    """``(R2, kappa, N_tot, D_tot)`` of a state from :class:`AnnulusJets`, the coordinate ``x0`` and the sheet's
    ``s`` and ``s'`` there (jets; ``R1 = N_tot - lambda D_tot``)."""
    ratio = 1.0 + ring.tau * s
    r2 = ring.x - x0 - _log(ratio)
    r2_phi = ring.x1 - ring.tau1 * s / ratio
    r2_0 = ring.x_s * s1 - 1.0 - ring.tau * s1 / ratio
    kappa = -1.0 * s1 * r2_phi / r2_0
    n_tot = ring.f1 * ring.e + ring.f * ring.e1 + kappa * (ring.f * ring.e_s)
    d_tot = ring.f1 * ring.t + ring.f * ring.t1 + kappa * (ring.f * ring.t_s)
    return r2, kappa, n_tot, d_tot


def section_jets(table, label, x0, s, tau):
    """Jets of the section point of sheets ``label`` at the jet ``x0`` with ``cd/cl = s``: ``alpha, cl, cd, Re,
    Re C`` (``ln cl = x0 - ell``, ``Re C = p exp(x0) (1 + tau s)``, times ``p`` by the caller)."""
    point = table.curve(np.real(x0.v), label, ("alpha", "ell"))
    alpha = _curve_jets(point["alpha"], x0)[0]
    ell = _curve_jets(point["ell"], x0)[0]
    cl = _exp(x0 - ell)
    return alpha, cl, cl * s, _exp(ell), _exp(x0) * (1.0 + tau * s)


def station_jets(table, flow, phi, x0, label, outputs=True):
    """:class:`StationJets` at the states ``(phi, x0)`` on sheets ``label`` (flat; real states, real or complex
    inputs).  The same model as :func:`trial`, written with :class:`~bild_mdo.utils.jet.Jet` so that every
    partial with respect to :data:`STATES` and :data:`INPUTS` is exact (the table's derivatives to the second
    order, the Prandtl factor's :func:`~bild_mdo.bem.prandtl.prandtl_loss_jet`)."""
    xj, lam = variable(x0, "x0"), variable(flow.lam, "lam")
    values = table.curve(x0, label, ("s",))["s"]
    s, s1 = _curve_jets(values, xj)
    ring = annulus_jets(flow, variable(phi, "phi"), s)
    r2, _, n_tot, d_tot = loading_jets(ring, xj, s, s1)
    covered = np.isfinite(values.f)
    head = (n_tot - lam * d_tot, r2, n_tot, d_tot, ring.f * (ring.e - lam * ring.t),
            ring.w / variable(flow.v_theta, "v_theta"))
    if not outputs:
        return StationJets(*head, None, None, None, None, None, covered)
    alpha, cl, cd, reynolds, load = section_jets(table, label, xj, s, ring.tau)
    return StationJets(*head, alpha, cl, cd, reynolds, ring.p * load, covered)
