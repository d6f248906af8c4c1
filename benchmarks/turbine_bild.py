"""The turbine BILD next to the propeller BILD: one design and a batch, in one run.

Run:  .venv/bin/python benchmarks/turbine_bild.py [--repeats 25] [--levels 10]

Issue 27 asks that the turbine BILD (:class:`~bild_mdo.bild.turbine_group.TurbineBILDGroup`)
cost at most twice the propeller BILD (the paper's, :class:`~bild_mdo.bild.BILDGroup` with its
defaults) per design, alone and in a batch of 10,000.  With the built-in NACA 4412 polar and
``num_radial = 30`` this prints, timed interleaved in ONE run (setup excluded, every repeat a
DIFFERENT design, so that nothing is served from a cache):

* one design: ``run_model`` with ``num_nodes = 1`` (median of the repeats);
* a batch: one ``run_model`` of ``levels**4`` designs (10,000 by default), per design, the median of
  three runs with the inputs moved by 0.1 % between them.

The propeller designs are the paper's Sec. 5.1 sweep (``bild_speed.paper_sweep``).  The turbine designs
are a full factorial of tip-speed ratio 3 ... 10, radius 20 ... 80 m, wind speed 5 ... 12 m/s and
altitude 0 ... 2000 m (three blades, hub 0.05 R, reference station 0.7 R).  Two members of the turbine
family are timed: the design for maximum power (``design_for='multiplier'``, multiplier 0) and the member
at a given reference chord (``design_for='ref_chord'``, 80 % of the maximum-power design's), the counterpart of the
propeller BILD's input ``ref_chord``.  Every time is given as wall time (``time.perf_counter``) and CPU
time of this process, all its threads (``time.process_time``); ratios are to the propeller BILD of the same
run.  Nothing is asserted: on a shared machine, repeat the run.
"""
import argparse
import sys
import warnings
from pathlib import Path

import numpy as np
import openmdao.api as om

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bild_speed import paper_sweep, set_design, single_designs  # noqa: E402
from bild_variants import clocks, median_pair  # noqa: E402

from bild_mdo.airfoil import naca4412  # noqa: E402
from bild_mdo.bild import BILDGroup  # noqa: E402
from bild_mdo.bild.turbine_group import TurbineBILDGroup  # noqa: E402

NUM_RADIAL = 30
CASES = ("propeller BILD (paper)", "turbine BILD, maximum power", "turbine BILD at a reference chord")
TARGET = 2.0


def turbine_sweep(levels):
    """Inputs of the turbine sweep (``levels**4`` designs; module docstring)."""
    tsr, radius, wind, altitude = np.meshgrid(np.linspace(3.0, 10.0, levels), np.linspace(20.0, 80.0, levels),
                                              np.linspace(5.0, 12.0, levels), np.linspace(0.0, 2000.0, levels),
                                              indexing="ij")
    tsr, radius, wind = tsr.ravel(), radius.ravel(), wind.ravel()
    n = tsr.size
    return {"v_axial": wind, "rpm": tsr * wind / radius * 60.0 / (2.0 * np.pi), "radius": radius,
            "hub_radius_ratio": np.full(n, 0.05), "ref_radius_ratio": np.full(n, 0.7),
            "altitude": altitude.ravel()}


def _member(case, sweep):
    values = dict(sweep)
    chord = values.pop("member_chord")
    if case == CASES[1]:
        values["power_thrust_multiplier"] = np.zeros(sweep["rpm"].size)
        values["section_chord"] = chord / 0.8
    else:
        values["ref_chord"] = chord
    return values


def with_member_chords(sweep, polar):
    """The sweep with ``member_chord``: 80 % of the reference chord of its maximum-power design (the section
    chord iterated to that chord, as :func:`~bild_mdo.results.turbine_design.design_turbine` does)."""
    chord = 0.04 * sweep["radius"]
    prob = problem(CASES[1], _member(CASES[1], dict(sweep, member_chord=0.8 * chord)), polar)
    for _ in range(20):
        prob.set_val("section_chord", chord, units="m")
        prob.run_model()
        chord, previous = prob.get_val("ref_chord", units="m").copy(), chord
        if np.max(np.abs(chord / previous - 1.0)) < 1e-6:
            break
    return dict(sweep, member_chord=0.8 * chord)


def problem(case, values, polar):
    nn = values["rpm"].size
    if case == CASES[0]:
        group = BILDGroup(num_nodes=nn, num_radial=NUM_RADIAL, polar=polar, on_infeasible="flag")
    else:
        group = TurbineBILDGroup(num_nodes=nn, num_radial=NUM_RADIAL, polar=polar,
                                 design_for="multiplier" if case == CASES[1] else "ref_chord")
    prob = om.Problem(group, reports=False)
    prob.setup(check=False)
    set_design(prob, values)
    prob.final_setup()
    return prob


def cases_of(propeller, turbine):
    return {CASES[0]: propeller, CASES[1]: _member(CASES[1], turbine), CASES[2]: _member(CASES[2], turbine)}


def moved(values, factor):
    return {name: (value * factor if name in ("v_axial", "ref_chord", "section_chord") else value)
            for name, value in values.items()}


def one_design(propellers, turbines, polar, repeats):
    designs = [cases_of(p, t) for p, t in zip(propellers, turbines)]
    probs = {case: problem(case, designs[0][case], polar) for case in CASES}
    for prob in probs.values():
        prob.run_model()
    samples = {case: [] for case in CASES}
    for k in range(repeats):
        for case, prob in probs.items():
            set_design(prob, designs[(k + 1) % len(designs)][case])
            samples[case].append(clocks(prob.run_model))
    return {case: median_pair(s) for case, s in samples.items()}


def batch(propeller, turbine, polar):
    values = cases_of(propeller, turbine)
    probs = {case: problem(case, values[case], polar) for case in CASES}
    for prob in probs.values():
        prob.run_model()
    samples = {case: [] for case in CASES}
    for k in range(3):
        for case, prob in probs.items():
            nn = values[case]["rpm"].size
            set_design(prob, moved(values[case], 1.0 + 1e-3 * (k + 1)))
            wall, cpu = clocks(prob.run_model)
            samples[case].append((wall / nn, cpu / nn))
    return {case: median_pair(s) for case, s in samples.items()}


def report(label, values, unit, scale):
    base = values[CASES[0]]
    print(f"\n{label}")
    for case in CASES:
        wall, cpu = values[case]
        line = (f"  {case:<36} {wall * scale:9.3f} {unit} (CPU {cpu * scale:9.3f})   x propeller: "
                f"{wall / base[0]:6.2f} (CPU {cpu / base[1]:6.2f})")
        if case != CASES[0]:
            line += f"   target <= {TARGET:g}x"
        print(line)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=25)
    parser.add_argument("--levels", type=int, default=10, help="levels of the batch sweeps (levels**4 designs)")
    args = parser.parse_args()
    warnings.simplefilter("ignore")
    polar = naca4412()
    propeller, turbine = paper_sweep(args.levels), with_member_chords(turbine_sweep(args.levels), polar)
    count = max(2, min(args.repeats, propeller["rpm"].size))
    props = single_designs(propeller, count)
    turbs = single_designs(turbine, count)
    print(f"num_radial {NUM_RADIAL}, NACA 4412 built-in polar; one design: median of {args.repeats} repeats")
    report("one design (run_model, num_nodes = 1)", one_design(props, turbs, polar, args.repeats), "ms", 1e3)
    n = propeller["rpm"].size
    report(f"batch of {n} designs (one run_model), per design", batch(propeller, turbine, polar), "us", 1e6)


if __name__ == "__main__":
    main()
