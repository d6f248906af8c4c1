"""``bild-mdo noise``: tonal and broadband noise of a blade geometry file at observers, with its figures."""
from __future__ import annotations

import numpy as np

from bild_mdo import validation
from bild_mdo.acoustics.bpm.bluntness import MAX_TRAILING_EDGE_ANGLE, NACA0012_TRAILING_EDGE_ANGLE
from bild_mdo.acoustics.rotor_noise_group import check_observers
from bild_mdo.bem.analyze import analyze_rotor
from bild_mdo.cli.files import AIRFOIL_HELP, airfoil_polar, figure_file
from bild_mdo.io.airfoil import resolve_airfoil
from bild_mdo.io.files import read_geometry
from bild_mdo.plots.noise import arc_observers, plot_directivity, plot_noise_spectrum
from bild_mdo.results.noise import rotor_noise

#: One-line help of the subcommand.
HELP = "tonal and broadband noise of a blade geometry file at observers (dB, dBA), spectrum and directivity plots"
#: Description of the subcommand.
DESCRIPTION = (
    "Analyse a blade (a CSV, JSON or QPROP file as written by 'bild-mdo design') with BEM at its design point "
    "(or --rpm, --v-axial, --altitude) and compute its far-field noise at each --observer X Y Z [m] in the rotor "
    "frame: x along the rotor axis in the direction of the thrust (an observer on the ground below a hovering "
    "lift rotor has x < 0), y and z in the disc plane.  Tonal noise: Hanson's compact far-field loading and "
    "thickness noise at the blade-passage harmonics; broadband: BPM self-noise in 1/3-octave bands.  Prints "
    "OASPL [dB] and A-weighted level [dBA] per observer.")
# Observers of the --directivity arc.
_ARC_POINTS = 37


def add_noise_arguments(parser):
    """Add the ``noise`` options to an argparse parser and return it."""
    parser.add_argument("geometry", metavar="GEOMETRY_FILE", help="blade geometry: .csv, .json, or a QPROP file")
    parser.add_argument("--observer", type=float, nargs=3, action="append", metavar=("X", "Y", "Z"),
                        required=True, help="observer position [m] in the rotor frame (x along the thrust); "
                                            "repeat for several observers")
    parser.add_argument("--harmonics", type=int, default=10, metavar="N",
                        help="blade-passage harmonics of the tonal noise [-] (default 10)")
    parser.add_argument("--untripped", action="store_true",
                        help="BPM boundary-layer fits of an untripped (clean) section (default: tripped)")
    parser.add_argument("--trailing-edge-thickness", type=float, default=0.0, metavar="H",
                        help="trailing-edge thickness [m] at every station, for the BPM bluntness noise "
                             "(default 0: a sharp edge, no bluntness noise)")
    parser.add_argument("--trailing-edge-angle", type=float, default=NACA0012_TRAILING_EDGE_ANGLE, metavar="PSI",
                        help="solid angle between the surfaces at the trailing edge [deg] (default 14, NACA 0012; "
                             "at most 30)")
    parser.add_argument("--azimuths", type=int, default=24, metavar="N",
                        help="azimuth samples of the broadband noise [-] (default 24; fewer are coarser, most near "
                             "the disc plane)")
    parser.add_argument("--rpm", type=float, default=None, metavar="RPM",
                        help="rotor speed [rpm] (default: the file's design rpm)")
    parser.add_argument("--v-axial", type=float, default=None, metavar="V",
                        help="axial velocity [m/s] (default: the file's design value, else 0)")
    parser.add_argument("--altitude", type=float, default=None, metavar="H",
                        help="ISA altitude [m] (default: the file's design altitude, else 0)")
    parser.add_argument("--airfoil", default=None, metavar="AIRFOIL",
                        help=AIRFOIL_HELP + " (default: the airfoil the file carries)")
    parser.add_argument("--design", type=int, default=0, metavar="I",
                        help="design to analyse in a multi-design JSON file [-]")
    parser.add_argument("--plot", metavar="FILE.png", help="write the spectra of the observers as PNG")
    parser.add_argument("--directivity", metavar="FILE.png",
                        help="write OASPL and dBA against the polar angle on an arc through the first observer "
                             "(37 observers from 0 to 180 deg in the plane of the axis and that observer) as PNG")
    return parser


