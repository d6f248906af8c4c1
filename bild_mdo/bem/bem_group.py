"""BEMAnalysisGroup: atmosphere, stations, inflow solve, section loads and rotor performance."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.acoustics.noise_options import NOISE_OUTPUTS, declare_noise_options
from bild_mdo.acoustics.rotor_noise_group import make_noise_group
from bild_mdo.atmosphere import AtmosphereComp
from bild_mdo.bem.blade_element import SECTION_INPUTS, declare_section_options
from bild_mdo.bem.flow_states import declare_flow_state_options, declare_high_induction_option
from bild_mdo.bem.inflow import InflowComp
from bild_mdo.bem.loads import SECTION_OUTPUTS, BladeElementLoadsComp
from bild_mdo.bem.metrics import PERFORMANCE_OUTPUTS
from bild_mdo.bem.performance import SEA_LEVEL_SPEED_OF_SOUND, RotorPerformanceComp
from bild_mdo.bem.stations import StationsComp, declare_station_options


class BEMAnalysisGroup(om.Group):
    """Full BEM analysis of a rotor in axial flow (paper Sec. 3), vectorised over designs.

    Feed-forward chain on RunOnce (the inflow component solves itself):
    ``atmosphere -> stations -> inflow (phi) -> loads -> performance``.

    Options
    -------
    num_nodes, num_radial, num_blades, polar, loss_model
        Sizes, blades, airfoil polar (not recorded) and Prandtl loss model, as in
        :func:`~bild_mdo.bem.blade_element.declare_section_options`.
    use_atmosphere : bool
        True: ``rho``, ``mu`` and ``speed_of_sound`` come from the ISA at input ``altitude``;
        False: ``rho``, ``mu`` and ``speed_of_sound`` are inputs of the group.
    radial_fractions, width_fractions : array_like or None
        Optional user stations (see :class:`~bild_mdo.bem.stations.StationsComp`).
    solve_range : {'physical', 'full'}
        'physical' (default): CCBlade.jl's search order, only roots with ``W > 0``; a station
        without one gets the zero-loading fallback and code ``NO_SOLUTION``.  'full': the first
        sign change in ``[-pi/2, pi)``, as before the flow states existed (mirror roots with
        ``W < 0`` are kept and flagged ``MIRROR_ROOT``).  See :mod:`bild_mdo.bem.flow_states`.
    high_induction : {'none', 'buhl'}
        The momentum thrust above ``a = 0.4``: 'none' (default; such stations are flagged
        ``TURBULENT_WAKE``) or Buhl's (2005) correction, as CCBlade and AeroDyn apply
        (:mod:`bild_mdo.bem.inflow_residual`).
    on_invalid : {'warn', 'raise', 'ignore'}
        Stations in an invalid flow state (``NO_SOLUTION``, ``TURBULENT_WAKE``, ``MIRROR_ROOT``):
        one :class:`~bild_mdo.bem.flow_states.BEMStateWarning` per run naming them (default),
        ``om.AnalysisError`` naming them, or nothing.
    warm_start : bool
        Start each inflow solve from the previous run's phi (default False; see
        :class:`~bild_mdo.bem.inflow.InflowComp`): the same roots and flow states as the cold
        solve, in about a third of the residual passes, for drivers that re-run nearby inputs.
    noise_observers : array_like or None
        None (default): no noise, the group exactly as without it.  An ``(n, 3)`` array of observer
        positions (m, rotor frame, x along the thrust) adds the subsystem ``noise``
        (:class:`~bild_mdo.acoustics.rotor_noise_group.RotorNoiseGroup`) fed by the BEM loads, angles of
        attack and inflow speeds, with input ``observer_position[nn, n, 3]`` (default: these positions at
        every node) and outputs ``oaspl[nn, n]``, ``oaspl_dba[nn, n]``, ``tonal_spl``, ``band_spl`` ...
    noise_harmonics, noise_boundary_layer
        Harmonics of the tonal noise (default 10) and BPM boundary layer (``'tripped'``, default, or
        ``'untripped'``), with ``noise_observers``.

    Inputs
    ------
    v_axial[nn] (m/s)
        Freestream axial velocity, >= 0.
    rpm[nn] (rpm), radius[nn] (m), hub_radius[nn] (m)
        Rotational speed, tip radius, hub radius.
    chord[nn, nr] (m), twist[nn, nr] (rad)
        Blade geometry at the stations.
    collective_pitch[nn] (rad)
        Collective pitch added to the twist at every station (default 0).
    altitude[nn] (m)
        Geometric altitude (with ``use_atmosphere``); else rho[nn] (kg/m**3), mu[nn] (Pa*s)
        and speed_of_sound[nn] (m/s, default sea-level ISA).

    Outputs
    -------
    radii, dr, phi, flow_state (integer codes of :mod:`bild_mdo.bem.flow_states`; no derivatives),
    mach[nn, nr] (local Mach number ``W0 / a``, see :mod:`bild_mdo.bem.blade_element`)
    and the station outputs of
    :class:`~bild_mdo.bem.loads.BladeElementLoadsComp` (nn, nr); the per-design
    outputs of :class:`~bild_mdo.bem.performance.RotorPerformanceComp` (nn,), among them
    ``tip_mach = sqrt(V_x^2 + (Omega R)^2) / a``;
    rho, mu, speed_of_sound (nn,) with ``use_atmosphere``.
    """

    def initialize(self):
        declare_section_options(self.options)
        declare_high_induction_option(self.options)
        declare_flow_state_options(self.options)
        self.options.declare("use_atmosphere", types=bool, default=True,
                             desc="compute rho and mu from the ISA at input altitude (else they are inputs)")
        declare_station_options(self.options)
        self.options.declare("warm_start", types=bool, default=False,
                             desc="start each inflow solve from the previous run's phi (InflowComp)")
        declare_noise_options(self.options)

    def setup(self):
        opts = self.options
        nn, nr = opts["num_nodes"], opts["num_radial"]
        section = dict(num_nodes=nn, num_radial=nr, num_blades=opts["num_blades"],
                       polar=opts["polar"], loss_model=opts["loss_model"],
                       high_induction=opts["high_induction"])

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
        self.add_subsystem("inflow", InflowComp(**section, solve_range=opts["solve_range"],
                                                on_invalid=opts["on_invalid"], warm_start=opts["warm_start"]),
                           promotes_inputs=list(SECTION_INPUTS),
                           promotes_outputs=["phi", "flow_state"])
        self.add_subsystem("loads", BladeElementLoadsComp(**section),
                           promotes_inputs=["phi", "flow_state"] + list(SECTION_INPUTS),
                           promotes_outputs=list(SECTION_OUTPUTS))
        self.add_subsystem("performance",
                           RotorPerformanceComp(num_nodes=nn, num_radial=nr, num_blades=opts["num_blades"]),
                           promotes_inputs=["dthrust_dr", "dtorque_dr", "dr", "chord", "v_axial", "rpm",
                                            "radius", "rho", "speed_of_sound"],
                           promotes_outputs=list(PERFORMANCE_OUTPUTS))
        noise = make_noise_group(opts, nn, nr, opts["num_blades"], opts["polar"])
        if noise is not None:
            # Its inputs are the BEM outputs and inputs of the same names (rpm, radii, alpha, inflow_speed ...).
            self.add_subsystem("noise", noise, promotes_inputs=["*"], promotes_outputs=list(NOISE_OUTPUTS))

        self.set_input_defaults("v_axial", val=np.zeros(nn), units="m/s")
        self.set_input_defaults("rpm", val=np.full(nn, 1000.0), units="rpm")
        self.set_input_defaults("radius", val=np.ones(nn), units="m")
        self.set_input_defaults("hub_radius", val=np.full(nn, 0.1), units="m")
        self.set_input_defaults("chord", val=np.full((nn, nr), 0.1), units="m")
        self.set_input_defaults("twist", val=np.full((nn, nr), 0.3), units="rad")
        self.set_input_defaults("collective_pitch", val=np.zeros(nn), units="rad")
        if opts["use_atmosphere"]:
            self.set_input_defaults("altitude", val=np.zeros(nn), units="m")
        else:
            self.set_input_defaults("rho", val=np.full(nn, 1.225), units="kg/m**3")
            self.set_input_defaults("mu", val=np.full(nn, 1.789e-5), units="Pa*s")
            self.set_input_defaults("speed_of_sound", val=np.full(nn, SEA_LEVEL_SPEED_OF_SOUND), units="m/s")
