"""A wind-turbine rotor for a rated power, a thrust limit and a tip-speed limit, designed for annual energy.

The rotor of a 5-MW class turbine (R = 63 m, three blades, hub 0.05 R) is
designed by the turbine BILD loading (:class:`~bild_mdo.bild.turbine_group.TurbineBILDGroup`,
``design_for='thrust'``: the most power for a given thrust at the design
wind speed).  Its power curve is the same blade analysed by the turbine BEM
from cut-in to cut-out (:class:`~bild_mdo.energy.PowerCurveGroup`): below
rated at the design tip-speed ratio until the tip speed reaches its limit
(80 m/s), then at that rotor speed (region 2.5, WISDEM's ``control_maxTS``),
above rated the collective pitch trimmed to rated power.  The optimiser
picks the design tip-speed ratio and the design thrust for the most AEP,
with the thrust of the whole curve (it peaks at rated, not at the design
wind speed) under the limit, with exact total derivatives through the blade
design and both Newton solves of the curve::

    rotor   TurbineBILDGroup(design_for='thrust'): wind 10 m/s, thrust_target -> chord, twist, C_P, C_T
    curve   PowerCurveGroup(tip_speed_limit=True): the blade, P_r = 5 MW, max tip speed 80 m/s,
            Weibull c = 8.5 m/s, k = 2, cut-in 3, cut-out 25 m/s -> annual_energy, thrust, pitch
    aep     AnnualEnergyComp: the design's C_P held over all of region 2 (no tip-speed limit: the
            constant-C_P estimate, printed beside)

    maximise   curve.annual_energy   w.r.t. rpm (design tip-speed ratio 4 ... 8: the design point
                                     itself within the tip-speed limit) and thrust_target
    subject to curve.thrust <= thrust limit (450 kN) at every wind speed of the curve

Assumptions (round numbers, not a manufacturer's): the built-in NACA 4412
polar frozen at Re = 2e6, the top of its data, along the whole span (a real
blade has thicker sections inboard, and runs at Re of order 1e7); sea-level
ISA air.  The AEP models' own assumptions are in
:mod:`bild_mdo.energy.annual_energy` and :mod:`bild_mdo.energy.power_curve_group`.

Run:  .venv/bin/python examples/turbine_aep.py
"""
import argparse
import time

import numpy as np
import openmdao.api as om

from bild_mdo.bild.turbine_group import TurbineBILDGroup
from bild_mdo.energy import AnnualEnergyComp, PowerCurveGroup
from bild_mdo.energy.wind_speeds import region_sizes
from bild_mdo.io.airfoil import resolve_airfoil

RADIUS = 63.0
WIND_SPEED = 10.0
THRUST_LIMIT = 4.5e5
RATED_POWER = 5.0e6
#: The tip-speed limit (m/s): the NREL 5-MW rotor's 12.1 rpm at 63 m (NREL/TP-500-38060, Table 1-1).
MAX_TIP_SPEED = 80.0
#: Design tip-speed ratios: from 4 to the one whose tip speed at the design wind speed is the limit.
TSR_BOUNDS = (4.0, MAX_TIP_SPEED / WIND_SPEED)
#: Design thrusts at the design wind speed (N): the optimiser's bounds and the start.
THRUST_BOUNDS = (2.0e5, THRUST_LIMIT)
THRUST_START = 3.0e5
WEIBULL_SCALE, WEIBULL_SHAPE = 8.5, 2.0
#: The built-in NACA 4412 frozen at the top of its table (Re 2e6): the sections of a 63-m blade run at Re of
#: order 1e7, beyond the data, where the table's extrapolation would make the drag vanish.
AIRFOIL = "naca4412@re=2e6"


def rpm_of(tip_speed_ratio):
    return tip_speed_ratio * WIND_SPEED / RADIUS * 30.0 / np.pi


