"""Speed of the BILD method against the framework floor: one design, 10,000 designs, total derivatives.

Run:  .venv/bin/python benchmarks/bild_speed.py [--repeats 40]

Prints, side by side in ONE run, for :class:`~bild_mdo.bild.BILDGroup` with the
built-in NACA 4412 polar and ``num_radial = 30``:

* the framework floor: ``run_model`` of a trivial chain of 16
  ExplicitComponents (``num_nodes = 1``, a few array operations each, sparse
  analytic partials), timed interleaved with the single BILD design;
* one design per ``run_model`` (``num_nodes = 1``, setup excluded; median and
  best), and its ratio to the floor.  Every repeat runs a DIFFERENT design of
  the paper sweep (only ``run_model`` is timed), so nothing is served from a
  value cached for the same inputs;
* the time per design of ONE ``run_model`` of a 10,000-design problem, the
  full-factorial sweep of the paper's Sec. 5.1 (J 0 ... 3, R 0.5 ... 1.5 m,
  altitude 0 ... 3000 m, c_ref 0.08 ... 0.22 m, 800 rpm), and its ratio to the
  single-design time;
* ``compute_totals`` of one design (thrust, torque, chord and twist with
  respect to every input: v_axial, rpm, radius, hub and reference radius
  ratios, ref_chord, altitude) in fwd and rev mode, each timed right after the
  ``run_model`` of the same design, and the ratio of the two; once with the
  group's linear solver as shipped (``TriangularDirectSolver(assemble_jac=True)``,
  :mod:`bild_mdo.utils.linear_solvers`: the Jacobian factored in dependency
  order, one back-substitution per forward seed, the reverse seeds of one
  variable in one back-substitution by levels) and once with ``LinearRunOnce``
  set by the user (one sweep of the chain per seed);
* every time twice: wall time (``time.perf_counter``) and the CPU time of this
  process, all its threads (``time.process_time``), which other processes on a
  shared machine do not inflate; the ratios are given for both;
* the wall time of :func:`bild_mdo.results.design.design_rotor` for one design
  once its model is cached (the Python API's overhead on top of ``run_model``).

The issue-11 targets are printed next to the ratios.  Nothing is asserted; on
a shared machine, repeat the run.
"""
import argparse
import statistics
import time
import warnings

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil import naca4412
from bild_mdo.bild import BILDGroup
from bild_mdo.results.design import design_rotor

NUM_RADIAL = 30
LEVELS = 10
FLOOR_COMPONENTS = 16
INPUTS = ["v_axial", "rpm", "radius", "hub_radius_ratio", "ref_radius_ratio", "ref_chord", "altitude"]
OF = ["thrust", "torque", "chord", "twist"]


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


class _FloorComp(om.ExplicitComponent):
    """``y = 2 x + sin(x) / 3``: a few array operations with exact sparse partials."""

    def initialize(self):
        self.options.declare("size", types=int)

    def setup(self):
        n = self.options["size"]
        self.add_input("x", val=np.ones(n))
        self.add_output("y", val=np.ones(n))
        self.declare_partials("y", "x", rows=np.arange(n), cols=np.arange(n))

    def compute(self, inputs, outputs):
        x = inputs["x"]
        outputs["y"] = 2.0 * x + np.sin(x) / 3.0

    def compute_partials(self, inputs, partials):
        partials["y", "x"] = 2.0 + np.cos(inputs["x"]) / 3.0


def floor_problem(size=NUM_RADIAL):
    """A chain of 16 trivial components (``num_nodes = 1``): the framework's own cost per run."""
    model = om.Group()
    model.add_subsystem("c0", _FloorComp(size=size), promotes_inputs=["x"])
    for k in range(1, FLOOR_COMPONENTS):
        model.add_subsystem(f"c{k}", _FloorComp(size=size))
        model.connect(f"c{k - 1}.y", f"c{k}.x")
    prob = om.Problem(model, reports=False)
    prob.setup(check=False)
    prob.set_val("x", np.linspace(0.1, 0.2, size))
    prob.final_setup()
    return prob


def make_problem(values, polar, mode="auto", run_once=False):
    nn = values["rpm"].size
    group = BILDGroup(num_nodes=nn, num_radial=NUM_RADIAL, polar=polar)
    if run_once:
        group.linear_solver = om.LinearRunOnce()
    prob = om.Problem(group, reports=False)
    prob.setup(check=False, mode=mode)
    set_design(prob, values)
    prob.final_setup()
    return prob


def set_design(prob, values):
    for name, value in values.items():
        prob.set_val(name, value)


def timed(function, clock=time.perf_counter):
    start = clock()
    function()
    return clock() - start


def cpu_timed(function):
    """CPU time of this process, all its threads (``time.process_time``): not inflated by other processes."""
    return timed(function, time.process_time)


def single_designs(sweep, count):
    """``count`` different single designs of the sweep (feasible, spread over it; 5555 first)."""
    picks = np.unique(np.concatenate([[5555], np.linspace(0, sweep["rpm"].size - 1, count).astype(int)]))
    return [{name: value[[i]] for name, value in sweep.items()} for i in picks[:count]]


def single_and_floor(designs, polar, repeats):
    """Median/best ``run_model`` times of one BILD design and of the floor chain, interleaved."""
    single = make_problem(designs[0], polar)
    floor = floor_problem()
    single.run_model()
    floor.run_model()
    bild_times, floor_times, bild_cpu, floor_cpu = [], [], [], []
    for k in range(repeats):
        set_design(single, designs[k % len(designs)])
        bild_times.append(timed(single.run_model))
        floor_times.append(timed(floor.run_model))
        set_design(single, designs[(k + 1) % len(designs)])
        bild_cpu.append(cpu_timed(single.run_model))
        floor_cpu.append(cpu_timed(floor.run_model))
    return bild_times, floor_times, bild_cpu, floor_cpu


