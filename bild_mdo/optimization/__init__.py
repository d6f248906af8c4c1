"""Full-BEM rotor optimisation, the reference BILD is verified against (paper Sec. 5.1).

Public API
----------
BEMOptimizationGroup
    Parameterisation + :class:`~bild_mdo.bem.BEMAnalysisGroup` + normalised
    objective ``E/E_ref`` and thrust constraint ``T/T* - 1``.
ParameterizationComp, NormalizedResponsesComp, ResponseSumsComp
    Its components (``parameterization.py``, ``responses.py``).
OPTIMIZERS, build_optimization_problem, set_optimization_case
    A ready ``om.Problem`` with SLSQP, Ipopt or SNOPT, and loading cases into it (``problem.py``).
run_optimization, optimize_rotor, optimize_rotors, OptimizationResult, trim_to_thrust
    Running it (``run.py``); many cases at once in lockstep through one vectorised model
    (``lockstep.py``, ``batch_model.py``).
hessian_scaling, lagrangian_hessian_diagonal
    Design-variable scaling (``scaling.py``).
ideal_energy_loss, linear_initial_design, twist_bounds
    Objective reference, cold start and bounds (``initial_design.py``).
bspline_matrix, parameterization_matrix, design_value_fractions, fit_design_values
    Parameterisation matrices.
IpoptDriver
    OpenMDAO driver for Ipopt through cyipopt (``ipopt_driver.py``; cyipopt is needed only to make one).
"""
from bild_mdo.optimization.bem_optimization_group import BEMOptimizationGroup
from bild_mdo.optimization.initial_design import ideal_energy_loss, linear_initial_design, twist_bounds
from bild_mdo.optimization.ipopt_driver import IpoptDriver
from bild_mdo.optimization.parameterization import (PARAMETERIZATIONS, ParameterizationComp, bspline_matrix,
                                                    design_value_fractions, fit_design_values,
                                                    parameterization_matrix)
from bild_mdo.optimization.problem import OPTIMIZERS, build_optimization_problem, set_optimization_case
from bild_mdo.optimization.responses import NormalizedResponsesComp, ResponseSumsComp
from bild_mdo.optimization.run import (OptimizationResult, optimize_rotor, optimize_rotors, run_optimization,
                                      trim_to_thrust)
from bild_mdo.optimization.scaling import hessian_scaling, lagrangian_hessian_diagonal

__all__ = [
    "BEMOptimizationGroup", "IpoptDriver", "NormalizedResponsesComp", "OPTIMIZERS", "OptimizationResult",
    "PARAMETERIZATIONS", "ParameterizationComp", "bspline_matrix", "build_optimization_problem",
    "design_value_fractions", "fit_design_values", "hessian_scaling", "ideal_energy_loss",
    "lagrangian_hessian_diagonal", "linear_initial_design", "optimize_rotor", "optimize_rotors",
    "parameterization_matrix", "ResponseSumsComp",
    "run_optimization", "set_optimization_case", "trim_to_thrust", "twist_bounds",
]
