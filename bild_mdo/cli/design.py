"""``bild-mdo design``: design ideal rotor blades with BILD and print or write them."""
from __future__ import annotations

import warnings

import numpy as np

from bild_mdo import validation
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bild.annulus_stationarity import IDEAL_LOADINGS
from bild_mdo.bild.chord import CHORD_FORMS
from bild_mdo.bild.variants import SECTION_POINTS
from bild_mdo.cli.design_turbine import CURVE_OPTIONS, TURBINE_DEFAULTS, add_turbine_arguments, run_turbine
from bild_mdo.cli.files import AIRFOIL_HELP, airfoil_polar, batch_files, figure_file, output_file
from bild_mdo.io.blade_3d import DEFAULT_STACKING, LIBRARIES, require, section_coordinates, write_step, write_stl
from bild_mdo.io.geometry import LENGTH_UNITS
from bild_mdo.io.qprop import write_qprop
from bild_mdo.plots.blade import plot_blade
from bild_mdo.fluid import FLUID_HELP, fluid_from_text
from bild_mdo.results.design import ReferenceChordWarning, UnloadedStationsWarning, design_rotor

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
    ("--ref-chord", None, "C", "chord at the reference station c_ref [m] (default 0.15, unless --thrust)"),
    ("--thrust", None, "T", "thrust target T* [N] instead of --ref-chord: the reference chord is solved for it"),
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
        # The sizing options --turbine shares default to None here, so that a value the user gives is told apart
        # from the propeller default (filled in by run_design; --turbine has its own, design_turbine.TURBINE_DEFAULTS).
        turbine = TURBINE_DEFAULTS.get(option[2:].replace("-", "_"))
        parser.add_argument(option, type=float, nargs="+", default=default if turbine is None else None,
                            metavar=metavar, help=text if turbine is None else
                            f"{text} (default {default:g}; with --turbine {turbine:g})")
    parser.add_argument("--fluid", default=None, metavar="FLUID", help=FLUID_HELP)
    parser.add_argument("--num-blades", type=int, default=3, metavar="B", help="number of blades B [-]")
    parser.add_argument("--airfoil", default="naca4412", metavar="AIRFOIL",
                        help=AIRFOIL_HELP + "; the geometry files carry it (JSON embeds the polar, CSV and QPROP "
                                            "write NAME.polar.json next to them where a name does not rebuild it)")
    parser.add_argument("--num-radial", type=int, default=30, metavar="N",
                        help="radial stations [-] (midpoints of equal annuli from hub to tip)")
    parser.add_argument("--loss-model", choices=LOSS_MODELS, default="tip_hub", help="Prandtl loss factor")
    parser.add_argument("--chord-form", choices=CHORD_FORMS, default="thrust",
                        help="back-compute the chord from the thrust (Eq. (31)) or the torque balance")
    parser.add_argument("--root-chord-correction", type=float, default=None, metavar="K",
                        help="k of the root-chord correction, Eq. (32) [-]; omit for none")
    parser.add_argument("--section-point", choices=SECTION_POINTS, default="reference",
                        help="'reference': every station at the max-L/D point of the reference Reynolds number "
                             "(the paper); 'local': each station minimises cd/cl at its own load and Reynolds number")
    parser.add_argument("--ideal-loading", choices=IDEAL_LOADINGS, default="paper",
                        help="'paper': lambda and eta2 of Eqs. (22), (27) (default); 'exact': every annulus makes "
                             "E - lambda T stationary with the Prandtl loss factor differentiated too (the BEM "
                             "optimum for the airfoil point; with --section-point local each station's cd/cl "
                             "follows its own load too)")
    out = parser.add_argument_group("output files")
    out.add_argument("--csv", metavar="FILE", help="write the geometry table r [m], chord [m], twist [deg] "
                     "(a batch writes FILE_<i>.csv per design)")
    out.add_argument("--json", metavar="FILE", help="write geometry, performance and distributions as JSON")
    out.add_argument("--qprop", metavar="FILE", help="write a QPROP propeller file (r, c in m; beta in deg)")
    out.add_argument("--plot", metavar="FILE.png", help="write planform and twist as PNG (needs matplotlib)")
    out.add_argument("--stl", metavar="FILE", help="write the blade as a closed STL surface for CAD or 3D printing "
                     "(a batch writes FILE_<i>.stl per design)")
    out.add_argument("--step", metavar="FILE", help="write the blade as a STEP solid for CAD (needs OpenCascade: "
                     f"{LIBRARIES['step'][1]})")
    blade = parser.add_argument_group(
        "3D blade (--stl, --step)",
        "x is the rotation axis, positive in the thrust direction; z is the blade's pitch-change axis, radial "
        "(z = r, hub to tip); y completes the right-handed frame.  The blade turns positively about +x (a "
        "right-hand propeller, clockwise seen from behind): leading edge towards -y, suction side towards +x; "
        "mirror y for the other hand.  "
        "Each section's chord line crosses the z axis at --stacking and is twisted about it; the blade runs from "
        "hub to tip radius (end stations' chord and twist), with flat end caps and no hub.")
    blade.add_argument("--section", metavar="AIRFOIL", help="section shape: a NACA 4- or 5-digit designation or a "
                       "Selig coordinates file (default: --airfoil, when it is one of these)")
    blade.add_argument("--stacking", type=float, default=DEFAULT_STACKING, metavar="X",
                       help="chord fraction of each section on the pitch-change axis [-] (default 0.25, the "
                            "quarter chord)")
    blade.add_argument("--all-blades", action="store_true", help="write all B blades, turned about x by 360/B deg "
                       "(default: one blade along +z)")
    blade.add_argument("--cad-units", choices=tuple(LENGTH_UNITS), default="mm",
                       help="length unit of the STL and STEP files (STL carries none; slicers read mm)")
    add_turbine_arguments(parser)
    return parser


