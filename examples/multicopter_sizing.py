"""Sizing a tilting multicopter whose one rotor type hovers, climbs and cruises (MultipointRotorGroup).

Most rotorcraft fly one blade at several conditions.  This example sizes a
six-rotor eVTOL whose identical rotors tilt forward for cruise (the layout of
the Joby S4 class): every rotor hovers, climbs vertically and, tilted, works
as a propeller in cruise.  Tilted, the rotor disk faces the flow, so all three
conditions are axial flow, which is what the BEM models (an edgewise
multicopter in forward flight needs a model this package does not have).

One :class:`~bild_mdo.multipoint.MultipointRotorGroup` holds the rotor: the
blade is designed by BILD at the hover condition (so the hover point is the
BILD design itself) and analysed by the full BEM at the climb and cruise
conditions, each with its own rotor speed and collective pitch.

Model (feed-forward except the mass closure)::

    rotor     MultipointRotorGroup(num_nodes=2): BILD in hover (design_*), BEM in climb (0) and cruise (1)
    energy    mission energy E = n / eta_d (t_hover P_hover + t_climb P_climb + t_cruise P_cruise),
              battery mass E / (e_b u), motor mass n P_rated / p_m
    closure   gross mass m solving m = m_payload + f_s m + m_battery + m_motors (Newton)
    margins   thrust margins T / T_req - 1 (hover and climb T_req = m g / n, cruise m g / (n L/D)),
              power margins P / P_rated - 1

    minimise    gross_mass
    w.r.t.      radius, design_rpm, ref_chord (the blade), rpm[2], collective_pitch[2] (climb, cruise),
                motor_rated_power (per rotor)
    subject to  design_thrust_margin >= 0, thrust_margin >= 0, design_power_margin <= 0, power_margin <= 0,
                design_tip_mach <= 0.5 (hover), tip_mach <= [0.5, 0.6] (climb, cruise)

Every number the summary prints is constrained or in the objective: the hover,
climb and cruise powers all enter the mission energy (battery mass) and the
motor rating (motor mass), so no condition is left wherever the optimiser
stopped.

Assumptions (round numbers for a five-seat tilting multicopter, not
manufacturer data): payload 400 kg; empty-mass fraction without battery and
motors 0.45; 6 rotors, 3 blades each, NACA 4412 (the built-in polar), hub at
0.2 R, reference station at 0.5 R; mission: 90 s hover in total at sea level,
a vertical climb of 300 m at 2.5 m/s, 100 km of cruise at 60 m/s at 500 m
(ISA) with a wing of L/D = 10 (so the rotors' cruise thrust is m g / (6 L/D));
drivetrain efficiency 0.9; battery 250 Wh/kg at pack level, 80 % usable;
motors 5 kW/kg of rated shaft power; tip Mach 0.5 in hover and climb (noise),
0.6 helical in cruise; radius 0.5 ... 1.5 m; rotor speed 500 ... 3000 rpm in
hover and climb and at least 300 rpm in cruise (the motors' lowest efficient
speed); collective pitch -11 ... 17 deg in climb, up to 69 deg in cruise.

Result (16 stations, SLSQP or Ipopt): 1271 kg gross mass (264 kg battery,
35 kg motors, 52.7 kWh).  The radius sits at its upper bound (at fixed thrust
the induced power falls with the disk area), hover and climb run at the
tip-Mach limit (1083 rpm), and the cruise rotor runs at its lowest speed,
300 rpm, with 54 deg of collective pitch: at an advance ratio near 4 a slow
rotor loses the least to profile drag.  Every thrust requirement is met
exactly and the motors are rated at the climb power (29.5 kW per rotor), which
momentum theory puts above the hover power.

Run ``python -m examples.multicopter_sizing`` from the repository root (add
``--ipopt`` for Ipopt).
"""
from __future__ import annotations

import argparse
import dataclasses
import time
import warnings

import numpy as np
import openmdao.api as om

from bild_mdo import IpoptDriver
from bild_mdo.multipoint import MultipointRotorGroup
from examples.evtol_sizing import GRAVITY, MassClosureComp

OPTIMIZERS = ("slsqp", "ipopt")
CONDITIONS = ("climb", "cruise")


