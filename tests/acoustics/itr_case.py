"""Test fixture: the Ideally Twisted Rotor (ITR) in hover, with its loads from bild-mdo's own BEM analysis.

Source of the case: N. A. Pettingill, N. S. Zawodny, C. Thurman and L. V. Lopes, "Acoustic and
Performance Characteristics of an Ideally Twisted Rotor in Hover", AIAA 2021-1928 (NTRS 20205003328):
Table 1 and Eq. (1) give the blade, the figure captions the operating point.  Which numbers belong
to which figure was read from the docs and tests of the AcousticAnalogies.jl repository
(docs/src/itr_tests1.md, test/gen_bpmjl_data/itr_with_bpmjl.jl; numbers only, no code):

* ``num_blades = 4``, tip radius ``R = 0.1588 m``, constant chord ``c = 0.2 R``, hub at ``0.2 R``;
* twist ``theta(r) = theta_tip / (r / R)`` with ``theta_tip = 6.9 deg`` (the ideal twist, Eq. 1);
* NACA 0012 sections (``thickness_ratio = 0.12``); the polar is the airfoiltools.com XFOIL polar
  ``xf-n0012-il-500000`` (Re = 5e5, Ncrit = 9, copied into ``data/itr/``, see its README);
* hover (``v_axial = 0``) at ``rpm = 5465`` (the caption of Fig. 22, the paper's nominal case);
* standard day: ``T = 288.15 K``, ``p = 101325 Pa``, gas constant 287.052874 J/(kg K), so
  ``rho = p / (R_gas T)`` and ``speed_of_sound = sqrt(1.4 R_gas T)``; ``mu = 1.4502e-5 rho``;
* observers on an arc of radius 2.27 m about the hub, at elevation angles from the rotor plane,
  positive towards the thrust side (+x, above a lift rotor); the paper's spectra are for
  microphone 5 at -35 deg (below the plane).

Loads: :func:`bild_mdo.bem.analyze.analyze_rotor` with the default Prandtl tip and hub losses, at
``num_radial`` midpoints of equal annuli from hub to tip.  The result is cached per station count,
so importing modules share one analysis.
"""
from __future__ import annotations

import functools
import warnings
from pathlib import Path

import numpy as np

#: Folder of the ITR test data (figure CSVs, the NACA 0012 polar, README.md).
DATA_DIR = Path(__file__).resolve().parent / "data" / "itr"
#: The XFOIL polar of the NACA 0012 at Re = 5e5 (airfoiltools.com, xf-n0012-il-500000).
POLAR_FILE = DATA_DIR / "xf-n0012-il-500000.txt"

NUM_BLADES = 4
RADIUS = 0.1588                   # m, Table 1
HUB_RADIUS = 0.2 * RADIUS         # m
CHORD = 0.2 * RADIUS              # m, constant chord
THETA_TIP = np.deg2rad(6.9)       # rad, Table 1 / Eq. (1)
THICKNESS_RATIO = 0.12            # NACA 0012
RPM = 5465.0                      # caption of Fig. 22
V_AXIAL = 0.0                     # hover
TEMPERATURE = 288.15              # K, standard day
PRESSURE = 101325.0               # Pa
GAS_CONSTANT = 287.052874         # J/(kg K)
RHO = PRESSURE / (GAS_CONSTANT * TEMPERATURE)
SPEED_OF_SOUND = float(np.sqrt(1.4 * GAS_CONSTANT * TEMPERATURE))
MU = 1.4502e-5 * RHO
#: Radius of the microphone arc (m) and the elevation of microphone 5 (deg, below the rotor plane).
OBSERVER_DISTANCE = 2.27
MICROPHONE_5_ELEVATION = -35.0
#: Default number of radial stations.
NUM_RADIAL = 50


