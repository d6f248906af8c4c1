"""The same vehicle sized twice: with BILD blades inside the model, and with the blade shape optimised in it.

A sizing model that uses BILD gets the blade from three numbers (radius,
design rpm, reference chord) in one feed-forward pass.  The alternative is to
make the blade's chord and twist at every station design variables of the
sizing optimisation and analyse the rotor with the full BEM at every
condition.  This example sizes the tilting multicopter of
:mod:`examples.multicopter_sizing` both ways and prints gross mass, mission
energy, rotor geometry and wall time side by side, answering the question a
designer asks: how much does the sizing lose by using BILD, and how much time
does it save?

Models::

    BILD     multicopter_sizing.build_problem: MultipointRotorGroup (BILD in hover, BEM in climb and cruise);
             design variables radius, design_rpm, ref_chord, rpm[2], collective_pitch[2], motor_rated_power
    free     the same vehicle; the rotor is BladeBroadcastComp + BEMAnalysisGroup at hover, climb and cruise;
             design variables radius, design_rpm, rpm[2], collective_pitch[2], motor_rated_power and the
             blade's chord[nr] and twist[nr]

Both problems start from the same rotor (the BILD blade of the initial design
of :mod:`examples.multicopter_sizing`) and have the same constraints.  The
free blade contains every BILD blade, so its optimum can only be lighter, up to
the polar difference between the two hover models (BILD evaluates the airfoil
at the reference station's Reynolds number at every station, paper
Assumption 2, the BEM at each station's own: about 1e-3 in power, measured in
tests/multipoint).

Result (16 stations, SLSQP, measured on a shared two-core machine):

==================  ==========  ==========
                    BILD blade  free blade
==================  ==========  ==========
design variables    8           39
model evaluations   26          165
gross mass          1271.1 kg   1263.6 kg
mission energy      52.73 kWh   51.93 kWh
wall time           9.3 s       36.8 s
==================  ==========  ==========

The free blade is 0.59 % lighter and needs 1.5 % less energy; BILD's sizing
is about 4 times faster (6.7 times at 8 stations, and the gap grows with the
number of stations because the free problem has 2 nr + 7 design variables).
BILD's blade is the optimal one for hover, its design condition (paper Sec. 5
finds it within 0.2 % of the optimised blade there); the free blade gives up a
little hover power (26.62 vs 26.55 kW) for cruise (13.27 vs 13.53 kW), which
weighs more because the mission spends 28 min in cruise and 3.5 min in hover
and climb.  Its chord is narrower at the root and its twist steeper.

Run ``python -m examples.bild_vs_optimisation_sizing`` from the repository root.
"""
from __future__ import annotations

import argparse
import dataclasses

import numpy as np
import openmdao.api as om

from bild_mdo import BEMAnalysisGroup, resolve_polar
from bild_mdo.bild.geometry import GeometryComp
from bild_mdo.multipoint import BladeBroadcastComp
from examples import multicopter_sizing as sizing

#: Bounds of the free blade's chord (m) and twist (rad) at every station.
CHORD_BOUNDS = (0.01, 0.5)
TWIST_BOUNDS = (-0.3, 1.4)
HUB_RADIUS_RATIO = 0.2  # as BILDGroup's default, used by multicopter_sizing


