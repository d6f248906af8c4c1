"""Sizing a lift+cruise eVTOL with BILD rotors inside an OpenMDAO optimisation.

The BILD method gives the optimal blade of a rotor (chord, twist and
performance) from a handful of inputs in one feed-forward pass with exact
derivatives, so it can sit inside a vehicle-level optimisation where a
blade-shape optimisation per rotor would be too slow or fragile (paper
Sec. 6).  This example sizes a Vahana-class lift+cruise aircraft: eight lift
rotors that only work in hover and one pusher propeller that only works in
cruise.

Model (feed-forward except the mass closure)::

    conditions (IVC)   v_axial = [0, V_cruise], altitude = [0, h_cruise]
    vehicle (IVC)      the assumptions below, as inputs with units
    rotors             BILDGroup(num_nodes=2): node 0 = lift rotor in hover (J = 0),
                       node 1 = pusher propeller in cruise.  One group fits
                       because both rotors share the blade count and airfoil;
                       radius, rpm and ref_chord are two-element design variables.
    tip_mach           helical tip Mach number of both rotors
    mission            hover and cruise electric power, mission energy
    powertrain         battery mass from energy, motor mass from peak shaft power
    closure            gross mass m solving  m = m_payload + f_s m + m_battery + m_motors
                       (om.NewtonSolver + om.DirectSolver)
    thrust_margin      T_BILD / T_required - 1 for both rotors

    minimise    gross_mass (or mission_energy, ``objective='mission_energy'``)
    w.r.t.      radius[2], rpm[2], ref_chord[2]
    subject to  thrust_margin >= 0        hover: T >= m g / n_lift;  cruise: T >= m g / (L/D)
                tip_mach <= [0.5, 0.6]    hover (noise), cruise (helical, compressibility)

BILD's thrust follows from the reference chord (the blade is the optimal one
for that chord), so the thrust requirement is a constraint that the optimiser
meets through ``ref_chord``; at the optimum both thrust constraints are
active, because every extra newton costs power.

Result with the assumptions below (20 stations, SLSQP or Ipopt): 716.8 kg
gross mass (177.0 kg battery, 31.4 kg motors, 35.4 kWh).  Every design
variable is fixed by an active constraint: both radii sit at their upper
bounds (at fixed thrust the induced power falls with the disk area), both
rotor speeds at their tip-Mach limits (2166 and 2088 rpm) and the reference
chords (0.092 m and 0.043 m) give exactly the required thrusts.  Lower the
tip-Mach limits or raise the radius bounds to move the optimum.

The mass residual is linear in the gross mass (the rotor powers do not
depend on it; the mass enters only through the thrust constraints), so
Newton converges in one iteration.  It is an implicit closure all the same so
that the optimiser sees a closed mass at every iterate and mass-dependent
disciplines can be added without changing the solver set-up.

Assumptions (Vahana-class, single seat; round numbers, not Airbus data):

* gross mass near the paper's Vahana, 725 kg (Sec. 5.1): the payload and
  range below are chosen so that the optimum lands there;
* payload 150 kg (one occupant and baggage);
* empty-mass fraction without battery and motors ``f_s = 0.5`` (airframe,
  rotors, systems, avionics);
* 8 lift rotors, 1 pusher; 3 blades each; NACA 4412 (the library's
  built-in polar); hub at 0.2 R, reference station at 0.5 R;
* mission: 3 min of hover in total (take-off, landing, reserve) at sea level,
  120 km of cruise at 50 m/s (180 km/h) at 500 m (ISA);
* cruise lift-to-drag ratio 10 (wing with stopped lift rotors and booms), so
  the pusher's thrust requirement is ``m g / 10``;
* drivetrain (motor x inverter) efficiency 0.9 from battery to shaft;
* battery: 250 Wh/kg at pack level, 80 % usable;
* motors: 5 kW/kg of peak shaft power, sized at the hover power (lift motors)
  and the cruise power (pusher motor), no margins;
* tip Mach limits: 0.5 for the lift rotors in hover (noise), 0.6 helical for
  the pusher in cruise;
* bounds: lift-rotor radius 0.4 ... 0.75 m (1.5 m diameter: eight rotors on a
  Vahana-size wing and canard leave no more room), pusher radius
  0.4 ... 0.9 m (ground clearance), rpm and reference chord within ranges
  where every BILD design is valid (``DESIGN_BOUNDS``).

Run ``python -m examples.evtol_sizing`` from the repository root (add
``--ipopt`` for Ipopt, ``--energy`` to minimise the mission energy).
"""
from __future__ import annotations

