"""The Reynolds gap of the reference station: its state on the polar itself, where no sheet of the table
covers ``Re_ref`` (:mod:`~bild_mdo.bild.variants.local_point.reference_solve`).

Next to a fold of the load-path table the curve of stationary ``cd/cl`` turns
in ``x0 = ln Re + ln cl`` and its Reynolds number changes fast; the cells the
table leaves out there (:data:`~bild_mdo.airfoil.load_path_table.FOLD_TRIM`)
hide a band of Reynolds numbers (with the NACA 4412 surrogate about 2.1e5 to
2.2e5, and the last few thousand of the lower branch of minima below 1.94e5).
A reference station whose ``Re_ref`` lies in it is solved on the polar: its section point ``(alpha, Re_ref)`` is a root of ``G = a_pol (C + Re
C_Re) - Re d_pol C_alpha`` (the stationarity of ``cd/cl`` along its path of
fixed load; ``C = p cl + q cd`` the chord formula's force coefficient, ``a_pol
= cd_alpha cl - cd cl_alpha``, ``d_pol = cd_Re cl - cd cl_Re``), the lowest
``cd/cl`` of the roots that are a minimum along their path, else of all roots
(:func:`solve_reference_point`, a scan of ``alpha`` and bracketed Newton
solves); then Newton's method on the BEM residual and ``G`` in ``(phi, alpha)``
(:func:`gap_solve`).  :func:`gap_jets` gives the jets of that state and
:func:`terms` the exact loading's ``N_tot, D_tot`` on the polar (the Reynolds
feedback ``kappa`` of the local point), for lambda.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from bild_mdo.airfoil.max_lift_to_drag import DEFAULT_SCAN_RANGE
from bild_mdo.bem.prandtl import prandtl_loss_jet
from bild_mdo.utils.batches import isolate_failures
from bild_mdo.utils.jet import Jet, variable
from bild_mdo.utils.newton import bracketed_newton

_SCAN_STEP = np.radians(0.5)
_MAX_ITERATIONS = 100
_PASSES = 40
_STEP_MAX = 0.05
_TOL = 1e-13
#: Added to cd/cl of a stationary point that is not a minimum of its path, so any minimum ranks first.
_GAP_RANK = 1.0e3


def force_factors(phi, chord_form):
    """``(p, q)`` of the chord formula's force coefficient ``C = p cl + q cd`` (``dp/dphi = q``, ``dq/dphi = -p``)."""
    if chord_form == "thrust":
        return np.cos(phi), -np.sin(phi)
    return np.sin(phi), np.cos(phi)


class _Terms(NamedTuple):
    """Values of the stationarity system at ``(alpha, Re)`` (see the module docstring)."""

    cl: np.ndarray
    cd: np.ndarray
    cl_a: np.ndarray
    cl_re: np.ndarray
    cd_a: np.ndarray
    cd_re: np.ndarray
    force: np.ndarray
    force_a: np.ndarray
    force_re: np.ndarray
    b: np.ndarray
    g: np.ndarray
    g_scale: np.ndarray


def _first_terms(polar, alpha, reynolds, p, q):
    v = polar.evaluate(alpha, reynolds)
    force = p * v.cl + q * v.cd
    force_a = p * v.dcl_dalpha + q * v.dcd_dalpha
    force_re = p * v.dcl_dre + q * v.dcd_dre
    a = v.dcd_dalpha * v.cl - v.cd * v.dcl_dalpha
    b = force + reynolds * force_re
    d = v.dcd_dre * v.cl - v.cd * v.dcl_dre
    g = a * b - reynolds * d * force_a
    scale = (np.abs(v.dcd_dalpha * v.cl) + np.abs(v.cd * v.dcl_dalpha)) * np.abs(b) + np.abs(reynolds * force_a) * (
        np.abs(v.dcd_dre * v.cl) + np.abs(v.cd * v.dcl_dre))
    return _Terms(v.cl, v.cd, v.dcl_dalpha, v.dcl_dre, v.dcd_dalpha, v.dcd_dre, force, force_a, force_re, b, g,
                  scale)