def _design_value(geometry, name, given, default):
    if given is not None:
        return given
    value = geometry.design_point.get(name)
    if value is None and default is None:
        raise ValueError(f"the geometry file keeps no design {name}; give --{name.replace('_', '-')}")
    return default if value is None else float(value)


def _arc(first):
    """Observers on the arc through ``first`` in the plane of the rotor axis and ``first``."""
    distance = float(np.linalg.norm(first))
    arc = arc_observers(distance, _ARC_POINTS)
    side = np.array([0.0, first[1], first[2]])
    norm = np.linalg.norm(side)
    side = np.array([0.0, 1.0, 0.0]) if norm == 0.0 else side / norm
    return np.outer(arc[:, 0] / distance, [distance, 0.0, 0.0]) + np.outer(arc[:, 1], side)


def run_noise(args, out):
    """Read the geometry file, analyse it at its operating point, print the noise table and write the figures.

    Returns
    -------
    int
        Exit code, 0.
    """
    observers = check_observers(args.observer)
    harmonics = validation.integer("--harmonics", args.harmonics, minimum=1)
    azimuths = validation.integer("--azimuths", args.azimuths, minimum=1)
    for option, value in (("--rpm", args.rpm), ("--v-axial", args.v_axial), ("--altitude", args.altitude)):
        if value is not None:
            validation.real_array(option, value, ndim=(0,))
    if args.rpm is not None:
        validation.positive("--rpm", args.rpm, units="rpm")
    if args.v_axial is not None:
        validation.non_negative("--v-axial", args.v_axial, units="m/s")
    validation.non_negative("--trailing-edge-thickness", args.trailing_edge_thickness, units="m")
    validation.in_range("--trailing-edge-angle", args.trailing_edge_angle, 0.0, MAX_TRAILING_EDGE_ANGLE, units="deg")
    plot_file = figure_file("--plot", args.plot)
    directivity_file = figure_file("--directivity", args.directivity)
    polar = airfoil_polar("--airfoil", args.airfoil)
    geometry = read_geometry(args.geometry, design=args.design, load_polar=polar is None)
    if polar is None:
        polar = geometry.polar if geometry.polar is not None else (
            resolve_airfoil(geometry.airfoil) if geometry.airfoil else None)
    if polar is None:
        raise ValueError("the geometry file names no airfoil; give --airfoil")
    check_observers(observers, radius=geometry.radius)
    rotor = dict(chord=geometry.chord, rpm=_design_value(geometry, "rpm", args.rpm, None),
                 v_axial=_design_value(geometry, "v_axial", args.v_axial, 0.0), radius=geometry.radius,
                 hub_radius=geometry.hub_radius, num_blades=geometry.num_blades)
    altitude = _design_value(geometry, "altitude", args.altitude, 0.0)
    analysis = analyze_rotor(twist=geometry.twist, radii=geometry.radii, polar=polar, altitude=altitude,
                             loss_model=geometry.loss_model or "tip_hub", **rotor)
    boundary_layer = "untripped" if args.untripped else "tripped"
    edge = dict(trailing_edge_thickness=args.trailing_edge_thickness, trailing_edge_angle=args.trailing_edge_angle,
                num_azimuth=azimuths)
    noise = rotor_noise(analysis, observers, num_harmonics=harmonics, boundary_layer=boundary_layer, polar=polar,
                        **edge, **rotor)
    print(f"geometry: {args.geometry}: {len(geometry.radii)} stations, B = {geometry.num_blades}, "
          f"R = {geometry.radius:.6g} m, airfoil {getattr(polar, 'name', polar)}; BEM thrust "
          f"{float(analysis.thrust):.6g} N, power {float(analysis.power) / 1e3:.6g} kW", file=out)
    print(noise.summary(), file=out)
    if plot_file:
        plot_noise_spectrum(noise, plot_file)
        print(f"wrote {plot_file}", file=out)
    if directivity_file:
        arc = rotor_noise(analysis, _arc(observers[0]), num_harmonics=harmonics, boundary_layer=boundary_layer,
                          polar=polar, **edge, **rotor)
        plot_directivity(arc, directivity_file)
        print(f"wrote {directivity_file}", file=out)
    return 0
