"""BEMAnalysisGroup: atmosphere, stations, inflow solve, section loads and rotor performance."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.polar import Polar
from bild_mdo.atmosphere import AtmosphereComp
from bild_mdo.bem.inflow import InflowComp
from bild_mdo.bem.performance import PERFORMANCE_OUTPUTS, RotorPerformanceComp
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bem.section_loads import SECTION_OUTPUTS, SectionLoadsComp
from bild_mdo.bem.stations import StationsComp

_SECTION_INPUTS = ["v_axial", "rpm", "radius", "hub_radius", "radii", "chord", "twist", "rho", "mu"]


class BEMAnalysisGroup(om.Group):
    """Full BEM analysis of a rotor in axial flow (paper Sec. 3), vectorised over designs.

    Feed-forward chain on RunOnce (the inflow component solves itself):
    ``atmosphere -> stations -> inflow (phi) -> loads -> performance``.

    Options
    -------
    num_nodes, num_radial : int
        Designs / operating points (axis 0) and radial stations (axis 1).
    num_blades : int
        Number of blades B.
    polar : Polar
        Airfoil polar (not recorded).
    loss_model : {'tip_hub', 'tip', 'none'}
        Prandtl loss factor model.
    use_atmosphere : bool
        True: ``rho``, ``mu`` come from the ISA at input ``altitude``;
        False: ``rho`` and ``mu`` are inputs of the group.
    radial_fractions, width_fractions : array_like or None
        Optional user stations (see :class:`~bild_mdo.bem.stations.StationsComp`).

    Inputs
    ------
    v_axial[nn] (m/s)
        Freestream axial velocity, >= 0.
    rpm[nn] (rpm), radius[nn] (m), hub_radius[nn] (m)
        Rotational speed, tip radius, hub radius.
    chord[nn, nr] (m), twist[nn, nr] (rad)
        Blade geometry at the stations.
    altitude[nn] (m)
        Geometric altitude (with ``use_atmosphere``); else rho[nn] (kg/m**3), mu[nn] (Pa*s).

    Outputs
    -------
    radii, dr, phi and the station outputs of
    :class:`~bild_mdo.bem.section_loads.SectionLoadsComp` (nn, nr); the per-design
    outputs of :class:`~bild_mdo.bem.performance.RotorPerformanceComp` (nn,);
    rho, mu, speed_of_sound (nn,) with ``use_atmosphere``.
    """

    def initialize(self):
        self.options.declare("num_nodes", types=int, default=1, desc="number of designs / operating points (axis 0)")
        self.options.declare("num_radial", types=int, default=20, desc="number of radial stations (axis 1)")
        self.options.declare("num_blades", types=int, desc="number of blades B")
        self.options.declare("polar", types=Polar, recordable=False, desc="airfoil polar cl, cd (alpha, Re)")
        self.options.declare("loss_model", default="tip_hub", values=LOSS_MODELS,
                             desc="Prandtl loss factor: tip x hub, tip only, or none")
        self.options.declare("use_atmosphere", types=bool, default=True,
                             desc="compute rho and mu from the ISA at input altitude (else they are inputs)")
        self.options.declare("radial_fractions", default=None, allow_none=True,
                             desc="station radii r/R, shape (nr,) or (nn, nr); None for equal annuli")
        self.options.declare("width_fractions", default=None, allow_none=True,
                             desc="station widths dr/R (with radial_fractions)")

    def setup(self):
        opts = self.options
        nn, nr = opts["num_nodes"], opts["num_radial"]
        section = dict(num_nodes=nn, num_radial=nr, num_blades=opts["num_blades"],
                       polar=opts["polar"], loss_model=opts["loss_model"])

        if opts["use_atmosphere"]:
            self.add_subsystem("atmosphere", AtmosphereComp(num_nodes=nn),
                               promotes_inputs=["altitude"],
                               promotes_outputs=["rho", "mu", "speed_of_sound"])
        self.add_subsystem("stations",
                           StationsComp(num_nodes=nn, num_radial=nr,
                                        radial_fractions=opts["radial_fractions"],
                                        width_fractions=opts["width_fractions"]),
                           promotes_inputs=["radius", "hub_radius"],
                           promotes_outputs=["radii", "dr"])
        self.add_subsystem("inflow", InflowComp(**section),
                           promotes_inputs=list(_SECTION_INPUTS),
                           promotes_outputs=["phi"])
        self.add_subsystem("loads", SectionLoadsComp(**section),
                           promotes_inputs=["phi"] + list(_SECTION_INPUTS),
                           promotes_outputs=list(SECTION_OUTPUTS))
        self.add_subsystem("performance",
                           RotorPerformanceComp(num_nodes=nn, num_radial=nr, num_blades=opts["num_blades"]),
                           promotes_inputs=["dthrust_dr", "dtorque_dr", "dr", "chord", "v_axial", "rpm",
                                            "radius", "rho"],
                           promotes_outputs=list(PERFORMANCE_OUTPUTS))

        self.set_input_defaults("v_axial", val=np.zeros(nn), units="m/s")
        self.set_input_defaults("rpm", val=np.full(nn, 1000.0), units="rpm")
        self.set_input_defaults("radius", val=np.ones(nn), units="m")
        self.set_input_defaults("hub_radius", val=np.full(nn, 0.1), units="m")
        self.set_input_defaults("chord", val=np.full((nn, nr), 0.1), units="m")
        self.set_input_defaults("twist", val=np.full((nn, nr), 0.3), units="rad")
        if opts["use_atmosphere"]:
            self.set_input_defaults("altitude", val=np.zeros(nn), units="m")
        else:
            self.set_input_defaults("rho", val=np.full(nn, 1.225), units="kg/m**3")
            self.set_input_defaults("mu", val=np.full(nn, 1.789e-5), units="Pa*s")
