"""BEM analysis of a turbine design with the package's propeller-convention analysis (for the tests).

``analyze_rotor`` takes ``V_x > 0`` from ahead and a polar whose lift produces thrust; a turbine section
meets the wind from its pressure side, so in that convention it is the mirror image of its airfoil:
``C_l(alpha) -> -C_l(-alpha)``, ``C_d(alpha) -> C_d(-alpha)``, with the same twist value.  The analysis
then returns thrust and torque with the propeller's signs: ``T_turbine = -thrust``, ``P = -Omega Q``.
"""
import dataclasses

import numpy as np

from bild_mdo.airfoil.polar import Polar, PolarValues
from bild_mdo.bem.analyze import analyze_rotor
from bild_mdo.constants import RPM_TO_RAD_PER_S


@dataclasses.dataclass(eq=False)
class MirroredPolar(Polar):
    """The polar of the mirrored section (upside down): ``C_l(alpha) = -C_l0(-alpha)``, ``C_d = C_d0(-alpha)``."""

    base: Polar

    @property
    def name(self):
        return f"mirrored {self.base.name}"

    def _evaluate_real(self, alpha, reynolds):
        v = self.base.evaluate(-np.asarray(alpha), reynolds)
        return PolarValues(-v.cl, v.cd, v.dcl_dalpha, -v.dcl_dre, -v.dcd_dalpha, v.dcd_dre)


def analyze_turbine(design):
    """``(power W, thrust N, flow_state)`` of a :class:`~bild_mdo.results.turbine_design.TurbineDesign`'s blade."""
    hub = design.radius * design.hub_radius_ratio
    result = analyze_rotor(design.chord, design.twist, design.radius, hub, design.rpm, design.wind_speed,
                           design.num_blades, MirroredPolar(design.polar), loss_model=design.loss_model,
                           radii=design.radii, dr=design.dr, rho=design.rho, mu=design.mu, on_invalid="raise")
    return -design.rpm * RPM_TO_RAD_PER_S * result.torque, -result.thrust, result.flow_state
