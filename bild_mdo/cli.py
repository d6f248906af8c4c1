"""The ``bild-mdo`` command: design rotors with BILD, analyse them off-design, run the verification sweep.

::

    bild-mdo demo                                    # the paper's rotor: tables, geometry files and PNGs
    bild-mdo design                                  # the paper's hover rotor (R = 1.5 m, B = 3, 800 rpm)
    bild-mdo design --advance-ratio 1.0 --csv blade.csv --qprop blade.prop --plot blade.png
    bild-mdo design --ref-chord 0.1 0.15 0.2         # a batch of three designs in one run
    bild-mdo analyze blade.csv --advance-ratio 0 2 21 --plot eta.png
    bild-mdo verify --levels 3 --workers 2

Errors in the arguments or from the library (``ValueError``,
``openmdao.api.AnalysisError``, missing files) print one line on stderr and
exit with code 2; ``--debug`` shows the traceback.  :func:`main` returns the
exit code.
"""
from __future__ import annotations

import argparse
import sys
import traceback
import warnings

from bild_mdo import __version__
from bild_mdo.airfoil.builtin import available_polars
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bild.chord import CHORD_FORMS

EXIT_USAGE = 2


class UsageError(Exception):
    """A command-line argument error (reported as one line, exit code 2)."""

    def __init__(self, prog, message):
        super().__init__(message)
        self.prog = prog


class _Parser(argparse.ArgumentParser):
    """ArgumentParser that raises instead of printing the usage block and exiting."""

    def error(self, message):
        raise UsageError(self.prog, message)


class _HelpFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """Defaults in the help, except for options whose absence has a meaning the help text explains."""

    def _get_help_string(self, action):
        if action.default is None or isinstance(action.default, bool) or "default" in (action.help or ""):
            return action.help
        return super()._get_help_string(action)


def _add_debug(parser, top_level=False):
    # On subcommands the default is SUPPRESS so a --debug given before the subcommand survives.
    parser.add_argument("--debug", action="store_true", default=False if top_level else argparse.SUPPRESS,
                        help="show the full traceback when an error occurs")


def _design_parser(sub):
    p = sub.add_parser(
        "design", formatter_class=_HelpFormatter,
        help="design ideal rotor blades with the BILD method (paper Alg. 1)",
        description="Design the ideal chord and twist of a rotor with the BILD method (Ruh & Hwang 2023, "
                    "Alg. 1) and print the station table and performance.  The defaults are the paper's rotor: "
                    "R = 1.5 m, B = 3, 800 rpm, NACA 4412, c_ref = 0.15 m at r/R = 0.5, hover, 30 stations.  "
                    "Numeric operating and sizing options take one value or several (a batch of designs, "
                    "computed in one vectorised run; lists must have equal lengths).  Units are SI.")
    speed = p.add_mutually_exclusive_group()
    speed.add_argument("--v-axial", type=float, nargs="+", default=0.0, metavar="V",
                       help="axial (climb/flight) velocity [m/s]; 0 is hover")
    speed.add_argument("--advance-ratio", type=float, nargs="+", default=None, metavar="J",
                       help="advance ratio J = V/(nD) [-], instead of --v-axial")
    p.add_argument("--rpm", type=float, nargs="+", default=800.0, metavar="RPM", help="rotor speed [rpm]")
    p.add_argument("--radius", type=float, nargs="+", default=1.5, metavar="R", help="tip radius R [m]")
    p.add_argument("--hub-radius-ratio", type=float, nargs="+", default=0.2, metavar="X",
                   help="hub radius / tip radius [-]")
    p.add_argument("--ref-radius-ratio", type=float, nargs="+", default=0.5, metavar="X",
                   help="reference station r_ref / R [-]")
    p.add_argument("--ref-chord", type=float, nargs="+", default=0.15, metavar="C",
                   help="chord at the reference station c_ref [m]")
    p.add_argument("--altitude", type=float, nargs="+", default=0.0, metavar="H",
                   help="geometric altitude for the ISA atmosphere [m], 0 ... 11000")
    p.add_argument("--num-blades", type=int, default=3, metavar="B", help="number of blades B [-]")
    p.add_argument("--airfoil", choices=available_polars(), default="naca4412",
                   help="airfoil polar (naca4412: built-in XFOIL surrogate; analytic: closed-form test polar)")
    p.add_argument("--num-radial", type=int, default=30, metavar="N",
                   help="radial stations [-] (midpoints of equal annuli from hub to tip)")
    p.add_argument("--loss-model", choices=LOSS_MODELS, default="tip_hub", help="Prandtl loss factor")
    p.add_argument("--chord-form", choices=CHORD_FORMS, default="thrust",
                   help="back-compute the chord from the thrust (Eq. (31)) or the torque balance")
    p.add_argument("--root-chord-correction", type=float, default=None, metavar="K",
                   help="k of the root-chord correction, Eq. (32) [-]; omit for none")
    out = p.add_argument_group("output files")
    out.add_argument("--csv", metavar="FILE", help="write the geometry table r [m], chord [m], twist [deg] "
                     "(a batch writes FILE_<i>.csv per design)")
    out.add_argument("--json", metavar="FILE", help="write geometry, performance and distributions as JSON")
    out.add_argument("--qprop", metavar="FILE", help="write a QPROP propeller file (r, c in m; beta in deg)")
    out.add_argument("--plot", metavar="FILE.png", help="write planform and twist as PNG (needs matplotlib)")
    _add_debug(p)
    p.set_defaults(handler=_run_design)


