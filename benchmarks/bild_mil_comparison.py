"""BILD (three variants), minimum-induced-loss design and the full-BEM optimum at the same thrust.

Run:  .venv/bin/python benchmarks/bild_mil_comparison.py [--levels 3] [--airfoil naca4412] [--figure PATH]

On the forward-flight cases (J > 0) of the verification sweep of ``--levels``
(54 cases at levels 3: J 1.5 and 3, R 0.5 ... 1.5 m, altitude 0 ... 3000 m,
c_ref 0.08 ... 0.22 m, 800 rpm, 3 blades, 30 stations, hub 0.2 R) and the
``--airfoil`` of the verification (default: the built-in NACA 4412), per case
(:func:`bild_mdo.verification.method_comparison.compare_methods`):

* BILD with the reference section point (the paper's method) for the case's c_ref;
* BILD with the local section point for the same thrust (its reference chord follows);
* BILD with the Reynolds-aware exact ideal loading (the local point with
  ``ideal_loading='exact'``) for the same thrust;
* the MIL design (Adkins & Liebeck 1994, A&L's tip factor) for the same thrust
  at the same operating point and BILD's reference airfoil point;
* the full-BEM optimum (SLSQP, min energy loss) for the same thrust: the lower of
  the runs started from the three BILD designs (the optimum is not unique with the
  Reynolds-dependent polar: issue 12);

then every design is trimmed by collective pitch to the optimum's thrust in the
full BEM model (tip and hub loss, the same polar, stations and ISA) and compared
with the optimum.  Prints ONE table: per method, the energy loss over the
optimum's (mean, worst, best: negative where a design beats the optimum), the
twist and chord differences against the optimum (||x - x_opt|| / ||x_opt||, the
verification's measure, of the trimmed design; mean, max), the largest pitch
trim, and the time per design: one design per model run (best of ``--repeats``
passes through the cases) and one batched run of all cases (per design); the
optimiser's wall time per case (s, the run from BILD's reference design).
BILD's local-point variants are designed for a thrust (``thrust_target=True``),
which iterates on the reference chord: their times are those of that mode.  Saves a
figure (energy excess per case and method; chord and twist of the case of
median BILD excess) to ``--figure``.

Nothing is asserted; timings on a shared machine are noisy (all in one run).
"""
import argparse
import os
import sys
import time
import warnings

import numpy as np

from bild_mdo.airfoil.text import DEFAULT_AIRFOIL, sweep_polar
from bild_mdo.bem.analyze import station_radii
from bild_mdo.io.airfoil import airfoil_text
from bild_mdo.optimization.initial_design import CHORD_RATIO_BOUNDS, TWIST_LIMITS
from bild_mdo.verification.cases import SweepSpec
from bild_mdo.verification.method_comparison import METHOD_LABELS, METHODS, compare_methods, forward_flight_cases

DEFAULT_FIGURE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "output", "bild_mil_comparison.png")