@dataclasses.dataclass(frozen=True)
class MulticopterAssumptions:
    """Vehicle and mission numbers (see the module docstring); SI units."""

    payload_mass: float = 400.0
    structural_mass_fraction: float = 0.45
    num_rotors: int = 6
    num_blades: int = 3
    hover_time: float = 90.0
    climb_speed: float = 2.5
    climb_height: float = 300.0
    cruise_speed: float = 60.0
    cruise_range: float = 100.0e3
    cruise_altitude: float = 500.0
    lift_to_drag: float = 10.0
    drivetrain_efficiency: float = 0.9
    battery_specific_energy: float = 250.0 * 3600.0
    battery_usable_fraction: float = 0.8
    motor_specific_power: float = 5.0e3
    hover_tip_mach: float = 0.5
    tip_mach_limits: tuple = (0.5, 0.6)

    def weight_fractions(self):
        """Thrust per rotor over the weight: hover (design point), then climb and cruise."""
        n = self.num_rotors
        return np.array([1.0 / n, 1.0 / n, 1.0 / (n * self.lift_to_drag)])

    def times(self):
        """Time spent in hover, climb and cruise (s)."""
        return np.array([self.hover_time, self.climb_height / self.climb_speed,
                         self.cruise_range / self.cruise_speed])


#: Design variables: (lower, upper, units, ref); per-condition entries are (climb, cruise).
DESIGN_BOUNDS = {
    "radius": (0.5, 1.5, "m", 1.0),
    "design_rpm": (500.0, 3000.0, "rpm", 1000.0),
    "ref_chord": (0.03, 0.4, "m", 0.1),
    "rpm": (np.array([500.0, 300.0]), np.array([3000.0, 3000.0]), "rpm", 1000.0),
    "collective_pitch": (np.array([-0.2, -0.2]), np.array([0.3, 1.2]), "rad", 0.1),
    "motor_rated_power": (1.0e3, 3.0e5, "W", 1.0e5),
}
#: Initial design and mass guess (kg).
INITIAL_DESIGN = {"radius": 1.0, "design_rpm": 1200.0, "ref_chord": 0.15, "rpm": np.array([1300.0, 900.0]),
                  "collective_pitch": np.array([0.03, 0.4]), "motor_rated_power": 1.2e5, "gross_mass": 1500.0}


class MarginsComp(om.ExplicitComponent):
    """Thrust margins ``T / (f m g) - 1`` and power margins ``P / P_rated - 1`` of the design point and conditions.

    Options
    -------
    weight_fractions : ndarray
        ``f`` of the design point then of each condition (thrust per rotor over the weight).

    Inputs
    ------
    gross_mass (kg), motor_rated_power (W), design_thrust[1] (N), design_power[1] (W), thrust[K] (N), power[K] (W)

    Outputs
    -------
    design_thrust_margin[1], thrust_margin[K], design_power_margin[1], power_margin[K] (-)
    """

    def initialize(self):
        self.options.declare("weight_fractions", types=np.ndarray, desc="thrust per rotor over the weight")

    def setup(self):
        k = self.options["weight_fractions"].size - 1
        self.add_input("gross_mass", val=1000.0, units="kg", desc="gross mass")
        self.add_input("motor_rated_power", val=1.0e5, units="W", desc="rated shaft power of one motor")
        for prefix, size in (("design_", 1), ("", k)):
            self.add_input(f"{prefix}thrust", val=np.ones(size), units="N", desc="thrust of one rotor")
            self.add_input(f"{prefix}power", val=np.ones(size), units="W", desc="shaft power of one rotor")
            self.add_output(f"{prefix}thrust_margin", val=np.zeros(size), desc="T / T_required - 1")
            self.add_output(f"{prefix}power_margin", val=np.zeros(size), desc="P / P_rated - 1")
            ar = np.arange(size)
            self.declare_partials(f"{prefix}thrust_margin", f"{prefix}thrust", rows=ar, cols=ar)
            self.declare_partials(f"{prefix}thrust_margin", "gross_mass")
            self.declare_partials(f"{prefix}power_margin", f"{prefix}power", rows=ar, cols=ar)
            self.declare_partials(f"{prefix}power_margin", "motor_rated_power")

    def _split(self, inputs):
        f = self.options["weight_fractions"]
        weight = inputs["gross_mass"][0] * GRAVITY
        return (("design_", weight * f[:1]), ("", weight * f[1:])), inputs["motor_rated_power"][0]

    def compute(self, inputs, outputs):
        required, rated = self._split(inputs)
        for prefix, thrust_required in required:
            outputs[f"{prefix}thrust_margin"] = inputs[f"{prefix}thrust"] / thrust_required - 1.0
            outputs[f"{prefix}power_margin"] = inputs[f"{prefix}power"] / rated - 1.0

    def compute_partials(self, inputs, partials):
        required, rated = self._split(inputs)
        m = inputs["gross_mass"][0]
        for prefix, thrust_required in required:
            partials[f"{prefix}thrust_margin", f"{prefix}thrust"] = 1.0 / thrust_required
            # T_required is proportional to m.
            ratio = inputs[f"{prefix}thrust"] / thrust_required
            partials[f"{prefix}thrust_margin", "gross_mass"] = (-ratio / m)[:, None]
            partials[f"{prefix}power_margin", f"{prefix}power"] = 1.0 / rated
            partials[f"{prefix}power_margin", "motor_rated_power"] = (-inputs[f"{prefix}power"] / rated**2)[:, None]


