"""The noise options of the rotor groups and the check of observer positions every noise entry point shares.

:func:`declare_noise_options` gives :class:`~bild_mdo.bild.bild_group.BILDGroup`,
:class:`~bild_mdo.bem.bem_group.BEMAnalysisGroup` and
:class:`~bild_mdo.multipoint.multipoint_group.MultipointRotorGroup` the same options
(``noise_observers``, ``noise_harmonics``, ``noise_boundary_layer``, ``noise_trailing_edge_angle``,
``noise_azimuths``);
:func:`~bild_mdo.acoustics.rotor_noise_group.make_noise_group` builds the group they ask for.
"""
from __future__ import annotations

import numpy as np

from bild_mdo.acoustics.bpm.bluntness import MAX_TRAILING_EDGE_ANGLE, NACA0012_TRAILING_EDGE_ANGLE

#: Boundary-layer states of the BPM thickness fits (Brooks, Pope & Marcolini 1989, Sec. 3).
BOUNDARY_LAYERS = ("tripped", "untripped")
#: Outputs of the group (mean-square pressures in Pa**2, levels in dB re 20 uPa).
TONAL_OUTPUTS = ("loading_pressure_squared", "thickness_pressure_squared", "tonal_pressure_squared",
                 "tonal_frequency", "tonal_spl")
BROADBAND_OUTPUTS = ("broadband_source_pressure_squared", "broadband_pressure_squared", "band_spl")
LEVEL_OUTPUTS = ("oaspl", "oaspl_dba")


def check_observers(observers, radius=None):
    """Observer positions as a float array of shape ``(n, 3)`` (m, rotor frame), or ``ValueError`` (one line).

    Parameters
    ----------
    observers : array_like
        ``(n, 3)`` positions (a single ``(3,)`` position is one observer).
    radius : float, optional
        Tip radius: an observer at most one radius from the rotor centre (inside the sphere through the
        blade tips, where the far-field models do not hold) is refused.
    """
    try:
        array = np.array(observers, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"observers must be numbers (x, y, z) in metres, got {observers!r}") from None
    if array.ndim == 1 and array.size == 3:
        array = array[None, :]
    if array.ndim != 2 or array.shape[1] != 3 or array.shape[0] < 1:
        raise ValueError(f"observers must have shape (n, 3) (x, y, z in metres), got shape {array.shape}")
    bad = np.flatnonzero(~np.all(np.isfinite(array), axis=1))
    if bad.size:
        raise ValueError(f"observer {bad[0]} is not finite: {array[bad[0]].tolist()}")
    if radius is not None:
        distance = np.linalg.norm(array, axis=1)
        near = np.flatnonzero(distance <= float(radius))
        if near.size:
            k = near[0]
            raise ValueError(f"observer {k} at {array[k].tolist()} m is {distance[k]:.3g} m from the rotor centre, "
                             f"inside the rotor (radius {float(radius):.3g} m): the far-field noise models need "
                             "observers several radii away")
    return array


def check_observers_option(name, value):
    """OpenMDAO ``check_valid`` of an observers option: None or positions :func:`check_observers` accepts."""
    if value is not None:
        check_observers(value)


def check_boundary_layer(name, value):
    """OpenMDAO ``check_valid`` of a boundary-layer option."""
    if value not in BOUNDARY_LAYERS:
        raise ValueError(f"{name} must be 'tripped' or 'untripped', got {value!r}")


def declare_noise_options(options):
    """Declare the options that add a :class:`RotorNoiseGroup` to a rotor group (``noise_observers`` ...).

    ``noise_observers`` None (default) leaves the group exactly as without noise; an ``(n, 3)`` array of
    observer positions (m, rotor frame) adds the subsystem ``noise`` with ``num_observers = n``, the input
    ``observer_position[nn, n, 3]`` (default: these positions at every node) and the outputs ``oaspl``,
    ``oaspl_dba``, ``tonal_spl``, ``band_spl`` ... of :class:`RotorNoiseGroup`.
    """
    options.declare("noise_observers", default=None, allow_none=True, check_valid=check_observers_option,
                    desc="None (no noise) or (n, 3) observer positions (m, rotor frame): adds RotorNoiseGroup")
    options.declare("noise_harmonics", types=int, default=10, lower=1,
                    desc="blade-passage harmonics of the tonal noise (with noise_observers)")
    options.declare("noise_boundary_layer", default="tripped", check_valid=check_boundary_layer,
                    desc="BPM boundary layer 'tripped' or 'untripped' (with noise_observers)")
    options.declare("noise_trailing_edge_angle", types=float, default=NACA0012_TRAILING_EDGE_ANGLE, lower=0.0,
                    upper=MAX_TRAILING_EDGE_ANGLE,
                    desc="solid angle Psi (deg) of the trailing edge, bluntness noise (with noise_observers and "
                         "the input trailing_edge_thickness)")
    options.declare("noise_azimuths", types=int, default=24, lower=1,
                    desc="azimuth samples of the broadband noise (with noise_observers; fewer are coarser, most "
                         "near the disc plane)")


#: Outputs a rotor group promotes from its ``noise`` subsystem.
NOISE_OUTPUTS = TONAL_OUTPUTS + BROADBAND_OUTPUTS + LEVEL_OUTPUTS
