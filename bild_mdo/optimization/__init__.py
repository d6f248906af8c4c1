"""Full-BEM rotor optimisation, the reference BILD is verified against (paper Sec. 5.1).

Public API
----------
BEMOptimizationGroup
    Parameterisation + :class:`~bild_mdo.bem.BEMAnalysisGroup` + normalised
    objective ``E/E_ref`` and thrust constraint ``T/T* - 1``.
ParameterizationComp, NormalizedResponsesComp
    Its components.
build_optimization_problem, set_optimization_case, run_optimization, optimize_rotor, OptimizationResult
    A ready ``om.Problem`` with SLSQP, Ipopt or SNOPT; loading cases into it; running it.
hessian_scaling, lagrangian_hessian_diagonal, trim_to_thrust, ideal_energy_loss, linear_initial_design
    Helpers: design-variable scaling, collective-pitch trim, objective reference, cold start.
bspline_matrix, parameterization_matrix, design_value_fractions, fit_design_values
    Parameterisation matrices.
"""
from bild_mdo.optimization.bem_optimization_group import BEMOptimizationGroup
from bild_mdo.optimization.normalized_responses import NormalizedResponsesComp
from bild_mdo.optimization.parameterization import (PARAMETERIZATIONS, ParameterizationComp, bspline_matrix,
                                                    design_value_fractions, fit_design_values,
                                                    parameterization_matrix)
from bild_mdo.optimization.problem import (OPTIMIZERS, OptimizationResult, build_optimization_problem,
                                           hessian_scaling, ideal_energy_loss, lagrangian_hessian_diagonal,
                                           linear_initial_design, optimize_rotor, run_optimization,
                                           set_optimization_case, trim_to_thrust)

__all__ = [
    "BEMOptimizationGroup", "NormalizedResponsesComp", "OPTIMIZERS", "OptimizationResult", "PARAMETERIZATIONS",
    "ParameterizationComp", "bspline_matrix", "build_optimization_problem", "design_value_fractions",
    "fit_design_values", "hessian_scaling", "ideal_energy_loss", "lagrangian_hessian_diagonal",
    "linear_initial_design", "optimize_rotor", "parameterization_matrix", "run_optimization",
    "set_optimization_case", "trim_to_thrust",
]