import argparse
import dataclasses
import time
import warnings

import numpy as np
import openmdao.api as om

from bild_mdo import BILDGroup, IpoptDriver

GRAVITY = 9.80665  # m/s^2, standard gravity
OBJECTIVES = ("gross_mass", "mission_energy")
OPTIMIZERS = ("slsqp", "ipopt")


@dataclasses.dataclass(frozen=True)
class VehicleAssumptions:
    """Vehicle and mission numbers of the sizing problem (see the module docstring).

    Attributes
    ----------
    payload_mass : float
        kg.
    structural_mass_fraction : float
        Mass of everything but payload, battery and motors over the gross mass.
    num_lift_rotors : int
        Number of lift rotors (each carries ``1/num_lift_rotors`` of the weight in hover).
    num_blades : int
        Blades per rotor (lift rotors and pusher).
    hover_time : float
        s, total time in hover.
    cruise_range : float
        m.
    cruise_speed : float
        m/s.
    cruise_altitude : float
        m (ISA); hover is at sea level.
    lift_to_drag : float
        Cruise lift-to-drag ratio of the aircraft.
    drivetrain_efficiency : float
        Battery-to-shaft efficiency.
    battery_specific_energy : float
        J/kg at pack level.
    battery_usable_fraction : float
        Usable fraction of the stored energy.
    motor_specific_power : float
        W/kg of peak shaft power.
    tip_mach_limits : tuple of float
        Upper bounds on the helical tip Mach number (lift rotor in hover, pusher in cruise).
    """

    payload_mass: float = 150.0
    structural_mass_fraction: float = 0.5
    num_lift_rotors: int = 8
    num_blades: int = 3
    hover_time: float = 180.0
    cruise_range: float = 120.0e3
    cruise_speed: float = 50.0
    cruise_altitude: float = 500.0
    lift_to_drag: float = 10.0
    drivetrain_efficiency: float = 0.9
    battery_specific_energy: float = 250.0 * 3600.0
    battery_usable_fraction: float = 0.8
    motor_specific_power: float = 5.0e3
    tip_mach_limits: tuple = (0.5, 0.6)


#: Design-variable bounds, node 0 = lift rotor, node 1 = pusher.  Inside them every BILD design is
#: valid (BILD's Assumption 3, u_theta < V_theta at r_ref, fails for a slow, wide pusher: J > ~3).
DESIGN_BOUNDS = {
    "radius": (np.array([0.4, 0.4]), np.array([0.75, 0.9]), "m", 1.0),
    "rpm": (np.array([1000.0, 1200.0]), np.array([3500.0, 3500.0]), "rpm", 1000.0),
    "ref_chord": (np.array([0.03, 0.03]), np.array([0.3, 0.3]), "m", 0.1),
}

#: Initial design (radius m, rpm, ref_chord m) and mass guess (kg).
INITIAL_DESIGN = {"radius": np.array([0.6, 0.7]), "rpm": np.array([1800.0, 1600.0]),
                  "ref_chord": np.array([0.15, 0.1]), "gross_mass": 700.0}


