"""The four BILD variants side by side: one design, a batch, a thrust target and total derivatives.

Run:  .venv/bin/python benchmarks/bild_variants.py [--repeats 25] [--levels 10] [--batch-repeats 5] [--skip-batch]

The variants are :class:`~bild_mdo.bild.BILDGroup`'s ``(section_point,
ideal_loading)`` pairs: the paper's BILD (reference point, paper loading), the
exact loading at the reference point, the local point with the paper's
loading, and the Reynolds-aware exact loading (local point, exact loading).
With the built-in NACA 4412 polar and ``num_radial = 30`` it prints, in ONE
run, every variant timed interleaved with the others (setup excluded, every
repeat a DIFFERENT design of the paper's Sec. 5.1 sweep, so that nothing is
served from a cache):

* one design: ``run_model`` with ``num_nodes = 1`` (median of the repeats);
* a batch: one ``run_model`` of the ``levels**4`` designs of the sweep (10,000
  by default; the reference chords are moved by 0.1 % between the timed runs,
  ``--batch-repeats``, 5 by default, their median), per design; the
  local-point variants solve their stations on several threads
  (:func:`bild_mdo.utils.compiled.num_threads`) and are timed once more,
  interleaved, on one (``BILD_MDO_NUM_THREADS=1``);
* a thrust target: ``design_rotor(thrust=T)`` against ``design_rotor(ref_chord=c)``
  of the same variant (``T`` the variant's own thrust at ``c``, the solve
  starting from the model's last reference chord), both with the model
  cached and without the BEM analysis of the blade (``bem_analysis=False``) (``design_rotor`` keeps four set-up models, so these two are timed
  interleaved variant by variant, not across the variants), and the ratio of
  the two;
* ``compute_totals`` of thrust, torque, chord and twist with respect to every
  input of one design, in fwd and rev mode, each right after the
  ``run_model`` of the same design, and its ratio to that ``run_model``.

Every time is given as wall time (``time.perf_counter``) and CPU time of this
process, all its threads (``time.process_time``); every ratio to the paper's BILD is of the same
run.  Issue 23's targets for the Reynolds-aware exact loading are printed
beside its ratios.  Nothing is asserted: on a shared machine, repeat the run.
"""
import argparse
import os
import statistics
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import openmdao.api as om

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bild_speed import INPUTS, OF, paper_sweep, set_design, single_designs  # noqa: E402

from bild_mdo.airfoil import naca4412  # noqa: E402
from bild_mdo.bild import BILDGroup  # noqa: E402
from bild_mdo.results.design import design_rotor  # noqa: E402
from bild_mdo.utils.compiled import num_threads  # noqa: E402

NUM_RADIAL = 30
VARIANTS = (("reference", "paper"), ("reference", "exact"), ("local", "paper"), ("local", "exact"))
NAMES = {VARIANTS[0]: "paper (reference point, paper loading)", VARIANTS[1]: "exact loading, reference point",
         VARIANTS[2]: "local point, paper loading", VARIANTS[3]: "Reynolds-aware exact (local, exact)"}
#: Issue 23's targets for the Reynolds-aware exact loading.
TARGETS = {"one": 3.0, "batch": 5.0, "thrust": 3.0, "fwd": 3.0, "rev": 3.0}


def clocks(function):
    """``(wall, cpu)`` seconds of one call."""
    wall, cpu = time.perf_counter(), time.process_time()
    function()
    return time.perf_counter() - wall, time.process_time() - cpu


def problem(variant, values, polar, mode="auto", **options):
    nn = values["rpm"].size
    prob = om.Problem(BILDGroup(num_nodes=nn, num_radial=NUM_RADIAL, polar=polar, section_point=variant[0],
                                ideal_loading=variant[1], **options), reports=False)
    prob.setup(check=False, mode=mode)
    set_design(prob, values)
    prob.final_setup()
    return prob


def median_pair(samples):
    return statistics.median(s[0] for s in samples), statistics.median(s[1] for s in samples)


def one_design(designs, polar, repeats):
    probs = {v: problem(v, designs[0], polar) for v in VARIANTS}
    for prob in probs.values():
        prob.run_model()
    samples = {v: [] for v in VARIANTS}
    for k in range(repeats):
        for v, prob in probs.items():
            set_design(prob, designs[(k + 1) % len(designs)])
            samples[v].append(clocks(prob.run_model))
    return {v: median_pair(s) for v, s in samples.items()}


