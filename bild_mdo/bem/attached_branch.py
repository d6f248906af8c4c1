"""Stall hysteresis of the BEM residual: where region 1 holds several roots, the attached-flow root is taken.

Past stall the lift falls as the angle of attack rises, and the residual of a
heavily loaded station can have three roots in region 1, ``[eps, pi/2]`` (the
S-curve of stall hysteresis): an attached-flow root at the largest ``phi``
(smallest ``alpha``), a stalled root at the smallest ``phi`` and an unstable one
between.  The bracketed solve returns whichever root its iterates reach, and at
the fold where the stalled pair is born that choice jumps: levels-10 case 0 of
the verification (hover, R = 0.5 m, root station at Re ~ 3e4) has its root
station's ``phi`` jump from 23.8 deg to 21.0 deg when the twist rises by 1e-4 deg
across 35.455 deg, the thrust jumps with it, and SLSQP spends 400 evaluations at
the jump.

Rule (deterministic, the same for cold and warm solves): at a region-1 root
whose angle of attack lies above the section's maximum-L/D angle ``alpha*(Re)``
(``d(cl/cd)/dalpha < 0`` there) or past the lift peak (``dcl/dalpha <= 0``),
the residual is scanned on ``phi`` in ``(phi_0, min(pi/2, pitch)]`` (angles of
attack from the root's down to 0) and the admissible root at the largest ``phi``
is taken.  Below ``alpha*`` the lift curve rises with ``alpha`` over
``[0, alpha_0]``, so the residual has no further root there and nothing is
scanned.  The attached branch is then followed up to the far fold of the S-curve,
where it ends and the solution must jump to the stalled branch: no root choice
that is a function of the inputs alone avoids a jump where a branch ends.

With Buhl's high-induction correction (``high_induction='buhl'``,
:mod:`bild_mdo.bem.inflow_residual`) the residual grows without bound as ``phi -> 0+``
in forward flow, and a heavily loaded annulus can have up to three roots in region 1
(about 0.15 % of random turbine stations): the same rule picks among them.  At a
region-1 root where the correction acts (``a > 0.4``, :func:`high_induction_candidates`) the
residual and its slope are sampled on ``(phi, pi/2]`` at :data:`HIGH_INDUCTION_SCAN_POINTS`
angles, and the admissible root at the largest ``phi``, the least induced, is taken
(:func:`least_induced_root`): in the last interval with a sign change, or where two roots hide
between two negative samples (the cubic Hermite fit of their values and slopes rises above zero
and the residual at its peak confirms it).  So cold and warm solves agree where the correction
acts, and a root below ``a = 0.4``, momentum theory's, above the candidate is kept.  (A turbine's
stalled triple of roots all below ``a = 0.4`` is covered by neither rule, with or without the
correction.)  Limitation: a pair of roots closer together than the samples and the fit resolve
is not seen (as for stall, the pair is then just born).
"""
from __future__ import annotations

import numpy as np

from bild_mdo.bem.blade_element import _station_setup
from bild_mdo.bem.inflow_residual import buhl_residual_term
from bild_mdo.bem.prandtl import prandtl_loss
from bild_mdo.bem.root_finding import _check_finite, _scan_admissible, _solve_in, opposite_signs

#: Scan points between the stalled root and the upper end (the roots of an S-curve are degrees apart).
SCAN_POINTS = 24
#: Samples between a root past a = 0.4 and pi/2 (with their slopes: a root pair between two is found by the
#: cubic fit; the roots Buhl's correction adds lie 0.005-0.1 rad apart).
HIGH_INDUCTION_SCAN_POINTS = 64
#: First scan point above the root, as a fraction of the scan step (so the root itself is not counted).
_OFFSET = 1.0e-3