def _scalar_or_list(values):
    if not isinstance(values, list):
        return values
    return values[0] if len(values) == 1 else values


def _batch_length(values):
    return len(values) if isinstance(values, list) else 1


def _zero_chord_message(result):
    """What is wrong with designs whose ideal chord vanishes at some station; None if every chord is positive.

    BILD returns a zero chord where the ideal load it prescribes vanishes (a very
    light loading, e.g. a tiny ``c_ref`` for the radius).  Such a blade ends
    before the tip radius R, but the Prandtl tip loss of the design (and of any
    BEM analysis of the file) assumes it reaches R, and the BEM inflow of a
    zero-solidity station in hover is 0/0.  So the design is flagged instead of
    writing files that describe no real rotor and that ``analyze`` rejects.
    """
    chord = np.atleast_2d(result.chord)
    radii = np.atleast_2d(result.radii)
    bad = np.flatnonzero(np.any(chord <= 0.0, axis=1))
    if not bad.size:
        return None
    first = int(bad[0])
    stations = np.flatnonzero(chord[first] <= 0.0)
    label = (f"design {first}" + (f" (and {bad.size - 1} more)" if bad.size > 1 else "")) if result.is_batch \
        else "the design"
    at_tip = stations[-1] == chord.shape[1] - 1 and np.all(np.diff(stations) == 1)
    why = ("so the blade ends before the tip radius its tip loss assumes" if at_tip else
           "and a blade file needs a chord at every station (a BEM analysis or a 3D blade has none there)")
    return (f"{label} has zero chord at {stations.size} of {chord.shape[1]} stations (r = "
            f"{radii[first, stations[0]]:.4g} ... {radii[first, stations[-1]]:.4g} m): the ideal load vanishes "
            f"there, {why}; raise --ref-chord or --thrust, or lower --radius")


def _blade_options(args):
    """The options of ``--stl``/``--step``, checked before any work (libraries, stacking, section); None without."""
    if not (args.stl or args.step):
        return None
    for option in ("stl", "step"):
        if getattr(args, option):
            require(option)
    validation.in_range("--stacking", args.stacking, 0.0, 1.0, ndim=(0,))
    section = args.section or args.airfoil
    try:
        section_coordinates(section)
    except ValueError as err:
        if args.section:
            raise ValueError(f"--section: {err}") from None
        raise ValueError(f"--stl/--step need the section shape, and --airfoil {args.airfoil!r} gives none; add "
                         "--section with a NACA designation (naca4412) or a Selig coordinates file") from None
    return {"airfoil": section, "stacking": args.stacking, "all_blades": args.all_blades, "units": args.cad_units}


