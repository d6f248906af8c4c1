"""Blade element momentum (BEM) analysis of rotors in axial flow (paper Sec. 3).

Public API
----------
analyze_rotor, BEMResult, station_radii
    Plain-Python entry point (:mod:`bild_mdo.bem.analysis`).
BEMAnalysisGroup
    OpenMDAO group: atmosphere -> stations -> inflow -> loads -> performance.
StationsComp, InflowComp, SectionLoadsComp, RotorPerformanceComp
    The components.
prandtl_loss, inflow_residual, induced_velocities, solve_bracketed, complex_newton_update
    Building blocks shared with the BILD method.
"""
from bild_mdo.bem.analysis import BEMResult, analyze_rotor, station_radii
from bild_mdo.bem.bem_analysis_group import BEMAnalysisGroup
from bild_mdo.bem.inflow import InflowComp
from bild_mdo.bem.inflow_residual import (InducedVelocities, InflowResidual, force_coefficients,
                                          induced_velocities, inflow_residual)
from bild_mdo.bem.performance import RotorPerformanceComp, rotor_performance
from bild_mdo.bem.prandtl import LOSS_MODELS, PrandtlLoss, prandtl_loss
from bild_mdo.bem.root_finding import complex_newton_update, find_brackets, solve_bracketed
from bild_mdo.bem.section_loads import SectionLoadsComp
from bild_mdo.bem.stations import StationsComp

__all__ = [
    "BEMAnalysisGroup", "BEMResult", "InducedVelocities", "InflowComp", "InflowResidual",
    "LOSS_MODELS", "PrandtlLoss", "RotorPerformanceComp", "SectionLoadsComp", "StationsComp",
    "analyze_rotor", "complex_newton_update", "find_brackets", "force_coefficients",
    "induced_velocities", "inflow_residual", "prandtl_loss", "rotor_performance", "solve_bracketed",
    "station_radii",
]
