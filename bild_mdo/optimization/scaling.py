"""Design-variable scaling of the BEM optimisation from the curvature of its Lagrangian.

The objective ``E/E_ref`` and the relative thrust constraint are of order one
for every case (:class:`~bild_mdo.optimization.responses.NormalizedResponsesComp`);
the design variables are scaled by the curvature of the Lagrangian at the
initial design (:func:`hessian_scaling`), which cuts SLSQP's iterations five-
to tenfold against the fixed references :data:`CHORD_RATIO_REF` and
:data:`TWIST_REF`.
"""
from __future__ import annotations

import numpy as np

SCALINGS = ("hessian", "fixed")

#: Fixed design-variable references of ``scaling='fixed'`` (c/R, rad).
CHORD_RATIO_REF = 0.1
TWIST_REF = 1.0


def response_gradients(prob, x_chord, x_twist):
    """Objective and constraint gradients (model units) at the given design values.

    Parameters
    ----------
    prob : om.Problem
        From :func:`~bild_mdo.optimization.problem.build_optimization_problem`;
        its design values are set to ``x_chord``, ``x_twist`` and the model is run.
    x_chord, x_twist : ndarray, shape (ncp,)
        Chord (c/R) and twist (rad) design values.

    Returns
    -------
    grad_energy, grad_thrust : ndarray, shape (2 ncp,)
        Gradients of ``E/E_ref`` and ``T/T* - 1``: chord entries, then twist entries.
    """
    prob.set_val("chord_ratio_cp", x_chord[None, :])
    prob.set_val("twist_cp", x_twist[None, :], units="rad")
    prob.run_model()
    jac = prob.compute_totals(of=["energy_loss_ratio", "thrust_residual"], wrt=["chord_ratio_cp", "twist_cp"],
                              return_format="array", driver_scaling=False)
    return jac[0], jac[1]


def lagrangian_hessian_diagonal(prob, step=1.0e-6):
    """Diagonal of the Hessian of the Lagrangian at the current design, by forward differences.

    The Lagrangian is ``E/E_ref + lambda (T/T* - 1)`` with ``lambda`` the
    least-squares multiplier ``-(g_E . g_T) / (g_T . g_T)`` of the exact
    gradients at the current design.

    Blade elements interact only through the thrust constraint (every annulus
    is an independent BEM solve), so ``E`` and ``T`` are sums of per-station
    terms and their Hessians in the station values are block diagonal: one
    perturbation of all chords and one of all twists give every diagonal
    entry.  B-spline control points couple ``order`` neighbours, so they are
    perturbed in ``order`` interleaved groups per distribution.  That costs
    3 gradients for ``'stations'`` and ``2 order + 1`` for ``'bspline'``.

    Parameters
    ----------
    prob : om.Problem
        From :func:`~bild_mdo.optimization.problem.build_optimization_problem`,
        with a case loaded; its design values are left unchanged.
    step : float
        Forward-difference step of the design values (model units).

    Returns
    -------
    diagonal : ndarray, shape (2 ncp,)
        Chord entries (per (c/R)^2), then twist entries (per rad^2).
    multiplier : float
        ``lambda``.
    """
    meta = prob._bild_optimization
    x_c = prob.get_val("chord_ratio_cp")[0].copy()
    x_t = prob.get_val("twist_cp", units="rad")[0].copy()
    result = hessian_diagonal_from_gradients(lambda c, t: response_gradients(prob, c, t), x_c, x_t,
                                             meta["parameterization"], meta["order"], step)
    prob.set_val("chord_ratio_cp", x_c[None, :])
    prob.set_val("twist_cp", x_t[None, :], units="rad")
    return result


def hessian_diagonal_from_gradients(gradients, x_c, x_t, parameterization, order, step=1.0e-6):
    """:func:`lagrangian_hessian_diagonal` from a gradient function instead of a problem.

    Parameters
    ----------
    gradients : callable
        ``gradients(x_chord, x_twist) -> (grad_energy, grad_thrust)`` as
        :func:`response_gradients` returns them.
    x_c, x_t : ndarray, shape (ncp,)
        The design values (model units).
    parameterization : {'stations', 'bspline'}
    order : int
        B-spline order (``'bspline'`` only).
    step : float
        Forward-difference step (model units).

    Returns
    -------
    diagonal : ndarray, shape (2 ncp,)
    multiplier : float
    """
    n = x_c.size
    g_e, g_t = gradients(x_c, x_t)
    lam = -float(g_e @ g_t) / float(g_t @ g_t)
    g0 = g_e + lam * g_t
    stride = 1 if parameterization == "stations" else order
    diag = np.zeros(2 * n)
    for which in range(2):
        for color in range(stride):
            dx = np.zeros(n)
            dx[color::stride] = step
            if which == 0:
                g_e1, g_t1 = gradients(x_c + dx, x_t)
            else:
                g_e1, g_t1 = gradients(x_c, x_t + dx)
            idx = which * n + np.arange(color, n, stride)
            diag[idx] = ((g_e1 + lam * g_t1) - g0)[idx] / step
    return diag, lam


def references_from_diagonal(diag, floor=1.0e-2):
    """Design-variable references ``1 / sqrt(|H_ii|)`` from a Hessian diagonal (see :func:`hessian_scaling`).

    Returns
    -------
    ref_chord, ref_twist : ndarray
    """
    n = diag.size // 2
    refs = []
    for part in (np.abs(diag[:n]), np.abs(diag[n:])):
        refs.append(1.0 / np.sqrt(np.maximum(part, floor * np.median(part))))
    return refs[0], refs[1]


def hessian_scaling(prob, step=1.0e-6, floor=1.0e-2):
    """Design-variable references from the curvature of the Lagrangian at the current design.

    Each design value ``x_i`` gets the reference ``1 / sqrt(|H_ii|)``
    (:func:`lagrangian_hessian_diagonal`), so that the quasi-Newton Hessian of
    SLSQP or Ipopt, which starts as the identity in scaled variables, starts
    close to the true one.  The curvatures of chord and twist from root to
    tip differ by orders of magnitude; with fixed references SLSQP needs
    several hundred iterations, with these about thirty from a BILD start.

    Parameters
    ----------
    prob : om.Problem
        From :func:`~bild_mdo.optimization.problem.build_optimization_problem`, with a case loaded.
    step : float
        Forward-difference step of the design values (model units).
    floor : float
        Curvatures below ``floor`` times the median of their distribution are
        raised to it (flat or concave directions, e.g. near the tip).

    Returns
    -------
    ref_chord, ref_twist : ndarray
        The references (model units).
    """
    diag, _ = lagrangian_hessian_diagonal(prob, step)
    return references_from_diagonal(diag, floor)