class OperatingPointsComp(om.ExplicitComponent):
    """Rotor speed and collective pitch of hover (the design point, zero pitch) followed by the K conditions.

    ``rpm_all = [design_rpm, rpm]``, ``collective_pitch_all = [0, collective_pitch]``; constant partials.

    Options
    -------
    num_conditions : int
        K.

    Inputs
    ------
    design_rpm[1] (rpm), rpm[K] (rpm), collective_pitch[K] (rad)

    Outputs
    -------
    rpm_all[K + 1] (rpm), collective_pitch_all[K + 1] (rad)
    """

    def initialize(self):
        self.options.declare("num_conditions", types=int, default=2, desc="conditions after hover")

    def setup(self):
        k = self.options["num_conditions"]
        self.add_input("design_rpm", val=np.full(1, 1000.0), units="rpm", desc="hover rotor speed")
        self.add_input("rpm", val=np.full(k, 1000.0), units="rpm", desc="rotor speed per condition")
        self.add_input("collective_pitch", val=np.zeros(k), units="rad", desc="collective pitch per condition")
        self.add_output("rpm_all", val=np.full(k + 1, 1000.0), units="rpm", desc="hover, then each condition")
        self.add_output("collective_pitch_all", val=np.zeros(k + 1), units="rad", desc="0 in hover, then each")
        self.declare_partials("rpm_all", "design_rpm", rows=[0], cols=[0], val=1.0)
        self.declare_partials("rpm_all", "rpm", rows=np.arange(1, k + 1), cols=np.arange(k), val=1.0)
        self.declare_partials("collective_pitch_all", "collective_pitch", rows=np.arange(1, k + 1),
                              cols=np.arange(k), val=1.0)

    def compute(self, inputs, outputs):
        outputs["rpm_all"] = np.concatenate([inputs["design_rpm"], inputs["rpm"]])
        outputs["collective_pitch_all"] = np.concatenate([np.zeros(1), inputs["collective_pitch"]])


def build_free_problem(start, assumptions=None, num_radial=16, optimizer="slsqp", tol=1e-8, maxiter=500):
    """The sizing problem with the blade's chord and twist as design variables (full BEM at every condition).

    Parameters
    ----------
    start : dict
        Initial values: ``chord``, ``twist`` (nr,), ``radius``, ``design_rpm``, ``rpm`` (2,),
        ``collective_pitch`` (2,), ``motor_rated_power``, ``gross_mass`` in the units of
        :data:`examples.multicopter_sizing.DESIGN_BOUNDS` (m, rad, kg).
    assumptions, num_radial, optimizer, tol, maxiter
        As in :func:`examples.multicopter_sizing.build_problem`.

    Returns
    -------
    om.Problem
    """
    a = sizing.MulticopterAssumptions() if assumptions is None else assumptions
    k = len(sizing.CONDITIONS)
    prob = om.Problem(reports=False)
    model = prob.model
    bounds = {name: sizing.DESIGN_BOUNDS[name] for name in sizing.DESIGN_BOUNDS if name != "ref_chord"}
    bounds["chord"] = (*CHORD_BOUNDS, "m", 0.1)
    bounds["twist"] = (*TWIST_BOUNDS, "rad", 0.1)
    initial = {name: start[name] for name in bounds}
    initial["chord"] = np.reshape(start["chord"], (1, num_radial))
    initial["twist"] = np.reshape(start["twist"], (1, num_radial))
    sizing.add_design_variables(model, bounds, initial)
    conditions = model.add_subsystem("conditions", om.IndepVarComp(), promotes_outputs=["*"])
    conditions.add_output("v_axial", val=np.array([0.0, a.climb_speed, a.cruise_speed]), units="m/s",
                          desc="axial speed in hover, climb and cruise")
    conditions.add_output("altitude", val=np.array([0.0, 0.0, a.cruise_altitude]), units="m",
                          desc="altitude of hover, climb and cruise, ISA")
    conditions.add_output("hub_radius_ratio", val=HUB_RADIUS_RATIO, desc="hub radius over tip radius")

    rotor = model.add_subsystem("rotor", om.Group(), promotes_inputs=[
        "radius", "hub_radius_ratio", "design_rpm", "rpm", "collective_pitch", "v_axial", "altitude",
        ("blade_chord", "chord"), ("blade_twist", "twist")])
    rotor.add_subsystem("geometry", GeometryComp(num_nodes=1), promotes_inputs=["radius", "hub_radius_ratio"],
                        promotes_outputs=["hub_radius"])
    rotor.add_subsystem("points", OperatingPointsComp(num_conditions=k),
                        promotes_inputs=["design_rpm", "rpm", "collective_pitch"])
    rotor.add_subsystem("blade", BladeBroadcastComp(num_nodes=k + 1, num_radial=num_radial),
                        promotes_inputs=["blade_chord", "blade_twist", ("blade_radius", "radius"),
                                         ("blade_hub_radius", "hub_radius")])
    rotor.add_subsystem("bem", BEMAnalysisGroup(num_nodes=k + 1, num_radial=num_radial, num_blades=a.num_blades,
                                                polar=resolve_polar("naca4412")),
                        promotes_inputs=["v_axial", "altitude"])
    for name in ("chord", "twist", "radius", "hub_radius"):
        rotor.connect(f"blade.{name}", f"bem.{name}")
    rotor.connect("points.rpm_all", "bem.rpm")
    rotor.connect("points.collective_pitch_all", "bem.collective_pitch")
    rotor.set_input_defaults("radius", val=1.0, units="m")

    sizing.add_vehicle(model, a)
    for name in ("thrust", "power"):
        model.connect(f"rotor.bem.{name}", f"design_{name}", src_indices=[0])
        model.connect(f"rotor.bem.{name}", name, src_indices=np.arange(1, k + 1))
    sizing.add_requirements(model)
    model.add_constraint("rotor.bem.tip_mach", upper=np.array([a.hover_tip_mach, *a.tip_mach_limits]), ref=0.1)
    return sizing.finish_problem(prob, optimizer, tol, maxiter, gross_mass=start["gross_mass"])