def observer_positions(elevation_deg, distance=OBSERVER_DISTANCE):
    """Observer positions (m), shape ``(n, 3)``, in the rotor frame of the noise layer.

    ``elevation_deg`` is the angle from the rotor plane, positive towards +x (the thrust side);
    the polar angle from the +x axis is ``theta = 90 deg - elevation``.  The observers lie in the
    x-y plane (``z = 0``); in axial flight and hover the tones do not depend on the azimuth.
    """
    elevation = np.deg2rad(np.atleast_1d(np.asarray(elevation_deg, dtype=float)))
    return np.stack([distance * np.sin(elevation), distance * np.cos(elevation), np.zeros_like(elevation)], axis=-1)


def read_figure(name):
    """A digitized curve of the paper as ``(x, y)`` arrays sorted by ``y`` (``name`` e.g. ``'figure21a-loading'``)."""
    data = np.loadtxt(DATA_DIR / f"{name}.csv", delimiter=",")
    order = np.argsort(data[:, 1])
    return data[order, 0], data[order, 1]


@functools.lru_cache(maxsize=4)
def _analysis(num_radial):
    from bild_mdo.bem.analyze import analyze_rotor, station_radii

    radii = station_radii(RADIUS, HUB_RADIUS, num_radial)
    chord = np.full(num_radial, CHORD)
    twist = THETA_TIP / (radii / RADIUS)
    with warnings.catch_warnings():
        # One polar at Re = 5e5 serves every station (Re 4e4 ... 2e5 here): known, documented above.
        warnings.filterwarnings("ignore", message=".*Reynolds numbers outside the tabulated range")
        return analyze_rotor(chord, twist, RADIUS, HUB_RADIUS, RPM, V_AXIAL, NUM_BLADES, str(POLAR_FILE),
                             rho=RHO, mu=MU, speed_of_sound=SPEED_OF_SOUND, on_invalid="raise")


def itr_stations(num_radial=NUM_RADIAL):
    """The ITR case as the arrays of the noise layer's shared interface (one design, ``nn = 1``).

    Returns
    -------
    dict
        Per station, shape ``(1, nr)``: ``radii`` (m), ``dr`` (m), ``chord`` (m), ``alpha`` (rad), ``phi`` (rad),
        ``inflow_speed`` (m/s), ``dthrust_dr`` (N/m, all blades), ``dtorque_dr`` (N*m/m, all blades),
        ``thickness_ratio``; per design, shape ``(1,)``: ``rpm`` (rpm), ``v_axial`` (m/s), ``radius`` (m),
        ``hub_radius`` (m), ``rho`` (kg/m**3), ``mu`` (Pa*s), ``speed_of_sound`` (m/s); ``num_blades``
        (int); ``thrust`` (N) and ``torque`` (N*m) of the analysis, shape ``(1,)``; and
        ``observer_position`` (m), shape ``(1, 3, 3)``: microphone 5 (-35 deg) and the two ends of the
        figure's arc (-45 and +45 deg elevation), with ``observer_elevation_deg`` their angles.
        Fresh copies: callers may modify them.
    """
    res = _analysis(int(num_radial))
    nr = int(num_radial)

    def dist(values):
        return np.array(values, dtype=float).reshape(1, nr)

    def node(value):
        return np.array(value, dtype=float).reshape(1)

    elevations = np.array([MICROPHONE_5_ELEVATION, -45.0, 45.0])
    return {
        "radii": dist(res.radii), "dr": dist(res.dr), "chord": dist(np.full(nr, CHORD)),
        "alpha": dist(res.alpha), "inflow_speed": dist(res.inflow_speed), "phi": dist(res.phi),
        "dthrust_dr": dist(res.dthrust_dr), "dtorque_dr": dist(res.dtorque_dr),
        "thickness_ratio": dist(np.full(nr, THICKNESS_RATIO)),
        "rpm": node(RPM), "v_axial": node(V_AXIAL), "radius": node(RADIUS), "hub_radius": node(HUB_RADIUS),
        "rho": node(RHO), "mu": node(MU), "speed_of_sound": node(SPEED_OF_SOUND),
        "num_blades": NUM_BLADES, "thrust": node(res.thrust), "torque": node(res.torque),
        "observer_position": observer_positions(elevations)[None, :, :],
        "observer_elevation_deg": elevations,
    }
