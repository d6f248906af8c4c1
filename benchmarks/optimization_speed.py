"""Time per BEM optimisation of the verification sweep (paper Sec. 5.1), SLSQP and Ipopt, warm and cold start.

Run:  .venv/bin/python benchmarks/optimization_speed.py [--levels 3] [--every 4]

Takes every ``--every``-th case of a ``--levels`` sweep (levels=3, every=4:
21 cases spread over J, R, altitude and c_ref), designs them with one batched
BILD run, then optimises each case with every optimiser and start, reusing
one set-up problem per configuration (as the sweep's workers do).  Prints per
configuration: converged fraction, iterations and wall time per case (mean,
median, max), the BILD times, and the wall time the 10,000-case sweep would
need on 2 cores at that mean.  Nothing is asserted; on a shared machine,
repeat the run.
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


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--levels", type=int, default=3, help="levels per swept axis (default 3: 81 cases)")
    parser.add_argument("--every", type=int, default=4, help="take every n-th case (default 4)")
    parser.add_argument("--optimizers", nargs="+", default=None, help="default: slsqp, and ipopt if installed")
    parser.add_argument("--starts", nargs="+", default=["bild", "linear"], choices=["bild", "linear"])
    parser.add_argument("--parameterization", default="stations", choices=["stations", "bspline"])
    parser.add_argument("--maxiter", type=int, default=300, help="iteration limit of every optimiser (default 300)")
    args = parser.parse_args()
    optimizers = args.optimizers or (["slsqp", "ipopt"] if _have_ipopt() else ["slsqp"])
    # The polar clamps Re outside its table and warns once; that is expected in this sweep.
    warnings.filterwarnings("ignore", message=".*Reynolds numbers outside the tabulated range.*")
    run(args.levels, args.every, optimizers, args.starts, args.parameterization, args.maxiter)


if __name__ == "__main__":
    main()