class MissionEnergyComp(om.ExplicitComponent):
    """Electric power in hover and cruise and the mission energy.

    ``P_hover = n_lift P_0 / eta_d``, ``P_cruise = P_1 / eta_d`` and
    ``E = t_hover P_hover + (d / V) P_cruise``, with ``P_0, P_1`` the BILD
    shaft powers of one lift rotor in hover and of the pusher in cruise.

    Options
    -------
    num_lift_rotors : int

    Inputs
    ------
    power[2] (W), hover_time (s), cruise_range (m), cruise_speed (m/s), drivetrain_efficiency (-)

    Outputs
    -------
    hover_electric_power (W), cruise_electric_power (W), mission_energy (J)
    """

    def initialize(self):
        self.options.declare("num_lift_rotors", types=int, default=8, desc="number of lift rotors")

    def setup(self):
        self.add_input("power", val=np.ones(2), units="W",
                       desc="shaft power of one lift rotor in hover (0) and of the pusher in cruise (1)")
        self.add_input("hover_time", val=180.0, units="s", desc="total hover time")
        self.add_input("cruise_range", val=1.0e5, units="m", desc="cruise distance")
        self.add_input("cruise_speed", val=50.0, units="m/s", desc="cruise speed")
        self.add_input("drivetrain_efficiency", val=0.9, units=None, desc="battery-to-shaft efficiency")
        self.add_output("hover_electric_power", val=1.0e5, units="W", desc="battery power in hover")
        self.add_output("cruise_electric_power", val=1.0e4, units="W", desc="battery power in cruise")
        self.add_output("mission_energy", val=1.0e8, units="J", desc="battery energy used by the mission")

    def setup_partials(self):
        self.declare_partials("hover_electric_power", "power", rows=[0], cols=[0])
        self.declare_partials("hover_electric_power", "drivetrain_efficiency")
        self.declare_partials("cruise_electric_power", "power", rows=[0], cols=[1])
        self.declare_partials("cruise_electric_power", "drivetrain_efficiency")
        self.declare_partials("mission_energy", ["power", "hover_time", "cruise_range", "cruise_speed",
                                                 "drivetrain_efficiency"])

    def compute(self, inputs, outputs):
        n = self.options["num_lift_rotors"]
        eta = inputs["drivetrain_efficiency"]
        p_hover = n * inputs["power"][0] / eta
        p_cruise = inputs["power"][1] / eta
        outputs["hover_electric_power"] = p_hover
        outputs["cruise_electric_power"] = p_cruise
        outputs["mission_energy"] = (inputs["hover_time"] * p_hover
                                     + inputs["cruise_range"] / inputs["cruise_speed"] * p_cruise)

    def compute_partials(self, inputs, partials):
        n = self.options["num_lift_rotors"]
        eta = inputs["drivetrain_efficiency"]
        power = inputs["power"]
        t_hover, distance, speed = inputs["hover_time"], inputs["cruise_range"], inputs["cruise_speed"]
        p_hover = n * power[0] / eta
        p_cruise = power[1] / eta
        cruise_time = distance / speed
        partials["hover_electric_power", "power"] = n / eta
        partials["hover_electric_power", "drivetrain_efficiency"] = -p_hover / eta
        partials["cruise_electric_power", "power"] = 1.0 / eta
        partials["cruise_electric_power", "drivetrain_efficiency"] = -p_cruise / eta
        partials["mission_energy", "power"] = np.array([[t_hover[0] * n / eta[0], cruise_time[0] / eta[0]]])
        partials["mission_energy", "hover_time"] = p_hover
        partials["mission_energy", "cruise_range"] = p_cruise / speed
        partials["mission_energy", "cruise_speed"] = -cruise_time * p_cruise / speed
        partials["mission_energy", "drivetrain_efficiency"] = -(t_hover * p_hover + cruise_time * p_cruise) / eta