class EnergyAndMassComp(om.ExplicitComponent):
    """Mission energy, battery mass and motor mass.

    ``E = n / eta_d (t_0 P_design + sum_k t_k P_k)``, ``m_battery = E / (e_b u)``,
    ``m_motors = n P_rated / p_m``.

    Options
    -------
    assumptions : MulticopterAssumptions

    Inputs
    ------
    design_power[1] (W), power[K] (W), motor_rated_power (W)

    Outputs
    -------
    mission_energy (J), battery_mass (kg), motor_mass (kg)
    """

    def initialize(self):
        self.options.declare("assumptions", types=MulticopterAssumptions, desc="vehicle and mission numbers")

    def setup(self):
        a = self.options["assumptions"]
        k = a.times().size - 1
        self.add_input("design_power", val=np.ones(1), units="W", desc="hover shaft power of one rotor")
        self.add_input("power", val=np.ones(k), units="W", desc="shaft power of one rotor per condition")
        self.add_input("motor_rated_power", val=1.0e5, units="W", desc="rated shaft power of one motor")
        self.add_output("mission_energy", val=1.0e8, units="J", desc="battery energy used by the mission")
        self.add_output("battery_mass", val=100.0, units="kg", desc="battery pack mass")
        self.add_output("motor_mass", val=30.0, units="kg", desc="mass of all motors")
        t = a.times() * a.num_rotors / a.drivetrain_efficiency
        self.declare_partials("mission_energy", "design_power", val=t[:1][None, :])
        self.declare_partials("mission_energy", "power", val=t[1:][None, :])
        battery = 1.0 / (a.battery_specific_energy * a.battery_usable_fraction)
        self.declare_partials("battery_mass", "design_power", val=battery * t[:1][None, :])
        self.declare_partials("battery_mass", "power", val=battery * t[1:][None, :])
        self.declare_partials("motor_mass", "motor_rated_power", val=a.num_rotors / a.motor_specific_power)

    def compute(self, inputs, outputs):
        a = self.options["assumptions"]
        t = a.times() * a.num_rotors / a.drivetrain_efficiency
        energy = t[0] * inputs["design_power"] + np.dot(t[1:], inputs["power"])
        outputs["mission_energy"] = energy
        outputs["battery_mass"] = energy / (a.battery_specific_energy * a.battery_usable_fraction)
        outputs["motor_mass"] = a.num_rotors * inputs["motor_rated_power"] / a.motor_specific_power


def add_vehicle(model, a):
    """Add the vehicle inputs, mission energy, powertrain masses, mass closure and margins to ``model``.

    They read the promoted rotor outputs ``design_thrust``, ``design_power`` (hover), ``thrust[K]``,
    ``power[K]`` (climb, cruise) and the design variable ``motor_rated_power``.
    """
    vehicle = model.add_subsystem("vehicle", om.IndepVarComp(), promotes_outputs=["*"])
    vehicle.add_output("payload_mass", val=a.payload_mass, units="kg", desc="payload mass")
    vehicle.add_output("structural_mass_fraction", val=a.structural_mass_fraction,
                       desc="mass of all but payload, battery and motors over the gross mass")
    model.add_subsystem("energy", EnergyAndMassComp(assumptions=a),
                        promotes_inputs=["design_power", "power", "motor_rated_power"],
                        promotes_outputs=["mission_energy", "battery_mass", "motor_mass"])
    closure = model.add_subsystem("closure", om.Group(), promotes=["*"])
    closure.add_subsystem("mass", MassClosureComp(),
                          promotes_inputs=["payload_mass", "structural_mass_fraction", "battery_mass", "motor_mass"],
                          promotes_outputs=["gross_mass"])
    # The residual is linear in m (the rotor powers do not depend on it): Newton converges in one step.
    closure.nonlinear_solver = om.NewtonSolver(solve_subsystems=False, maxiter=20, atol=1e-10, rtol=1e-12,
                                               iprint=-1, err_on_non_converge=True)
    closure.linear_solver = om.DirectSolver()
    model.add_subsystem("margins", MarginsComp(weight_fractions=a.weight_fractions()), promotes=["*"])