def build(num_radial=30, num_wind_speeds=13):
    prob = om.Problem(reports=False)
    model = prob.model
    polar = resolve_airfoil(AIRFOIL)
    model.add_subsystem("rotor", TurbineBILDGroup(num_radial=num_radial, design_for="thrust", polar=polar),
                        promotes=["*"])
    model.add_subsystem("aep", AnnualEnergyComp(), promotes_inputs=["power_coefficient", "radius", "rho"],
                        promotes_outputs=["annual_energy", "capacity_factor", "rated_wind_speed"])
    # Inboard stations of the feathered blade run outside momentum theory's valid states: not a concern here.
    model.add_subsystem("curve", PowerCurveGroup(num_radial=num_radial, num_wind_speeds=num_wind_speeds, polar=polar,
                                                 on_invalid="ignore", tip_speed_limit=True),
                        promotes_inputs=["chord", "twist", "radius", "hub_radius", "tip_speed_ratio"])
    model.set_input_defaults("radius", RADIUS, units="m")
    model.add_design_var("rpm", lower=rpm_of(TSR_BOUNDS[0]), upper=rpm_of(TSR_BOUNDS[1]), units="rpm")
    model.add_design_var("thrust_target", lower=THRUST_BOUNDS[0], upper=THRUST_BOUNDS[1], ref=1e5, units="N")
    model.add_constraint("curve.thrust", upper=THRUST_LIMIT, ref=1e5, units="N")
    model.add_objective("curve.annual_energy", ref=-1e13, units="J")
    prob.driver = om.ScipyOptimizeDriver(optimizer="SLSQP", tol=1e-10, maxiter=60, disp=False)
    prob.setup(force_alloc_complex=True)
    prob.set_val("v_axial", WIND_SPEED, units="m/s")
    prob.set_val("radius", RADIUS, units="m")
    prob.set_val("thrust_target", THRUST_START, units="N")
    prob.set_val("section_chord", 3.0, units="m")
    prob.set_val("rpm", rpm_of(7.0), units="rpm")
    for group in ("aep", "curve"):
        prob.set_val(f"{group}.rated_power", RATED_POWER, units="W")
        prob.set_val(f"{group}.weibull_scale", WEIBULL_SCALE, units="m/s")
        prob.set_val(f"{group}.weibull_shape", WEIBULL_SHAPE)
    prob.set_val("curve.max_tip_speed", MAX_TIP_SPEED, units="m/s")
    return prob


def curve_summary(prob):
    """The pitch-trimmed BEM power curve of the current design beyond :func:`row`: the numbers :func:`main`
    prints under the table."""
    thrust = prob.get_val("curve.thrust", units="kN")[0]
    n2, _ = region_sizes(thrust.size, tip_speed_limit=True)
    return {"thrust at rated (kN)": float(thrust[n2 - 1]), "thrust at cut-out (kN)": float(thrust[-1]),
            "pitch at cut-out (deg)": float(prob.get_val("curve.collective_pitch", units="deg")[0, -1]),
            "rotor speed at rated (rpm)": float(prob.get_val("curve.rpm", units="rpm")[0, n2 - 1])}


def row(prob):
    """One column of the printed table: the design and its power curve."""
    return {"tip-speed ratio": float(prob.get_val("tip_speed_ratio")[0]),
            "design thrust (kN)": float(prob.get_val("thrust", units="kN")[0]),
            "C_P": float(prob.get_val("power_coefficient")[0]), "C_T": float(prob.get_val("thrust_coefficient")[0]),
            f"power at {WIND_SPEED:g} m/s (MW)": float(prob.get_val("power", units="MW")[0]),
            "tip-speed limit from (m/s)": float(prob.get_val("curve.tip_speed_limit_wind_speed")[0]),
            "rated wind speed (m/s)": float(prob.get_val("curve.rated_wind_speed")[0]),
            "peak thrust (kN)": float(np.max(prob.get_val("curve.thrust", units="kN")[0])),
            "AEP (GWh)": float(prob.get_val("curve.annual_energy", units="GW*h")[0]),
            "capacity factor": float(prob.get_val("curve.capacity_factor")[0]),
            "AEP, constant C_P (GWh)": float(prob.get_val("annual_energy", units="GW*h")[0])}


def main(num_radial=30, verbose=True, num_wind_speeds=13):
    """Run the optimisation; returns ``(problem, start_row, optimum_row, success, wall_seconds)``.

    The optimum's row also holds :func:`curve_summary` (the pitch-trimmed BEM power curve).
    """
    prob = build(num_radial, num_wind_speeds)
    prob.run_model()
    start = row(prob)
    wall = time.perf_counter()
    result = prob.run_driver()
    wall = time.perf_counter() - wall
    prob.run_model()
    best = row(prob)
    summary = curve_summary(prob)
    if verbose:
        print(f"Turbine rotor R = {RADIUS:g} m, rated {RATED_POWER / 1e6:g} MW, thrust limit "
              f"{THRUST_LIMIT / 1e3:g} kN, tip-speed limit {MAX_TIP_SPEED:g} m/s, designed at {WIND_SPEED:g} m/s; "
              f"Weibull c {WEIBULL_SCALE:g} m/s, k {WEIBULL_SHAPE:g}")
        print(f"{'':<28}{'start':>12}{'optimum':>12}")
        for name in start:
            print(f"{name:<28}{start[name]:12.4f}{best[name]:12.4f}")
        print(f"optimiser: {'converged' if result.success else 'NOT converged'} in {wall:.2f} s "
              f"(exact totals through the BILD design and the power curve)")
        print("AEP: the BEM power curve with the tip-speed limit; 'constant C_P' holds the design's C_P over all "
              "of region 2 (AnnualEnergyComp, no limit).")
        print("Pitch-trimmed BEM power curve of the optimum (pitch to feather above rated):")
        for name, value in summary.items():
            print(f"  {name:<30}{value:12.4f}")
    best.update(summary)
    return prob, start, best, bool(result.success), wall


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--num-radial", type=int, default=30)
    main(parser.parse_args().num_radial)
