"""BILD: the BEM-based ideal-loading design method (paper Sec. 4, Algorithm 1).

:class:`BILDGroup` assembles the whole chain; the components are exported for
users who build their own groups, and :func:`~bild_mdo.bild.problem.bild_problem`
returns the set-up (cached) problem of one configuration.
"""
from bild_mdo.bild.advance_ratio import AdvanceRatioComp
from bild_mdo.bild.bild_group import BILDGroup
from bild_mdo.bild.chord import ChordComp
from bild_mdo.bild.variants.paper.eta2 import Eta2Comp
from bild_mdo.bild.feasibility import FeasibilityComp, FeasibilityLedger
from bild_mdo.bild.geometry import GeometryComp
from bild_mdo.bild.variants.paper.ideal_loading import IdealLoadingComp
from bild_mdo.bild.induced_velocity import InducedVelocityComp
from bild_mdo.bild.inflow_angle import InflowAngleComp
from bild_mdo.bild.mach import LocalMachComp
from bild_mdo.bild.momentum_loads import MomentumLoadsComp
from bild_mdo.bild.problem import bild_problem, clear_model_cache
from bild_mdo.bild.variants.reference_point.reference_airfoil import ReferenceAirfoilComp
from bild_mdo.bild.reference_induced_velocity import ReferenceInducedVelocityComp
from bild_mdo.bild.variants.reference_point.reference_station import ReferenceStationComp
from bild_mdo.bild.root_chord_correction import RootChordCorrectionComp
from bild_mdo.bild.rotational_speed import RotationalSpeedComp
from bild_mdo.bild.thrust_target import ReferenceChordSolver, ThrustTargetComp

__all__ = [
    "AdvanceRatioComp",
    "BILDGroup",
    "ChordComp",
    "Eta2Comp",
    "FeasibilityComp",
    "FeasibilityLedger",
    "GeometryComp",
    "IdealLoadingComp",
    "InducedVelocityComp",
    "InflowAngleComp",
    "LocalMachComp",
    "ReferenceChordSolver",
    "ReferenceAirfoilComp",
    "ReferenceInducedVelocityComp",
    "ReferenceStationComp",
    "RootChordCorrectionComp",
    "RotationalSpeedComp",
    "ThrustTargetComp",
    "MomentumLoadsComp",
    "bild_problem",
    "clear_model_cache",
]
