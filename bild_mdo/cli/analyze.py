"""``bild-mdo analyze``: BEM off-design analysis of a blade geometry file over J or rpm."""
from __future__ import annotations

import numpy as np

from bild_mdo import validation
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.cli.files import AIRFOIL_HELP, airfoil_polar, figure_file, output_file
from bild_mdo.fluid import FLUID_HELP, fluid_from_text
from bild_mdo.io.files import read_geometry
from bild_mdo.plots.curves import plot_performance_curves
from bild_mdo.results.off_design import off_design_sweep
from bild_mdo.results.thrust_trim import TRIM_VARIABLES

#: One-line help of the subcommand.
HELP = "BEM off-design analysis of a blade geometry file over J, airspeed, rpm or collective pitch"
#: Description of the subcommand.
DESCRIPTION = (
    "Analyse a fixed blade (a CSV, JSON or QPROP file as written by 'bild-mdo design', or any QPROP propeller "
    "file) with BEM over a range of advance ratios J = V/(nD) [-] or of airspeeds [m/s] at fixed rpm, of rotor "
    "speeds [rpm] at fixed axial velocity [m/s], or of collective pitches [deg] (alone: at the design point; with a "
    "J, airspeed or rpm sweep: "
    "every pitch at every point), in one vectorised run.  Prints T [N], Q [N m], P [kW], eta, FM, C_T, C_Q, C_P "
    "and the maximum-efficiency point.")


def add_analyze_arguments(parser):
    """Add the ``analyze`` options to an argparse parser and return it."""
    parser.add_argument("geometry", metavar="GEOMETRY_FILE", help="blade geometry: .csv, .json, or a QPROP file")
    sweep = parser.add_mutually_exclusive_group()
    sweep.add_argument("--advance-ratio", type=float, nargs=3, metavar=("START", "STOP", "N"),
                       help="sweep J [-] from START to STOP in N points, at --at-rpm")
    sweep.add_argument("--rpm", type=float, nargs=3, metavar=("START", "STOP", "N"),
                       help="sweep the rotor speed [rpm] from START to STOP in N points, at --v-axial")
    parser.add_argument("--collective-pitch", type=float, nargs=3, metavar=("START", "STOP", "N"),
                        help="collective pitch [deg] added to the twist, from START to STOP in N points: alone, a "
                             "pitch sweep at the design point; with --advance-ratio or --rpm, every pitch at every "
                             "point (one value: START STOP 1)")
    parser.add_argument("--thrust", type=float, default=None, metavar="T",
                        help="trim every point to this thrust [N] by --trim (alone: at the design point)")
    parser.add_argument("--trim", choices=TRIM_VARIABLES, default="collective_pitch",
                        help="what --thrust sets: the collective pitch (default; with a J, airspeed or rpm sweep) "
                             "or the rotor speed (with an airspeed sweep or at the design point)")
    parser.add_argument("--at-rpm", type=float, default=None, metavar="RPM",
                        help="rotor speed [rpm] of a J or airspeed sweep (default: the design rpm stored in the "
                             "file)")
    parser.add_argument("--v-axial", type=float, nargs="+", default=None, metavar="V",
                        help="one value: the axial velocity [m/s] of an rpm or pitch sweep (default: the file's "
                             "design value, else 0); three values START STOP N: sweep the airspeed [m/s] from "
                             "START to STOP in N points, at --at-rpm")
    parser.add_argument("--altitude", type=float, default=None, metavar="H",
                        help="ISA altitude [m] (default: the file's design altitude, else 0)")
    parser.add_argument("--fluid", default=None, metavar="FLUID",
                        help=FLUID_HELP + " (default: the fluid the file keeps, else the ISA)")
    parser.add_argument("--airfoil", default=None, metavar="AIRFOIL",
                        help=AIRFOIL_HELP + " (default: the airfoil the file carries: the JSON's polar, the polar "
                                            "file named in a CSV or QPROP file, else its airfoil name; for a "
                                            "foreign QPROP file, its CL/CD model lines)")
    parser.add_argument("--loss-model", choices=LOSS_MODELS, default=None,
                        help="Prandtl loss factor (default: the file's, else tip_hub)")
    parser.add_argument("--design", type=int, default=0, metavar="I",
                        help="design to analyse in a multi-design JSON file [-]")
    parser.add_argument("--csv", metavar="FILE", help="write the performance table as CSV (units in the header)")
    parser.add_argument("--plot", metavar="FILE.png", help="write the performance curves as PNG (needs matplotlib)")
    return parser


