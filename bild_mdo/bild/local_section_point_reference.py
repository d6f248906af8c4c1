"""The local section point of the reference station, whose chord (and so Reynolds number) is given.

At the reference station the chord is ``c_ref``, so ``Re_ref = rho W0 c_ref / mu``
is known and the load follows from the section point, not the other way round.
The point that a station at ``r_ref`` would choose for that load is a point
``(alpha, Re_ref)`` that is itself a minimum of ``cd/cl`` along its own path of
fixed load (:mod:`bild_mdo.bild.local_section_point`)::

    G(alpha, Re_ref; phi_ref) = 0   and   dG/dalpha (total, along the path) > 0,

a scalar equation in ``alpha`` at fixed ``Re``.  Of its roots that are minima of
their paths the one with the lowest ``cd/cl`` is taken.  Iterating "load from
the point, point from the load" instead has no fixed point where two minima
are nearly equal (the lower minimum of the path through one is the other, and
back), so the reference station is solved in this form.

The chord c_ref cannot always be reached (limitation).  With the NACA 4412
surrogate near Re 1e5-3e5 the minima along paths of fixed load form two
branches, and a band of Reynolds numbers between them is the optimum of no
path: a ``c_ref`` whose ``Re_ref`` lies in that band is a chord no station
chooses.  There ``G(., Re_ref) = 0`` has only roots that are maxima along their
paths; the lowest-``cd/cl`` of them is taken (continuous in ``c_ref``, so
``lambda`` stays continuous), and a station placed at ``r_ref`` takes a
minimum of the same path instead, so its chord differs from ``c_ref``.  Also
where a path through the chosen point has a second, lower minimum, the
station takes that one.  Outside these bands the chord at ``r_ref`` is
``c_ref`` to round-off.

Derivatives: ``dalpha/dp = -G_p / G_alpha`` for ``p`` in ``(phi, Re)`` (``G_alpha``
at fixed ``Re``), then ``cl, cd`` by the chain rule.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from bild_mdo.bild.local_section_point import (
    _SCAN_STEP,
    _first_terms,
    _gradient,
    _scan_range,
    force_factors,
)
from bild_mdo.utils.newton import bracketed_newton

_MAX_ITERATIONS = 100
#: Added to cd/cl of a stationary point that is not a minimum of its path, so any minimum ranks first.
_GAP_RANK = 1.0e3


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
