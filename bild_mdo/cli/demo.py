"""``bild-mdo demo``: design the paper's rotor and write its station table, files and figures."""
from __future__ import annotations

import numpy as np

from bild_mdo.cli.files import AIRFOIL_HELP, airfoil_polar, output_folder
from bild_mdo.io.airfoil import polar_file_for
from bild_mdo.io.qprop import write_qprop
from bild_mdo.plots.blade import plot_blade
from bild_mdo.plots.curves import plot_performance_curves
from bild_mdo.results.design import design_rotor
from bild_mdo.results.off_design import off_design_sweep

#: One-line help of the subcommand.
HELP = "design the paper's rotor and write its station table, files and figures"
#: Description of the subcommand.
DESCRIPTION = (
    "Design the paper's default rotor (R = 1.5 m, B = 3, 800 rpm, NACA 4412 or --airfoil, c_ref = 0.15 m at "
    "r/R = 0.5, hover, 30 stations), print its performance [N, N m, kW] and station table (r [m], chord [m], "
    "twist [deg]), and write into DIR: the blade geometry (CSV, JSON, QPROP), the planform/twist PNG, and the "
    "off-design efficiency curve of a rotor designed for J = 1 (the paper's Fig. 9).")


def add_demo_arguments(parser):
    """Add the ``demo`` options to an argparse parser and return it."""
    parser.add_argument("--output-dir", metavar="DIR", default="bild-mdo-demo", help="directory for the files")
    parser.add_argument("--airfoil", default="naca4412", metavar="AIRFOIL", help=AIRFOIL_HELP)
    return parser


def run_demo(args, out):
    """Design the paper's rotor, print its tables and write its files and figures into ``args.output_dir``.

    Returns
    -------
    int
        Exit code, 0.
    """
    if not str(args.output_dir).strip():
        raise ValueError("--output-dir is empty: give the folder for the demo's files (default bild-mdo-demo), "
                         "or '.' for the current folder")
    folder = output_folder("--output-dir", args.output_dir)
    polar = airfoil_polar("--airfoil", args.airfoil)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise ValueError(f"--output-dir {folder}: cannot create the folder ({err.strerror})") from None
    rotor = design_rotor(airfoil=polar)
    print(rotor.summary(), file=out)
    print("\nstations:", file=out)
    print(rotor.station_table(), file=out)
    written = rotor.to_csv(folder / "hover_blade.csv") + [rotor.to_json(folder / "hover_blade.json"),
                                                          write_qprop(folder / "hover_blade.prop", rotor)]
    # The CSV and QPROP files name this polar file where the airfoil's name does not rebuild its polar.
    written += [path for path in [polar_file_for(folder / "hover_blade.csv")] if path.is_file()]
    cruise = design_rotor(advance_ratio=1.0, airfoil=polar)
    sweep = off_design_sweep(cruise, advance_ratios=np.linspace(0.2, 2.0, 19))
    print(f"\nrotor designed for J = 1: eta = {cruise.efficiency:.4f} at the design point; off design:", file=out)
    print(sweep.summary(), file=out)

    def blades(path):
        plot_blade(design_rotor(advance_ratio=[0.0, 0.5, 1.0, 1.5, 2.0], airfoil=polar), path)

    figures = {"hover_blade.png": lambda path: plot_blade(rotor, path),
               "blades_J0-2.png": blades,
               "efficiency_Jdes1.png": lambda path: plot_performance_curves(sweep, path)}
    try:
        for name, draw in figures.items():
            draw(folder / name)
            written.append(folder / name)
    except ImportError as exc:
        print(f"figures skipped: {exc}", file=out)
    for path in written:
        print(f"wrote {path}", file=out)
    return 0