class PowertrainMassComp(om.ExplicitComponent):
    """Battery mass from the mission energy and motor mass from the peak shaft powers.

    ``m_battery = E / (e_b u)`` and ``m_motors = (n_lift P_0 + P_1) / p_m``.

    Options
    -------
    num_lift_rotors : int

    Inputs
    ------
    mission_energy (J), power[2] (W), battery_specific_energy (J/kg), battery_usable_fraction (-),
    motor_specific_power (W/kg)

    Outputs
    -------
    battery_mass (kg), motor_mass (kg)
    """

    def initialize(self):
        self.options.declare("num_lift_rotors", types=int, default=8, desc="number of lift rotors")

    def setup(self):
        self.add_input("mission_energy", val=1.0e8, units="J", desc="battery energy used by the mission")
        self.add_input("power", val=np.ones(2), units="W",
                       desc="shaft power of one lift rotor in hover (0) and of the pusher in cruise (1)")
        self.add_input("battery_specific_energy", val=9.0e5, units="J/kg", desc="pack specific energy")
        self.add_input("battery_usable_fraction", val=0.8, units=None, desc="usable fraction of the energy")
        self.add_input("motor_specific_power", val=5.0e3, units="W/kg", desc="motor peak power per mass")
        self.add_output("battery_mass", val=100.0, units="kg", desc="battery pack mass")
        self.add_output("motor_mass", val=30.0, units="kg", desc="mass of all motors")

    def setup_partials(self):
        self.declare_partials("battery_mass", ["mission_energy", "battery_specific_energy",
                                               "battery_usable_fraction"])
        self.declare_partials("motor_mass", "power")
        self.declare_partials("motor_mass", "motor_specific_power")

    def compute(self, inputs, outputs):
        n = self.options["num_lift_rotors"]
        outputs["battery_mass"] = inputs["mission_energy"] / (
            inputs["battery_specific_energy"] * inputs["battery_usable_fraction"])
        outputs["motor_mass"] = (n * inputs["power"][0] + inputs["power"][1]) / inputs["motor_specific_power"]

    def compute_partials(self, inputs, partials):
        n = self.options["num_lift_rotors"]
        energy, e_b, u = inputs["mission_energy"], inputs["battery_specific_energy"], inputs["battery_usable_fraction"]
        p_m = inputs["motor_specific_power"]
        partials["battery_mass", "mission_energy"] = 1.0 / (e_b * u)
        partials["battery_mass", "battery_specific_energy"] = -energy / (e_b**2 * u)
        partials["battery_mass", "battery_usable_fraction"] = -energy / (e_b * u**2)
        partials["motor_mass", "power"] = np.array([[n / p_m[0], 1.0 / p_m[0]]])
        partials["motor_mass", "motor_specific_power"] = -(n * inputs["power"][0] + inputs["power"][1]) / p_m**2


class MassClosureComp(om.ImplicitComponent):
    """Gross mass as the state of ``R = m - (m_payload + f_s m + m_battery + m_motors) = 0``.

    Solved by the Newton solver of the enclosing group.

    Inputs
    ------
    payload_mass (kg), structural_mass_fraction (-), battery_mass (kg), motor_mass (kg)

    Outputs
    -------
    gross_mass (kg)
    """

    def setup(self):
        self.add_input("payload_mass", val=150.0, units="kg", desc="payload mass")
        self.add_input("structural_mass_fraction", val=0.5, units=None,
                       desc="mass of all but payload, battery and motors over the gross mass")
        self.add_input("battery_mass", val=100.0, units="kg", desc="battery pack mass")
        self.add_input("motor_mass", val=30.0, units="kg", desc="mass of all motors")
        self.add_output("gross_mass", val=700.0, units="kg", ref=700.0, desc="gross (take-off) mass")

    def setup_partials(self):
        self.declare_partials("gross_mass", ["gross_mass", "structural_mass_fraction"])
        self.declare_partials("gross_mass", ["payload_mass", "battery_mass", "motor_mass"], val=-1.0)

    def apply_nonlinear(self, inputs, outputs, residuals):
        m = outputs["gross_mass"]
        residuals["gross_mass"] = m - (inputs["payload_mass"] + inputs["structural_mass_fraction"] * m
                                       + inputs["battery_mass"] + inputs["motor_mass"])

    def linearize(self, inputs, outputs, jacobian):
        jacobian["gross_mass", "gross_mass"] = 1.0 - inputs["structural_mass_fraction"]
        jacobian["gross_mass", "structural_mass_fraction"] = -outputs["gross_mass"]


