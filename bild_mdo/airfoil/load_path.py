"""Stationary points of the profile-loss ratio ``s = cd/cl`` along paths of fixed load.

A blade element of chord ``c`` at inflow angle ``phi`` carries a load per unit
span proportional to ``c C`` with the force coefficient ``C = p cl + q cd`` of
BILD's chord formula (``(p, q) = (cos phi, -sin phi)`` from the thrust,
``(sin phi, cos phi)`` from the torque).  With ``Re = rho W0 c / mu`` a fixed
load is a fixed *load Reynolds number* ``Q = Re C``; with ``tau = q / p``::

    Re (cl + tau cd) = Q / p.

Along this path ``s`` is stationary where (multiplied by ``cl**2 B~ > 0``,
``c~ = cl + tau cd``, ``B~ = c~ + Re c~_Re``)::

    G = A B~ - Re D c~_alpha = 0,   A = cd_alpha cl - cd cl_alpha,   D = cd_Re cl - cd cl_Re,

and ``G`` factors (a hand derivation, checked with sympy in the tests)::

    G = c~ H,   H(alpha, Re) = A + Re (cd_alpha cl_Re - cl_alpha cd_Re).

``H`` does not depend on ``tau``: the points where ``cd/cl`` is stationary
along a path of fixed load do not depend on the inflow angle or the chord
form.  (The path is ``Re cl (1 + tau s) = Q / p``, and the factor ``1 + tau
s`` is a function of ``s`` itself, so it does not move the points where the
path is tangent to a level line of ``s``.)  They form curves in the ``(alpha,
Re)`` plane, which this module and :mod:`~bild_mdo.airfoil.load_path_table`
parametrise by the load coordinate of the path with ``tau = 0``::

    x0 = ln Re + ln cl,     and for any tau:   x = ln(Q / p) = x0 + ln(1 + tau s).

(``x0`` is smooth along a curve where it turns back in ``Re``; it folds where
a minimum along the path turns into a maximum.)  :func:`refine` solves ``H =
0`` and ``ln Re + ln cl = x0`` by Newton's method in ``(alpha, ln Re)``;
:func:`path_point` gives the slopes ``d/dx0`` by the implicit-function
theorem.  At ``tau = 0`` a point is a minimum along its path where the
Jacobian ``J`` of that system has ``det J > 0``; at another ``tau`` the
Jacobian of the path system is ``c~ det J dx/dx0``, so a minimum keeps its
kind where ``dx/dx0 = 1 + tau s' / (1 + tau s) > 0``.  Polars must vary with
the Reynolds number only.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

#: Lift coefficients below this are left out: far from any minimum of cd/cl, and near zero lift the path's
#: Reynolds number would leave any polar's data.
LIFT_FLOOR = 0.1
#: Newton passes of :func:`refine`, and its step limits in alpha (rad) and ln Re.
MAX_PASSES = 30
_ALPHA_STEP_MAX = 0.02
_ELL_STEP_MAX = 0.5
#: A Newton correction below this (in alpha, rad, and ln Re) ends :func:`refine` (it is applied).
STEP_TOL = 1e-13


class StationaryTerms(NamedTuple):
    """``H`` and its partials ``H_alpha``, ``H_ell = Re H_Re`` at ``(alpha, Re)``."""

    h: np.ndarray
    h_alpha: np.ndarray
    h_ell: np.ndarray


def stationary_value(values, reynolds):
    """``H`` from the polar's first derivatives alone (the function a scan brackets)."""
    v = values
    return (v.dcd_dalpha * v.cl - v.cd * v.dcl_dalpha) + reynolds * (v.dcd_dalpha * v.dcl_dre
                                                                     - v.dcl_dalpha * v.dcd_dre)


def stationary_terms(values, second, reynolds):
    """:class:`StationaryTerms` from the polar's values and second derivatives at ``(alpha, Re)``."""
    v, s, re = values, second, reynolds
    k = v.dcd_dalpha * v.dcl_dre - v.dcl_dalpha * v.dcd_dre
    a_alpha = s.d2cd_dalpha2 * v.cl - v.cd * s.d2cl_dalpha2
    k_alpha = (s.d2cd_dalpha2 * v.dcl_dre + v.dcd_dalpha * s.d2cl_dalpha_dre - s.d2cl_dalpha2 * v.dcd_dre
               - v.dcl_dalpha * s.d2cd_dalpha_dre)
    a_re = (s.d2cd_dalpha_dre * v.cl + v.dcd_dalpha * v.dcl_dre - v.dcd_dre * v.dcl_dalpha
            - v.cd * s.d2cl_dalpha_dre)
    k_re = (s.d2cd_dalpha_dre * v.dcl_dre + v.dcd_dalpha * s.d2cl_dre2 - s.d2cl_dalpha_dre * v.dcd_dre
            - v.dcl_dalpha * s.d2cd_dre2)
    return StationaryTerms(stationary_value(v, re), a_alpha + re * k_alpha, re * (a_re + k + re * k_re))


