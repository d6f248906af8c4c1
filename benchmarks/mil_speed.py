"""Speed of minimum-induced-loss design (Adkins & Liebeck 1994): one design per run, batches, totals.

Run:  .venv/bin/python benchmarks/mil_speed.py

Prints, for :class:`~bild_mdo.mil.MILGroup` (thrust-specified, 3 blades,
``num_radial = 30``) on the forward-flight (J > 0) part of the paper's Sec. 5.1
sweep (J 0.3 ... 3, R 0.5 ... 1.5 m, altitude 0 ... 3000 m, 800 rpm, hub 0.2 R),
with a fixed airfoil point (alpha* = 6 deg, C_l* = 0.9, C_d* = 0.012) and a
thrust target at T_c = 2T/(rho V^2 pi R^2) = 0.15 (A&L's design relations reach
T_c of about 0.23 at most at J = 3):

* the time per design of a set-up single-design problem (``run_model`` repeated,
  setup excluded; median and best);
* the time per design of ONE ``run_model`` of batches of 100 and 1,000 designs, and
  the ratio to the single-design time;
* the time of ``compute_totals`` of one design (chord, twist, thrust, power with
  respect to every input);
* the wall time of :func:`bild_mdo.mil.design_mil` for one design once its model
  is cached.

Nothing is asserted; on a shared machine, repeat the run.
"""
import statistics
import time

import numpy as np
import openmdao.api as om

from bild_mdo.atmosphere import isa
from bild_mdo.mil import MILGroup, design_mil

NUM_RADIAL = 30
INPUTS = ["v_axial", "rpm", "radius", "hub_radius", "altitude", "design_thrust", "alpha_star", "cl_star", "cd_star"]
AIRFOIL = {"alpha_star": np.radians(6.0), "cl_star": 0.9, "cd_star": 0.012}


def forward_flight_sweep(levels):
    """levels**3 forward-flight designs of the paper's sweep (J > 0), thrust at T_c = 0.15."""
    j, radius, altitude = np.meshgrid(np.linspace(0.3, 3.0, levels), np.linspace(0.5, 1.5, levels),
                                      np.linspace(0.0, 3000.0, levels), indexing="ij")
    j, radius, altitude = j.ravel(), radius.ravel(), altitude.ravel()
    rpm = np.full(j.size, 800.0)
    v_axial = j * rpm / 60.0 * 2.0 * radius
    thrust = 0.15 * 0.5 * isa(altitude).rho * v_axial ** 2 * np.pi * radius ** 2
    values = {"v_axial": v_axial, "rpm": rpm, "radius": radius, "hub_radius": 0.2 * radius, "altitude": altitude,
              "design_thrust": thrust}
    values.update({name: np.full(j.size, value) for name, value in AIRFOIL.items()})
    return values


def make_problem(values):
    nn = values["rpm"].size
    prob = om.Problem(MILGroup(num_nodes=nn, num_radial=NUM_RADIAL, num_blades=3), reports=False)
    prob.setup(check=False, mode="auto")
    for name, value in values.items():
        prob.set_val(name, value)
    prob.final_setup()
    return prob


def time_runs(prob, repeats):
    prob.run_model()  # warm-up
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        prob.run_model()
        times.append(time.perf_counter() - start)
    return statistics.median(times), min(times)


def main():
    sweep = forward_flight_sweep(10)
    single = {name: value[[555]] for name, value in sweep.items()}
    median, best = time_runs(make_problem(single), 50)
    print(f"MILGroup, num_radial = {NUM_RADIAL}, 3 blades, thrust-specified")
    print(f"single design:          median {median * 1e3:8.3f} ms   best {best * 1e3:8.3f} ms per design")
    for size in (100, 1000):
        batch = {name: value[:size] for name, value in sweep.items()}
        median_b, _ = time_runs(make_problem(batch), 5)
        print(f"batch of {size:5d} designs: {median_b / size * 1e3:8.4f} ms per design "
              f"({median / (median_b / size):6.1f} x faster than one at a time)")
    prob = make_problem(single)
    prob.run_model()
    start = time.perf_counter()
    prob.compute_totals(of=["chord", "twist", "thrust", "power"], wrt=INPUTS)
    print(f"compute_totals, one design ({len(INPUTS)} inputs): {(time.perf_counter() - start) * 1e3:8.3f} ms")
    kwargs = {name: float(value[0]) for name, value in single.items() if name != "design_thrust"}
    kwargs["hub_radius"] = kwargs.pop("hub_radius")
    design_mil(float(single["design_thrust"][0]), num_blades=3, num_radial=NUM_RADIAL, **kwargs)
    start = time.perf_counter()
    design = design_mil(float(single["design_thrust"][0]), num_blades=3, num_radial=NUM_RADIAL, **kwargs)
    print(f"design_mil, one design (model cached): {(time.perf_counter() - start) * 1e3:8.3f} ms "
          f"(zeta = {design.zeta[0]:.4f}, eta = {design.efficiency[0]:.4f})")


if __name__ == "__main__":
    main()