class ThrustMarginComp(om.ExplicitComponent):
    """Required thrust and the relative thrust margin of the lift rotor (hover) and the pusher (cruise).

    ``T_req = [m g / n_lift, m g / (L/D)]`` and ``margin = T / T_req - 1``.

    Options
    -------
    num_lift_rotors : int

    Inputs
    ------
    thrust[2] (N), gross_mass (kg), lift_to_drag (-)

    Outputs
    -------
    required_thrust[2] (N), thrust_margin[2] (-)
    """

    def initialize(self):
        self.options.declare("num_lift_rotors", types=int, default=8, desc="number of lift rotors")

    def setup(self):
        self.add_input("thrust", val=np.ones(2), units="N", desc="BILD thrust: lift rotor (0), pusher (1)")
        self.add_input("gross_mass", val=700.0, units="kg", desc="gross mass")
        self.add_input("lift_to_drag", val=10.0, units=None, desc="cruise lift-to-drag ratio")
        self.add_output("required_thrust", val=np.ones(2), units="N",
                        desc="thrust required per lift rotor in hover (0) and of the pusher in cruise (1)")
        self.add_output("thrust_margin", val=np.zeros(2), units=None, desc="T / T_required - 1")

    def setup_partials(self):
        ar = np.arange(2)
        self.declare_partials("required_thrust", "gross_mass")
        self.declare_partials("required_thrust", "lift_to_drag", rows=[1], cols=[0])
        self.declare_partials("thrust_margin", "thrust", rows=ar, cols=ar)
        self.declare_partials("thrust_margin", "gross_mass")
        self.declare_partials("thrust_margin", "lift_to_drag", rows=[1], cols=[0])

    def _required(self, inputs):
        weight = inputs["gross_mass"][0] * GRAVITY
        return np.array([weight / self.options["num_lift_rotors"], weight / inputs["lift_to_drag"][0]])

    def compute(self, inputs, outputs):
        required = self._required(inputs)
        outputs["required_thrust"] = required
        outputs["thrust_margin"] = inputs["thrust"] / required - 1.0

    def compute_partials(self, inputs, partials):
        required = self._required(inputs)
        m, ld = inputs["gross_mass"][0], inputs["lift_to_drag"][0]
        ratio = inputs["thrust"] / required
        partials["required_thrust", "gross_mass"] = (required / m)[:, None]
        partials["required_thrust", "lift_to_drag"] = -required[1] / ld
        partials["thrust_margin", "thrust"] = 1.0 / required
        # T_req is proportional to m, and to 1/(L/D) for the pusher.
        partials["thrust_margin", "gross_mass"] = (-ratio / m)[:, None]
        partials["thrust_margin", "lift_to_drag"] = ratio[1] / ld