def _analyze_parser(sub):
    p = sub.add_parser(
        "analyze", formatter_class=_HelpFormatter,
        help="BEM off-design analysis of a blade geometry file over J or rpm",
        description="Analyse a fixed blade (a CSV, JSON or QPROP file as written by 'bild-mdo design', or any "
                    "QPROP propeller file) with BEM over a range of advance ratios J = V/(nD) [-] at fixed rpm, "
                    "or of rotor speeds [rpm] at fixed axial velocity [m/s], in one vectorised run.  Prints "
                    "T [N], Q [N m], P [kW], eta, FM, C_T, C_Q, C_P and the maximum-efficiency point.")
    p.add_argument("geometry", metavar="GEOMETRY_FILE", help="blade geometry: .csv, .json, or a QPROP file")
    sweep = p.add_mutually_exclusive_group(required=True)
    sweep.add_argument("--advance-ratio", type=float, nargs=3, metavar=("START", "STOP", "N"),
                       help="sweep J [-] from START to STOP in N points, at --at-rpm")
    sweep.add_argument("--rpm", type=float, nargs=3, metavar=("START", "STOP", "N"),
                       help="sweep the rotor speed [rpm] from START to STOP in N points, at --v-axial")
    p.add_argument("--at-rpm", type=float, default=None, metavar="RPM",
                   help="rotor speed [rpm] of a J sweep (default: the design rpm stored in the file)")
    p.add_argument("--v-axial", type=float, default=None, metavar="V",
                   help="axial velocity [m/s] of an rpm sweep (default: the file's design value, else 0)")
    p.add_argument("--altitude", type=float, default=None, metavar="H",
                   help="ISA altitude [m] (default: the file's design altitude, else 0)")
    p.add_argument("--airfoil", choices=available_polars(), default=None,
                   help="airfoil polar (default: the airfoil named in the file; for a foreign QPROP file, "
                        "its CL/CD model lines)")
    p.add_argument("--loss-model", choices=LOSS_MODELS, default=None,
                   help="Prandtl loss factor (default: the file's, else tip_hub)")
    p.add_argument("--design", type=int, default=0, metavar="I",
                   help="design to analyse in a multi-design JSON file [-]")
    p.add_argument("--csv", metavar="FILE", help="write the performance table as CSV (units in the header)")
    p.add_argument("--plot", metavar="FILE.png", help="write the performance curves as PNG (needs matplotlib)")
    _add_debug(p)
    p.set_defaults(handler=_run_analyze)


_VERIFY_DESCRIPTION = (
    "Reproduce the paper's verification (Sec. 5.1, Table 3): a full-factorial sweep of advance ratio J "
    "(0 ... 3) [-], tip radius (0.5 ... 1.5 m), altitude (0 ... 3000 m) and reference chord (0.08 ... 0.22 m) "
    "at 800 rpm and r_ref/R = 0.5, designing every case with BILD in one batch and optimising each with BEM; "
    "prints the Table 3 statistics.  Results go to an SQLite store that a rerun resumes.")