def _gradient(polar, alpha, reynolds, p, q, t):
    """``(G_alpha, G_Re, G_phi)`` at ``(alpha, Re)`` with the first-order terms ``t``."""
    s = polar.second_derivatives(alpha, reynolds)
    cl_aa, cl_ar, cd_aa, cd_ar = s.d2cl_dalpha2, s.d2cl_dalpha_dre, s.d2cd_dalpha2, s.d2cd_dalpha_dre
    cl_rr, cd_rr = s.d2cl_dre2, s.d2cd_dre2
    re = reynolds
    a = t.cd_a * t.cl - t.cd * t.cl_a
    d = t.cd_re * t.cl - t.cd * t.cl_re
    force_aa, force_ar, force_rr = p * cl_aa + q * cd_aa, p * cl_ar + q * cd_ar, p * cl_rr + q * cd_rr
    force_phi, force_aphi, force_rphi = q * t.cl - p * t.cd, q * t.cl_a - p * t.cd_a, q * t.cl_re - p * t.cd_re
    a_a = cd_aa * t.cl - t.cd * cl_aa
    a_r = cd_ar * t.cl + t.cd_a * t.cl_re - t.cd_re * t.cl_a - t.cd * cl_ar
    d_a = cd_ar * t.cl + t.cd_re * t.cl_a - t.cd_a * t.cl_re - t.cd * cl_ar
    d_r = cd_rr * t.cl - t.cd * cl_rr
    b_a = t.force_a + re * force_ar
    b_r = 2.0 * t.force_re + re * force_rr
    b_phi = force_phi + re * force_rphi
    g_a = a_a * t.b + a * b_a - re * (d_a * t.force_a + d * force_aa)
    g_r = a_r * t.b + a * b_r - d * t.force_a - re * (d_r * t.force_a + d * force_ar)
    g_phi = a * b_phi - re * d * force_aphi
    return g_a, g_r, g_phi, force_phi


def _scan_range(polar, alpha_range):
    if alpha_range is None:
        alpha_range = getattr(polar, "alpha_scan_range", DEFAULT_SCAN_RANGE)
    return tuple(float(a) for a in alpha_range)


class ReferencePoint(NamedTuple):
    """``alpha`` (rad), ``cl``, ``cd`` and their derivatives with respect to ``phi`` and ``Re`` (flat arrays)."""

    alpha: np.ndarray
    cl: np.ndarray
    cd: np.ndarray
    dalpha_dphi: np.ndarray
    dalpha_dre: np.ndarray
    dcl_dphi: np.ndarray
    dcl_dre: np.ndarray
    dcd_dphi: np.ndarray
    dcd_dre: np.ndarray


def _path_slope(polar, alpha, reynolds, p, q):
    """``(G, dG/dalpha at fixed Re, dG/dalpha along the path, G's rounding scale)``."""
    t = _first_terms(polar, alpha, reynolds, p, q)
    g_a, g_r, _, _ = _gradient(polar, alpha, reynolds, p, q, t)
    return t.g, g_a, g_a - g_r * reynolds * t.force_a / t.b, t.g_scale, t


def solve_reference_point(polar, phi, reynolds, chord_form="thrust", alpha_range=None):
    """The reference station's local point at given ``phi`` and ``Re`` (module docstring).

    Parameters
    ----------
    polar : Polar
        A Reynolds-only polar.
    phi, reynolds : array_like
        Inflow angle (rad) and chord Reynolds number (> 0), 1-D.
    chord_form : str
        ``'thrust'`` or ``'torque'``.
    alpha_range : tuple of float, optional
        Scan range (rad).

    Returns
    -------
    ReferencePoint

    Raises
    ------
    ValueError
        Where no root is a minimum of ``cd/cl`` along its path with ``cl > 0``.
    """
    phi = np.asarray(phi, dtype=float).ravel()
    reynolds = np.asarray(reynolds, dtype=float).ravel()
    if not (np.all(np.isfinite(phi)) and np.all(np.isfinite(reynolds)) and np.all(reynolds > 0.0)):
        raise ValueError("reference section point: phi must be finite and the Reynolds number finite and > 0")
    low, high = _scan_range(polar, alpha_range)
    grid = np.linspace(low, high, max(int(np.ceil((high - low) / _SCAN_STEP)) + 1, 3))
    n, k_grid = phi.size, grid.size
    p, q = force_factors(phi, chord_form)
    pp, qq, rr = (np.repeat(x, k_grid) for x in (p, q, reynolds))
    t = _first_terms(polar, np.tile(grid, n), rr, pp, qq)
    valid = ((t.cl > 0.0) & (t.cd > 0.0) & (t.force > 0.0) & (t.b > 0.0)).reshape(n, k_grid)
    g = t.g.reshape(n, k_grid)
    change = valid[:, :-1] & valid[:, 1:] & (np.sign(g[:, :-1]) != np.sign(g[:, 1:]))
    elem, k = np.nonzero(change)
    def residual(x, idx):
        at = elem[idx]
        return _fixed_re(polar, x, reynolds[at], p[at], q[at])

    solution = bracketed_newton(residual, grid[k], grid[k + 1], g[elem, k], max_iter=_MAX_ITERATIONS)
    alpha_c = solution.x
    _, g_a, g_total, _, tc = _path_slope(polar, alpha_c, reynolds[elem], p[elem], q[elem])
    # Minima of their own path first (the lowest cd/cl of them); where Re_ref lies in the gap between two
    # branches of minima, the stationary point that is a maximum along its path (see the module docstring).
    ratio = np.where(solution.converged & (tc.cl > 0.0), tc.cd / tc.cl + np.where(g_total > 0.0, 0.0, _GAP_RANK),
                     np.inf)
    best = np.full(n, np.inf)
    np.minimum.at(best, elem, ratio)
    if not np.all(np.isfinite(best)):
        bad = int(np.flatnonzero(~np.isfinite(best))[0])
        raise ValueError(
            f"reference section point: cd/cl has no stationary point along a path of fixed load through Re = "
            f"{reynolds[bad]:.4g} for alpha in [{np.degrees(low):g}, {np.degrees(high):g}] deg (phi = "
            f"{phi[bad]:.4g} rad); check the polar or the reference chord")
    pick = np.full(n, -1)
    winner = np.flatnonzero(ratio == best[elem])
    pick[elem[winner[::-1]]] = winner[::-1]  # the first (lowest-alpha) candidate among exact ties
    alpha = alpha_c[pick]
    t = _first_terms(polar, alpha, reynolds, p, q)
    g_a, g_r, g_phi, _ = _gradient(polar, alpha, reynolds, p, q, t)
    dalpha_dphi, dalpha_dre = -g_phi / g_a, -g_r / g_a
    return ReferencePoint(alpha, t.cl, t.cd, dalpha_dphi, dalpha_dre,
                          t.cl_a * dalpha_dphi, t.cl_a * dalpha_dre + t.cl_re,
                          t.cd_a * dalpha_dphi, t.cd_a * dalpha_dre + t.cd_re)


