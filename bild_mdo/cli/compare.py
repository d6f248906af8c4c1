"""``bild-mdo compare``: a table and an overlay figure of several blade geometry files."""
from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from bild_mdo.cli.files import figure_file
from bild_mdo.io.files import read_geometry
from bild_mdo.plots.blade import plot_blade

#: One-line help of the subcommand.
HELP = "compare several blade geometry files: a table and an overlay figure of chord and twist"
#: Description of the subcommand.
DESCRIPTION = (
    "Read two or more geometry files (CSV, JSON or QPROP, as 'bild-mdo design' writes them, or any QPROP "
    "propeller file) and print one row per file: blades, tip and hub radius [m], stations, airfoil, the design "
    "point the file keeps (thrust [N], power [kW], eta in forward flight or FM in hover), and how far its chord "
    "and twist lie from the first file's, ||x - x_1|| / ||x_1|| [%] over r/R (interpolated onto the first "
    "file's stations).  --plot overlays the planforms and twist distributions.")


def add_compare_arguments(parser):
    """Add the ``compare`` options to an argparse parser and return it."""
    parser.add_argument("geometry", metavar="GEOMETRY_FILE", nargs="+",
                        help="two or more blade geometry files: .csv, .json, or QPROP files")
    parser.add_argument("--plot", metavar="FILE.png", help="write the overlay of planforms and twist as PNG "
                        "(needs matplotlib)")
    return parser


def _difference(reference, other, name):
    """``||x - x_ref|| / ||x_ref||`` (%) of chord or twist over r/R, ``other`` interpolated onto the reference."""
    fractions = reference.radii / reference.radius
    values = np.interp(fractions, other.radii / other.radius, getattr(other, name))
    base = np.linalg.norm(getattr(reference, name))
    return 100.0 * np.linalg.norm(values - getattr(reference, name)) / base if base > 0.0 else float("nan")


def _point(geometry, name, scale=1.0, fmt=".5g"):
    value = geometry.design_point.get(name)
    return f"{value * scale:{fmt}}" if value is not None else "-"


def compare_table(paths, geometries):
    """The lines of the comparison table (the first file is the reference of the differences)."""
    width = max(len(str(path)) for path in paths)
    lines = [f"{'file':<{width}} {'B':>3} {'R [m]':>8} {'hub [m]':>8} {'stations':>8} {'T [N]':>10} "
             f"{'P [kW]':>9} {'eta|FM':>8} {'chord %':>8} {'twist %':>8}  airfoil"]
    reference = geometries[0]
    for path, geometry in zip(paths, geometries):
        hover = geometry.design_point.get("v_axial", 1.0) == 0.0
        merit = _point(geometry, "figure_of_merit" if hover else "efficiency", fmt=".4f")
        merit = merit + (" FM" if hover and merit != "-" else "")
        chord, twist = (("ref", "ref") if geometry is reference else
                        (f"{_difference(reference, geometry, 'chord'):.3f}",
                         f"{_difference(reference, geometry, 'twist'):.3f}"))
        lines.append(f"{str(path):<{width}} {geometry.num_blades:>3d} {geometry.radius:>8.4g} "
                     f"{geometry.hub_radius:>8.4g} {geometry.num_radial:>8d} {_point(geometry, 'thrust'):>10} "
                     f"{_point(geometry, 'power', 1e-3):>9} {merit:>8} {chord:>8} {twist:>8}  "
                     f"{geometry.airfoil or '(QPROP CL/CD lines)'}")
    return lines


def run_compare(args, out):
    """Read the files of parsed ``compare`` options, print the table and write the figure.

    Returns
    -------
    int
        Exit code, 0.
    """
    if len(args.geometry) < 2:
        raise ValueError(f"compare needs at least two geometry files, got {len(args.geometry)}")
    plot_file = figure_file("--plot", args.plot)
    geometries = [read_geometry(path, load_polar=False) for path in args.geometry]
    for line in compare_table(args.geometry, geometries):
        print(line, file=out)
    if plot_file:
        named = [dataclasses.replace(geometry, name=Path(path).name) for path, geometry in zip(args.geometry,
                                                                                               geometries)]
        plot_blade(named, plot_file)
        print(f"wrote {plot_file}", file=out)
    return 0
