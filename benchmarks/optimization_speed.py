"""Time per BEM optimisation of the verification sweep (paper Sec. 5.1): SLSQP and Ipopt, starts, exact vs FD totals.

Run:  .venv/bin/python benchmarks/optimization_speed.py [--levels 3] [--every 4] [--fd-cases 5]

Takes every ``--every``-th case of a ``--levels`` sweep (levels=3, every=4:
21 cases spread over J, R, altitude and c_ref), designs them with one batched
BILD run, then optimises each case with every optimiser and start, reusing
one set-up problem per configuration (as the sweep's workers do).  Prints per
configuration: converged fraction, iterations and wall time per case (mean,
median, max), the BILD times, and the wall time the 10,000-case sweep would
need on 2 cores at that mean.

Then, side by side in the same run, one SLSQP optimisation per case (BILD
start, one set-up problem each, solo against solo) with the exact totals of
the analytic partials and with forward finite-difference totals of the whole
model (``approx_totals='fd'``, what a user without analytic partials runs), on
``--fd-cases`` of the cases: time per case, iterations, model evaluations, the
ratio of the times and how far apart the two optima are.  Nothing is
asserted; on a shared machine, repeat the run.
"""
import argparse
import time
import warnings

import numpy as np

from bild_mdo.optimization.problem import build_optimization_problem
from bild_mdo.optimization.run import optimize_rotor
from bild_mdo.verification.case_functions import bild_batch, time_single_bild_design
from bild_mdo.verification.cases import SweepSpec

SWEEP_CASES = 10_000
CORES = 2


def _have_ipopt():
    try:
        import cyipopt  # noqa: F401
    except ImportError:
        return False
    return True


def run(levels, every, optimizers, starts, parameterization, maxiter):
    spec = SweepSpec(levels=levels)
    cases = spec.cases(range(0, spec.num_cases, every))
    start = time.perf_counter()
    designs = bild_batch(cases)
    bild_time = (time.perf_counter() - start) / len(cases)
    print(f"{len(cases)} cases of a levels={levels} sweep; BILD: {1e3 * bild_time:.2f} ms per case in one batch "
          f"(set-up included), {1e3 * time_single_bild_design(cases[0]):.2f} ms for one design alone")
    print(f"{'optimizer':>9} {'start':>6} {'conv':>6} {'iter mean/med/max':>18} {'time mean/med/max (s)':>22} "
          f"{'10k on 2 cores':>15}")
    for optimizer in optimizers:
        for initial in starts:
            prob = build_optimization_problem(optimizer=optimizer, parameterization=parameterization,
                                              maxiter=maxiter)
            times, iterations, converged = [], [], []
            for case, bild in zip(cases, designs):
                i = case.inputs
                begin = time.perf_counter()
                result = optimize_rotor(i["v_axial"], i["rpm"], i["radius"], i["hub_radius"], bild["thrust"],
                                        i["altitude"], problem=prob, initial=initial, bild_chord=bild["chord"],
                                        bild_twist=bild["twist"], reference_chord=i["reference_chord"])
                times.append(time.perf_counter() - begin)
                iterations.append(result.iterations)
                converged.append(result.converged)
            t, it = np.array(times), np.array(iterations)
            sweep_minutes = t.mean() * SWEEP_CASES / CORES / 60.0
            print(f"{optimizer:>9} {initial:>6} {100 * np.mean(converged):5.1f}% "
                  f"{it.mean():8.1f} {np.median(it):4.0f} {it.max():4d} "
                  f"{t.mean():8.3f} {np.median(t):6.3f} {t.max():6.2f} {sweep_minutes:11.1f} min", flush=True)


def _solo(prob, case, bild):
    i = case.inputs
    begin, begin_cpu = time.perf_counter(), time.process_time()
    result = optimize_rotor(i["v_axial"], i["rpm"], i["radius"], i["hub_radius"], bild["thrust"], i["altitude"],
                            problem=prob, initial="bild", bild_chord=bild["chord"], bild_twist=bild["twist"])
    return result, time.perf_counter() - begin, time.process_time() - begin_cpu