def _fixed_re(polar, alpha, reynolds, p, q):
    """``(G, G_alpha, scale)`` at fixed ``Re``: the function :func:`solve_reference_point` brackets."""
    t = _first_terms(polar, alpha, reynolds, p, q)
    g_a, _, _, _ = _gradient(polar, alpha, reynolds, p, q, t)
    return t.g, g_a, t.g_scale


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


class GapJets(NamedTuple):
    """Jets of the gap state: the BEM residual and ``G`` in the states ``(phi, alpha)``, ``cl, cd`` and the load
    Reynolds number ``Re C``, with ``Re`` (for the exact loading's lambda)."""

    bem: Jet
    g: Jet
    cl: Jet
    cd: Jet
    load_reynolds: Jet
    reynolds: Jet


def _reynolds_jet(ref):
    vx, vt = variable(ref.v_axial, "v_axial"), variable(ref.v_theta, "v_theta")
    w0 = Jet(np.sqrt(ref.v_axial ** 2 + ref.v_theta ** 2), {})
    w0 = Jet(w0.v, {"v_axial": vx.v / w0.v, "v_theta": vt.v / w0.v})
    return variable(ref.rho, "rho") * w0 * variable(ref.chord, "chord") / variable(ref.mu, "mu")


def _shifted(value, slopes, deltas, base):
    """Jet of a polar quantity at ``(alpha, Re)`` from its real value and ``(d/dalpha, d/dRe)`` slopes, carrying
    the complex parts of the states to first order (``deltas``: the jets of alpha and Re)."""
    out = Jet(value + sum(s * (d.v - b) for s, d, b in zip(slopes, deltas, base)), {})
    for slope, delta in zip(slopes, deltas):
        out = out + Jet(0.0, {k: slope * x for k, x in delta.d.items()})
    return out


def gap_jets(polar, ref, phi, alpha, seed=True):
    """:class:`GapJets` at ``(phi, alpha)`` (real states; real or complex inputs); ``seed=False``: partials with
    respect to the states only (the inputs constants, as the solve needs them)."""
    al = variable(alpha, "alpha")
    re = _reynolds_jet(ref) if seed else Jet(reference_reynolds(ref), {})
    re_real = np.real(re.v)
    v, sec = polar.evaluate_with_second_derivatives(alpha, re_real)
    deltas, base = (al, re), (alpha, re_real)
    cl = _shifted(v.cl, (v.dcl_dalpha, v.dcl_dre), deltas, base)
    cd = _shifted(v.cd, (v.dcd_dalpha, v.dcd_dre), deltas, base)
    cl_a = _shifted(v.dcl_dalpha, (sec.d2cl_dalpha2, sec.d2cl_dalpha_dre), deltas, base)
    cd_a = _shifted(v.dcd_dalpha, (sec.d2cd_dalpha2, sec.d2cd_dalpha_dre), deltas, base)
    cl_r = _shifted(v.dcl_dre, (sec.d2cl_dalpha_dre, sec.d2cl_dre2), deltas, base)
    cd_r = _shifted(v.dcd_dre, (sec.d2cd_dalpha_dre, sec.d2cd_dre2), deltas, base)
    sn = Jet(np.sin(phi), {"phi": np.cos(phi)})
    cs = Jet(np.cos(phi), {"phi": -np.sin(phi)})
    p, q = (sn, cs) if ref.chord_form == "torque" else (cs, -1.0 * sn)
    force, force_a, force_r = p * cl + q * cd, p * cl_a + q * cd_a, p * cl_r + q * cd_r
    a_pol, d_pol = cd_a * cl - cd * cl_a, cd_r * cl - cd * cl_r
    g = a_pol * (force + re * force_r) - re * d_pol * force_a
    jet = prandtl_loss_jet(phi, ref.r, ref.radius, ref.hub_radius, ref.num_blades, ref.loss_model)
    var = variable if seed else (lambda value, name: Jet(value, {}))
    f = Jet(jet.F, {"phi": jet.dF_dphi, **({"r": jet.dF_dr, "radius": jet.dF_dradius,
                                             "hub_radius": jet.dF_dhub_radius} if seed else {})})
    vx, vt = var(ref.v_axial, "v_axial"), var(ref.v_theta, "v_theta")
    sigma = (ref.num_blades / (2.0 * np.pi)) * var(ref.chord, "chord") / var(ref.r, "r")
    c_x, c_theta = cl * cs - cd * sn, cl * sn + cd * cs
    bem = (vx / vt) * (sigma * c_theta + 4.0 * f * sn * cs) + sigma * c_x - 4.0 * f * sn * sn
    return GapJets(bem, g, cl, cd, re * force, re)


