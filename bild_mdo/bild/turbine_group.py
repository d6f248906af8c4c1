"""TurbineBILDGroup: the BILD method for energy extraction (wind and tidal turbines) as one group."""
import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.polar import Polar
from bild_mdo.atmosphere import AtmosphereComp
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bem.stations import StationsComp, declare_station_options
from bild_mdo.bild.geometry import GeometryComp
from bild_mdo.bild.rotational_speed import RotationalSpeedComp
from bild_mdo.bild.variants.base import Wiring
from bild_mdo.bild.variants.reference_point.reference_airfoil import default_polar
from bild_mdo.bild.variants.turbine.turbine_performance import TURBINE_OUTPUTS, TurbinePerformanceComp
from bild_mdo.bild.variants.turbine.variant import DESIGN_FOR, TurbineVariant
from bild_mdo.fluid import FLUIDS, fluid_arrays
from bild_mdo.utils.options import VARIABLES, declare_size_options


def _check_polar(name, value):
    if value is not None and not isinstance(value, Polar):
        raise ValueError(f"{name} must be a bild_mdo.airfoil.Polar or None (built-in NACA 4412), "
                         f"got {type(value).__name__}")


class TurbineBILDGroup(om.Group):
    """Ideal chord and twist of a turbine rotor and its performance, by the turbine BILD loading.

    A feed-forward chain on RunOnce (the solves are inside the components)::

        atmosphere (ISA)       altitude -> rho, mu, a          (or rho, mu, speed_of_sound inputs)
        geometry, stations     R, ratios -> r_hub, r_ref, radii, dr           (shared with BILDGroup)
        rotational_speed       V_theta = Omega r, Omega r_ref                 (shared)
        reference_airfoil      max-L/D point at Re_ref (paper Assumption 2)   (shared)
        [thrust_limit]         mu with T = thrust_target                      (design_for='thrust')
        reference_station      mu <-> c_ref at r_ref
        inflow                 phi of (F p)' = mu (F t)' at every station     (bracketed Newton)
        loads                  a, a', u_axial, W, F, dT/dr, dQ/dr
        chord                  chord (paper's Eq. (31), windmill signs), twist = phi - alpha*
        performance            thrust, torque, power, C_P, C_T, tip-speed ratio

    The family (:mod:`bild_mdo.bild.variants.turbine.kernel`) is parameterised by the multiplier ``mu``
    (m/s): the marginal power per marginal thrust.  ``design_for='multiplier'`` (default) takes it as an
    input, default 0: the design for maximum power at the input rpm and wind speed; its reference chord is
    an output.  ``'ref_chord'``: the member whose chord at ``r_ref`` is ``ref_chord``.  ``'thrust'``: the
    member whose thrust is ``thrust_target`` (the most power for that thrust).  The section point's
    Reynolds number is taken with ``ref_chord`` in the second case and with the input ``section_chord``
    otherwise (:func:`~bild_mdo.results.turbine_design.design_turbine` iterates it to the designed
    reference chord).

    Options
    -------
    num_nodes, num_radial : int
        Designs (axis 0) and radial stations (axis 1).
    num_blades : int
        Number of blades B (default 3).
    polar : Polar or None
        One airfoil along the span; ``None`` is the built-in NACA 4412.
    loss_model : str
        Prandtl loss factor: ``'tip_hub'`` (default), ``'tip'`` or ``'none'``.
    design_for : str
        ``'multiplier'`` (default), ``'ref_chord'`` or ``'thrust'`` (above).
    use_atmosphere : bool
        True (default): ``rho, mu, speed_of_sound`` of the ISA at ``altitude``; False: inputs.
    radial_fractions, width_fractions : array_like or None
        User stations, as in :class:`~bild_mdo.bem.stations.StationsComp`.

    Inputs
    ------
    v_axial[nn] (m/s), rpm[nn] (rpm), radius[nn] (m), hub_radius_ratio[nn] (-), ref_radius_ratio[nn] (-)
        Wind speed, rotor speed, tip radius, hub and reference radii over the tip radius.
    power_thrust_multiplier[nn] (m/s), ref_chord[nn] (m) or thrust_target[nn] (N)
        The member (``design_for``); ``section_chord[nn] (m)`` with the first and the last.
    altitude[nn] (m)
        ISA altitude (or ``rho``, ``mu``, ``speed_of_sound``).

    Outputs
    -------
    chord, twist, phi, axial_induction, tangential_induction, u_axial, inflow_speed, loss_factor,
    dthrust_dr, dtorque_dr, lift_coefficient, drag_coefficient, radii, dr : [nn, nr]
        The ideal blade and its stations.
    thrust, torque, power, power_coefficient, thrust_coefficient, tip_speed_ratio : [nn]
        Turbine performance (power extracted > 0, thrust downwind > 0).
    power_thrust_multiplier or ref_chord, phi_ref, alpha_star, cl_star, cd_star, reynolds_ref : [nn]
        The member's other parameter and the section point.
    """

    def initialize(self):
        declare_size_options(self.options)
        self.options.declare("num_blades", types=int, default=3, desc="number of blades B")
        self.options.declare("polar", default=None, allow_none=True, recordable=False, check_valid=_check_polar,
                             desc="airfoil Polar; None selects the built-in NACA 4412")
        self.options.declare("loss_model", default="tip_hub", values=LOSS_MODELS,
                             desc="Prandtl losses: 'tip_hub', 'tip' or 'none'")
        self.options.declare("design_for", default="multiplier", values=DESIGN_FOR,
                             desc="member of the family: input multiplier (0: maximum power), ref_chord or thrust")
        self.options.declare("use_atmosphere", types=bool, default=True,
                             desc="rho, mu and speed_of_sound from the ISA at input altitude (else inputs)")
        declare_station_options(self.options)

    def setup(self):
        opts = self.options
        nn, nr = opts["num_nodes"], opts["num_radial"]
        if nr < 2:
            raise ValueError(f"{self.msginfo}: num_radial must be at least 2, got {nr}")
        node, size = dict(num_nodes=nn), dict(num_nodes=nn, num_radial=nr)
        polar = default_polar() if opts["polar"] is None else opts["polar"]
        if opts["use_atmosphere"]:
            self.add_subsystem("atmosphere", AtmosphereComp(num_nodes=nn), promotes_inputs=["altitude"],
                               promotes_outputs=["rho", "mu", "speed_of_sound"])
        self.add_subsystem("geometry", GeometryComp(**node),
                           promotes_inputs=["radius", "hub_radius_ratio", "ref_radius_ratio"],
                           promotes_outputs=["hub_radius", "ref_radius"])
        self.add_subsystem("stations", StationsComp(**size, radial_fractions=opts["radial_fractions"],
                                                    width_fractions=opts["width_fractions"]),
                           promotes_inputs=["radius", "hub_radius"], promotes_outputs=["radii", "dr"])
        self.add_subsystem("rotational_speed", RotationalSpeedComp(**size),
                           promotes_inputs=["rpm", "radii", "ref_radius"], promotes_outputs=["v_theta", "v_theta_ref"])
        loss = dict(num_blades=opts["num_blades"], loss_model=opts["loss_model"])
        #: The member of the BILD family (:class:`~bild_mdo.bild.variants.turbine.variant.TurbineVariant`).
        self.variant = TurbineVariant(Wiring(self, polar, node, size, loss, {}, "thrust"))
        self.variant.add()
        self.add_subsystem("performance", TurbinePerformanceComp(**size),
                           promotes_inputs=["dthrust_dr", "dtorque_dr", "dr", "rpm", "radius", "v_axial", "rho"],
                           promotes_outputs=list(TURBINE_OUTPUTS))

        self.set_input_defaults("v_axial", val=np.full(nn, 10.0), units="m/s")
        self.set_input_defaults("rpm", val=np.full(nn, 20.0), units="rpm")
        self.set_input_defaults("radius", val=np.full(nn, 40.0), units="m")
        self.set_input_defaults("hub_radius_ratio", val=np.full(nn, 0.05), units=None)
        self.set_input_defaults("ref_radius_ratio", val=np.full(nn, 0.7), units=None)
        design_for = opts["design_for"]
        if design_for == "ref_chord":
            self.set_input_defaults("ref_chord", val=np.full(nn, 2.0), units="m")
        else:
            self.set_input_defaults("section_chord", val=np.full(nn, 2.0), units="m")
        if design_for == "thrust":
            self.set_input_defaults("thrust_target", val=np.full(nn, 1.0e5), units="N")
        if design_for == "multiplier":
            self.set_input_defaults("power_thrust_multiplier", val=np.zeros(nn), units="m/s")
        if opts["use_atmosphere"]:
            self.set_input_defaults("altitude", val=np.zeros(nn), units="m")
        else:
            for name, value in fluid_arrays(FLUIDS["air"], nn).items():
                self.set_input_defaults(name, val=value, units=VARIABLES[name][2])
