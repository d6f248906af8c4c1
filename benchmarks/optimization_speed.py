"""Time per BEM optimisation of the verification sweep (paper Sec. 5.1): alone, in lockstep, exact vs FD totals.

Run:  .venv/bin/python benchmarks/optimization_speed.py [--solo-cases 64] [--lockstep 8 64 512] [--fd-cases 80 19]

Cases are spread evenly over the 10,000 cases of the paper's sweep (J, R,
altitude and c_ref all vary) and designed by one batched BILD run.  Printed
side by side in ONE run (timings on a shared machine are noisy: compare
within a run, and prefer the CPU columns, which count every thread of this
process):

1. SLSQP per case alone (one set-up problem, reused, as the sweep did),
   ``--solo-cases`` cases;
2. the same cases optimised in lockstep (``optimize_rotor`` with arrays: one
   vectorised model evaluation per step) in batches of every size of
   ``--lockstep``, with the time per case against the solo time per case and
   the largest differences from the solo optima (energy loss, relative;
   thrust constraint, absolute).  A batch larger than the cases optimised
   alone uses further cases of the sweep; with ``--estimate-above N`` a batch
   above N cases is not run and its time per case is taken from the largest
   batch run (said in the output);
3. SLSQP alone with finite-difference totals of the whole model
   (``approx_totals='fd'``) against exact totals, on the levels-3 cases ``--fd-cases``;
4. the wall time of the 10,000-case sweep on 2 cores at each lockstep time
   per case (``bild-mdo verify`` runs chunks of 256 cases, 64 at a time, so
   the largest batch is the closest) and alone.

Nothing is asserted.
"""
import argparse
import time
import warnings

import numpy as np

from bild_mdo.optimization.problem import build_optimization_problem
from bild_mdo.optimization.run import optimize_rotor
from bild_mdo.verification.case_functions import bild_batch
from bild_mdo.verification.cases import SweepSpec

SWEEP_CASES = 10_000
CORES = 2


def _cases(count):
    spec = SweepSpec(levels=10)
    ids = np.unique(np.linspace(0, spec.num_cases - 1, count).round().astype(int))
    cases = spec.cases(ids)
    return cases, bild_batch(cases)


def _args(cases, designs):
    columns = [[c.inputs[k] for c in cases] for k in ("v_axial", "rpm", "radius", "hub_radius")]
    return (*map(np.array, columns), np.array([d["thrust"] for d in designs]),
            np.array([c.inputs["altitude"] for c in cases]))


def _clock():
    return time.perf_counter(), time.process_time()


def _since(start):
    wall, cpu = _clock()
    return wall - start[0], cpu - start[1]


def solo(prob, cases, designs):
    """Each case alone on a reused problem: results, wall and CPU seconds in total."""
    start = _clock()
    results = []
    for case, bild in zip(cases, designs):
        i = case.inputs
        results.append(optimize_rotor(i["v_axial"], i["rpm"], i["radius"], i["hub_radius"], bild["thrust"],
                                      i["altitude"], problem=prob, restarts=1, bild_chord=bild["chord"],
                                      bild_twist=bild["twist"]))
    return results, *_since(start)


def lockstep(prob, cases, designs):
    """All cases in one lockstep run: results, wall and CPU seconds in total."""
    start = _clock()
    results = optimize_rotor(*_args(cases, designs), problem=prob, restarts=1,
                             bild_chord=np.array([d["chord"] for d in designs]),
                             bild_twist=np.array([d["twist"] for d in designs]))
    return results, *_since(start)


def _differences(results, reference):
    d_energy = max(abs(r.performance["energy_loss"] / s.performance["energy_loss"] - 1.0)
                   for r, s in zip(results, reference))
    d_thrust = max(abs(r.thrust_error - s.thrust_error) for r, s in zip(results, reference))
    same_iterations = all(r.iterations == s.iterations for r, s in zip(results, reference))
    return d_energy, d_thrust, same_iterations