def _verify_parser(sub):
    p = sub.add_parser("verify", formatter_class=_HelpFormatter,
                       help="verification sweep against BEM optimisation (paper Table 3)",
                       description=_VERIFY_DESCRIPTION)
    try:
        from bild_mdo.verification.runner import add_verify_arguments
    except ImportError as exc:
        # The other subcommands must keep working when the verification machinery is absent.
        p.set_defaults(handler=_verify_unavailable, verify_error=f"{exc}")
        p.add_argument("rest", nargs=argparse.REMAINDER, help=argparse.SUPPRESS)
    else:
        add_verify_arguments(p)
        p.set_defaults(handler=_run_verify)
    _add_debug(p)


def _demo_parser(sub):
    p = sub.add_parser(
        "demo", formatter_class=_HelpFormatter,
        help="design the paper's rotor and write its station table, files and figures",
        description="Design the paper's default rotor (R = 1.5 m, B = 3, 800 rpm, NACA 4412, c_ref = 0.15 m at "
                    "r/R = 0.5, hover, 30 stations), print its performance [N, N m, kW] and station table "
                    "(r [m], chord [m], twist [deg]), and write into DIR: the blade geometry (CSV, JSON, QPROP), "
                    "the planform/twist PNG, and the off-design efficiency curve of a rotor designed for "
                    "J = 1 (the paper's Fig. 9).")
    p.add_argument("--output-dir", metavar="DIR", default="bild-mdo-demo", help="directory for the files")
    _add_debug(p)
    p.set_defaults(handler=_run_demo)


def build_parser():
    """The ``bild-mdo`` argument parser (subcommands design, analyze, verify, demo).

    Returns
    -------
    argparse.ArgumentParser
    """
    parser = _Parser(prog="bild-mdo", formatter_class=_HelpFormatter,
                     description="BILD: fast ideal-loading design of rotors with BEM theory (Ruh & Hwang, "
                                 "AIAA J. 61(9), 2023).  SI units: m, m/s, N, W; rotor speed in rpm.")
    parser.add_argument("--version", action="version", version=f"bild-mdo {__version__}")
    _add_debug(parser, top_level=True)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", title="commands")
    _design_parser(sub)
    _analyze_parser(sub)
    _verify_parser(sub)
    _demo_parser(sub)
    return parser


# -- handlers -------------------------------------------------------------------------------------------
def _scalar_or_list(values):
    if not isinstance(values, list):
        return values
    return values[0] if len(values) == 1 else values


