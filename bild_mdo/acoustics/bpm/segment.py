"""The BPM self-noise of one blade segment at one observer: every mechanism, one call (NASA RP-1218).

:func:`segment_spectra` evaluates the report's predictions for a segment of chord ``c`` and span ``L`` in a
flow of speed ``U`` at the angle of attack ``alpha*``, heard at distance ``r_e`` and angles ``Theta_e``,
``Phi_e`` (the report's wind-tunnel cases: ``r_e = 1.22 m``, ``Theta_e = Phi_e = 90 deg``, ``L = 45.72 cm``).
The mechanisms are those of :data:`SEGMENT_SOURCES`; the tip vortex, a property of the blade's tip and
not of a segment, is :func:`~bild_mdo.acoustics.bpm.tip_vortex.tip_vortex_pressure_squared`.
"""
from __future__ import annotations

from bild_mdo.acoustics.bpm.directivity import high_frequency_directivity, low_frequency_directivity
from bild_mdo.acoustics.bpm.laminar_vortex_shedding import lbl_vs_pressure_squared
from bild_mdo.acoustics.bpm.turbulent_trailing_edge import tbl_te_pressure_squared

#: The segment mechanisms, in the order of the noise layer's ``BROADBAND_SOURCES``.
SEGMENT_SOURCES = ("tbl_te_pressure", "tbl_te_suction", "separation", "lbl_vs")


def segment_spectra(frequency, chord, span, speed, alpha, reynolds, distance, theta_e, phi_e, speed_of_sound,
                    tripped=True):
    """1/3-octave mean-square pressures (Pa**2) of every segment mechanism.

    Parameters
    ----------
    frequency : array_like
        Band centre frequencies (Hz), broadcast against the other arguments.
    chord, span : array_like
        Chord ``c`` and span ``L`` (m).
    speed : array_like
        Flow speed ``U`` (m/s); the Mach number is ``M = U / speed_of_sound``.
    alpha : array_like
        Angle of attack ``alpha*`` (rad).
    reynolds : array_like
        Chord Reynolds number ``R_c = U c / nu``.
    distance : array_like
        Observer distance ``r_e`` (m).
    theta_e, phi_e : array_like
        Directivity angles (rad, :mod:`~bild_mdo.acoustics.bpm.directivity`).
    speed_of_sound : array_like
        ``c_0`` (m/s).
    tripped : bool
        Tripped boundary layer (LBL-VS is then zero) or untripped.

    Returns
    -------
    dict
        ``{name: p2}`` for the names of :data:`SEGMENT_SOURCES`.
    """
    mach = speed / speed_of_sound
    d_high = high_frequency_directivity(theta_e, phi_e, mach)
    d_low = low_frequency_directivity(theta_e, phi_e, mach)
    p2_p, p2_s, p2_alpha = tbl_te_pressure_squared(frequency, chord, span, speed, mach, alpha, reynolds, distance,
                                                   d_high, d_low, tripped)
    if tripped:
        p2_lbl = 0.0 * p2_p
    else:
        p2_lbl = lbl_vs_pressure_squared(frequency, chord, span, speed, mach, alpha, reynolds, distance, d_high)
    return dict(zip(SEGMENT_SOURCES, (p2_p, p2_s, p2_alpha, p2_lbl)))