def batch(sweep, polar, repeats):
    probs = {v: problem(v, sweep, polar, on_infeasible="flag") for v in VARIANTS}
    for prob in probs.values():
        prob.run_model()
    samples = {v: [] for v in VARIANTS}
    single = {v: [] for v in VARIANTS[2:]}
    nn = sweep["rpm"].size
    setting = os.environ.get("BILD_MDO_NUM_THREADS")
    for k in range(repeats):
        for v, prob in probs.items():
            set_design(prob, dict(sweep, ref_chord=sweep["ref_chord"] * (1.0 + 1e-3 * (k + 1))))
            wall, cpu = clocks(prob.run_model)
            samples[v].append((wall / nn, cpu / nn))
            if v in single:  # the local-point solves once more on one thread (other inputs again)
                set_design(prob, dict(sweep, ref_chord=sweep["ref_chord"] * (1.0 - 1e-3 * (k + 1))))
                os.environ["BILD_MDO_NUM_THREADS"] = "1"
                try:
                    wall, cpu = clocks(prob.run_model)
                finally:
                    if setting is None:
                        del os.environ["BILD_MDO_NUM_THREADS"]
                    else:
                        os.environ["BILD_MDO_NUM_THREADS"] = setting
                single[v].append((wall / nn, cpu / nn))
    feasible = {v: int(np.sum(prob.get_val("feasible"))) for v, prob in probs.items()}
    return ({v: median_pair(s) for v, s in samples.items()}, {v: median_pair(s) for v, s in single.items()},
            feasible)


def _rotor_kwargs(design):
    return {"v_axial": float(design["v_axial"][0]), "rpm": float(design["rpm"][0]),
            "radius": float(design["radius"][0]), "hub_radius_ratio": float(design["hub_radius_ratio"][0]),
            "ref_radius_ratio": float(design["ref_radius_ratio"][0]), "altitude": float(design["altitude"][0])}


def thrust_target(designs, polar, repeats):
    """Per variant: median ``(wall, cpu)`` of ``design_rotor`` at ``c_ref`` and for the thrust it gives there,
    the largest relative thrust error of the target solves that met their target, and how many did not (a NaN
    thrust: infeasible, with its reason in ``result.status``)."""
    cases = []
    for design in designs:
        kw = _rotor_kwargs(design)
        cases.append((kw, float(design["ref_chord"][0])))
    at_chord = {v: [] for v in VARIANTS}
    at_thrust = {v: [] for v in VARIANTS}
    error = {v: 0.0 for v in VARIANTS}
    failed = {v: 0 for v in VARIANTS}
    thrusts = {}
    for v in VARIANTS:
        for i, (kw, chord) in enumerate(cases):
            thrusts[v, i] = design_rotor(ref_chord=chord, airfoil=polar, section_point=v[0], ideal_loading=v[1],
                                         on_infeasible="skip", bem_analysis=False, **kw).thrust
        design_rotor(thrust=thrusts[v, 0], airfoil=polar, section_point=v[0], ideal_loading=v[1],
                     on_infeasible="skip", bem_analysis=False, **cases[0][0])
    # design_rotor keeps four set-up models: the two of one variant stay cached within its block.
    for v in VARIANTS:
        for k in range(repeats):
            i = (k + 1) % len(cases)
            kw, chord = cases[i]
            opts = dict(airfoil=polar, section_point=v[0], ideal_loading=v[1], on_infeasible="skip",
                        bem_analysis=False, **kw)
            at_chord[v].append(clocks(lambda: design_rotor(ref_chord=chord, **opts)))
            result = []
            at_thrust[v].append(clocks(lambda: result.append(design_rotor(thrust=thrusts[v, i], **opts))))
            if np.isfinite(result[0].thrust):
                error[v] = max(error[v], abs(result[0].thrust / thrusts[v, i] - 1.0))
            else:
                failed[v] += 1
    return {v: (median_pair(at_chord[v]), median_pair(at_thrust[v])) for v in VARIANTS}, error, failed


