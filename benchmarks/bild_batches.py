"""Batches that survive bad members: 100,000 random BILD designs in batches of 10,000 with on_infeasible='skip'.

Run:  .venv/bin/python benchmarks/bild_batches.py [--designs 100000] [--batch 10000] [--sample 200] [--seed 9]

Each design is drawn uniformly from a box of valid-looking inputs (every one
passes the API's input checks): V_x 0 ... 40 m/s, 400 ... 1600 rpm,
R 0.5 ... 2 m, c_ref 0.05 ... 0.25 m, hub ratio 0.1 ... 0.35, r_ref/R between
the hub ratio and 0.9, altitude 0 ... 5000 m; NACA 4412, 3 blades, 30
stations.  Some of them have no ideal loading (the paper's Assumption 3
fails at a station, or a hover rotor cannot load any station).

Prints, per batch, the wall time and the number of infeasible designs; then
the reasons with their counts; then two identity checks of the feasible
designs against the same designs computed without the infeasible ones:

* a sample of ``--sample`` feasible designs, each recomputed alone
  (``num_nodes = 1``), and a few infeasible ones, each of which must be
  infeasible alone too, with the same reason;
* every batch rerun with only its feasible designs.

"identical" means every value (distributions and per-design quantities) is
bitwise equal; otherwise the largest relative difference is printed.
"""
import argparse
import collections
import time

import numpy as np
import openmdao.api as om

from bild_mdo.results.design import design_rotor

INPUT_NAMES = ("v_axial", "rpm", "radius", "hub_radius_ratio", "ref_radius_ratio", "ref_chord", "altitude")


def random_designs(count, rng):
    """Inputs of ``count`` random valid-looking designs (see the module docstring)."""
    hub = rng.uniform(0.1, 0.35, count)
    return {"v_axial": rng.uniform(0.0, 40.0, count), "rpm": rng.uniform(400.0, 1600.0, count),
            "radius": rng.uniform(0.5, 2.0, count), "hub_radius_ratio": hub,
            "ref_radius_ratio": hub + (0.9 - hub) * rng.uniform(0.001, 1.0, count),
            "ref_chord": rng.uniform(0.05, 0.25, count), "altitude": rng.uniform(0.0, 5000.0, count)}


def take(inputs, index):
    return {name: value[index] for name, value in inputs.items()}


def largest_difference(a, b):
    """0.0 if every value of the two results is bitwise equal (NaN == NaN), else the largest relative difference."""
    worst = 0.0
    for name, value in a.values.items():
        x, y = np.asarray(value, dtype=float), np.asarray(b.values[name], dtype=float)
        if np.array_equal(x, y, equal_nan=True):
            continue
        scale = np.maximum(np.abs(x), np.abs(y))
        with np.errstate(invalid="ignore", divide="ignore"):
            worst = max(worst, float(np.nanmax(np.where(scale > 0, np.abs(x - y) / scale, 0.0))))
    return worst


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=100_000)
    parser.add_argument("--batch", type=int, default=10_000)
    parser.add_argument("--sample", type=int, default=200)
    parser.add_argument("--seed", type=int, default=9)
    args = parser.parse_args(argv)
    rng = np.random.default_rng(args.seed)
    inputs = random_designs(args.designs, rng)

    results, reasons, infeasible_total = [], collections.Counter(), 0
    print(f"{args.designs} random designs in batches of {args.batch} (on_infeasible='skip')")
    for start in range(0, args.designs, args.batch):
        index = np.arange(start, min(start + args.batch, args.designs))
        tic = time.perf_counter()
        result = design_rotor(**take(inputs, index), on_infeasible="skip")
        seconds = time.perf_counter() - tic
        bad = int(np.sum(~result.feasible))
        infeasible_total += bad
        reasons.update(result.status[~result.feasible].tolist())
        results.append((index, result))
        nan_in_feasible = sum(int(np.sum(~np.isfinite(np.asarray(v, dtype=float)[result.feasible])))
                              for v in result.values.values())
        print(f"  batch {start // args.batch}: {len(result)} designs, {seconds:.2f} s, {bad} infeasible, "
              f"{nan_in_feasible} non-finite values in feasible designs")
    print(f"infeasible: {infeasible_total} of {args.designs} ({100.0 * infeasible_total / args.designs:.2f} %)")
    for reason, count in reasons.most_common():
        print(f"  {count:6d} x {reason}")

    # Identity 1: a sample recomputed alone.
    feasible = np.concatenate([index[r.feasible] for index, r in results])
    infeasible = np.concatenate([index[~r.feasible] for index, r in results])
    by_design = {int(i): (r, k) for index, r in results for k, i in enumerate(index)}
    sample = rng.choice(feasible, size=min(args.sample, feasible.size), replace=False)
    tic = time.perf_counter()
    worst, identical = 0.0, 0
    for i in sample:
        batch_result, k = by_design[int(i)]
        alone = design_rotor(**take(inputs, int(i)), on_infeasible="skip")
        diff = largest_difference(batch_result[k], alone)
        identical += diff == 0.0
        worst = max(worst, diff)
    print(f"sample of {sample.size} feasible designs recomputed alone ({time.perf_counter() - tic:.1f} s): "
          f"{identical} bitwise identical, largest relative difference {worst:.3g}")
    agree = 0
    checked = rng.choice(infeasible, size=min(20, infeasible.size), replace=False)
    for i in checked:
        batch_result, k = by_design[int(i)]
        alone = design_rotor(**take(inputs, int(i)), on_infeasible="skip")
        try:
            design_rotor(**take(inputs, int(i)))
            raised = False
        except om.AnalysisError:
            raised = True
        agree += (not alone.feasible) and alone.status == batch_result.status[k] and raised
    print(f"{checked.size} infeasible designs recomputed alone: {agree} infeasible with the same reason "
          "(and raising with on_infeasible='raise')")

    # Identity 2: every batch rerun with only its feasible designs.
    tic = time.perf_counter()
    worst, identical_batches = 0.0, 0
    for index, result in results:
        only = design_rotor(**take(inputs, index[result.feasible]), on_infeasible="raise")
        diff = largest_difference(result.feasible_designs(), only)
        identical_batches += diff == 0.0
        worst = max(worst, diff)
    print(f"batches rerun with only their feasible designs ({time.perf_counter() - tic:.1f} s): "
          f"{identical_batches} of {len(results)} bitwise identical, largest relative difference {worst:.3g}")


if __name__ == "__main__":
    main()
