"""InclinedBEMGroup: BEM of a propeller, lift rotor or wind turbine with precone, tilt, yaw, shear and sectors."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.atmosphere import AtmosphereComp
from bild_mdo.bem.blade_element import declare_section_options
from bild_mdo.bem.flow_states import declare_flow_state_options, declare_high_induction_option
from bild_mdo.bem.inflow import InflowComp
from bild_mdo.bem.inflow_residual import resolve_high_induction
from bild_mdo.bem.loads import SECTION_OUTPUTS, BladeElementLoadsComp
from bild_mdo.bem.metrics import PERFORMANCE_OUTPUTS, TURBINE_OUTPUTS
from bild_mdo.bem.performance import SEA_LEVEL_SPEED_OF_SOUND, RotorPerformanceComp
from bild_mdo.bem.sector_average import AVERAGED_LOADS, SectorAverageComp
from bild_mdo.bem.sector_stations import SECTOR_COPIES, SectorStationsComp
from bild_mdo.bem.sectors import declare_sector_option
from bild_mdo.bem.stations import StationsComp, declare_station_options
from bild_mdo.bem.turbine_performance import TurbinePerformanceComp
from bild_mdo.bem.turbine_polar import TurbinePolar
from bild_mdo.bem.wind_components import INFLOW_GEOMETRY, WindComponentsComp

#: Values of the ``rotor_type`` option.
ROTOR_TYPES = ("propeller", "turbine")
#: Inputs of the sector blade elements that are the same in every sector (per node).
_NODE_SECTION_INPUTS = ["radius", "hub_radius", "rho", "mu", "speed_of_sound", "collective_pitch"]


class InclinedBEMGroup(om.Group):
    """BEM analysis in inclined flow, averaged over azimuth sectors, for propellers and wind turbines.

    Feed-forward chain on RunOnce: ``atmosphere -> stations -> wind (V_x, V_theta of every station
    and sector) -> sectors (the blade copied to every sector) -> inflow (phi) -> loads -> average
    (loads along the shaft, mean over the sectors) -> performance``.  The kinematics of precone,
    tilt, yaw and shear are those of :mod:`bild_mdo.bem.wind_components` (CCBlade's conventions); the
    sector arrays are laid out as :mod:`bild_mdo.bem.sectors` says.  With ``precone = tilt = yaw = 0``,
    ``shear_exponent = 0`` and ``num_sectors = 1`` a propeller's outputs equal those of
    :class:`~bild_mdo.bem.bem_group.BEMAnalysisGroup` exactly (bit for bit).

    Options
    -------
    num_nodes, num_radial, num_blades, polar, loss_model
        As in :class:`~bild_mdo.bem.bem_group.BEMAnalysisGroup`; for a turbine ``polar`` is the
        airfoil's own polar (``alpha = phi - theta``), wrapped in
        :class:`~bild_mdo.bem.turbine_polar.TurbinePolar` here.
    num_sectors : int
        Azimuth sectors averaged (default 1; CCBlade uses at least 4 when tilt, yaw or shear is nonzero).
    rotor_type : {'propeller', 'turbine'}
        'propeller' (default): the performance of :class:`~bild_mdo.bem.performance.RotorPerformanceComp`.
        'turbine': the turbine airfoil orientation and the turbine-signed outputs of
        :class:`~bild_mdo.bem.turbine_performance.TurbinePerformanceComp` (power extracted, C_P, C_T,
        C_Q, tip-speed ratio); ``twist + collective_pitch`` is CCBlade's ``theta``.
    use_atmosphere, radial_fractions, width_fractions, solve_range, on_invalid
        As in :class:`~bild_mdo.bem.bem_group.BEMAnalysisGroup`.
    high_induction : {None, 'none', 'buhl'}
        As in :class:`~bild_mdo.bem.bem_group.BEMAnalysisGroup`; None (default): Buhl's correction for a
        turbine (as CCBlade), none for a propeller.

    Inputs
    ------
    v_axial[nn] (m/s)
        Freestream (wind) speed at hub height, >= 0 (> 0 for a turbine).
    rpm[nn] (rpm), radius[nn] (m), hub_radius[nn] (m), chord[nn, nr] (m), twist[nn, nr] (rad),
    collective_pitch[nn] (rad)
        As in :class:`~bild_mdo.bem.bem_group.BEMAnalysisGroup`; radii are distances along the blade.
    precone[nn] (rad), tilt[nn] (rad), yaw[nn] (rad), hub_height[nn] (m), shear_exponent[nn]
        :data:`~bild_mdo.bem.wind_components.INFLOW_GEOMETRY` (defaults 0, 0, 0, 100 m, 0).
    altitude[nn] (m), or rho[nn] (kg/m**3), mu[nn] (Pa*s), speed_of_sound[nn] (m/s)
        As in :class:`~bild_mdo.bem.bem_group.BEMAnalysisGroup`.

    Outputs
    -------
    radii[nn, nr] (m), dr[nn, nr] (m)
    v_axial_local[nn, ns*nr] (m/s), v_theta_local[nn, ns*nr] (m/s), phi[nn, ns*nr] (rad), flow_state[nn, ns*nr]
        Per sector and station (sector-major; the kernel's propeller convention).
    alpha, reynolds, mach, lift_coefficient, drag_coefficient, u_axial, u_theta, loss_factor,
    inflow_speed [nn, ns*nr]; sector_dthrust_dr[nn, ns*nr] (N/m), sector_dtorque_dr[nn, ns*nr] (N*m/m)
        Station outputs of :class:`~bild_mdo.bem.loads.BladeElementLoadsComp` in every sector, in the
        kernel's propeller convention (a turbine's ``alpha`` and ``lift_coefficient`` are minus its own).
    dthrust_dr[nn, nr] (N/m), dtorque_dr[nn, nr] (N*m/m)
        Along the shaft, sector mean (:class:`~bild_mdo.bem.sector_average.SectorAverageComp`).
    The per-design outputs (nn,) of :data:`~bild_mdo.bem.metrics.PERFORMANCE_OUTPUTS` (propeller) or
    :data:`~bild_mdo.bem.metrics.TURBINE_OUTPUTS` (turbine); rho, mu, speed_of_sound with ``use_atmosphere``.
    """

    def initialize(self):
        declare_section_options(self.options)
        declare_high_induction_option(self.options, by_rotor_type=True)
        declare_flow_state_options(self.options)
        declare_sector_option(self.options)
        self.options.declare("rotor_type", default="propeller", values=ROTOR_TYPES,
                             desc="'propeller' (thrust-producing) or 'turbine' (energy-extracting, turbine airfoils)")
        self.options.declare("use_atmosphere", types=bool, default=True,
                             desc="compute rho and mu from the ISA at input altitude (else they are inputs)")
        declare_station_options(self.options)

    def setup(self):
        opts = self.options
        nn, nr, ns = opts["num_nodes"], opts["num_radial"], opts["num_sectors"]
        turbine = opts["rotor_type"] == "turbine"
        polar = TurbinePolar(opts["polar"]) if turbine else opts["polar"]
        section = dict(num_nodes=nn, num_radial=ns * nr, num_blades=opts["num_blades"], polar=polar,
                       loss_model=opts["loss_model"], station_velocities=True,
                       high_induction=resolve_high_induction(opts["high_induction"], opts["rotor_type"]))
        sizes = dict(num_nodes=nn, num_radial=nr)

        if opts["use_atmosphere"]:
            self.add_subsystem("atmosphere", AtmosphereComp(num_nodes=nn), promotes_inputs=["altitude"],
                               promotes_outputs=["rho", "mu", "speed_of_sound"])
        self.add_subsystem("stations", StationsComp(**sizes, radial_fractions=opts["radial_fractions"],
                                                    width_fractions=opts["width_fractions"]),
                           promotes_inputs=["radius", "hub_radius"], promotes_outputs=["radii", "dr"])
        self.add_subsystem("wind", WindComponentsComp(**sizes, num_sectors=ns),
                           promotes_inputs=["v_axial", "rpm", "radii", *INFLOW_GEOMETRY],
                           promotes_outputs=["v_axial_local", "v_theta_local"])
        self.add_subsystem("sectors", SectorStationsComp(**sizes, num_sectors=ns),
                           promotes_inputs=list(SECTOR_COPIES), promotes_outputs=list(SECTOR_COPIES.values()))
        blade_inputs = list(SECTOR_COPIES.items()) + ["v_axial_local", "v_theta_local"] + _NODE_SECTION_INPUTS
        self.add_subsystem("inflow", InflowComp(**section, solve_range=opts["solve_range"],
                                                on_invalid=opts["on_invalid"]),
                           promotes_inputs=blade_inputs, promotes_outputs=["phi", "flow_state"])
        load_outputs = [(name, AVERAGED_LOADS.get(name, name)) for name in SECTION_OUTPUTS]
        self.add_subsystem("loads", BladeElementLoadsComp(**section),
                           promotes_inputs=["phi", "flow_state"] + blade_inputs, promotes_outputs=load_outputs)
        self.add_subsystem("average", SectorAverageComp(**sizes, num_sectors=ns),
                           promotes_inputs=list(AVERAGED_LOADS.values()) + ["precone"],
                           promotes_outputs=list(AVERAGED_LOADS))
        common = ["dthrust_dr", "dtorque_dr", "dr", "v_axial", "rpm", "radius", "rho", "speed_of_sound"]
        if turbine:
            self.add_subsystem("performance", TurbinePerformanceComp(**sizes),
                               promotes_inputs=common + ["precone"], promotes_outputs=list(TURBINE_OUTPUTS))
        else:
            self.add_subsystem("performance", RotorPerformanceComp(**sizes, num_blades=opts["num_blades"]),
                               promotes_inputs=common + ["chord"], promotes_outputs=list(PERFORMANCE_OUTPUTS))

        self.set_input_defaults("v_axial", val=np.full(nn, 10.0 if turbine else 0.0), units="m/s")
        self.set_input_defaults("rpm", val=np.full(nn, 1000.0), units="rpm")
        self.set_input_defaults("radius", val=np.ones(nn), units="m")
        self.set_input_defaults("hub_radius", val=np.full(nn, 0.1), units="m")
        self.set_input_defaults("chord", val=np.full((nn, nr), 0.1), units="m")
        self.set_input_defaults("twist", val=np.full((nn, nr), 0.3), units="rad")
        self.set_input_defaults("collective_pitch", val=np.zeros(nn), units="rad")
        for name, (default, units, _) in INFLOW_GEOMETRY.items():
            self.set_input_defaults(name, val=np.full(nn, default), units=units)
        if opts["use_atmosphere"]:
            self.set_input_defaults("altitude", val=np.zeros(nn), units="m")
        else:
            self.set_input_defaults("rho", val=np.full(nn, 1.225), units="kg/m**3")
            self.set_input_defaults("mu", val=np.full(nn, 1.789e-5), units="Pa*s")
            self.set_input_defaults("speed_of_sound", val=np.full(nn, SEA_LEVEL_SPEED_OF_SOUND), units="m/s")