def _run_design(args, out):
    from bild_mdo.design import design_rotor

    speed = ({"advance_ratio": _scalar_or_list(args.advance_ratio)} if args.advance_ratio is not None
             else {"v_axial": _scalar_or_list(args.v_axial)})
    result = design_rotor(**speed, rpm=_scalar_or_list(args.rpm), radius=_scalar_or_list(args.radius),
                          hub_radius_ratio=_scalar_or_list(args.hub_radius_ratio),
                          ref_radius_ratio=_scalar_or_list(args.ref_radius_ratio),
                          ref_chord=_scalar_or_list(args.ref_chord), altitude=_scalar_or_list(args.altitude),
                          num_blades=args.num_blades, airfoil=args.airfoil, num_radial=args.num_radial,
                          loss_model=args.loss_model, chord_form=args.chord_form,
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
        from pathlib import Path

        from bild_mdo.geometry_io import write_qprop

        base = Path(args.qprop)
        for i, design in enumerate(result):
            target = base if not result.is_batch else base.with_name(f"{base.stem}_{i}{base.suffix}")
            written.append(write_qprop(target, design))
    if args.plot:
        from bild_mdo.plots import plot_blade

        plot_blade(result, args.plot)
        written.append(args.plot)
    for path in written:
        print(f"wrote {path}", file=out)
    return 0


def _sweep_points(name, triple):
    start, stop, count = triple
    if count != int(count) or count < 1:
        raise UsageError(f"bild-mdo analyze {name}", f"N must be a positive integer, got {count:g}")
    import numpy as np

    return np.linspace(start, stop, int(count))


def _run_analyze(args, out):
    from bild_mdo.geometry_io import read_geometry
    from bild_mdo.off_design import off_design_sweep

    # Argument errors first: they need no file.
    points = (_sweep_points("--advance-ratio", args.advance_ratio) if args.advance_ratio is not None
              else _sweep_points("--rpm", args.rpm))
    geometry = read_geometry(args.geometry, design=args.design)
    kwargs = dict(altitude=args.altitude, loss_model=args.loss_model, polar=args.airfoil)
    if args.advance_ratio is not None:
        result = off_design_sweep(geometry, advance_ratios=points, rpm=args.at_rpm, **kwargs)
    else:
        result = off_design_sweep(geometry, rpms=points, v_axial=args.v_axial, **kwargs)
    print(f"geometry: {args.geometry}: {geometry.num_radial} stations, B = {geometry.num_blades}, "
          f"R = {geometry.radius:.6g} m, hub radius {geometry.hub_radius:.6g} m, "
          f"airfoil {args.airfoil or geometry.airfoil or 'from the QPROP CL/CD lines'}", file=out)
    print(result.summary(), file=out)
    if args.csv:
        print(f"wrote {result.to_csv(args.csv)}", file=out)
    if args.plot:
        from bild_mdo.plots import plot_performance_curves

        plot_performance_curves(result, args.plot)
        print(f"wrote {args.plot}", file=out)
    return 0


def _run_verify(args, out):
    from bild_mdo.verification.case_functions import bild_batch, optimize_case
    from bild_mdo.verification.runner import run_verify_from_args

    run_verify_from_args(args, bild_batch, optimize_case, stream=out)
    return 0


def _run_demo(args, out):
    from pathlib import Path

    import numpy as np

    from bild_mdo.design import design_rotor
    from bild_mdo.geometry_io import write_qprop
    from bild_mdo.off_design import off_design_sweep

    folder = Path(args.output_dir)
    folder.mkdir(parents=True, exist_ok=True)
    rotor = design_rotor()
    print(rotor.summary(), file=out)
    print("\nstations:", file=out)
    print(rotor.station_table(), file=out)
    written = rotor.to_csv(folder / "hover_blade.csv") + [rotor.to_json(folder / "hover_blade.json"),
                                                          write_qprop(folder / "hover_blade.prop", rotor)]
    cruise = design_rotor(advance_ratio=1.0)
    sweep = off_design_sweep(cruise, advance_ratios=np.linspace(0.2, 2.0, 19))
    print(f"\nrotor designed for J = 1: eta = {cruise.efficiency:.4f} at the design point; off design:", file=out)
    print(sweep.summary(), file=out)
    try:
        from bild_mdo.plots import plot_blade, plot_performance_curves

        figures = {"hover_blade.png": lambda path: plot_blade(rotor, path),
                   "blades_J0-2.png": lambda path: plot_blade(
                       design_rotor(advance_ratio=[0.0, 0.5, 1.0, 1.5, 2.0]), path),
                   "efficiency_Jdes1.png": lambda path: plot_performance_curves(sweep, path)}
        for name, draw in figures.items():
            draw(folder / name)
            written.append(folder / name)
    except ImportError as exc:
        print(f"figures skipped: {exc}", file=out)
    for path in written:
        print(f"wrote {path}", file=out)
    return 0


def _verify_unavailable(args, out):
    raise ImportError(f"the verification sweep is unavailable: {args.verify_error}")


# -- entry point ------------------------------------------------------------------------------------------
def _one_line(text):
    return " ".join(str(text).split())


def _show_warning(message, category, filename, lineno, file=None, line=None):
    print(f"bild-mdo: warning: {_one_line(message)}", file=sys.stderr if file is None else file)


def main(argv=None):
    """Run the ``bild-mdo`` command.

    Parameters
    ----------
    argv : list of str, optional
        Arguments without the program name (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit code: 0 on success, 2 for bad arguments or a failed analysis.
    """
    import openmdao.api as om

    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except UsageError as err:
        print(f"{err.prog}: error: {_one_line(err)} (see '{err.prog} --help')", file=sys.stderr)
        return EXIT_USAGE
    except SystemExit as done:  # --help and --version
        return done.code if isinstance(done.code, int) else 0
    if args.command is None:
        print("bild-mdo: error: give a command: design, analyze, verify or demo (see 'bild-mdo --help')",
              file=sys.stderr)
        return EXIT_USAGE
    debug = getattr(args, "debug", False)
    try:
        with warnings.catch_warnings():
            if not debug:
                warnings.showwarning = _show_warning
            return args.handler(args, sys.stdout)
    except UsageError as err:
        print(f"{err.prog}: error: {_one_line(err)}", file=sys.stderr)
        return EXIT_USAGE
    except (ValueError, om.AnalysisError, OSError, ImportError) as err:
        if debug:
            traceback.print_exc()
        print(f"bild-mdo {args.command}: error: {_one_line(err)}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        print("bild-mdo: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