def _system(values, second, reynolds):
    """``H`` terms and the Jacobian of ``(H, ln Re + ln cl - x0)`` in ``(alpha, ln Re)``."""
    terms = stationary_terms(values, second, reynolds)
    return terms, terms.h_alpha, terms.h_ell, values.dcl_dalpha / values.cl, 1.0 + reynolds * values.dcl_dre / values.cl


class PathPoint(NamedTuple):
    """A stationary point: ``alpha`` (rad), ``ell = ln Re``, ``s = cd/cl``, ``det`` (``> 0``: a minimum along the
    path at ``tau = 0``) and the slopes ``d/dx0`` of ``alpha, ell, s`` (flat arrays)."""

    alpha: np.ndarray
    ell: np.ndarray
    s: np.ndarray
    det: np.ndarray
    alpha1: np.ndarray
    ell1: np.ndarray
    s1: np.ndarray


def path_point(polar, alpha, ell):
    """:class:`PathPoint` at the stationary points ``(alpha, ell)`` (real, flat)."""
    reynolds = np.exp(ell)
    v, sec = polar.evaluate_with_second_derivatives(alpha, reynolds)
    _, j11, j12, j21, j22 = _system(v, sec, reynolds)
    det = j11 * j22 - j12 * j21
    with np.errstate(divide="ignore", invalid="ignore"):
        alpha1, ell1 = -j12 / det, j11 / det
        s = v.cd / v.cl
        s_alpha = (v.dcd_dalpha - s * v.dcl_dalpha) / v.cl
        s_ell = reynolds * (v.dcd_dre - s * v.dcl_dre) / v.cl
    return PathPoint(alpha, ell, s, det, alpha1, ell1, s_alpha * alpha1 + s_ell * ell1)


def refine(polar, x0, alpha, ell, alpha_bounds=None):
    """Solve ``H = 0``, ``ln Re + ln cl = x0`` by Newton's method in ``(alpha, ell)`` at every element.

    Steps are limited to 0.02 rad in ``alpha`` and 0.5 in ``ln Re``; an element
    fails where an iterate has ``cl <= LIFT_FLOOR`` or ``cd <= 0``, leaves
    ``alpha_bounds`` (``(low, high)`` arrays), or does not converge in
    :data:`MAX_PASSES` passes.

    Returns
    -------
    alpha, ell : ndarray
        The roots (last iterates where not converged).
    converged : ndarray of bool
    """
    alpha = np.array(alpha, dtype=float)
    ell = np.array(ell, dtype=float)
    x0 = np.broadcast_to(np.asarray(x0, dtype=float), alpha.shape)
    n = alpha.size
    converged = np.zeros(n, dtype=bool)
    failed = np.zeros(n, dtype=bool)
    active = np.arange(n)
    for _ in range(MAX_PASSES):
        if active.size == 0:
            break
        re = np.exp(ell[active])
        v, sec = polar.evaluate_with_second_derivatives(alpha[active], re)
        terms, j11, j12, j21, j22 = _system(v, sec, re)
        with np.errstate(divide="ignore", invalid="ignore"):
            r2 = ell[active] + np.log(np.where(v.cl > 0.0, v.cl, 1.0)) - x0[active]
            det = j11 * j22 - j12 * j21
            d_alpha = (j22 * terms.h - j12 * r2) / det
            d_ell = (j11 * r2 - j21 * terms.h) / det
        bad = ~((v.cl > LIFT_FLOOR) & (v.cd > 0.0) & np.isfinite(d_alpha) & np.isfinite(d_ell))
        d_alpha = np.clip(np.where(bad, 0.0, d_alpha), -_ALPHA_STEP_MAX, _ALPHA_STEP_MAX)
        d_ell = np.clip(np.where(bad, 0.0, d_ell), -_ELL_STEP_MAX, _ELL_STEP_MAX)
        alpha[active] -= d_alpha
        ell[active] -= d_ell
        if alpha_bounds is not None:
            bad |= (alpha[active] < alpha_bounds[0][active]) | (alpha[active] > alpha_bounds[1][active])
        failed[active[bad]] = True
        done = (np.abs(d_alpha) <= STEP_TOL) & (np.abs(d_ell) <= STEP_TOL) & ~bad
        converged[active[done]] = True
        active = active[~bad & ~done]
    return alpha, ell, converged & ~failed