def gap_solve(polar, ref, phi):
    """The gap state: the exact reference point at ``phi`` (scan), then Newton's method on ``(BEM, G)``."""
    n = phi.size
    re = reference_reynolds(ref)
    alpha = np.full(n, np.nan)

    def run(part):
        return solve_reference_point(polar, phi[part], re[part], ref.chord_form)

    for part, point in isolate_failures(run, np.arange(n), ValueError)[0]:
        alpha[part] = point.alpha
    ok = np.isfinite(alpha)
    done = np.zeros(n, dtype=bool)
    active = np.flatnonzero(ok)
    for _ in range(_PASSES):
        if active.size == 0:
            break
        jets = gap_jets(polar, take_reference(ref, active), phi[active], alpha[active], seed=False)
        j11, j12 = np.broadcast_to(jets.bem.partial("phi"), active.shape), np.broadcast_to(jets.bem.partial("alpha"),
                                                                                             active.shape)
        j21, j22 = np.broadcast_to(jets.g.partial("phi"), active.shape), np.broadcast_to(jets.g.partial("alpha"),
                                                                                           active.shape)
        with np.errstate(all="ignore"):
            det = j11 * j22 - j12 * j21
            d_phi = (j22 * jets.bem.v - j12 * jets.g.v) / det
            d_alpha = (j11 * jets.g.v - j21 * jets.bem.v) / det
        bad = ~(np.isfinite(d_phi) & np.isfinite(d_alpha))
        d_phi = np.clip(np.where(bad, 0.0, d_phi), -_STEP_MAX, _STEP_MAX)
        d_alpha = np.clip(np.where(bad, 0.0, d_alpha), -_STEP_MAX, _STEP_MAX)
        phi[active] -= d_phi
        alpha[active] -= d_alpha
        ok[active[bad]] = False
        small = (np.abs(d_phi) <= _TOL) & (np.abs(d_alpha) <= _TOL) & ~bad
        done[active[small]] = True
        active = active[~bad & ~small]
    return phi, alpha, ok & done




def reference_reynolds(ref):
    """``Re_ref = rho W0 c_ref / mu`` (``W0 = sqrt(V_x**2 + V_theta**2)``, the BEM convention)."""
    return ref.rho * np.sqrt(ref.v_axial ** 2 + ref.v_theta ** 2) * ref.chord / ref.mu


def reynolds_partials(v_axial, v_theta, chord, rho, mu):
    """``Re = (rho W0 / mu) c`` (:func:`reference_reynolds`) and its partials with respect to ``v_axial, v_theta,
    chord, rho, mu`` (a dict; the chord's is ``rho W0 / mu``, finite at ``c = 0``)."""
    w0sq = v_axial ** 2 + v_theta ** 2
    per_chord = rho * np.sqrt(w0sq) / mu
    re = per_chord * chord
    return re, {"v_axial": re * v_axial / w0sq, "v_theta": re * v_theta / w0sq, "chord": per_chord,
                "rho": re / rho, "mu": -re / mu}


#: Inputs of the reference station (flat per design), in the order of its partials.
REFERENCE_FIELDS = ("v_axial", "v_theta", "r", "chord", "radius", "hub_radius", "rho", "mu")


def take_reference(ref, idx):
    """The designs ``idx`` of a :class:`~bild_mdo.bild.variants.local_point.reference_solve.ReferenceFlow`."""
    return ref._replace(**{name: getattr(ref, name)[idx] for name in REFERENCE_FIELDS})
