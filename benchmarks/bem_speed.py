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
import warnings

import numpy as np
import openmdao.api as om

import bild_mdo.bem.inflow as inflow_module

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


def make_problem(num_nodes, polar, seed=0, warm_start=False):
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
    prob = om.Problem(BEMAnalysisGroup(num_nodes=num_nodes, num_radial=NUM_RADIAL, num_blades=3, polar=polar,
                                       warm_start=warm_start, on_invalid="ignore"), reports=False)
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


class _Counter:
    """Counts calls and evaluated stations of the residual and admissibility functions of the inflow solve."""

    def __init__(self):
        self.calls = self.points = 0
        self._factories = {}

    def install(self):
        for name in ("residual_function", "denominator_function"):
            factory = getattr(inflow_module, name)
            self._factories[name] = factory
            setattr(inflow_module, name, self._wrap(factory))

    def _wrap(self, factory):
        def make(**kwargs):
            function = factory(**kwargs)

            def counted(phi, idx):
                self.calls += 1
                self.points += np.size(phi)
                return function(phi, idx)
            return counted
        return make


def _timed_solve(prob, clock):
    """Wrap the inflow component's solve_nonlinear so its wall time accumulates in ``clock[0]``."""
    comp = prob.model.inflow
    solve = comp.solve_nonlinear

    def timed(inputs, outputs):
        start = time.perf_counter()
        solve(inputs, outputs)
        clock[0] += time.perf_counter() - start
    comp.solve_nonlinear = timed


def warm_start(polar, num_nodes, steps, counter):
    """Cold vs warm-started inflow solve over ``steps`` optimiser-like twist steps (interleaved)."""
    probs = {label: make_problem(num_nodes, polar, warm_start=label == "warm") for label in ("cold", "warm")}
    clocks = {label: [0.0] for label in probs}
    totals = {label: 0.0 for label in probs}
    counts = {label: [0, 0] for label in probs}
    for label, prob in probs.items():
        _timed_solve(prob, clocks[label])
        prob.run_model()                       # the first solve is cold in both
    clocks = {label: [0.0] for label in probs}
    for label, prob in probs.items():
        _timed_solve(prob, clocks[label])
    twist = probs["cold"].get_val("twist").copy()
    rng = np.random.default_rng(1)
    worst = 0.0
    for _ in range(steps):
        twist = twist + 1e-3 * rng.standard_normal(twist.shape)
        for label, prob in probs.items():
            prob.set_val("twist", twist)
            calls, points = counter.calls, counter.points
            start = time.perf_counter()
            prob.run_model()
            totals[label] += time.perf_counter() - start
            counts[label][0] += counter.calls - calls
            counts[label][1] += counter.points - points
        cold, warm = probs["cold"].get_val("phi"), probs["warm"].get_val("phi")
        worst = max(worst, float(np.max(np.abs(warm - cold) / np.maximum(np.abs(cold), 1e-3))))
    stations = num_nodes * NUM_RADIAL
    print(f"\nInflow warm start, num_nodes = {num_nodes}, num_radial = {NUM_RADIAL}: mean of {steps} twist steps "
          "(1e-3 rad rms), cold and warm interleaved")
    print(f"{'':>6} {'inflow solve [s]':>17} {'run_model [s]':>14} {'residual passes':>16} "
          f"{'evaluations/station':>20}")
    row = {}
    for label in probs:
        row[label] = (clocks[label][0] / steps, totals[label] / steps, counts[label][0] / steps,
                      counts[label][1] / steps / stations)
        print(f"{label:>6} {row[label][0]:>17.4e} {row[label][1]:>14.4e} {row[label][2]:>16.1f} {row[label][3]:>20.2f}")
    ratio = [c / w for c, w in zip(row["cold"], row["warm"])]
    print(f"{'ratio cold/warm':>6} {ratio[0]:>8.2f}x {ratio[1]:>13.2f}x {ratio[2]:>15.2f}x {ratio[3]:>19.2f}x")
    print(f"largest relative difference of phi, warm vs cold: {worst:.1e}")


def main():
    run(AnalyticPolar(reynolds_exponent=0.2), "AnalyticPolar (Viterna post-stall)")
    run(LinearPolar(), "Linear polar (BEM machinery only)")
    counter = _Counter()
    counter.install()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        for num_nodes, steps in ((1, 200), (512, 10)):
            warm_start(AnalyticPolar(reynolds_exponent=0.2), num_nodes, steps, counter)


if __name__ == "__main__":
    main()