def compare_lockstep(solo_cases, sizes, estimate_above):
    largest = max(max(sizes), solo_cases)
    cases, designs = _cases(largest)
    prob = build_optimization_problem(optimizer="slsqp")
    # Warm-up: the polar and the first problem are set up once per process, as in a sweep's worker.
    lockstep(prob, cases[:2], designs[:2])
    picks = np.unique(np.linspace(0, len(cases) - 1, solo_cases).round().astype(int))
    alone, wall, cpu = solo(prob, [cases[k] for k in picks], [designs[k] for k in picks])
    solo_wall, solo_cpu = wall / len(picks), cpu / len(picks)
    iterations = np.array([r.iterations for r in alone])
    print(f"SLSQP alone: {len(picks)} cases, {100 * np.mean([r.converged for r in alone]):.0f} % converged, "
          f"{iterations.mean():.1f} iterations and {np.mean([r.model_evaluations for r in alone]):.1f} model "
          f"evaluations per case; {solo_wall:.3f} s wall, {solo_cpu:.3f} s CPU per case")
    print("A lockstep run lasts as many steps as its slowest case needs model evaluations (the 'evals' column: "
          "mean/max per case); up to 64 cases run at a time, the next starting when one finishes.")
    print(f"{'lockstep':>9} {'wall s/case':>12} {'CPU s/case':>11} {'alone/lockstep (CPU)':>21} "
          f"{'max |dE/E|':>11} {'max |d(T/T*)|':>14} {'same iterations':>16} {'evals':>9}")
    per_case = {}
    for size in sizes:
        if size > estimate_above:
            base = max(s for s in per_case if s <= estimate_above)
            wall_s, cpu_s = per_case[base]
            print(f"{size:9d} {wall_s:12.4f} {cpu_s:11.4f} {solo_cpu / cpu_s:20.1f}x   estimated: not run, the "
                  f"time per case of {base} cases")
            continue
        # Batches of the first solo cases where they fit, so that every case can be compared with its solo run.
        chosen = list(picks[:size]) if size <= len(picks) else list(range(size))
        results, wall, cpu = lockstep(prob, [cases[k] for k in chosen], [designs[k] for k in chosen])
        # Wall time without the set-up of batch models of new sizes (once per process; the CPU time includes it).
        wall = sum(r.wall_time for r in results)
        per_case[size] = wall / size, cpu / size
        compared = [(r, alone[list(picks).index(k)]) for r, k in zip(results, chosen) if k in picks]
        d_e, d_t, same = _differences(*zip(*compared)) if compared else (np.nan, np.nan, "-")
        evals = np.array([r.model_evaluations for r in results])
        print(f"{size:9d} {wall / size:12.4f} {cpu / size:11.4f} {solo_cpu / (cpu / size):20.1f}x "
              f"{d_e:11.1e} {d_t:14.1e} {str(same):>16} {evals.mean():4.0f}/{evals.max():<4d}  "
              f"({len(compared)} compared with their solo runs; "
              f"{100 * np.mean([r.converged for r in results]):.0f} % converged)", flush=True)
    return per_case, solo_cpu


def compare_fd(case_ids):
    """SLSQP per case alone with exact totals against the same with finite-difference totals (levels-3 cases)."""
    cases = SweepSpec(levels=3).cases(case_ids)
    designs = bild_batch(cases)
    problems = {kind: build_optimization_problem(optimizer="slsqp", approx_totals=None if kind == "exact" else "fd")
                for kind in ("exact", "fd")}
    print(f"\nSLSQP alone, BILD start, {len(cases)} cases: exact totals vs forward finite differences")
    print(f"{'case':>5} {'J':>5} {'R':>5} {'exact wall/CPU s':>17} {'iter':>5} {'evals':>6} "
          f"{'FD wall/CPU s':>15} {'iter':>5} {'evals':>6} {'FD/exact CPU':>13} {'|dE|/E':>9}")
    totals = {"exact": [], "fd": []}
    for case, bild in zip(cases, designs):
        (exact, _, c_exact), (fd, _, c_fd) = (solo(problems[kind], [case], [bild]) for kind in ("exact", "fd"))
        totals["exact"].append(c_exact)
        totals["fd"].append(c_fd)
        exact, fd = exact[0], fd[0]
        de = abs(fd.performance["energy_loss"] / exact.performance["energy_loss"] - 1.0)
        flag = "" if exact.converged and fd.converged else f"  (converged: exact {exact.converged}, FD {fd.converged})"
        print(f"{case.case_id:5d} {case.inputs['advance_ratio']:5.2f} {case.inputs['radius']:5.2f} "
              f"{exact.wall_time:8.3f} {c_exact:8.3f} {exact.iterations:5d} {exact.model_evaluations:6d} "
              f"{fd.wall_time:7.2f} {c_fd:7.2f} {fd.iterations:5d} {fd.model_evaluations:6d} "
              f"{c_fd / c_exact:12.1f}x {de:9.1e}{flag}", flush=True)
    ratio = np.sum(totals["fd"]) / np.sum(totals["exact"])
    print(f"mean CPU per case: exact {np.mean(totals['exact']):.3f} s, FD {np.mean(totals['fd']):.2f} s: exact "
          f"totals {ratio:.1f}x faster (solo against solo)")
    return ratio


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--solo-cases", type=int, default=64, help="cases optimised alone (default 64)")
    parser.add_argument("--lockstep", type=int, nargs="+", default=[8, 64, 512], help="lockstep batch sizes")
    parser.add_argument("--estimate-above", type=int, default=10**9,
                        help="do not run lockstep batches above this size; estimate them (default: run all)")
    parser.add_argument("--fd-cases", type=int, nargs="*", default=[80, 19, 46, 4],
                        help="levels-3 case ids of the exact-vs-FD comparison (none skips it; default 80 19 46 4)")
    args = parser.parse_args()
    warnings.filterwarnings("ignore", message=".*Reynolds numbers outside the tabulated range.*")
    per_case, solo_cpu = compare_lockstep(args.solo_cases, args.lockstep, args.estimate_above)
    if args.fd_cases:
        compare_fd(args.fd_cases)
    # bild-mdo verify optimises chunks of 256 cases, 64 at a time: the largest batch is the closer model.
    minutes = {size: cpu_s * SWEEP_CASES / CORES / 60.0 for size, (_, cpu_s) in per_case.items()}
    shown = ", ".join(f"{m:.1f} min at the CPU time per case of {size} in lockstep" for size, m in sorted(minutes.items()))
    print(f"\n10,000 cases on {CORES} cores (one process per core, BILD and set-up excluded): {shown}; "
          f"{solo_cpu * SWEEP_CASES / CORES / 60.0:.1f} min alone")


if __name__ == "__main__":
    main()
