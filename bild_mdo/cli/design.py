"""``bild-mdo design``: design ideal rotor blades with BILD and print or write them."""
from __future__ import annotations

from pathlib import Path

from bild_mdo.airfoil.builtin import available_polars
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bild.chord import CHORD_FORMS
from bild_mdo.io.qprop import write_qprop
from bild_mdo.plots.blade import plot_blade
from bild_mdo.results.design import design_rotor

#: One-line help of the subcommand.
HELP = "design ideal rotor blades with the BILD method (paper Alg. 1)"
#: Description of the subcommand.
DESCRIPTION = (
    "Design the ideal chord and twist of a rotor with the BILD method (Ruh & Hwang 2023, Alg. 1) and print the "
    "station table and performance.  The defaults are the paper's rotor: R = 1.5 m, B = 3, 800 rpm, NACA 4412, "
    "c_ref = 0.15 m at r/R = 0.5, hover, 30 stations.  Numeric operating and sizing options take one value or "
    "several (a batch of designs, computed in one vectorised run; lists must have equal lengths).  Units are SI.")

# Operating and sizing inputs of design_rotor that take one value or a batch: (option, default, metavar, help).
_BATCH_OPTIONS = (
    ("--rpm", 800.0, "RPM", "rotor speed [rpm]"),
    ("--radius", 1.5, "R", "tip radius R [m]"),
    ("--hub-radius-ratio", 0.2, "X", "hub radius / tip radius [-]"),
    ("--ref-radius-ratio", 0.5, "X", "reference station r_ref / R [-]"),
    ("--ref-chord", 0.15, "C", "chord at the reference station c_ref [m]"),
    ("--altitude", 0.0, "H", "geometric altitude for the ISA atmosphere [m], 0 ... 11000"),
)


def add_design_arguments(parser):
    """Add the ``design`` options to an argparse parser and return it."""
    speed = parser.add_mutually_exclusive_group()
    speed.add_argument("--v-axial", type=float, nargs="+", default=0.0, metavar="V",
                       help="axial (climb/flight) velocity [m/s]; 0 is hover")
    speed.add_argument("--advance-ratio", type=float, nargs="+", default=None, metavar="J",
                       help="advance ratio J = V/(nD) [-], instead of --v-axial")
    for option, default, metavar, text in _BATCH_OPTIONS:
        parser.add_argument(option, type=float, nargs="+", default=default, metavar=metavar, help=text)
    parser.add_argument("--num-blades", type=int, default=3, metavar="B", help="number of blades B [-]")
    parser.add_argument("--airfoil", choices=available_polars(), default="naca4412",
                        help="airfoil polar (naca4412: built-in XFOIL surrogate; analytic: closed-form test polar)")
    parser.add_argument("--num-radial", type=int, default=30, metavar="N",
                        help="radial stations [-] (midpoints of equal annuli from hub to tip)")
    parser.add_argument("--loss-model", choices=LOSS_MODELS, default="tip_hub", help="Prandtl loss factor")
    parser.add_argument("--chord-form", choices=CHORD_FORMS, default="thrust",
                        help="back-compute the chord from the thrust (Eq. (31)) or the torque balance")
    parser.add_argument("--root-chord-correction", type=float, default=None, metavar="K",
                        help="k of the root-chord correction, Eq. (32) [-]; omit for none")
    out = parser.add_argument_group("output files")
    out.add_argument("--csv", metavar="FILE", help="write the geometry table r [m], chord [m], twist [deg] "
                     "(a batch writes FILE_<i>.csv per design)")
    out.add_argument("--json", metavar="FILE", help="write geometry, performance and distributions as JSON")
    out.add_argument("--qprop", metavar="FILE", help="write a QPROP propeller file (r, c in m; beta in deg)")
    out.add_argument("--plot", metavar="FILE.png", help="write planform and twist as PNG (needs matplotlib)")
    return parser


def _scalar_or_list(values):
    if not isinstance(values, list):
        return values
    return values[0] if len(values) == 1 else values


def run_design(args, out):
    """Design the rotor(s) of parsed ``design`` options, print them and write the files asked for.

    Returns
    -------
    int
        Exit code, 0.
    """
    speed = ({"advance_ratio": _scalar_or_list(args.advance_ratio)} if args.advance_ratio is not None
             else {"v_axial": _scalar_or_list(args.v_axial)})
    names = [option[2:].replace("-", "_") for option, *_ in _BATCH_OPTIONS]  # argparse's dest of each option
    sizing = {name: _scalar_or_list(getattr(args, name)) for name in names}
    result = design_rotor(**speed, **sizing, num_blades=args.num_blades, airfoil=args.airfoil,
                          num_radial=args.num_radial, loss_model=args.loss_model, chord_form=args.chord_form,
                          root_chord_correction=args.root_chord_correction)
    if result.is_batch:
        print(result.summary(max_rows=50), file=out)
    else:
        print(result.summary(), file=out)
        print("\nstations:", file=out)
        print(result.station_table(), file=out)
    written = []
    if args.csv:
        written += result.to_csv(args.csv)
    if args.json:
        written.append(result.to_json(args.json))
    if args.qprop:
        base = Path(args.qprop)
        for i, design in enumerate(result):
            target = base if not result.is_batch else base.with_name(f"{base.stem}_{i}{base.suffix}")
            written.append(write_qprop(target, design))
    if args.plot:
        plot_blade(result, args.plot)
        written.append(args.plot)
    for path in written:
        print(f"wrote {path}", file=out)
    return 0