def compare_fd(levels, every, num_cases, parameterization, maxiter):
    """SLSQP per case with exact totals against the same with finite-difference totals (solo vs solo)."""
    spec = SweepSpec(levels=levels)
    selected = spec.cases(range(0, spec.num_cases, every))
    picks = np.unique(np.linspace(0, len(selected) - 1, num_cases).round().astype(int))
    cases = [selected[k] for k in picks]
    designs = bild_batch(cases)
    problems = {kind: build_optimization_problem(optimizer="slsqp", parameterization=parameterization, maxiter=maxiter,
                                                 approx_totals=None if kind == "exact" else "fd")
                for kind in ("exact", "fd")}
    print(f"\nSLSQP, BILD start, {len(cases)} cases, each alone: exact totals vs forward finite differences")
    # CPU time of this process as well as wall time: the optimisation is single-threaded (BLAS limited to one
    # thread), so on a shared machine the CPU time is the fairer measure of the pair.
    print(f"{'case':>5} {'J':>5} {'R':>5} {'exact: wall/CPU s':>18} {'iter':>5} {'evals':>6} "
          f"{'FD: wall/CPU s':>16} {'iter':>5} {'evals':>6} {'FD/exact CPU':>13} {'|dE|/E':>9}")
    totals = {"exact": [], "fd": [], "exact_cpu": [], "fd_cpu": []}
    for case, bild in zip(cases, designs):
        (exact, t_exact, c_exact), (fd, t_fd, c_fd) = (_solo(problems[kind], case, bild) for kind in ("exact", "fd"))
        for key, value in (("exact", t_exact), ("fd", t_fd), ("exact_cpu", c_exact), ("fd_cpu", c_fd)):
            totals[key].append(value)
        de = abs(fd.performance["energy_loss"] / exact.performance["energy_loss"] - 1.0)
        flag = "" if exact.converged and fd.converged else f"  (converged: exact {exact.converged}, FD {fd.converged})"
        print(f"{case.case_id:5d} {case.inputs['advance_ratio']:5.2f} {case.inputs['radius']:5.2f} "
              f"{t_exact:8.3f} {c_exact:8.3f} {exact.iterations:5d} {exact.model_evaluations:6d} "
              f"{t_fd:8.2f} {c_fd:7.2f} {fd.iterations:5d} {fd.model_evaluations:6d} {c_fd / c_exact:12.1f}x "
              f"{de:9.1e}{flag}", flush=True)
    mean = {key: float(np.mean(values)) for key, values in totals.items()}
    print(f"mean per case: exact {mean['exact']:.3f} s wall, {mean['exact_cpu']:.3f} s CPU; FD {mean['fd']:.2f} s "
          f"wall, {mean['fd_cpu']:.2f} s CPU: exact totals {mean['fd_cpu'] / mean['exact_cpu']:.1f}x faster in CPU "
          f"time ({mean['fd'] / mean['exact']:.1f}x in wall time)")
    print(f"10,000 cases on {CORES} cores at these CPU times: {mean['exact_cpu'] * SWEEP_CASES / CORES / 60.0:.1f} min "
          f"with exact totals, {mean['fd_cpu'] * SWEEP_CASES / CORES / 3600.0:.1f} h with FD totals")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--levels", type=int, default=3, help="levels per swept axis (default 3: 81 cases)")
    parser.add_argument("--every", type=int, default=4, help="take every n-th case (default 4)")
    parser.add_argument("--optimizers", nargs="+", default=None, help="default: slsqp, and ipopt if installed")
    parser.add_argument("--starts", nargs="+", default=["bild", "linear"], choices=["bild", "linear"])
    parser.add_argument("--parameterization", default="stations", choices=["stations", "bspline"])
    parser.add_argument("--maxiter", type=int, default=300, help="iteration limit of every optimiser (default 300)")
    parser.add_argument("--fd-cases", type=int, default=5,
                        help="cases of the exact-vs-finite-difference comparison (default 5; 0 skips it)")
    args = parser.parse_args()
    optimizers = args.optimizers or (["slsqp", "ipopt"] if _have_ipopt() else ["slsqp"])
    # The polar clamps Re outside its table and warns once; that is expected in this sweep.
    warnings.filterwarnings("ignore", message=".*Reynolds numbers outside the tabulated range.*")
    run(args.levels, args.every, optimizers, args.starts, args.parameterization, args.maxiter)
    if args.fd_cases > 0:
        compare_fd(args.levels, args.every, args.fd_cases, args.parameterization, args.maxiter)


if __name__ == "__main__":
    main()