def build_model(model, assumptions, num_radial):
    """Add the sizing model to ``model`` (see the module docstring for the layout)."""
    a = assumptions
    n_lift = a.num_lift_rotors
    conditions = model.add_subsystem("conditions", om.IndepVarComp(), promotes_outputs=["*"])
    conditions.add_output("v_axial", val=np.array([0.0, a.cruise_speed]), units="m/s",
                          desc="axial speed: lift rotor in hover (0), pusher in cruise (1)")
    conditions.add_output("altitude", val=np.array([0.0, a.cruise_altitude]), units="m",
                          desc="altitude of hover (0) and cruise (1), ISA")
    vehicle = model.add_subsystem("vehicle", om.IndepVarComp(), promotes_outputs=["*"])
    for name, units, desc in (
            ("payload_mass", "kg", "payload mass"),
            ("structural_mass_fraction", None, "mass of all but payload, battery and motors over the gross mass"),
            ("hover_time", "s", "total hover time"),
            ("cruise_range", "m", "cruise distance"),
            ("lift_to_drag", None, "cruise lift-to-drag ratio"),
            ("drivetrain_efficiency", None, "battery-to-shaft efficiency"),
            ("battery_specific_energy", "J/kg", "pack specific energy"),
            ("battery_usable_fraction", None, "usable fraction of the battery energy"),
            ("motor_specific_power", "W/kg", "motor peak shaft power per mass")):
        vehicle.add_output(name, val=getattr(a, name), units=units, desc=desc)

    design = model.add_subsystem("rotor_design", om.IndepVarComp(), promotes_outputs=["*"])
    for name, (_, _, units, _) in DESIGN_BOUNDS.items():
        design.add_output(name, val=INITIAL_DESIGN[name], units=units,
                          desc=f"{name}: lift rotor (0) and pusher (1), a design variable")
    design.add_output("hub_radius_ratio", val=np.full(2, 0.2), units=None, desc="hub radius over tip radius")
    design.add_output("ref_radius_ratio", val=np.full(2, 0.5), units=None, desc="reference radius over tip radius")

    model.add_subsystem("rotors", BILDGroup(num_nodes=2, num_radial=num_radial, num_blades=a.num_blades),
                        promotes_inputs=["v_axial", "altitude", "rpm", "radius", "ref_chord",
                                         "hub_radius_ratio", "ref_radius_ratio"],
                        promotes_outputs=["thrust", "power", "torque", "efficiency", "figure_of_merit",
                                          "solidity", "chord", "twist", "tip_mach"])
    model.add_subsystem("mission", MissionEnergyComp(num_lift_rotors=n_lift),
                        promotes_inputs=["power", "hover_time", "cruise_range", "cruise_speed",
                                         "drivetrain_efficiency"],
                        promotes_outputs=["hover_electric_power", "cruise_electric_power", "mission_energy"])
    model.connect("v_axial", "cruise_speed", src_indices=[1])
    model.add_subsystem("powertrain", PowertrainMassComp(num_lift_rotors=n_lift),
                        promotes_inputs=["mission_energy", "power", "battery_specific_energy",
                                         "battery_usable_fraction", "motor_specific_power"],
                        promotes_outputs=["battery_mass", "motor_mass"])
    closure = model.add_subsystem("closure", om.Group(), promotes=["*"])
    closure.add_subsystem("mass", MassClosureComp(),
                          promotes_inputs=["payload_mass", "structural_mass_fraction", "battery_mass",
                                           "motor_mass"],
                          promotes_outputs=["gross_mass"])
    closure.nonlinear_solver = om.NewtonSolver(solve_subsystems=False, maxiter=20, atol=1e-10, rtol=1e-12,
                                               iprint=-1, err_on_non_converge=True)
    closure.linear_solver = om.DirectSolver()
    model.add_subsystem("thrust_requirement", ThrustMarginComp(num_lift_rotors=n_lift),
                        promotes_inputs=["thrust", "gross_mass", "lift_to_drag"],
                        promotes_outputs=["required_thrust", "thrust_margin"])


