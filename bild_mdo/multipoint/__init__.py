"""One blade at several operating conditions: designed by BILD at one, analysed by the BEM at the others.

:class:`MultipointRotorGroup` is the model a vehicle sizing study puts in place of a rotor
(multicopter: hover and climb; tiltrotor: hover and cruise; propeller: take-off, climb, cruise);
:class:`BladeBroadcastComp` passes the blade's geometry to the analyses.
"""
from bild_mdo.multipoint.blade_broadcast import BladeBroadcastComp
from bild_mdo.multipoint.multipoint_group import MultipointRotorGroup
from bild_mdo.multipoint.trim import TRIM_VARIABLES, AnalysisGroup, trim_guess

__all__ = ["AnalysisGroup", "BladeBroadcastComp", "MultipointRotorGroup", "TRIM_VARIABLES", "trim_guess"]