#: Quantities compared, with their units.
COMPARED = {"gross_mass": "kg", "battery_mass": "kg", "motor_mass": "kg", "mission_energy": "kW*h",
            "radius": "m", "design_rpm": "rpm", "rpm": "rpm", "collective_pitch": "deg", "motor_rated_power": "kW",
            "design_power": "kW", "power": "kW", "chord": "m", "twist": "deg"}


@dataclasses.dataclass
class SizingRun:
    """One sizing: the problem at its optimum, the optimiser's verdict, evaluations, wall time (s), values."""

    problem: om.Problem
    success: bool
    message: str
    model_evaluations: int
    wall_time: float
    values: dict


@dataclasses.dataclass
class ComparisonResult:
    """Outcome of :func:`main`: the BILD sizing, the free-blade sizing and the number of stations."""

    bild: SizingRun
    free: SizingRun
    num_radial: int


def _values(prob, names):
    return {name: np.atleast_1d(prob.get_val(name, units=COMPARED[name])).ravel().copy() for name in names}


def _start(assumptions, num_radial):
    """The initial design of multicopter_sizing with its BILD blade: the common start of both problems."""
    prob = sizing.build_problem(assumptions, num_radial=num_radial)
    prob.run_model()
    start = {name: prob.get_val(name, units=sizing.DESIGN_BOUNDS[name][2]).copy()
             for name in sizing.DESIGN_BOUNDS}
    start.update(chord=prob.get_val("chord", units="m").ravel(), twist=prob.get_val("twist", units="rad").ravel(),
                 gross_mass=sizing.INITIAL_DESIGN["gross_mass"])
    return start


def main(num_radial=16, optimizer="slsqp", assumptions=None, tol=1e-8, verbose=True):
    """Size the vehicle with BILD and with the free blade; print and return both.

    Parameters
    ----------
    num_radial : int
        Radial stations (16 at full size; 8 for a test).
    optimizer : {'slsqp', 'ipopt'}
    assumptions : examples.multicopter_sizing.MulticopterAssumptions, optional
    tol : float
        Optimiser tolerance of both problems.
    verbose : bool
        Print the comparison.

    Returns
    -------
    ComparisonResult
    """
    names = [n for n in COMPARED if n not in ("design_power", "power")]
    start = _start(assumptions, num_radial)

    prob = sizing.build_problem(assumptions, num_radial=num_radial, optimizer=optimizer, tol=tol)
    success, message, evaluations, wall = sizing.run_driver(prob, optimizer)
    values = _values(prob, names + ["design_power", "power"])
    bild = SizingRun(prob, success, message, evaluations, wall, values)

    prob = build_free_problem(start, assumptions, num_radial=num_radial, optimizer=optimizer, tol=tol)
    success, message, evaluations, wall = sizing.run_driver(prob, optimizer)
    values = _values(prob, names)
    values["design_power"] = np.atleast_1d(prob.get_val("design_power", units="kW")).copy()
    values["power"] = prob.get_val("power", units="kW").copy()
    free = SizingRun(prob, success, message, evaluations, wall, values)

    result = ComparisonResult(bild=bild, free=free, num_radial=num_radial)
    if verbose:
        print_summary(result, optimizer)
    return result