def build_problem(assumptions=None, num_radial=20, objective="gross_mass", optimizer="slsqp", tol=1e-9,
                  maxiter=200, print_level=0):
    """Set up the eVTOL sizing optimisation.

    Parameters
    ----------
    assumptions : VehicleAssumptions, optional
        Vehicle and mission numbers; default :class:`VehicleAssumptions`.
    num_radial : int
        Radial stations of each BILD rotor.
    objective : {'gross_mass', 'mission_energy'}
        Quantity to minimise.
    optimizer : {'slsqp', 'ipopt'}
        ``om.ScipyOptimizeDriver`` (SLSQP) or :class:`bild_mdo.IpoptDriver`.
    tol, maxiter : float, int
        Optimiser tolerance and iteration limit.
    print_level : int
        0 is silent.

    Returns
    -------
    om.Problem
        Set up (complex step allocated for derivative checks), initial design loaded.
    """
    if objective not in OBJECTIVES:
        raise ValueError(f"objective must be one of {OBJECTIVES}, got {objective!r}")
    if optimizer not in OPTIMIZERS:
        raise ValueError(f"optimizer must be one of {OPTIMIZERS}, got {optimizer!r}")
    assumptions = VehicleAssumptions() if assumptions is None else assumptions
    prob = om.Problem(reports=False)
    build_model(prob.model, assumptions, num_radial)
    for name, (lower, upper, units, ref) in DESIGN_BOUNDS.items():
        prob.model.add_design_var(name, lower=lower, upper=upper, units=units, ref=ref)
    if objective == "gross_mass":
        prob.model.add_objective("gross_mass", ref=700.0)
    else:
        prob.model.add_objective("mission_energy", ref=1.0e8)
    prob.model.add_constraint("thrust_margin", lower=0.0, ref=0.1)
    prob.model.add_constraint("tip_mach", upper=np.array(assumptions.tip_mach_limits), ref=0.1)
    if optimizer == "slsqp":
        prob.driver = om.ScipyOptimizeDriver(optimizer="SLSQP", tol=tol, maxiter=maxiter, disp=print_level > 0)
    else:
        prob.driver = IpoptDriver(tol=tol, maxiter=maxiter, print_level=min(print_level, 12),
                                  disp=print_level > 0)
    prob.setup(force_alloc_complex=True)
    with warnings.catch_warnings():
        # The closure group is meant to be one unit for the optimiser's relevance graph.
        warnings.filterwarnings("ignore", message=".*have a nonlinear solver that computes gradients")
        prob.final_setup()
    prob.set_val("gross_mass", INITIAL_DESIGN["gross_mass"], units="kg")
    return prob


@dataclasses.dataclass
class SizingResult:
    """Outcome of :func:`main`.

    Attributes
    ----------
    problem : om.Problem
        The problem, left at the optimum.
    success : bool
        The optimiser reports success.
    message : str
        The optimiser's exit message.
    model_evaluations : int
        Model runs requested by the driver (``driver.iter_count``).
    iterations : int
        Major iterations of the optimiser.
    gradient_evaluations : int or None
        Total-derivative evaluations (SLSQP's ``njev``; None for Ipopt, which does not report it).
    wall_time : float
        Driver run time (s).
    optimum : dict
        Name -> value (units in :data:`SUMMARY_UNITS`).
    """

    problem: om.Problem
    success: bool
    message: str
    model_evaluations: int
    iterations: int
    gradient_evaluations: int | None
    wall_time: float
    optimum: dict


#: Quantities reported by :func:`main`, with their units.
SUMMARY_UNITS = {
    "gross_mass": "kg", "battery_mass": "kg", "motor_mass": "kg", "payload_mass": "kg",
    "mission_energy": "kW*h", "hover_electric_power": "kW", "cruise_electric_power": "kW",
    "radius": "m", "rpm": "rpm", "ref_chord": "m", "thrust": "N", "required_thrust": "N", "power": "kW",
    "figure_of_merit": None, "efficiency": None, "solidity": None, "tip_mach": None, "thrust_margin": None,
}