def add_design_variables(model, bounds, initial):
    """One IndepVarComp output and one design variable per entry of ``bounds`` (initial values from ``initial``)."""
    design = model.add_subsystem("design", om.IndepVarComp(), promotes_outputs=["*"])
    for name, (lower, upper, units, ref) in bounds.items():
        design.add_output(name, val=initial[name], units=units, desc=f"design variable {name}")
        model.add_design_var(name, lower=lower, upper=upper, units=units, ref=ref)


def add_requirements(model):
    """Objective (gross mass) and the thrust and power margins of the module docstring."""
    model.add_objective("gross_mass", ref=1000.0)
    for name in ("design_thrust_margin", "thrust_margin"):
        model.add_constraint(name, lower=0.0, ref=0.1)
    for name in ("design_power_margin", "power_margin"):
        model.add_constraint(name, upper=0.0, ref=0.1)


def finish_problem(prob, optimizer="slsqp", tol=1e-8, maxiter=300, gross_mass=INITIAL_DESIGN["gross_mass"]):
    """Attach the driver, set up with complex step allocated and set the mass guess (kg)."""
    if optimizer not in OPTIMIZERS:
        raise ValueError(f"optimizer must be one of {OPTIMIZERS}, got {optimizer!r}")
    if optimizer == "slsqp":
        prob.driver = om.ScipyOptimizeDriver(optimizer="SLSQP", tol=tol, maxiter=maxiter, disp=False)
    else:
        prob.driver = IpoptDriver(tol=tol, maxiter=maxiter, print_level=0, disp=False)
    prob.setup(force_alloc_complex=True)
    with warnings.catch_warnings():
        # The closure group is meant to be one unit for the optimiser's relevance graph.
        warnings.filterwarnings("ignore", message=".*have a nonlinear solver that computes gradients")
        prob.final_setup()
    prob.set_val("gross_mass", gross_mass, units="kg")
    return prob


def build_problem(assumptions=None, num_radial=16, optimizer="slsqp", tol=1e-8, maxiter=300):
    """Set up the sizing optimisation with the BILD blade (complex step allocated for derivative checks).

    Parameters
    ----------
    assumptions : MulticopterAssumptions, optional
    num_radial : int
        Radial stations of the blade.
    optimizer : {'slsqp', 'ipopt'}
    tol, maxiter : float, int
        Optimiser tolerance and iteration limit.

    Returns
    -------
    om.Problem
    """
    a = MulticopterAssumptions() if assumptions is None else assumptions
    prob = om.Problem(reports=False)
    model = prob.model
    add_design_variables(model, DESIGN_BOUNDS, INITIAL_DESIGN)
    conditions = model.add_subsystem("conditions", om.IndepVarComp(), promotes_outputs=["*"])
    conditions.add_output("v_axial", val=np.array([a.climb_speed, a.cruise_speed]), units="m/s",
                          desc="axial speed in climb and cruise")
    conditions.add_output("altitude", val=np.array([0.0, a.cruise_altitude]), units="m",
                          desc="altitude of climb (start) and cruise, ISA")
    model.add_subsystem("rotor", MultipointRotorGroup(num_nodes=len(CONDITIONS), num_radial=num_radial,
                                                      num_blades=a.num_blades),
                        promotes_inputs=["radius", "design_rpm", "ref_chord", "rpm", "collective_pitch", "v_axial",
                                         "altitude"],
                        promotes_outputs=["design_thrust", "design_power", "design_figure_of_merit",
                                          "design_tip_mach", "thrust", "power", "efficiency", "figure_of_merit",
                                          "tip_mach", "chord", "twist"])
    add_vehicle(model, a)
    add_requirements(model)
    model.add_constraint("design_tip_mach", upper=a.hover_tip_mach, ref=0.1)
    model.add_constraint("tip_mach", upper=np.array(a.tip_mach_limits), ref=0.1)
    return finish_problem(prob, optimizer, tol, maxiter)


