"""Blade element momentum (BEM) analysis of rotors in axial flow (paper Sec. 3).

Public API
----------
analyze_rotor, BEMResult, station_radii
    Plain-Python entry point (:mod:`bild_mdo.bem.analyze`).
BEMAnalysisGroup
    OpenMDAO group: atmosphere -> stations -> inflow -> loads -> performance.
StationsComp, InflowComp, BladeElementLoadsComp, RotorPerformanceComp
    The components.
prandtl_loss, inflow_residual, induced_velocities, solve_bracketed
    Building blocks shared with the BILD method.
BEMStateWarning, FLOW_STATE_NAMES
    Per-station flow states (:mod:`bild_mdo.bem.flow_states`): the warning of
    ``on_invalid='warn'`` and the names of the integer codes.
TipMachWarning
    Warned by ``analyze_rotor`` and ``design_rotor`` where a tip Mach number is >= 1.
"""
from bild_mdo.bem.analyze import BEMResult, analyze_rotor, station_radii
from bild_mdo.bem.analyze_inclined import InclinedBEMResult, TurbineBEMResult
from bild_mdo.bem.bem_group import BEMAnalysisGroup
from bild_mdo.bem.flow_states import FLOW_STATE_NAMES, BEMStateWarning
from bild_mdo.bem.inclined_bem_group import InclinedBEMGroup
from bild_mdo.bem.inflow import InflowComp
from bild_mdo.bem.inflow_residual import (InducedVelocities, InflowResidual, force_coefficients,
                                          induced_velocities, inflow_residual)
from bild_mdo.bem.loads import BladeElementLoadsComp
from bild_mdo.bem.metrics import TipMachWarning
from bild_mdo.bem.performance import RotorPerformanceComp, rotor_performance
from bild_mdo.bem.prandtl import LOSS_MODELS, PrandtlLoss, prandtl_loss
from bild_mdo.bem.root_finding import find_brackets, solve_bracketed
from bild_mdo.bem.stations import StationsComp
from bild_mdo.bem.turbine_performance import TurbinePerformanceComp
from bild_mdo.bem.turbine_polar import TurbinePolar
from bild_mdo.bem.wind_components import WindComponentsComp

__all__ = [
    "BEMAnalysisGroup", "BEMResult", "BEMStateWarning", "FLOW_STATE_NAMES", "InducedVelocities", "InflowComp", "InflowResidual",
    "LOSS_MODELS", "PrandtlLoss", "RotorPerformanceComp", "BladeElementLoadsComp", "StationsComp", "TipMachWarning",
    "analyze_rotor", "find_brackets", "force_coefficients",
    "induced_velocities", "inflow_residual", "prandtl_loss", "rotor_performance", "solve_bracketed",
    "station_radii", "InclinedBEMGroup", "InclinedBEMResult", "TurbineBEMResult", "TurbinePerformanceComp",
    "TurbinePolar", "WindComponentsComp",
]