def main(num_radial=20, objective="gross_mass", optimizer="slsqp", assumptions=None, tol=1e-9, verbose=True):
    """Size the aircraft and return the optimum.

    Parameters
    ----------
    num_radial : int
        Radial stations per rotor (20 at full size; 8 is enough for a test).
    objective, optimizer, assumptions, tol
        See :func:`build_problem`.
    verbose : bool
        Print the optimum.

    Returns
    -------
    SizingResult
    """
    prob = build_problem(assumptions, num_radial=num_radial, objective=objective, optimizer=optimizer, tol=tol)
    start = time.perf_counter()
    run_success = bool(prob.run_driver().success)
    wall_time = time.perf_counter() - start
    driver = prob.driver
    if optimizer == "slsqp":
        res = driver._scipy_optimize_result
        success, message = bool(res.success) and run_success, str(res.message)
        iterations, njev = int(res.nit), int(res.njev)
    else:
        success = run_success and not driver.fail
        message = f"{driver.ipopt_status_name}: {driver.ipopt_message}"
        iterations, njev = int(driver.ipopt_iterations), None
    optimum = {name: prob.get_val(name, units=units).copy() for name, units in SUMMARY_UNITS.items()}
    result = SizingResult(problem=prob, success=success, message=message, model_evaluations=int(driver.iter_count),
                          iterations=iterations, gradient_evaluations=njev, wall_time=wall_time, optimum=optimum)
    if verbose:
        print_summary(result, objective, optimizer)
    return result


def print_summary(result, objective="gross_mass", optimizer="slsqp"):
    """Print the optimum of :func:`main`."""
    o = {k: np.atleast_1d(v) for k, v in result.optimum.items()}
    print(f"eVTOL sizing ({optimizer}, minimise {objective}): {result.message}")
    gradients = "" if result.gradient_evaluations is None else f", {result.gradient_evaluations} gradient evaluations"
    print(f"  {result.iterations} iterations, {result.model_evaluations} model evaluations{gradients}, "
          f"{result.wall_time:.2f} s")
    print(f"  gross mass {o['gross_mass'][0]:.1f} kg = payload {o['payload_mass'][0]:.1f} + structure "
          f"{o['gross_mass'][0] - o['payload_mass'][0] - o['battery_mass'][0] - o['motor_mass'][0]:.1f} + battery "
          f"{o['battery_mass'][0]:.1f} + motors {o['motor_mass'][0]:.1f} kg")
    print(f"  mission energy {o['mission_energy'][0]:.2f} kWh; electric power hover "
          f"{o['hover_electric_power'][0]:.1f} kW, cruise {o['cruise_electric_power'][0]:.1f} kW")
    print(f"  {'':12s}{'radius m':>10s}{'rpm':>9s}{'c_ref m':>9s}{'T N':>9s}{'T_req N':>9s}{'P kW':>8s}"
          f"{'FM':>7s}{'eta':>7s}{'sigma':>7s}{'M_tip':>7s}")
    # The lift rotor hovers (figure of merit); the pusher flies (efficiency): each other metric means nothing there.
    for i, label in enumerate(("lift rotor", "pusher")):
        merit, eta = (f"{o['figure_of_merit'][i]:7.3f}", f"{'n/a':>7s}") if i == 0 else \
            (f"{'n/a':>7s}", f"{o['efficiency'][i]:7.3f}")
        print(f"  {label:12s}{o['radius'][i]:10.3f}{o['rpm'][i]:9.0f}{o['ref_chord'][i]:9.4f}{o['thrust'][i]:9.1f}"
              f"{o['required_thrust'][i]:9.1f}{o['power'][i]:8.2f}{merit}{eta}"
              f"{o['solidity'][i]:7.3f}{o['tip_mach'][i]:7.3f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ipopt", action="store_true", help="use Ipopt instead of SLSQP")
    parser.add_argument("--energy", action="store_true", help="minimise the mission energy")
    parser.add_argument("--num-radial", type=int, default=20, help="radial stations per rotor")
    args = parser.parse_args()
    main(num_radial=args.num_radial, objective="mission_energy" if args.energy else "gross_mass",
         optimizer="ipopt" if args.ipopt else "slsqp")
