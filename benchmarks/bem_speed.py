"""Time per BEM analysis for batches of 1, 100 and 10,000 rotors (num_radial = 30).

Run:  .venv/bin/python benchmarks/bem_speed.py

Prints the wall time of one ``run_model`` of :class:`BEMAnalysisGroup` (setup
excluded, best of a few repeats), the time per analysed rotor, and the ratio
of the per-rotor times, twice: with the library's :class:`AnalyticPolar`
(Viterna post-stall) and with a minimal linear polar, which isolates the cost
of the BEM machinery from that of the polar.  The target is a per-rotor time
at 10,000 at least 20x below that of a single rotor.  Nothing here is
asserted; on a shared machine, repeat the run.
"""
import time

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.airfoil.polar import Polar, PolarValues
from bild_mdo.bem import BEMAnalysisGroup, station_radii

NUM_RADIAL = 30
BATCHES = (1, 100, 10_000)


class LinearPolar(Polar):
    """cl = 0.4 + 2 pi alpha, cd = 0.008 + 0.01 (cl - 0.4)^2: the cheapest sensible polar."""

    name = "linear"

    def _evaluate_real(self, alpha, reynolds):
        cl = 0.4 + 2.0 * np.pi * alpha
        z = np.zeros_like(alpha)
        return PolarValues(cl, 0.008 + 0.01 * (cl - 0.4) ** 2, z + 2.0 * np.pi, z,
                           0.04 * np.pi * (cl - 0.4), z)


def make_problem(num_nodes, polar, seed=0):
    """A set-up problem with ``num_nodes`` propellers/lift rotors in hover and cruise."""
    rng = np.random.default_rng(seed)
    radius = rng.uniform(0.5, 2.0, num_nodes)
    hub = 0.15 * radius
    rpm = rng.uniform(1000.0, 4000.0, num_nodes)
    v_axial = rng.uniform(0.0, 60.0, num_nodes)
    r = station_radii(radius, hub, NUM_RADIAL)
    x = (r - hub[:, None]) / (radius - hub)[:, None]
    chord = radius[:, None] * (0.12 - 0.07 * x)
    twist = np.arctan((v_axial / (rpm * np.pi / 30.0))[:, None] / r) + np.radians(6.0)
    prob = om.Problem(BEMAnalysisGroup(num_nodes=num_nodes, num_radial=NUM_RADIAL, num_blades=3, polar=polar),
                      reports=False)
    prob.setup(check=False)
    for name, value in dict(radius=radius, hub_radius=hub, rpm=rpm, v_axial=v_axial, chord=chord,
                            twist=twist).items():
        prob.set_val(name, value)
    prob.final_setup()
    return prob


def time_batch(num_nodes, polar, repeats):
    prob = make_problem(num_nodes, polar)
    prob.run_model()  # warm-up
    best = np.inf
    for _ in range(repeats):
        start = time.perf_counter()
        prob.run_model()
        best = min(best, time.perf_counter() - start)
    return best


def run(polar, label):
    per_case = {}
    print(f"\n{label}: BEMAnalysisGroup run_model, num_radial = {NUM_RADIAL} (best of repeats, setup excluded)")
    print(f"{'num_nodes':>10} {'time per run [s]':>18} {'time per rotor [s]':>20}")
    for nn in BATCHES:
        t = time_batch(nn, polar, repeats=20 if nn <= 100 else 3)
        per_case[nn] = t / nn
        print(f"{nn:>10d} {t:>18.4e} {t / nn:>20.4e}")
    base = per_case[BATCHES[0]]
    for nn in BATCHES[1:]:
        print(f"per-rotor time of num_nodes = 1 / num_nodes = {nn}: {base / per_case[nn]:.0f}x")


def main():
    run(AnalyticPolar(reynolds_exponent=0.2), "AnalyticPolar (Viterna post-stall)")
    run(LinearPolar(), "Linear polar (BEM machinery only)")


if __name__ == "__main__":
    main()
