"""Tip-vortex formation noise (NASA RP-1218, Sec. 5.4, Eqs. 61-67).

One-third-octave band level of the tip of a blade, Eq. (61)::

    SPL_TIP = 10 log(M^2 M_max^3 l^2 D_h / r_e^2) - 30.5 (log St'' + 0.3)^2 + 126

with ``St'' = f l / U_max`` (Eq. 62), ``U_max = c_0 M_max`` and ``M_max = (1 + 0.036 alpha'_TIP) M``
(Eq. 64).  The spanwise extent ``l`` of the separated tip-vortex flow is ``l / c = 0.008 alpha'_TIP`` for a
rounded tip (Eq. 63) and ``0.0230 + 0.0169 alpha'_TIP`` up to 2 deg, ``0.0378 + 0.0095 alpha'_TIP`` above,
for a flat tip (Eq. 67).  The tip angle ``alpha'_TIP`` is the tip's angle of attack corrected for the
loading at the tip, Eq. (65); for BPM's untwisted wing in the open jet that factor is 0.71 (Eq. 66),
:data:`TIP_ALPHA_CORRECTION`, the default here.  Every function accepts arrays or jets.
"""
from __future__ import annotations

import numpy as np

from bild_mdo.acoustics.bands import REFERENCE_PRESSURE
from bild_mdo.acoustics.bpm.jet_math import log10, piecewise, pow10, sign_abs

_DEG = 180.0 / np.pi
#: ``alpha'_TIP / alpha_TIP`` of Eq. (66) (BPM's untwisted wing with its lift-slope ratio at the tip).
TIP_ALPHA_CORRECTION = 0.71
#: Tip shapes of Eqs. (63) and (67).
TIP_SHAPES = ("rounded", "flat")


def tip_extent_ratio(alpha_tip_deg, tip_shape="rounded"):
    """``l / c`` of the tip vortex for the corrected tip angle ``alpha'_TIP`` (deg): Eq. (63) or Eq. (67)."""
    a = sign_abs(alpha_tip_deg)
    if tip_shape == "rounded":
        return 0.008 * a
    if tip_shape == "flat":
        return piecewise(a, [2.0], [lambda x: 0.0230 + 0.0169 * x, lambda x: 0.0378 + 0.0095 * x])
    raise ValueError(f"tip_shape must be one of {TIP_SHAPES}, not {tip_shape!r}")


def tip_vortex_pressure_squared(frequency, chord, mach, speed_of_sound, alpha_tip, distance, d_high,
                                tip_shape="rounded", alpha_correction=TIP_ALPHA_CORRECTION):
    """Tip-vortex 1/3-octave mean-square pressure (Pa**2), Eq. (61).

    Parameters
    ----------
    frequency : array or Jet
        Band centre frequency (Hz) at the source.
    chord : array or Jet
        Chord at the tip ``c`` (m).
    mach : array or Jet
        Mach number ``M = U / c_0`` of the flow at the tip.
    speed_of_sound : array or Jet
        ``c_0`` (m/s).
    alpha_tip : array or Jet
        Angle of attack at the tip ``alpha_TIP`` (rad).
    distance, d_high : array or Jet
        Observer distance ``r_e`` (m) and high-frequency directivity ``D_h``.
    tip_shape : str
        ``'rounded'`` (Eq. 63) or ``'flat'`` (Eq. 67).
    alpha_correction : float
        ``alpha'_TIP / alpha_TIP`` (Eq. 65); 0.71 is BPM's value (Eq. 66).
    """
    alpha_prime = sign_abs(alpha_tip * (_DEG * alpha_correction))
    extent = chord * tip_extent_ratio(alpha_prime, tip_shape)
    mach_max = mach * (1.0 + 0.036 * alpha_prime)  # Eq. (64)
    st = frequency * extent / (speed_of_sound * mach_max)  # Eq. (62)
    log_st = log10(st) + 0.3
    scale = REFERENCE_PRESSURE ** 2 * mach * mach * mach_max * mach_max * mach_max * extent * extent * d_high
    return scale / (distance * distance) * pow10(0.1 * (126.0 - 30.5 * log_st * log_st))
