"""Rotor noise of a batch of BILD designs next to the BILD run of the same batch (issue 26's speed point).

Run:  .venv/bin/python benchmarks/noise_speed.py [--levels 10] [--repeats 3]

The designs are the paper's Sec. 5.1 sweep (``levels**4``, 1,296 by default; 30 stations, built-in NACA
4412).  The issue asks for 10,000: the broadband component holds arrays of every azimuth, station and band
of every design (about 3.5 MB per design), so 10,000 at once need about 35 GB, more than this machine has;
the cost per design is the same at 625 and 1,296 designs.  Three problems are set up (set-up excluded from the
times): :class:`~bild_mdo.bild.BILDGroup` alone, and the same group with one observer, 10 blade-passage
harmonics and the broadband BPM sources in the 31 one-third-octave bands 20 Hz - 20 kHz (24 azimuths), its
``noise_observers`` option: the observer 10 m below the rotor on its axis (where one azimuth stands for all,
:mod:`bild_mdo.acoustics.broadband_noise`) and 10 m below, 5 m off the axis (every azimuth evaluated).  Each ``run_model`` is timed (wall time and CPU time of this process, the median of
``--repeats`` runs, the reference chords moved by 0.1 % between them so that nothing is served from a cache);
the noise costs the difference, and the ratio noise / BILD is printed beside the issue's target (at most 1).
The same for ``compute_totals`` (of ``power``, and of ``oaspl_dba`` with the noise, with respect to ``rpm``): what
one gradient of a sizing optimiser costs.  Nothing is asserted: on a shared machine, repeat the run.
"""
import argparse
import statistics
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import openmdao.api as om

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bild_speed import paper_sweep, set_design  # noqa: E402

from bild_mdo.bild import BILDGroup  # noqa: E402

OBSERVERS = {"on the axis": np.array([[-10.0, 0.0, 0.0]]), "off the axis": np.array([[-10.0, 5.0, 0.0]])}
NUM_RADIAL, HARMONICS = 30, 10


def problem(sweep, observer=None):
    options = dict(noise_observers=observer, noise_harmonics=HARMONICS) if observer is not None else {}
    prob = om.Problem(BILDGroup(num_nodes=sweep["rpm"].size, num_radial=NUM_RADIAL, on_infeasible="flag",
                                **options), reports=False)
    prob.setup()
    set_design(prob, sweep)
    return prob


def clocks(function):
    wall, cpu = time.perf_counter(), time.process_time()
    function()
    return time.perf_counter() - wall, time.process_time() - cpu


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--levels", type=int, default=6,
                        help="levels of the sweep (levels**4 designs; 10 needs about 35 GB: see the docstring)")
    parser.add_argument("--repeats", type=int, default=3, help="timed runs of each problem")
    args = parser.parse_args(argv)
    sweep = paper_sweep(args.levels)
    n = sweep["rpm"].size
    probs = {"BILD": problem(sweep)}
    probs.update({f"noise {where}": problem(sweep, observer) for where, observer in OBSERVERS.items()})
    for prob in probs.values():
        prob.run_model()
    samples = {(name, what): [] for name in probs for what in ("run_model", "compute_totals")}
    for k in range(args.repeats):
        moved = dict(sweep, ref_chord=sweep["ref_chord"] * (1.0 + 1e-3 * (k + 1)))
        for name, prob in probs.items():
            set_design(prob, moved)
            samples[name, "run_model"].append(clocks(prob.run_model))
            of = ["power", "oaspl_dba"] if name != "BILD" else ["power"]
            samples[name, "compute_totals"].append(clocks(lambda: prob.compute_totals(of=of, wrt=["rpm"])))
    wall = {key: statistics.median(s[0] for s in v) / n for key, v in samples.items()}
    cpu = {key: statistics.median(s[1] for s in v) / n for key, v in samples.items()}
    print(f"{n} designs, {NUM_RADIAL} stations; noise: 1 observer, {HARMONICS} harmonics, 31 bands, 24 azimuths; "
          f"median of {args.repeats} runs, per design")
    for what in ("run_model", "compute_totals"):
        print(f" {what}" + (" (of power [and oaspl_dba] wrt rpm: the linearisation and one solve)"
                            if what == "compute_totals" else ""))
        print(f"  {'BILD':<34} {wall['BILD', what] * 1e6:10.2f} us (CPU {cpu['BILD', what] * 1e6:10.2f})")
        for name in probs:
            if name == "BILD":
                continue
            noise_wall, noise_cpu = wall[name, what] - wall["BILD", what], cpu[name, what] - cpu["BILD", what]
            print(f"  {name + ', noise alone':<34} {noise_wall * 1e6:10.2f} us (CPU {noise_cpu * 1e6:10.2f})   "
                  f"noise / BILD: {noise_wall / wall['BILD', what]:.2f} (CPU {noise_cpu / cpu['BILD', what]:.2f})"
                  + ("   target <= 1" if what == "run_model" else ""))


if __name__ == "__main__":
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        main()