def _num_design_variables(prob):
    return sum(meta["size"] for meta in prob.model.get_design_vars().values())


def print_summary(result, optimizer="slsqp"):
    """Print both sizings side by side and the closing note (differences and speed ratio)."""
    b, f = result.bild.values, result.free.values
    print(f"Tilting multicopter sized twice ({optimizer}, {result.num_radial} stations)")
    print(f"  {'':28s}{'BILD blade':>14s}{'free blade':>14s}")
    rows = [("optimiser", result.bild.message[:12], result.free.message[:12], "s"),
            ("design variables", _num_design_variables(result.bild.problem),
             _num_design_variables(result.free.problem), "d"),
            ("model evaluations", result.bild.model_evaluations, result.free.model_evaluations, "d"),
            ("wall time s", result.bild.wall_time, result.free.wall_time, ".2f"),
            ("gross mass kg", b["gross_mass"][0], f["gross_mass"][0], ".2f"),
            ("battery mass kg", b["battery_mass"][0], f["battery_mass"][0], ".2f"),
            ("motor mass kg", b["motor_mass"][0], f["motor_mass"][0], ".2f"),
            ("mission energy kWh", b["mission_energy"][0], f["mission_energy"][0], ".3f"),
            ("radius m", b["radius"][0], f["radius"][0], ".4f"),
            ("hover rpm", b["design_rpm"][0], f["design_rpm"][0], ".0f")]
    for k, label in enumerate(sizing.CONDITIONS):
        rows += [(f"{label} rpm", b["rpm"][k], f["rpm"][k], ".0f"),
                 (f"{label} pitch deg", b["collective_pitch"][k], f["collective_pitch"][k], ".2f")]
    rows += [("hover power kW", b["design_power"][0], f["design_power"][0], ".3f")]
    rows += [(f"{label} power kW", b["power"][k], f["power"][k], ".3f") for k, label in enumerate(sizing.CONDITIONS)]
    for label, x, y, fmt in rows:
        print(f"  {label:28s}{x:>14{fmt}}{y:>14{fmt}}")
    print(f"  {'r/R':>8s}{'chord BILD':>12s}{'chord free':>12s}{'twist BILD':>12s}{'twist free':>12s}  (m, deg)")
    fractions = HUB_RADIUS_RATIO + (1.0 - HUB_RADIUS_RATIO) * (np.arange(result.num_radial) + 0.5) / result.num_radial
    for j, x in enumerate(fractions):
        print(f"  {x:8.3f}{b['chord'][j]:12.4f}{f['chord'][j]:12.4f}{b['twist'][j]:12.2f}{f['twist'][j]:12.2f}")
    print(f"  closing note: free / BILD - 1: gross mass {f['gross_mass'][0] / b['gross_mass'][0] - 1.0:+.2e}, "
          f"mission energy {f['mission_energy'][0] / b['mission_energy'][0] - 1.0:+.2e}; "
          f"wall time free / BILD = {result.free.wall_time / result.bild.wall_time:.1f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ipopt", action="store_true", help="use Ipopt instead of SLSQP")
    parser.add_argument("--num-radial", type=int, default=16, help="radial stations of the blade")
    args = parser.parse_args()
    main(num_radial=args.num_radial, optimizer="ipopt" if args.ipopt else "slsqp")
