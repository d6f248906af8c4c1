"""The local section point of the Reynolds-aware BILD: each station's own angle of attack, lift and drag.

The paper's BILD (Assumption 2) runs every station at the maximum-L/D angle of
the polar at the reference station's Reynolds number.  With a polar that
depends on the Reynolds number a station can do better: its load per unit span
is fixed by the ideal loading (and its inflow angle ``phi`` and speed by the
induced velocities), but the chord follows from the load,

    c C(alpha, Re) = const,   Re = rho W0 c / mu   (W0 = sqrt(V_x**2 + V_theta**2), the BEM convention),

so a lower angle of attack with a larger chord runs the section at a higher
Reynolds number.  ``C`` is the force coefficient of the chord formula
(:class:`~bild_mdo.bild.chord.ChordComp`): ``C = cl cos(phi) - cd sin(phi)``
(thrust form) or ``cl sin(phi) + cd cos(phi)`` (torque form); in both
``C = p cl + q cd`` with ``dp/dphi = q``, ``dq/dphi = -p``.  Multiplying the
load relation by ``rho W0 / mu`` gives the path of fixed load in the
``(alpha, Re)`` plane through the *load Reynolds number* ``Q``::

    h(alpha, Re) = Re C(alpha, Re) - Q = 0,   Q = 2 (dT/dr) W0 / (mu W**2 B)   (thrust form).

Along it the station chooses ``alpha`` to minimise its profile-loss ratio
``s = cd/cl`` (the ratio that enters the quartic for eta2).  With
``Re'(alpha) = -h_alpha / h_Re = -Re C_alpha / B`` along the path, the
stationarity condition ``ds/dalpha = s_alpha + s_Re Re' = 0`` multiplied by
``cl**2 B`` (both positive) is::

    G(alpha, Re) = A B - Re D C_alpha = 0,
    A = cd_alpha cl - cd cl_alpha   (= cl**2 s_alpha),
    B = C + Re C_Re                 (= h_Re > 0),
    D = cd_Re cl - cd cl_Re         (= cl**2 s_Re).

Since ``G = cl**2 C (B / C) ds/dalpha``, a minimum of ``s`` along the path is
a root where ``G`` changes sign from - to +, and there the total derivative
``dG/dalpha = G_alpha + G_Re Re'`` is ``cl**2 B d2s/dalpha2 > 0``.  With a
polar that does not depend on ``Re`` (``D = 0``, ``C_Re = 0``) the condition is
``A = 0``: the maximum-L/D point, so the local point then equals the
reference point.

Solution (:func:`solve_local_point`): for each station a coarse scan of ``G``
along the path brackets the minima; the two brackets with the lowest ``s`` are
solved to round-off with :func:`bild_mdo.utils.newton.bracketed_newton`
(``Re`` on the path by an inner Newton iteration in ``ln Re`` at every trial
angle), and the lower ``s`` of the two is kept.  Where two minima are nearly
equal (the NACA 4412 near Re = 1e5-3e5 has minima near 2.5 and 7.8 deg) that
choice switches from one to the other as the inputs move: the design has a
kink (a jump in twist and chord) there, which a sizing optimiser may see.

Derivatives (:func:`point_derivatives`): the implicit-function theorem on
``(G, h) = 0`` in the unknowns ``(alpha, Re)`` with the parameters ``phi``
and ``Q``::

    J = [[G_alpha, G_Re], [h_alpha, h_Re]],   det J = B dG/dalpha > 0 at a minimum,
    d(alpha, Re)/dp = -J**-1 (G_p, h_p),      h_phi = Re C_phi, h_Q = -1, G_Q = 0.

``G_Re`` needs the polar's second Reynolds derivatives ``cl_ReRe, cd_ReRe``:
the exact fields ``d2cl_dre2, d2cd_dre2`` of its ``second_derivatives``
(:class:`~bild_mdo.airfoil.polar.PolarSecondDerivatives`), like every other
term of ``J``.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from bild_mdo.airfoil.max_lift_to_drag import DEFAULT_SCAN_RANGE
from bild_mdo.utils.newton import bracketed_newton

SECTION_POINTS = ("reference", "local")
#: Step of the bracket scan (rad); the minima are then solved to round-off.
_SCAN_STEP = np.radians(0.5)
_INNER_ITERATIONS = 40
#: Angles whose lift coefficient is below this on the path are left out of the scan: their cd/cl is far
#: from any minimum, and near zero lift their Reynolds number Q / C would lie far outside any polar's data.
_LIFT_FLOOR = 0.1
_MAX_ITERATIONS = 100


class LocalPoint(NamedTuple):
    """The local section point: ``alpha`` (rad), ``cl``, ``cd``, ``reynolds``, flat arrays."""

    alpha: np.ndarray
    cl: np.ndarray
    cd: np.ndarray
    reynolds: np.ndarray


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


def _reynolds_on_path(polar, alpha, load_reynolds, p, q, guess):
    """``Re`` with ``Re C(alpha, Re) = Q`` by Newton in ``ln Re`` (``d/dlnRe = B/C``); NaN where ``C <= 0``."""
    x = np.log(guess)
    ok = np.ones(alpha.shape, dtype=bool)
    active = np.arange(alpha.size)
    for _ in range(_INNER_ITERATIONS):
        if active.size == 0:
            break
        re = np.exp(x[active])
        v = polar.evaluate(alpha[active], re)
        force = p[active] * v.cl + q[active] * v.cd
        force_re = p[active] * v.dcl_dre + q[active] * v.dcd_dre
        bad = ~(force > 0.0) | ~(force + re * force_re > 0.0) | ~(v.cl > _LIFT_FLOOR)
        ok[active[bad]] = False
        with np.errstate(invalid="ignore", divide="ignore"):
            step = (x[active] + np.log(np.where(bad, 1.0, force)) - np.log(load_reynolds[active])) / (
                np.where(bad, 1.0, 1.0 + re * force_re / force))
        step = np.clip(np.where(bad, 0.0, step), -1.0, 1.0)
        x[active] -= step
        active = active[~bad & (np.abs(step) > 1e-13)]
    if active.size:
        ok[active] = False
    return np.where(ok, np.exp(x), np.nan)


def _scan_range(polar, alpha_range):
    if alpha_range is None:
        alpha_range = getattr(polar, "alpha_scan_range", DEFAULT_SCAN_RANGE)
    return tuple(float(a) for a in alpha_range)


def _validate(phi, load_reynolds):
    if not (np.all(np.isfinite(phi)) and np.all(np.isfinite(load_reynolds))):
        raise ValueError("local section point: phi and the load Reynolds number must be finite")
    if np.any(~(load_reynolds > 0.0)):
        raise ValueError("local section point: the load Reynolds number (Re times the force coefficient) must be "
                         f"> 0, got min {float(np.min(load_reynolds))!r}")


def solve_local_point(polar, phi, load_reynolds, chord_form="thrust", alpha_range=None, both=False):
    """Minimise ``cd/cl`` along the path of fixed load at every element (module docstring).

    Parameters
    ----------
    polar : Polar
        A Reynolds-only polar (``evaluate`` and ``second_derivatives`` are used).
    phi : array_like
        Inflow angles (rad), real, 1-D.
    load_reynolds : array_like
        ``Q = Re C``, > 0, same shape.
    chord_form : str
        ``'thrust'`` or ``'torque'``: the force coefficient ``C``.
    alpha_range : tuple of float, optional
        Scan range (rad); default the polar's ``alpha_scan_range`` or -10..25 deg.
    both : bool
        Also return the runner-up: the other of the two lowest minima (NaN where the path has one).

    Returns
    -------
    LocalPoint
        The lower minimum; with ``both=True`` a pair ``(lower, runner_up)``.

    Raises
    ------
    ValueError
        Where ``cd/cl`` has no interior minimum with ``cl > 0`` and ``C > 0`` on
        the path, or the Newton solve does not converge (the message names the element).
    """
    phi = np.asarray(phi, dtype=float).ravel()
    load_reynolds = np.asarray(load_reynolds, dtype=float).ravel()
    _validate(phi, load_reynolds)
    low, high = _scan_range(polar, alpha_range)
    n, grid = phi.size, np.linspace(low, high, max(int(np.ceil((high - low) / _SCAN_STEP)) + 1, 3))
    k_grid = grid.size
    p, q = force_factors(phi, chord_form)
    # Scan: Re on the path at every grid angle, marching in alpha so each inner solve starts close.
    pp, qq, qload = (np.repeat(x, k_grid) for x in (p, q, load_reynolds))
    aa = np.tile(grid, n)
    v0 = polar.evaluate(aa, np.full(aa.shape, 1e6))
    force0 = pp * v0.cl + qq * v0.cd
    guess = qload / np.where((force0 > 0.0) & (v0.cl > _LIFT_FLOOR), force0, 1.0)
    re_grid = _reynolds_on_path(polar, aa, qload, pp, qq, guess)
    valid = np.isfinite(re_grid)
    t = _first_terms(polar, aa, np.where(valid, re_grid, 1e6), pp, qq)
    valid &= (t.cl > 0.0) & (t.cd > 0.0)
    g = np.where(valid, t.g, np.nan).reshape(n, k_grid)
    ratio = np.where(valid, t.cd / t.cl, np.inf).reshape(n, k_grid)
    re_grid = re_grid.reshape(n, k_grid)
    is_min = (g[:, :-1] < 0.0) & (g[:, 1:] >= 0.0)
    score = np.where(is_min, np.minimum(ratio[:, :-1], ratio[:, 1:]), np.inf)
    order = np.argsort(score, axis=1)[:, :2]
    rows = np.arange(n)
    found = np.isfinite(score[rows, order[:, 0]])
    if not np.all(found):
        bad = int(np.flatnonzero(~found)[0])
        raise ValueError(
            f"local section point: cd/cl has no interior minimum with cl > 0 along the path of fixed load for alpha "
            f"in [{np.degrees(low):g}, {np.degrees(high):g}] deg (element {bad}: phi = {phi[bad]:.4g} rad, "
            f"Re*C = {load_reynolds[bad]:.4g}); check the polar or the operating point")
    second = np.isfinite(score[rows, order[:, 1]])
    # Candidate brackets: the best one of every element, then the runner-up where there is one.
    elem = np.concatenate([rows, rows[second]])
    k = np.concatenate([order[:, 0], order[second, 1]])
    lo, hi = grid[k], grid[k + 1]
    re_start = np.sqrt(re_grid[elem, k] * re_grid[elem, k + 1])
    state = {"re": re_start.copy()}

    def residual(alpha, idx):
        at = elem[idx]
        re = _reynolds_on_path(polar, alpha, load_reynolds[at], p[at], q[at], state["re"][idx])
        re = np.where(np.isfinite(re), re, state["re"][idx])
        state["re"][idx] = re
        terms = _first_terms(polar, alpha, re, p[at], q[at])
        g_a, g_r, _, _ = _gradient(polar, alpha, re, p[at], q[at], terms)
        return terms.g, g_a - g_r * re * terms.force_a / terms.b, terms.g_scale

    solution = bracketed_newton(residual, lo, hi, g[elem, k], max_iter=_MAX_ITERATIONS, quadratic_stop=True)
    if not np.all(solution.converged):
        bad = int(elem[~solution.converged][0])
        raise ValueError(f"local section point: the Newton solve did not converge in {_MAX_ITERATIONS} iterations at "
                         f"element {bad} (phi = {phi[bad]:.4g} rad, Re*C = {load_reynolds[bad]:.4g})")
    alpha_c = solution.x
    re_c = _reynolds_on_path(polar, alpha_c, load_reynolds[elem], p[elem], q[elem], state["re"])
    v = polar.evaluate(alpha_c, re_c)
    s = v.cd / v.cl
    # The lower of the two minima (ties go to the best scanned bracket).
    pick = np.arange(n)
    runner = np.arange(n, elem.size)
    better = s[runner] < s[rows[second]]
    pick[rows[second][better]] = runner[better]
    point = LocalPoint(alpha_c[pick], v.cl[pick], v.cd[pick], re_c[pick])
    if not both:
        return point
    other = np.full(n, -1)
    other[rows[second]] = np.where(better, rows[second], runner)
    has = other >= 0
    fields = [np.where(has, x[np.maximum(other, 0)], np.nan) for x in (alpha_c, v.cl, v.cd, re_c)]
    return point, LocalPoint(*fields)


class PointDerivatives(NamedTuple):
    """Derivatives of the local point with respect to ``phi`` and ``Q`` (flat arrays), and ``d2s/dalpha2``."""

    dalpha_dphi: np.ndarray
    dalpha_dq: np.ndarray
    dcl_dphi: np.ndarray
    dcl_dq: np.ndarray
    dcd_dphi: np.ndarray
    dcd_dq: np.ndarray
    dre_dphi: np.ndarray
    dre_dq: np.ndarray
    curvature: np.ndarray


def point_derivatives(polar, point, phi, chord_form="thrust"):
    """Implicit-function derivatives of a :class:`LocalPoint` (module docstring).

    ``curvature`` is ``d2(cd/cl)/dalpha2`` along the path, > 0 at a minimum.
    """
    phi = np.asarray(phi, dtype=float).ravel()
    p, q = force_factors(phi, chord_form)
    alpha, re = point.alpha, point.reynolds
    t = _first_terms(polar, alpha, re, p, q)
    g_a, g_r, g_phi, force_phi = _gradient(polar, alpha, re, p, q, t)
    h_a, h_r, h_phi = re * t.force_a, t.b, re * force_phi
    det = g_a * h_r - g_r * h_a
    dalpha_dphi = -(g_phi * h_r - g_r * h_phi) / det
    dre_dphi = -(g_a * h_phi - h_a * g_phi) / det
    dalpha_dq = -g_r / det
    dre_dq = g_a / det
    # det = B dG/dalpha (total) and dG/dalpha = cl**2 B d2s/dalpha2 at a root of G.
    curvature = det / (t.b * t.b * t.cl * t.cl)
    return PointDerivatives(
        dalpha_dphi, dalpha_dq,
        t.cl_a * dalpha_dphi + t.cl_re * dre_dphi, t.cl_a * dalpha_dq + t.cl_re * dre_dq,
        t.cd_a * dalpha_dphi + t.cd_re * dre_dphi, t.cd_a * dalpha_dq + t.cd_re * dre_dq,
        dre_dphi, dre_dq, curvature)