def totals(designs, polar, mode, repeats, run_once):
    """Median times of ``run_model`` and ``compute_totals`` of one design, each pair on the same design."""
    prob = make_problem(designs[0], polar, mode=mode, run_once=run_once)
    prob.run_model()
    prob.compute_totals(of=OF, wrt=INPUTS)  # builds the total-derivative machinery
    run_times, total_times, run_cpu, total_cpu = [], [], [], []
    for k in range(repeats):
        set_design(prob, designs[k % len(designs)])
        run_times.append(timed(prob.run_model))
        total_times.append(timed(lambda: prob.compute_totals(of=OF, wrt=INPUTS)))
        set_design(prob, designs[(k + 1) % len(designs)])
        run_cpu.append(cpu_timed(prob.run_model))
        total_cpu.append(cpu_timed(lambda: prob.compute_totals(of=OF, wrt=INPUTS)))
    return [statistics.median(t) for t in (run_times, total_times, run_cpu, total_cpu)]


def main(repeats=40):
    # The built-in polar clamps (or extrapolates) a few Reynolds numbers of the sweep; that warning is not timed.
    warnings.simplefilter("ignore")
    polar = naca4412()
    sweep = paper_sweep()
    designs = single_designs(sweep, 25)
    # First use of the polar builds its max-L/D table (bild_mdo.airfoil.max_lift_to_drag_table): one
    # batched solve, like setup, not timed.
    make_problem(sweep, polar).run_model()

    print(f"BILDGroup, NACA 4412 surrogate, num_radial = {NUM_RADIAL}; setup excluded; "
          f"{len(designs)} different designs cycled")
    bild_times, floor_times, bild_cpu, floor_cpu = single_and_floor(designs, polar, repeats)
    median_1, best_1 = statistics.median(bild_times), min(bild_times)
    median_f, best_f = statistics.median(floor_times), min(floor_times)
    cpu_1, cpu_f = statistics.median(bild_cpu), statistics.median(floor_cpu)
    print(f"  floor: {FLOOR_COMPONENTS} trivial ExplicitComponents, run_model ({repeats} runs): "
          f"median {median_f * 1e3:7.3f} ms, best {best_f * 1e3:7.3f} ms, CPU {cpu_f * 1e3:7.3f} ms")
    print(f"  one design per run_model (num_nodes = 1, {repeats} runs):           "
          f"median {median_1 * 1e3:7.3f} ms, best {best_1 * 1e3:7.3f} ms, CPU {cpu_1 * 1e3:7.3f} ms")
    print(f"  single design / floor: median {median_1 / median_f:5.2f}x, best {best_1 / best_f:5.2f}x, "
          f"CPU {cpu_1 / cpu_f:5.2f}x (target <= 5x)")

    start = time.perf_counter()
    batch = make_problem(sweep, polar)
    setup_time = time.perf_counter() - start
    batch.run_model()  # warm-up
    batch_times, batch_cpu = [], []
    for _ in range(3):
        batch_times.append(timed(batch.run_model))
        batch_cpu.append(cpu_timed(batch.run_model))
    median_b, best_b, cpu_b = statistics.median(batch_times), min(batch_times), statistics.median(batch_cpu)
    nn = sweep["rpm"].size
    print(f"  {nn} designs in one run_model (setup {setup_time:.2f} s, 3 runs): median {median_b:.3f} s per run, "
          f"{median_b / nn * 1e6:7.2f} us per design, CPU {cpu_b / nn * 1e6:7.2f} us per design "
          "(target <= 50 us)")
    print(f"  batched / single per design: median 1/{median_1 / (median_b / nn):.0f}, "
          f"best 1/{best_1 / (best_b / nn):.0f}, CPU 1/{cpu_1 / (cpu_b / nn):.0f} (target <= 1/150)")
    chord = batch.get_val("chord")
    print(f"  batch sanity: thrust {batch.get_val('thrust').min():.4g} ... {batch.get_val('thrust').max():.4g} N, "
          f"all finite: {bool(np.all(np.isfinite(chord)))}")

    size = 2 + 2 * NUM_RADIAL
    for run_once in (False, True):
        label = "LinearRunOnce set by the user" if run_once else "as shipped, TriangularDirectSolver"
        for mode in ("fwd", "rev"):
            run, total, run_cpu, total_cpu = totals(designs, polar, mode, repeats, run_once)
            print(f"  compute_totals ({size} x {len(INPUTS)}), {mode}, {label}: median {total * 1e3:7.3f} ms "
                  f"(run_model {run * 1e3:7.3f} ms) ratio {total / run:5.2f}x; CPU {total_cpu * 1e3:7.3f} ms "
                  f"(run_model {run_cpu * 1e3:7.3f} ms) ratio {total_cpu / run_cpu:5.2f}x (target <= 2x)")

    for analysis in (True, False):
        design_rotor(airfoil=polar, bem_analysis=analysis)  # builds and caches the models
        times = [timed(lambda: design_rotor(airfoil=polar, bem_analysis=analysis)) for _ in range(20)]
        label = "with the BEM analysis of its blade (default)" if analysis else "bem_analysis=False"
        print(f"  design_rotor() for one design, cached model, {label}: median {statistics.median(times) * 1e3:7.3f} ms")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=40, help="timed runs of the single design (default 40)")
    main(parser.parse_args().repeats)