def attached_branch(residual, admissible, phi, candidates, upper, describe, tol, max_iter):
    """Replace roots at ``candidates`` by the admissible root at the largest ``phi`` in ``(phi, upper]``.

    The scan and solve are :func:`bild_mdo.bem.root_finding._scan_admissible` (the last
    sign change of the grid, admissible end points), on a grid per station.

    Parameters
    ----------
    residual, admissible : callable
        ``residual(phi, idx) -> (R, dR_dphi)`` and ``admissible(phi, idx) -> bool``
        (:mod:`bild_mdo.bem.root_finding`).
    phi : ndarray
        Flat roots (rad), modified in place.
    candidates : ndarray of int
        Flat station indices whose roots may lie on a stalled branch.
    upper : ndarray
        Upper end of the scan (rad) at ``candidates``.
    describe, tol, max_iter
        As in :func:`bild_mdo.bem.root_finding.solve_bracketed`.
    """
    lower = phi[candidates]
    keep = upper > lower
    idx, lower, upper = candidates[keep], lower[keep], upper[keep]
    if idx.size == 0:
        return
    grid = _samples_above(lower, upper, SCAN_POINTS)
    _scan_admissible(residual, admissible, phi, np.zeros(phi.size, dtype=bool), describe, tol, max_iter, idx,
                     grid, last=True)


def _samples_above(lower, upper, points):
    """Per station, ``points`` equal steps from ``lower`` to ``upper`` and one sample just above ``lower``
    (:data:`_OFFSET` of a step, so the root itself is not counted): shape ``(n, points + 1)``."""
    fractions = np.concatenate([[_OFFSET], np.arange(1, points + 1)]) / points
    return lower[:, None] + (upper - lower)[:, None] * fractions


def stalled_candidates(phi, found, kernels):
    """Flat stations whose region-1 root lies above the maximum-L/D angle, and the upper end of their scan.

    The test needs only the polar's value and first derivatives at the root:
    ``d(cl/cd)/dalpha < 0`` (above the maximum-L/D angle) or ``dcl/dalpha <= 0`` (past the lift peak).

    Parameters
    ----------
    phi, found : ndarray
        Flat roots (rad) and where a root was found.
    kernels : dict
        The flat station inputs of :func:`bild_mdo.bem.blade_element.residual_function`
        (``v_axial, rpm, radii, chord, twist, rho, mu, radius, speed_of_sound, collective_pitch``,
        ``num_blades``, ``polar``).

    Returns
    -------
    candidates : ndarray of int
    upper : ndarray
        ``min(pi/2, pitch)`` at ``candidates`` (rad): angles of attack down to 0.
    """
    pitch = kernels["twist"] + kernels["collective_pitch"]
    idx = np.flatnonzero(found & (phi > 0.0) & (phi < 0.5 * np.pi) & (pitch - phi > 0.0))
    if idx.size == 0:
        return idx, np.empty(0)
    polar = kernels["polar"]
    _, _, reynolds, _, mach, fraction = _station_setup(
        *(kernels[name][idx] for name in ("v_axial", "rpm", "radii", "chord", "twist", "rho", "mu", "radius")),
        kernels["num_blades"], polar, kernels["speed_of_sound"][idx], kernels["collective_pitch"][idx])
    alpha = pitch[idx] - phi[idx]
    v = polar.evaluate(alpha, reynolds, mach=mach, radial_fraction=fraction)
    # Past the maximum of cl/cd (d(cl/cd)/dalpha < 0, i.e. alpha > alpha*) or past the lift peak.
    above = (v.dcl_dalpha * v.cd - v.cl * v.dcd_dalpha < 0.0) | (v.dcl_dalpha <= 0.0)
    return idx[above], np.minimum(0.5 * np.pi, pitch[idx[above]])


def high_induction_candidates(phi, found, kernels, high_induction):
    """Flat stations whose region-1 root lies past ``a = 0.4`` with Buhl's correction (:func:`least_induced_root`).

    Parameters
    ----------
    phi, found, kernels
        As in :func:`stalled_candidates` (``kernels`` also with ``hub_radius`` and ``loss_model``).
    high_induction : {'none', 'buhl'}
        No station is a candidate with 'none'.

    Returns
    -------
    ndarray of int
    """
    idx = np.flatnonzero(found & (phi > 0.0) & (phi < 0.5 * np.pi) & (kernels["v_axial"] > 0.0))
    if high_induction != "buhl" or idx.size == 0:
        return idx[:0]
    polar = kernels["polar"]
    v_theta, sigma, reynolds, pitch, mach, fraction = _station_setup(
        *(kernels[name][idx] for name in ("v_axial", "rpm", "radii", "chord", "twist", "rho", "mu", "radius")),
        kernels["num_blades"], polar, kernels["speed_of_sound"][idx], kernels["collective_pitch"][idx])
    v = polar.evaluate(pitch - phi[idx], reynolds, mach=mach, radial_fraction=fraction)
    loss = prandtl_loss(phi[idx], kernels["radii"][idx], kernels["radius"][idx], kernels["hub_radius"][idx],
                        kernels["num_blades"], kernels["loss_model"])
    active = buhl_residual_term(phi[idx], kernels["v_axial"][idx], v_theta, sigma, v.cl, v.cd, loss.F) > 0.0
    return idx[active]


