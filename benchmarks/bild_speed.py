"""Speed of the BILD method: one design per run, 10,000 designs in one run, and total derivatives.

Run:  .venv/bin/python benchmarks/bild_speed.py

Prints, for :class:`~bild_mdo.bild.BILDGroup` with the built-in NACA 4412 polar
and ``num_radial = 30``:

* the time per design of a set-up single-design problem (``num_nodes = 1``),
  ``run_model`` repeated (setup excluded; median and best of the repeats);
* the time per design of ONE ``run_model`` of a 10,000-design problem, the
  full-factorial sweep of the paper's Sec. 5.1 (J 0 ... 3, R 0.5 ... 1.5 m,
  altitude 0 ... 3000 m, c_ref 0.08 ... 0.22 m, 800 rpm), and the ratio of the
  two per-design times;
* the time of ``compute_totals`` of one design: thrust, torque, chord and twist
  with respect to every input (v_axial, rpm, radius, hub and reference radius
  ratios, ref_chord, altitude);
* the wall time of :func:`bild_mdo.results.design.design_rotor` for one design once
  its model is cached (the Python API's overhead on top of ``run_model``).

Nothing is asserted; on a shared machine, repeat the run.
"""
import statistics
import time

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil import naca4412
from bild_mdo.bild import BILDGroup
from bild_mdo.results.design import design_rotor

NUM_RADIAL = 30
LEVELS = 10
INPUTS = ["v_axial", "rpm", "radius", "hub_radius_ratio", "ref_radius_ratio", "ref_chord", "altitude"]


def paper_sweep(levels=LEVELS):
    """Inputs of the paper's full-factorial verification sweep (levels**4 designs)."""
    j, radius, altitude, ref_chord = np.meshgrid(np.linspace(0.0, 3.0, levels), np.linspace(0.5, 1.5, levels),
                                                 np.linspace(0.0, 3000.0, levels), np.linspace(0.08, 0.22, levels),
                                                 indexing="ij")
    rpm = np.full(j.size, 800.0)
    radius = radius.ravel()
    return {"v_axial": j.ravel() * rpm / 60.0 * 2.0 * radius, "rpm": rpm, "radius": radius,
            "hub_radius_ratio": np.full(j.size, 0.2), "ref_radius_ratio": np.full(j.size, 0.5),
            "ref_chord": ref_chord.ravel(), "altitude": altitude.ravel()}


def make_problem(values, polar):
    nn = values["rpm"].size
    prob = om.Problem(BILDGroup(num_nodes=nn, num_radial=NUM_RADIAL, polar=polar), reports=False)
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
    polar = naca4412()
    sweep = paper_sweep()
    single_values = {name: value[[5555]] for name, value in sweep.items()}

    print(f"BILDGroup, NACA 4412 surrogate, num_radial = {NUM_RADIAL}; setup excluded")
    single = make_problem(single_values, polar)
    median_1, best_1 = time_runs(single, repeats=50)
    print(f"  one design per run_model (num_nodes = 1, 50 runs): median {median_1 * 1e3:8.3f} ms, "
          f"best {best_1 * 1e3:8.3f} ms per design")

    start = time.perf_counter()
    batch = make_problem(sweep, polar)
    setup_time = time.perf_counter() - start
    median_b, best_b = time_runs(batch, repeats=3)
    nn = sweep["rpm"].size
    print(f"  {nn} designs in one run_model (setup {setup_time:.2f} s, 3 runs): median {median_b:.3f} s per run, "
          f"{median_b / nn * 1e6:8.2f} us per design")
    print(f"  per-design time, one per run / batch of {nn}: {median_1 / (median_b / nn):.0f}x "
          f"(best-of: {best_1 / (best_b / nn):.0f}x)")
    chord = batch.get_val("chord")
    print(f"  batch sanity: thrust {batch.get_val('thrust').min():.4g} ... {batch.get_val('thrust').max():.4g} N, "
          f"all finite: {bool(np.all(np.isfinite(chord)))}")

    of = ["thrust", "torque", "chord", "twist"]
    for mode in ("fwd", "rev"):
        prob = om.Problem(BILDGroup(num_nodes=1, num_radial=NUM_RADIAL, polar=polar), reports=False)
        prob.setup(check=False, mode=mode)
        for name, value in single_values.items():
            prob.set_val(name, value)
        prob.run_model()
        prob.compute_totals(of=of, wrt=INPUTS)  # warm-up (builds the total-derivative machinery)
        times = []
        for _ in range(20):
            start = time.perf_counter()
            prob.compute_totals(of=of, wrt=INPUTS)
            times.append(time.perf_counter() - start)
        size = 2 + 2 * NUM_RADIAL
        print(f"  compute_totals of one design ({size} outputs x {len(INPUTS)} inputs, mode {mode}): "
              f"median {statistics.median(times) * 1e3:8.3f} ms")

    design_rotor(airfoil=polar)  # builds and caches the model
    times = []
    for _ in range(20):
        start = time.perf_counter()
        design_rotor(airfoil=polar)
        times.append(time.perf_counter() - start)
    print(f"  design_rotor() for one design, cached model: median {statistics.median(times) * 1e3:8.3f} ms")


if __name__ == "__main__":
    main()