def parse_args(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--levels", type=int, default=3, help="levels per axis of the verification sweep (default 3)")
    parser.add_argument("--airfoil", default=DEFAULT_AIRFOIL, help="airfoil text, as for bild-mdo verify --airfoil")
    parser.add_argument("--figure", default=DEFAULT_FIGURE, help=f"PNG path (default {DEFAULT_FIGURE})")
    parser.add_argument("--repeats", type=int, default=3, help="timed single-design runs per case (best kept)")
    return parser.parse_args(argv)


def _pct(value):
    return f"{100.0 * value:7.3f}" if np.isfinite(value) else "      -"


def format_table(comparison):
    head = (f"{'method':28s} {'cases':>5s} | {'(E - E_opt)/E_opt (%)':>23s} | {'twist diff (%)':>15s} | "
            f"{'chord diff (%)':>15s} | {'max trim':>8s} | {'time per design':>21s}\n"
            f"{'':28s} {'':5s} | {'mean':>7s} {'worst':>7s} {'best':>7s} | {'mean':>7s} {'max':>7s} | "
            f"{'mean':>7s} {'max':>7s} | {'(deg)':>8s} | {'single':>10s} {'batched':>10s}")
    lines = [head, "-" * len(head.splitlines()[0])]
    for method in comparison.methods:
        s = comparison.summary(method)
        if method == "optimum":
            times = f"{s['time_per_design']:8.2f} s {'-':>10s}"
        else:
            times = f"{1e3 * s['time_per_design']:7.2f} ms {1e3 * s['batch_time_per_design']:7.2f} ms"
        columns = [" ".join(_pct(s[f"{name}_{stat}"]) for stat in stats) for name, stats in
                   (("energy_excess", ("mean", "max", "min")), ("twist_error", ("mean", "max")),
                    ("chord_error", ("mean", "max")))]
        lines.append(f"{METHOD_LABELS[method]:28s} {s['num_cases']:5d} | " + " | ".join(columns)
                     + f" | {np.degrees(s['pitch_offset_max']):8.3f} | {times}")
    return "\n".join(lines)


def inside_optimizer_bounds(comparison, method):
    """Per case: the trimmed design lies inside the optimiser's absolute twist and chord bounds.

    As trimmed: a zero chord (an unloaded annulus) is held at the lower chord bound by the trim.
    """
    chord_ratio = comparison.designs[method].chord / np.array([c.inputs["radius"] for c in comparison.cases])[:, None]
    chord_ratio = np.maximum(chord_ratio, CHORD_RATIO_BOUNDS[0])
    twist = comparison.twist_trimmed[method]
    return (np.all((twist >= TWIST_LIMITS[0]) & (twist <= TWIST_LIMITS[1]), axis=1)
            & np.all((chord_ratio >= CHORD_RATIO_BOUNDS[0]) & (chord_ratio <= CHORD_RATIO_BOUNDS[1]), axis=1))


def representative_case(comparison):
    """Index of the case whose BILD (reference) energy excess is the median of the compared cases."""
    excess = comparison.energy_excess["bild_reference"]
    ok = np.flatnonzero(np.isfinite(excess) & np.isfinite(comparison.energy_excess["mil"]))
    return int(ok[np.argsort(excess[ok])[ok.size // 2]])


def save_figure(comparison, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print(f"figure not written: matplotlib is not installed ({path})")
        return
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig, (ax_e, ax_c, ax_t) = plt.subplots(1, 3, figsize=(15, 4.5))
    markers = {"bild_reference": "o", "bild_local": "s", "bild_local_exact": "D", "mil": "^", "optimum": ""}
    index = np.arange(len(comparison.cases))
    for method in comparison.methods:
        if method != "optimum":
            ax_e.plot(index, 100.0 * comparison.energy_excess[method], markers[method], ms=4,
                      label=METHOD_LABELS[method])
    excess = np.concatenate([comparison.energy_excess[m] for m in comparison.methods if m != "optimum"])
    excess = 100.0 * excess[np.isfinite(excess)]
    if excess.size and excess.min() > 0.0:
        ax_e.set_yscale("log")
    else:  # a design beats the optimum somewhere
        ax_e.axhline(0.0, color="k", lw=0.8)
        ax_e.set_yscale("symlog", linthresh=0.01)
    ax_e.set_ylim(top=2.0 * excess.max() if excess.size else None)
    j = np.array([case.inputs["advance_ratio"] for case in comparison.cases])
    for boundary in np.flatnonzero(np.diff(j)) + 0.5:
        ax_e.axvline(boundary, color="0.6", ls="--", lw=0.8)
    ax_e.set_xlabel("case (J > 0 cases of the sweep in case-id order; dashed: J changes)")
    ax_e.set_ylabel("(E - E_opt) / E_opt (%), all trimmed to T_opt")
    ax_e.legend(fontsize=8, loc="lower right")
    k = representative_case(comparison)
    inputs = comparison.cases[k].inputs
    xi = station_radii(inputs["radius"], inputs["hub_radius"], int(inputs["num_radial"])) / inputs["radius"]
    for method in comparison.methods:
        style = {"color": "k", "lw": 2.0} if method == "optimum" else {"marker": markers[method], "ms": 3}
        ax_c.plot(xi, comparison.designs[method].chord[k] / inputs["radius"], label=METHOD_LABELS[method], **style)
        ax_t.plot(xi, np.degrees(comparison.twist_trimmed[method][k]), label=METHOD_LABELS[method], **style)
    title = (f"case {comparison.cases[k].case_id}: J = {inputs['advance_ratio']:g}, R = {inputs['radius']:g} m, "
             f"h = {inputs['altitude']:g} m, c_ref = {inputs['reference_chord']:g} m")
    for ax, label in ((ax_c, "chord c/R"), (ax_t, "twist (deg), trimmed")):
        ax.set_xlabel("r/R")
        ax.set_ylabel(label)
        ax.set_title(title, fontsize=8)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    print(f"figure: {path} (chord and twist of case {comparison.cases[k].case_id}, the median BILD excess)")


def main(argv=None):
    args = parse_args(argv)
    airfoil = airfoil_text(args.airfoil)
    sweep_polar(airfoil)  # an unknown airfoil stops here
    spec = SweepSpec(levels=args.levels, airfoil=airfoil)
    cases = forward_flight_cases(spec)
    warnings.simplefilter("ignore", UserWarning)  # Reynolds numbers clamped to the polar's table
    start = time.perf_counter()
    comparison = compare_methods(cases, repeats=args.repeats)
    elapsed = time.perf_counter() - start
    print(f"{len(cases)} forward-flight cases of --levels {args.levels} (airfoil {airfoil!r}, "
          f"{spec.num_radial} stations, {spec.num_blades} blades, {spec.rpm:g} rpm); all trimmed to the optimum's "
          f"BEM thrust ({elapsed:.0f} s in all)")
    print(format_table(comparison))
    for note in comparison.notes:
        print(f"note: {note}")
    for method in comparison.methods[:-1]:
        outside = ~inside_optimizer_bounds(comparison, method) & np.isfinite(comparison.energy_excess[method])
        if outside.any():
            print(f"note: {METHOD_LABELS[method]}: {int(outside.sum())} trimmed designs lie outside the optimiser's "
                  f"absolute bounds (twist {np.degrees(TWIST_LIMITS[0]):g}..{np.degrees(TWIST_LIMITS[1]):g} deg, "
                  f"c/R {CHORD_RATIO_BOUNDS[0]:g}..{CHORD_RATIO_BOUNDS[1]:g}); their (E - E_opt)/E_opt: "
                  + ", ".join(f"{100.0 * e:+.4f} %" for e in comparison.energy_excess[method][outside]))
    start = comparison.designs["optimum"].extra["start"]
    starts = [m for m in METHODS if m in comparison.designs and m.startswith("bild_")]
    print("note: BEM optimum = the lowest of the SLSQP runs from " + ", ".join(METHOD_LABELS[m] for m in starts)
          + "; the lowest came from " + ", ".join(f"{METHOD_LABELS[m]} in {int(np.sum(start == k))}"
                                                   for k, m in enumerate(starts))
          + f" of {int(np.sum(np.isfinite(start)))} cases; optimiser time per case is the run from BILD (reference)")
    save_figure(comparison, args.figure)
    return comparison


if __name__ == "__main__":
    main(sys.argv[1:])