def least_induced_root(residual, admissible, phi, candidates, describe, tol, max_iter,
                       points=HIGH_INDUCTION_SCAN_POINTS):
    """Replace roots at ``candidates`` by the admissible root at the largest ``phi`` in ``(phi, pi/2]`` (module
    docstring: sign changes of the samples, and root pairs between two negative samples where the cubic Hermite
    fit of their values and slopes rises above zero and the residual at its peak confirms it).

    ``residual, admissible, phi, describe, tol, max_iter`` as :func:`attached_branch`'s (``phi`` modified in
    place); ``points``: samples above each root.  Admissibility is tested at the ends of the chosen interval; a
    root there that is not admissible leaves the station's root as it was.
    """
    grid = _samples_above(phi[candidates], 0.5 * np.pi, points)
    stations = np.repeat(candidates, grid.shape[1])
    value, slope = (x.reshape(grid.shape) for x in residual(grid.ravel(), stations))
    _check_finite(value.ravel(), stations, grid.ravel(), describe)
    change = opposite_signs(value[:, :-1], value[:, 1:])
    # Two roots between negative samples: the peak of the cubic Hermite fit p(t) = y0 + c t + b t^2 + a t^3.
    width = np.diff(grid, axis=1)
    y0, y1, d0, d1 = value[:, :-1], value[:, 1:], slope[:, :-1] * width, slope[:, 1:] * width
    a, b = 2.0 * (y0 - y1) + d0 + d1, 3.0 * (y1 - y0) - 2.0 * d0 - d1
    with np.errstate(all="ignore"):
        disc = np.sqrt(np.maximum(b * b - 3.0 * a * d0, 0.0))
        best_t, best_p = np.zeros(y0.shape), np.full(y0.shape, -np.inf)
        for t in ((-b + disc) / (3.0 * a), (-b - disc) / (3.0 * a), -d0 / (2.0 * b)):
            t = np.where(np.isfinite(t) & (t > 0.0) & (t < 1.0), t, 0.5)
            fit = y0 + t * (d0 + t * (b + t * a))
            better = fit > best_p
            best_t, best_p = np.where(better, t, best_t), np.where(better, fit, best_p)
    hidden = (y0 < 0.0) & (y1 < 0.0) & (best_p > 0.0)
    rows, cols = np.nonzero(hidden)
    start, value_left = grid[:, :-1].copy(), value[:, :-1].copy()
    if rows.size:
        peak = grid[rows, cols] + width[rows, cols] * best_t[rows, cols]
        top = residual(peak, candidates[rows])[0]
        above = top > 0.0
        change[rows[above], cols[above]] = True
        start[rows[above], cols[above]] = peak[above]
        value_left[rows[above], cols[above]] = top[above]
    has = change.any(axis=1)
    if not np.any(has):
        return
    at = np.flatnonzero(has)
    last = change.shape[1] - 1 - np.argmax(change[:, ::-1], axis=1)[has]
    sel = candidates[at]
    lo, hi = start[at, last], grid[at, last + 1]
    ends = admissible(lo, sel) & admissible(hi, sel)
    if not np.any(ends):
        return
    at, last, sel, lo, hi = at[ends], last[ends], sel[ends], lo[ends], hi[ends]
    roots = _solve_in(residual, sel, lo, hi, value_left[at, last], value[at, last + 1], None, describe, tol,
                      max_iter)
    good = admissible(roots, sel) & (roots >= phi[sel])
    phi[sel[good]] = roots[good]