def run_design(args, out):
    """Design the rotor(s) of parsed ``design`` options, print them and write the files asked for.

    Every output file and the airfoil are checked before the design runs; a
    design with zero-chord stations is refused before any file is written.

    Returns
    -------
    int
        Exit code, 0.
    """
    if args.turbine:
        return run_turbine(args, out)
    for option in ("rated_power", *CURVE_OPTIONS):
        if getattr(args, option, None) is not None:
            raise ValueError(f"--{option.replace('_', '-')} belongs to a turbine's power curve: give it with --turbine")
    speed = ({"advance_ratio": _scalar_or_list(args.advance_ratio)} if args.advance_ratio is not None
             else {"v_axial": _scalar_or_list(args.v_axial)})
    names = [option[2:].replace("-", "_") for option, *_ in _BATCH_OPTIONS]  # argparse's dest of each option
    given = {name: getattr(args, name) for name in names}
    given.update({name: default for (option, default, *_), name in zip(_BATCH_OPTIONS, names)
                  if name in TURBINE_DEFAULTS and given[name] is None})
    sizing = {name: _scalar_or_list(value) for name, value in given.items()}
    num_radial = validation.integer("--num-radial", args.num_radial, minimum=2)
    lengths = {name: _batch_length(value) for name, value in {**speed, **sizing}.items()
               if isinstance(value, list)}
    count = validation.batch_size(lengths)
    validation.memory_bound("designs", count, num_radial, hint="use fewer designs or --num-radial")
    files = {"--csv": output_file("--csv", args.csv), "--json": output_file("--json", args.json),
             "--qprop": batch_files("--qprop", args.qprop, count), "--plot": figure_file("--plot", args.plot),
             "--stl": batch_files("--stl", args.stl, count), "--step": batch_files("--step", args.step, count)}
    blade = _blade_options(args)
    fluid = None if args.fluid is None else fluid_from_text(args.fluid)
    if fluid is not None and np.any(np.asarray(sizing["altitude"]) != 0.0):
        raise ValueError("give either --altitude (the ISA) or --fluid, not both")
    polar = airfoil_polar("--airfoil", args.airfoil)
    with warnings.catch_warnings():
        # The command says what is wrong with zero-chord stations itself (below), in its own words.
        warnings.simplefilter("ignore", UnloadedStationsWarning)
        warnings.simplefilter("ignore", ReferenceChordWarning)  # the summary's notes say it
        result = design_rotor(**speed, **sizing, num_blades=args.num_blades, airfoil=polar,
                              num_radial=num_radial, loss_model=args.loss_model, chord_form=args.chord_form,
                              root_chord_correction=args.root_chord_correction, section_point=args.section_point,
                              ideal_loading=args.ideal_loading, fluid=fluid)
    problem = _zero_chord_message(result)
    if problem and any(files[option] for option in ("--csv", "--json", "--qprop", "--stl", "--step")):
        raise ValueError(f"{problem} (no geometry file written)")
    if problem:
        warnings.warn(problem, stacklevel=1)
    if result.is_batch:
        print(result.summary(max_rows=50), file=out)
    else:
        print(result.summary(), file=out)
        print("\nstations:", file=out)
        print(result.station_table(), file=out)
    written = []
    if args.csv:
        written += result.to_csv(args.csv)
    if files["--json"]:
        written.append(result.to_json(files["--json"]))
    for design, target in zip(result, files["--qprop"]):
        written.append(write_qprop(target, design))
    for writer, option in ((write_stl, "--stl"), (write_step, "--step")):
        written += [writer(target, design, **blade) for design, target in zip(result, files[option])]
    if files["--plot"]:
        plot_blade(result, files["--plot"])
        written.append(files["--plot"])
    for path in written:
        print(f"wrote {path}", file=out)
    return 0