def run_driver(prob, optimizer):
    """Run the driver; ``(success, message, model evaluations, wall time s)``."""
    start = time.perf_counter()
    run_success = bool(prob.run_driver().success)
    wall_time = time.perf_counter() - start
    driver = prob.driver
    if optimizer == "slsqp":
        res = driver._scipy_optimize_result
        success, message = bool(res.success) and run_success, str(res.message)
    else:
        success = run_success and not driver.fail
        message = f"{driver.ipopt_status_name}: {driver.ipopt_message}"
    return success, message, int(driver.iter_count), wall_time


@dataclasses.dataclass
class MulticopterResult:
    """Outcome of :func:`main`: the problem at the optimum, the optimiser's verdict, counts and the optimum."""

    problem: om.Problem
    success: bool
    message: str
    model_evaluations: int
    wall_time: float
    optimum: dict


#: Quantities reported by :func:`main`, with their units.
SUMMARY_UNITS = {
    "gross_mass": "kg", "battery_mass": "kg", "motor_mass": "kg", "mission_energy": "kW*h",
    "radius": "m", "design_rpm": "rpm", "ref_chord": "m", "motor_rated_power": "kW",
    "design_thrust": "N", "design_power": "kW", "design_figure_of_merit": None, "design_tip_mach": None,
    "rpm": "rpm", "collective_pitch": "deg", "thrust": "N", "power": "kW", "efficiency": None,
    "figure_of_merit": None, "tip_mach": None,
}


def main(num_radial=16, optimizer="slsqp", assumptions=None, tol=1e-8, verbose=True):
    """Size the vehicle and return the optimum (:class:`MulticopterResult`)."""
    prob = build_problem(assumptions, num_radial=num_radial, optimizer=optimizer, tol=tol)
    success, message, evaluations, wall_time = run_driver(prob, optimizer)
    optimum = {name: prob.get_val(name, units=units).copy() for name, units in SUMMARY_UNITS.items()}
    result = MulticopterResult(problem=prob, success=success, message=message, model_evaluations=evaluations,
                               wall_time=wall_time, optimum=optimum)
    if verbose:
        print_summary(result, optimizer)
    return result


def print_summary(result, optimizer="slsqp"):
    """Print the optimum of :func:`main`."""
    o = {k: np.atleast_1d(v) for k, v in result.optimum.items()}
    print(f"Tilting multicopter sizing ({optimizer}, minimise gross mass): {result.message}")
    print(f"  {result.model_evaluations} model evaluations, {result.wall_time:.2f} s")
    print(f"  gross mass {o['gross_mass'][0]:.1f} kg (battery {o['battery_mass'][0]:.1f} kg, motors "
          f"{o['motor_mass'][0]:.1f} kg), mission energy {o['mission_energy'][0]:.2f} kWh")
    print(f"  blade: R = {o['radius'][0]:.3f} m, c_ref = {o['ref_chord'][0]:.4f} m; motor rating "
          f"{o['motor_rated_power'][0]:.1f} kW per rotor")
    # Hover is judged by its figure of merit, climb and cruise by V T / P (useful work over shaft power).
    print(f"  {'':8s}{'rpm':>8s}{'pitch deg':>10s}{'T N':>9s}{'P kW':>8s}{'FM/eta':>8s}{'M_tip':>7s}")
    print(f"  {'hover':8s}{o['design_rpm'][0]:8.0f}{0.0:10.2f}{o['design_thrust'][0]:9.1f}"
          f"{o['design_power'][0]:8.2f}{o['design_figure_of_merit'][0]:8.3f}{o['design_tip_mach'][0]:7.3f}")
    for k, label in enumerate(CONDITIONS):
        print(f"  {label:8s}{o['rpm'][k]:8.0f}{o['collective_pitch'][k]:10.2f}{o['thrust'][k]:9.1f}"
              f"{o['power'][k]:8.2f}{o['efficiency'][k]:8.3f}{o['tip_mach'][k]:7.3f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ipopt", action="store_true", help="use Ipopt instead of SLSQP")
    parser.add_argument("--num-radial", type=int, default=16, help="radial stations of the blade")
    args = parser.parse_args()
    main(num_radial=args.num_radial, optimizer="ipopt" if args.ipopt else "slsqp")