def totals(designs, polar, repeats):
    out = {}
    for mode in ("fwd", "rev"):
        probs = {v: problem(v, designs[0], polar, mode=mode) for v in VARIANTS}
        for prob in probs.values():
            prob.run_model()
            prob.compute_totals(of=OF, wrt=INPUTS)
        runs = {v: [] for v in VARIANTS}
        tots = {v: [] for v in VARIANTS}
        for k in range(repeats):
            for v, prob in probs.items():
                set_design(prob, designs[(k + 1) % len(designs)])
                runs[v].append(clocks(prob.run_model))
                tots[v].append(clocks(lambda: prob.compute_totals(of=OF, wrt=INPUTS)))
        out[mode] = {v: (median_pair(runs[v]), median_pair(tots[v])) for v in VARIANTS}
    return out


def _ratio_line(label, values, unit, scale, target_key=None, per_variant=None):
    base = values[VARIANTS[0]]
    print(f"\n{label}")
    for v in VARIANTS:
        wall, cpu = values[v]
        line = (f"  {NAMES[v]:<40} {wall * scale:9.3f} {unit} (CPU {cpu * scale:9.3f})   x paper: "
                f"{wall / base[0]:6.2f} (CPU {cpu / base[1]:6.2f})")
        if per_variant:
            line += per_variant(v)
        if target_key and v == VARIANTS[3]:
            line += f"   target <= {TARGETS[target_key]:g}x"
        print(line)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=25)
    parser.add_argument("--levels", type=int, default=10, help="levels of the batch sweep (levels**4 designs)")
    parser.add_argument("--batch-repeats", type=int, default=5, help="timed runs of each batch (their median)")
    parser.add_argument("--skip-batch", action="store_true")
    args = parser.parse_args()
    warnings.simplefilter("ignore")
    polar = naca4412()
    sweep = paper_sweep(args.levels)
    designs = single_designs(paper_sweep(), 25)
    print(f"BILDGroup, NACA 4412 surrogate, num_radial = {NUM_RADIAL}; setup excluded; {len(designs)} different "
          f"designs cycled, {args.repeats} repeats; medians")

    one = one_design(designs, polar, args.repeats)
    _ratio_line("one design (run_model, num_nodes = 1)", one, "ms", 1e3, "one")

    if not args.skip_batch:
        per, single, feasible = batch(sweep, polar, args.batch_repeats)
        _ratio_line(f"batch of {sweep['rpm'].size} designs (one run_model), per design; the local-point solves on "
                    f"{num_threads()} threads", per, "us", 1e6, "batch", lambda v: f"   feasible {feasible[v]}")
        base = per[VARIANTS[0]]
        print("  the same on one thread (BILD_MDO_NUM_THREADS=1):")
        for v, (wall, cpu) in single.items():
            print(f"  {NAMES[v]:<40} {wall * 1e6:9.3f} us (CPU {cpu * 1e6:9.3f})   x paper: {wall / base[0]:6.2f} "
                  f"(CPU {cpu / base[1]:6.2f})")

    timing, error, failed = thrust_target(designs, polar, args.repeats)
    _ratio_line("design_rotor at c_ref (model cached)", {v: t[0] for v, t in timing.items()}, "ms", 1e3)
    _ratio_line("design_rotor(thrust=T) (model cached)", {v: t[1] for v, t in timing.items()}, "ms", 1e3, None,
                lambda v: (f"   / same variant at c_ref: {timing[v][1][0] / timing[v][0][0]:5.2f} (CPU "
                           f"{timing[v][1][1] / timing[v][0][1]:5.2f}); max |T/T*-1| {error[v]:.1e}, not met "
                           f"{failed[v]}/{args.repeats}"
                           + (f"   target <= {TARGETS['thrust']:g}x" if v == VARIANTS[3] else "")))

    for mode, values in totals(designs, polar, args.repeats).items():
        _ratio_line(f"compute_totals ({len(OF)} outputs x {len(INPUTS)} inputs), {mode}",
                    {v: t[1] for v, t in values.items()}, "ms", 1e3, None,
                    lambda v, values=values, mode=mode: (
                        f"   / its run_model: {values[v][1][0] / values[v][0][0]:5.2f} (CPU "
                        f"{values[v][1][1] / values[v][0][1]:5.2f})"
                        + (f"   target <= {TARGETS[mode]:g}x" if v == VARIANTS[3] else "")))


if __name__ == "__main__":
    main()