def _sweep_points(option, triple):
    start, stop, count = triple
    count = validation.integer(f"{option} N", count)
    # The smallest blade has 2 stations: a count that cannot fit even then stops before the file is read.
    validation.memory_bound(f"{option} N", count, 2, hint="use fewer points", at_least=True)
    for label, value in (("START", start), ("STOP", stop)):
        if option == "--rpm":
            validation.positive(f"--rpm {label}", value, units="rpm")
        elif option == "--advance-ratio":
            validation.non_negative(f"--advance-ratio {label}", value)
        elif option == "--v-axial":
            validation.non_negative(f"--v-axial {label}", value, units="m/s")
        else:
            validation.real_array(f"{option} {label}", value, units="deg", ndim=(0,))
    return np.linspace(start, stop, count)


def run_analyze(args, out):
    """Read the geometry file of parsed ``analyze`` options, sweep it, print the table and write the files.

    Returns
    -------
    int
        Exit code, 0.
    """
    # Argument errors first: they need no file and leave none behind.
    pitch = None if args.collective_pitch is None else _sweep_points("--collective-pitch", args.collective_pitch)
    v_axial = args.v_axial
    if v_axial is not None and len(v_axial) not in (1, 3):
        raise ValueError(f"--v-axial takes one value V [m/s] or three START STOP N (an airspeed sweep), got "
                         f"{len(v_axial)}")
    airspeeds = v_axial if v_axial is not None and len(v_axial) == 3 else None
    v_axial = v_axial[0] if v_axial is not None and len(v_axial) == 1 else None
    if airspeeds is not None and (args.advance_ratio is not None or args.rpm is not None):
        raise ValueError("--v-axial START STOP N sweeps the airspeed: give it without --advance-ratio and --rpm")
    if args.advance_ratio is not None and v_axial is not None:
        raise ValueError("--advance-ratio fixes the airspeed by J and rpm (V = J n D): leave out --v-axial, or "
                         "sweep the airspeed with --v-axial START STOP N")
    if args.thrust is not None:
        validation.positive("--thrust", args.thrust, units="N")
    if args.advance_ratio is None and args.rpm is None and airspeeds is None and pitch is None and args.thrust is None:
        raise ValueError("give the sweep: --advance-ratio START STOP N, --v-axial START STOP N, --rpm START STOP N "
                         "or --collective-pitch START STOP N, or a trim: --thrust T")
    option, sweep = next(((name, value) for name, value in (("--advance-ratio", args.advance_ratio),
                                                             ("--v-axial", airspeeds), ("--rpm", args.rpm))
                          if value is not None), ("--rpm", None))
    points = _sweep_points(option, sweep) if sweep is not None else np.zeros(1)
    if pitch is not None:
        validation.memory_bound("--collective-pitch N times the sweep's N", pitch.size * points.size, 2,
                                hint="use fewer points", at_least=True)
    for name, value in (("at_rpm", args.at_rpm), ("v_axial", v_axial), ("altitude", args.altitude)):
        if value is not None:
            validation.real_array("--" + name.replace("_", "-"), value, ndim=(0,))
    csv_file = output_file("--csv", args.csv)
    plot_file = figure_file("--plot", args.plot)
    polar = airfoil_polar("--airfoil", args.airfoil)
    geometry = read_geometry(args.geometry, design=args.design, load_polar=polar is None)
    count = points.size * (1 if pitch is None else pitch.size)
    validation.memory_bound("sweep points", count, geometry.num_radial, hint="use fewer points")
    fluid = None if args.fluid is None else fluid_from_text(args.fluid)
    kwargs = dict(altitude=args.altitude, loss_model=args.loss_model, polar=polar, fluid=fluid)
    if args.thrust is not None:
        kwargs.update(thrust=args.thrust, trim=args.trim)
    if pitch is not None:
        kwargs["collective_pitch"] = np.radians(pitch)
    if args.advance_ratio is not None:
        result = off_design_sweep(geometry, advance_ratios=points, rpm=args.at_rpm, **kwargs)
    elif airspeeds is not None:
        result = off_design_sweep(geometry, v_axial=points, rpm=args.at_rpm, **kwargs)
    elif args.rpm is not None:
        result = off_design_sweep(geometry, rpms=points, v_axial=v_axial, **kwargs)
    else:
        result = off_design_sweep(geometry, rpm=args.at_rpm, v_axial=v_axial, **kwargs)
    print(f"geometry: {args.geometry}: {geometry.num_radial} stations, B = {geometry.num_blades}, "
          f"R = {geometry.radius:.6g} m, hub radius {geometry.hub_radius:.6g} m, "
          f"airfoil {args.airfoil or geometry.airfoil or 'from the QPROP CL/CD lines'}", file=out)
    print(result.summary(), file=out)
    if csv_file:
        print(f"wrote {result.to_csv(csv_file)}", file=out)
    if plot_file:
        plot_performance_curves(result, plot_file)
        print(f"wrote {plot_file}", file=out)
    return 0
