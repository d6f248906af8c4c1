"""BILD with the paper's reference section point against the local one, and both against the BEM optimum.

Run:  .venv/bin/python benchmarks/section_point.py [--cases N] [--num-radial NR]

For a handful of forward-flight and hover cases (B = 3, r_hub/R = 0.2,
r_ref/R = 0.5, NACA 4412 with its Reynolds-dependent polar; six of the paper's
rotor, R = 1.5 m, and two smaller, lower-Reynolds ones) it prints, in one run:

* T* = the thrust of BILD's reference design at c_ref;
* the BEM optimum for T* (``optimize_rotor``, SLSQP from the BILD geometry of
  each section point; the lower energy loss of the two starts is the optimum);
* each BILD geometry designed for T* (``design_rotor(thrust=T*)``), loaded into
  the optimisation problem (``build_optimization_problem(initial='bild')``) and
  trimmed to T* in the full BEM model by a collective-pitch offset
  (``trim_to_thrust``): its energy loss relative to the optimum's (the excess);
* the time per BILD design of each section point (one ``design_rotor`` call
  with the model cached, both measured in the same run, interleaved).

Issue 12's target on ``verify --levels 3`` for the local point: mean excess
<= 0.15 %, worst <= 1 %.  Nothing is asserted.
"""
import argparse
import time
import warnings

import numpy as np

from bild_mdo.optimization.problem import build_optimization_problem
from bild_mdo.optimization.run import optimize_rotor, trim_to_thrust
from bild_mdo.results.design import design_rotor

#: (advance ratio J, rpm, c_ref [m], altitude [m], R [m]); the last two run at Re_ref ~ 1e5-2e5, where the
#: NACA 4412's minima of cd/cl form two branches (c_ref in the band between them: chord(r_ref) != c_ref).
CASES = [
    (0.0, 800.0, 0.15, 0.0, 1.5),
    (0.0, 600.0, 0.10, 1000.0, 1.5),
    (0.3, 800.0, 0.15, 0.0, 1.5),
    (0.6, 800.0, 0.12, 0.0, 1.5),
    (1.0, 700.0, 0.10, 0.0, 1.5),
    (1.5, 800.0, 0.20, 2000.0, 1.5),
    (0.0, 800.0, 0.15, 3000.0, 0.5),
    (0.8, 800.0, 0.08, 0.0, 1.0),
]
HUB, REF = 0.2, 0.5


def _trimmed_energy(case, thrust, chord, twist, num_radial):
    v_axial, rpm, altitude, radius = case
    prob = build_optimization_problem(v_axial, rpm, radius, HUB * radius, thrust, altitude, initial="bild",
                                      bild_chord=chord, bild_twist=twist, num_radial=num_radial)
    trim_to_thrust(prob)
    return float(prob.get_val("energy_loss")[0])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=len(CASES))
    parser.add_argument("--num-radial", type=int, default=30)
    args = parser.parse_args()
    warnings.filterwarnings("ignore", message=".*Reynolds numbers outside the tabulated range")
    nr = args.num_radial
    rows = []
    times = {"reference": [], "local": []}
    print(f"{'J':>5} {'rpm':>5} {'R':>4} {'c_ref':>6} {'T* [N]':>9} {'E_opt [W]':>10} {'ref excess':>11}"
          f" {'local excess':>13} {'ref chord err':>14} {'local chord err':>16}")
    for j, rpm, c_ref, altitude, radius in CASES[:args.cases]:
        v_axial = j * rpm / 60.0 * 2.0 * radius
        common = dict(v_axial=v_axial, rpm=rpm, radius=radius, hub_radius_ratio=HUB, ref_radius_ratio=REF,
                      altitude=altitude, num_radial=nr)
        thrust = design_rotor(ref_chord=c_ref, **common).thrust
        designs = {}
        for point in ("reference", "local"):  # interleaved timings of cached models
            designs[point] = design_rotor(thrust=thrust, section_point=point, **common)
            start = time.perf_counter()
            design_rotor(thrust=thrust, section_point=point, **common)
            times[point].append(time.perf_counter() - start)
        case = (v_axial, rpm, altitude, radius)
        best = None
        for point, design in designs.items():
            result = optimize_rotor(v_axial, rpm, radius, HUB * radius, thrust, altitude, initial="bild",
                                    bild_chord=design.chord, bild_twist=design.twist, num_radial=nr)
            energy = result.performance["energy_loss"]
            if result.converged and (best is None or energy < best.performance["energy_loss"]):
                best = result
        if best is None:
            print(f"{j:5.2f} {rpm:5.0f} {radius:4.1f} {c_ref:6.3f}  no converged optimum")
            continue
        e_opt = float(best.performance["energy_loss"])
        excess = {p: _trimmed_energy(case, thrust, d.chord, d.twist, nr) / e_opt - 1.0
                  for p, d in designs.items()}
        chord_err = {p: float(np.mean(np.abs(d.chord / best.chord - 1.0))) for p, d in designs.items()}
        rows.append((excess["reference"], excess["local"]))
        print(f"{j:5.2f} {rpm:5.0f} {radius:4.1f} {c_ref:6.3f} {thrust:9.2f} {e_opt:10.2f}"
              f" {100 * excess['reference']:10.3f}% {100 * excess['local']:12.3f}%"
              f" {100 * chord_err['reference']:13.2f}% {100 * chord_err['local']:15.2f}%")
    rows = np.array(rows)
    if rows.size:
        print(f"energy excess over the optimum, mean / worst: reference {100 * rows[:, 0].mean():.3f} % / "
              f"{100 * rows[:, 0].max():.3f} %;  local {100 * rows[:, 1].mean():.3f} % / "
              f"{100 * rows[:, 1].max():.3f} %")
    t_ref, t_loc = np.median(times["reference"]), np.median(times["local"])
    print(f"time per thrust-target design (median, cached model): reference {1e3 * t_ref:.1f} ms, "
          f"local {1e3 * t_loc:.1f} ms, ratio local/reference {t_loc / t_ref:.2f}")


if __name__ == "__main__":
    main()
