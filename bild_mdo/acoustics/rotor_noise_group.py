"""RotorNoiseGroup: tonal and broadband noise of a rotor at far-field observers, and their levels in dB.

Also :func:`make_noise_group`, the group that the noise options of a rotor group ask for
(:mod:`bild_mdo.acoustics.noise_options`).
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.acoustics.bands import THIRD_OCTAVE_CENTRES
from bild_mdo.acoustics.bpm.bluntness import MAX_TRAILING_EDGE_ANGLE, NACA0012_TRAILING_EDGE_ANGLE
from bild_mdo.acoustics.broadband_noise import BroadbandNoiseComp
from bild_mdo.acoustics.noise_options import (BOUNDARY_LAYERS, BROADBAND_OUTPUTS, LEVEL_OUTPUTS, TONAL_OUTPUTS,
                                              check_boundary_layer, check_observers, check_observers_option)
from bild_mdo.acoustics.noise_totals import NoiseTotalsComp
from bild_mdo.acoustics.section_thickness import SectionThicknessComp
from bild_mdo.acoustics.tonal_noise import TonalNoiseComp
from bild_mdo.utils.options import declare_size_options

# Default observer (without the option observers): 10 m below the rotor, on its axis.
_DEFAULT_OBSERVER = np.array([[-10.0, 0.0, 0.0]])

__all__ = ["BOUNDARY_LAYERS", "RotorNoiseGroup", "check_observers", "make_noise_group"]


class RotorNoiseGroup(om.Group):
    """Far-field rotor noise at observers: tonal (loading, thickness) and broadband (BPM) sources, levels.

    ::

        thickness   SectionThicknessComp   airfoil, radii / radius -> thickness_ratio[nn, nr]
        tonal       TonalNoiseComp         Hanson's compact far field: loading and thickness per harmonic
        broadband   BroadbandNoiseComp     BPM self-noise per mechanism and 1/3-octave band (include_broadband)
        totals      NoiseTotalsComp        tonal_spl, band_spl, oaspl, oaspl_dba

    A feed-forward chain (RunOnce).  The sources exchange mean-square pressures (Pa**2); only the totals
    take decibels, with the floor of :mod:`bild_mdo.acoustics.bands` (a silent source reads -100 dB).
    Frame: x along the rotor axis in the thrust direction (an observer below a hovering lift rotor has
    x < 0), y and z in the disc plane, the rotor centre at the origin.

    Options
    -------
    num_nodes, num_radial : int
        Designs / operating points (axis 0) and stations (axis 1).
    num_observers : int
        Observers per node.
    num_harmonics : int
        Blade-passage harmonics ``m = 1 ... nh`` (default 10).
    num_blades : int
        Number of blades B (default 3).
    band_frequencies : array_like
        Band centre frequencies (Hz), default the 31 one-third-octave bands 20 Hz - 20 kHz.
    boundary_layer : str
        ``'tripped'`` (default) or ``'untripped'``: BPM's boundary-layer thickness fits.
    include_broadband : bool
        True (default); False leaves the BPM sources out (tones only).
    polar : Polar or None
        The blade's airfoil, for the section thickness (None: built-in NACA 4412, t/c = 0.12).
    observers : array_like or None
        Default value of the input ``observer_position``: ``(num_observers, 3)`` positions (m) used at
        every node; None: 10 m behind the rotor on its axis, ``(-10, 0, 0)``.

    Inputs
    ------
    observer_position[nn, no, 3] (m)
        Observer positions in the rotor frame.
    rpm[nn] (rpm), v_axial[nn] (m/s), radius[nn] (m), hub_radius[nn] (m), rho[nn] (kg/m**3), mu[nn] (Pa*s),
    speed_of_sound[nn] (m/s)
        Operating condition and fluid (those that the sources use).
    radii, dr, chord[nn, nr] (m), dthrust_dr[nn, nr] (N/m), dtorque_dr[nn, nr] (N*m/m), alpha[nn, nr] (rad),
    phi[nn, nr] (rad), inflow_speed[nn, nr] (m/s)
        Stations, blade and loads (thrust and torque per unit span of all blades; the chord pitched
        ``phi + alpha`` from the disc plane).

    Outputs
    -------
    loading_pressure_squared, thickness_pressure_squared, tonal_pressure_squared[nn, no, nh] (Pa**2)
        Mean-square pressure of each harmonic (tonal: loading and thickness added as complex amplitudes).
    tonal_frequency[nn, nh] (Hz)
        ``m B Omega / (2 pi)``.
    broadband_source_pressure_squared[nn, no, ns, nb], broadband_pressure_squared[nn, no, nb] (Pa**2)
        Per BPM mechanism (:data:`~bild_mdo.acoustics.broadband_noise.BROADBAND_SOURCES`) and summed.
    tonal_spl[nn, no, nh], band_spl[nn, no, nb], oaspl[nn, no] (dB), oaspl_dba[nn, no] (dBA)
        Levels re 20 uPa (OpenMDAO units None).
    """

    def initialize(self):
        declare_size_options(self.options)
        self.options.declare("num_observers", types=int, default=1, lower=1, desc="observers per node")
        self.options.declare("num_harmonics", types=int, default=10, lower=1, desc="blade-passage harmonics")
        self.options.declare("num_blades", types=int, default=3, desc="number of blades B")
        self.options.declare("band_frequencies", default=THIRD_OCTAVE_CENTRES,
                             desc="centre frequencies of the broadband bands (Hz)")
        self.options.declare("boundary_layer", default="tripped", check_valid=check_boundary_layer,
                             desc="BPM boundary-layer thickness fits: 'tripped' or 'untripped'")
        self.options.declare("include_broadband", types=bool, default=True,
                             desc="add the BPM broadband self-noise (False: tones only)")
        self.options.declare("num_azimuth", types=int, default=24, lower=1,
                             desc="azimuth samples of the blade around the disc, of the broadband noise")
        self.options.declare("trailing_edge_angle", types=float, default=NACA0012_TRAILING_EDGE_ANGLE, lower=0.0,
                             upper=MAX_TRAILING_EDGE_ANGLE,
                             desc="solid angle Psi (deg) of the trailing edge, of the bluntness noise")
        self.options.declare("polar", default=None, allow_none=True, recordable=False,
                             desc="airfoil Polar for the section thickness; None selects the built-in NACA 4412")
        self.options.declare("observers", default=None, allow_none=True, check_valid=check_observers_option,
                             desc="(num_observers, 3) default observer positions (m), the same at every node")

    def setup(self):
        opts = self.options
        nn, nr, no = opts["num_nodes"], opts["num_radial"], opts["num_observers"]
        size = dict(num_nodes=nn, num_radial=nr)
        observers = dict(num_observers=no)
        self.add_subsystem("thickness", SectionThicknessComp(**size, polar=opts["polar"]),
                           promotes_inputs=["radii", "radius"], promotes_outputs=["thickness_ratio"])
        # The sources declare the shared input names of bild_mdo.acoustics (one name per quantity), so they
        # are promoted as they come.
        self.add_subsystem("tonal", TonalNoiseComp(**size, **observers, num_harmonics=opts["num_harmonics"],
                                                   num_blades=opts["num_blades"]),
                           promotes_inputs=["*"], promotes_outputs=list(TONAL_OUTPUTS[:-1]))
        totals_inputs = ["tonal_pressure_squared", "tonal_frequency"]
        if opts["include_broadband"]:
            self.add_subsystem("broadband", BroadbandNoiseComp(**size, **observers, num_blades=opts["num_blades"],
                                                               band_frequencies=opts["band_frequencies"],
                                                               boundary_layer=opts["boundary_layer"],
                                                               trailing_edge_angle=opts["trailing_edge_angle"],
                                                               num_azimuth=opts["num_azimuth"]),
                               promotes_inputs=["*"], promotes_outputs=list(BROADBAND_OUTPUTS[:-1]))
            totals_inputs.append("broadband_pressure_squared")
        outputs = ["tonal_spl"] + (["band_spl"] if opts["include_broadband"] else []) + list(LEVEL_OUTPUTS)
        self.add_subsystem("totals", NoiseTotalsComp(num_nodes=nn, **observers, num_harmonics=opts["num_harmonics"],
                                                     band_frequencies=opts["band_frequencies"],
                                                     include_broadband=opts["include_broadband"]),
                           promotes_inputs=totals_inputs, promotes_outputs=outputs)
        positions = _DEFAULT_OBSERVER if opts["observers"] is None else check_observers(opts["observers"])
        if opts["observers"] is not None and positions.shape[0] != no:
            raise ValueError(f"{self.msginfo}: observers has {positions.shape[0]} positions but num_observers is {no}")
        self.set_input_defaults("observer_position", val=np.broadcast_to(positions, (nn, no, 3)).copy(), units="m")


def make_noise_group(options, num_nodes, num_radial, num_blades, polar):
    """The :class:`RotorNoiseGroup` that a rotor group's noise options ask for, or None without observers."""
    if options["noise_observers"] is None:
        return None
    observers = check_observers(options["noise_observers"])
    return RotorNoiseGroup(num_nodes=num_nodes, num_radial=num_radial, num_observers=observers.shape[0],
                           num_harmonics=options["noise_harmonics"], num_blades=num_blades,
                           boundary_layer=options["noise_boundary_layer"], polar=polar, observers=observers,
                           trailing_edge_angle=options["noise_trailing_edge_angle"],
                           num_azimuth=options["noise_azimuths"])
