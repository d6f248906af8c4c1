"""Design-variable scaling from the diagonal of the Hessian of the Lagrangian."""
import numpy as np

from bild_mdo.optimization.problem import build_optimization_problem
from bild_mdo.optimization.scaling import hessian_scaling, lagrangian_hessian_diagonal, response_gradients
from tests.optimization.conftest import case_args


def test_hessian_diagonal_matches_single_perturbations(designs):
    # The interleaved perturbations of lagrangian_hessian_diagonal must give the same diagonal as
    # perturbing one B-spline control point at a time (local support of order 4).
    case, bild = designs["cruise"]
    prob = build_optimization_problem(*case_args(case, bild), bild_chord=bild["chord"], bild_twist=bild["twist"],
                                      parameterization="bspline")
    step = 1e-6
    diag, lam = lagrangian_hessian_diagonal(prob, step)
    x_c = prob.get_val("chord_ratio_cp")[0].copy()
    x_t = prob.get_val("twist_cp")[0].copy()
    g0 = np.add(*(g * w for g, w in zip(response_gradients(prob, x_c, x_t), (1.0, lam))))
    n = x_c.size
    single = np.zeros(2 * n)
    for k in range(2 * n):
        dx = np.zeros(2 * n)
        dx[k] = step
        g_e, g_t = response_gradients(prob, x_c + dx[:n], x_t + dx[n:])
        single[k] = (g_e + lam * g_t - g0)[k] / step
    np.testing.assert_allclose(diag, single, rtol=1e-6, atol=1e-9 * np.abs(single).max())


def test_references_are_inverse_square_roots_of_the_curvature(designs):
    case, bild = designs["hover"]
    prob = build_optimization_problem(*case_args(case, bild), bild_chord=bild["chord"], bild_twist=bild["twist"])
    x_c = prob.get_val("chord_ratio_cp").copy()
    ref_chord, ref_twist = hessian_scaling(prob, floor=0.0)
    diag, _ = lagrangian_hessian_diagonal(prob)
    n = x_c.size
    # ref_i = 1 / sqrt(|H_ii|): the scaled Hessian has a unit diagonal.  The two diagonals come from two
    # sets of model runs; the inflow solve is warm-started from the previous run (BEMOptimizationGroup's
    # warm_start), which reproduces phi to its tolerance |R| <= 1e-13, amplified by the 1e-6
    # finite-difference step of the diagonal to ~1e-7 relative (1e-12 with cold solves).
    np.testing.assert_allclose(ref_chord, 1.0 / np.sqrt(np.abs(diag[:n])), rtol=1e-6)
    np.testing.assert_allclose(ref_twist, 1.0 / np.sqrt(np.abs(diag[n:])), rtol=1e-6)
    # The design is left where it was.
    np.testing.assert_array_equal(prob.get_val("chord_ratio_cp"), x_c)
