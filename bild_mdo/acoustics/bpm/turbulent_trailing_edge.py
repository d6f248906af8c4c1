"""Turbulent-boundary-layer trailing-edge noise (TBL-TE) and separation-stall noise (NASA RP-1218, Sec. 5.1.1).

One-third-octave band levels of a segment of span ``L``, Eqs. (24)-(26)::

    SPL_p     = 10 log(delta*_p M^5 L D_h / r_e^2) + A(St_p / St_1)     + (K_1 - 3) + dK_1
    SPL_s     = 10 log(delta*_s M^5 L D_h / r_e^2) + A(St_s / St1bar)   + (K_1 - 3)
    SPL_alpha = 10 log(delta*_s M^5 L D_h / r_e^2) + B(St_s / St_2)     + K_2

with ``St_p,s = f delta*_p,s / U`` (Eq. 28), the peak Strouhal numbers ``St_1``, ``St_2`` and their mean
``St1bar`` (Eqs. 31-33), the spectral shapes ``A`` (Eqs. 35-40) and ``B`` (Eqs. 41-46) and the amplitudes
``K_1``, ``dK_1``, ``K_2`` (Eqs. 47-50).  Above the stall angle ``alpha*_0 = min(gamma_0, 12.5 deg)`` the
pressure- and suction-side terms vanish and the separation term becomes
``10 log(delta*_s M^5 L D_l / r_e^2) + A'(St_s / St_2) + K_2`` with ``A'`` the curve ``A`` for three
times the actual ``R_c`` (Sec. 5.1.1).  The levels are returned as mean-square pressures (Pa**2,
re 20 uPa); every function accepts arrays (real or complex) or :class:`~bild_mdo.utils.jet.Jet`.
"""
from __future__ import annotations

import numpy as np

from bild_mdo.acoustics.bands import REFERENCE_PRESSURE
from bild_mdo.acoustics.bpm.boundary_layer import boundary_layer
from bild_mdo.acoustics.bpm.jet_math import (log10, piecewise, pow10, power, real_value, sign_abs, sqrt, univariate,
                                             where)

_DEG = 180.0 / np.pi
_P_REF2 = REFERENCE_PRESSURE ** 2
#: Stall angle cap of the separation switch (deg), Sec. 5.1.1.
STALL_ANGLE_CAP_DEG = 12.5


def peak_strouhal_1(mach):
    """``St_1 = 0.02 M^-0.6`` (Eq. 31)."""
    return 0.02 * power(mach, -0.6)


def peak_strouhal_2(mach, alpha_deg):
    """``St_2`` (Eq. 33): ``St_1`` times 1, ``10^(0.0054 (alpha* - 1.33)^2)`` or 4.72 (``alpha*`` in deg)."""
    a = sign_abs(alpha_deg)
    factor = piecewise(a, [1.33, 12.5], [lambda x: 1.0 + 0.0 * x,
                                        lambda x: pow10(0.0054 * (x - 1.33) * (x - 1.33)),
                                        lambda x: 4.72 + 0.0 * x])
    return peak_strouhal_1(mach) * factor


def shape_a_min(a):
    """``A_min(a)`` (Eq. 35)."""
    return piecewise(a, [0.204, 0.244], [lambda x: sqrt(67.552 - 886.788 * x * x) - 8.219,
                                         lambda x: -32.665 * x + 3.981,
                                         lambda x: ((-142.795 * x + 103.656) * x - 57.757) * x + 6.006], pure=True)


def shape_a_max(a):
    """``A_max(a)`` (Eq. 36)."""
    return piecewise(a, [0.13, 0.321], [lambda x: sqrt(67.552 - 886.788 * x * x) - 8.219,
                                        lambda x: -15.901 * x + 1.098,
                                        lambda x: ((-4.669 * x + 3.491) * x - 16.699) * x + 1.149], pure=True)


def shape_b_min(b):
    """``B_min(b)`` (Eq. 41)."""
    return piecewise(b, [0.13, 0.145], [lambda x: sqrt(16.888 - 886.788 * x * x) - 4.109,
                                        lambda x: -83.607 * x + 8.138,
                                        lambda x: ((-817.810 * x + 355.210) * x - 135.024) * x + 10.619], pure=True)


def shape_b_max(b):
    """``B_max(b)`` (Eq. 42)."""
    return piecewise(b, [0.10, 0.187], [lambda x: sqrt(16.888 - 886.788 * x * x) - 4.109,
                                        lambda x: -31.330 * x + 1.854,
                                        lambda x: ((-80.541 * x + 44.174) * x - 39.381) * x + 2.344], pure=True)


def _reynolds_blend(reynolds, low, amplitude, high):
    """``a_0`` (Eq. 38) or ``b_0`` (Eq. 44): ``low``, a parabola in ``R_c``, or ``high``."""
    return piecewise(reynolds, [9.52e4, 8.57e5], [lambda r: low + 0.0 * r,
                                                 lambda r: amplitude * (r - 8.57e5) * (r - 8.57e5) + high,
                                                 lambda r: high + 0.0 * r])


def _shape(ratio, reynolds, shape_min, shape_max, low, amplitude, high):
    # The shapes are functions of x alone, evaluated on every band, azimuth and station: with jets, each
    # runs with one seed and chains its derivative to the partials of x (jet_math.univariate).
    x = univariate(lambda r: sign_abs(log10(r)), ratio)  # Eqs. (37), (43)
    x0 = _reynolds_blend(reynolds, low, amplitude, high)
    min0, max0 = shape_min(x0), shape_max(x0)
    interpolation = (-20.0 - min0) / (max0 - min0)  # Eqs. (39), (45)
    lo = univariate(shape_min, x)
    return lo + interpolation * (univariate(shape_max, x) - lo)  # Eqs. (40), (46)


def spectral_shape_a(strouhal_ratio, reynolds):
    """Spectral shape ``A(St / St_peak)`` in dB for chord Reynolds number ``R_c`` (Eqs. 35-40)."""
    return _shape(strouhal_ratio, reynolds, shape_a_min, shape_a_max, 0.57, -9.57e-13, 1.13)


def spectral_shape_b(strouhal_ratio, reynolds):
    """Spectral shape ``B(St_s / St_2)`` in dB for chord Reynolds number ``R_c`` (Eqs. 41-46)."""
    return _shape(strouhal_ratio, reynolds, shape_b_min, shape_b_max, 0.30, -4.48e-13, 0.56)


def amplitude_k1(reynolds):
    """``K_1(R_c)`` in dB (Eq. 47)."""
    return piecewise(reynolds, [2.47e5, 8.0e5], [lambda r: -4.31 * log10(r) + 156.3,
                                                lambda r: -9.0 * log10(r) + 181.6,
                                                lambda r: 128.5 + 0.0 * r])


def amplitude_delta_k1(alpha_deg, reynolds_delta_star_p):
    """``dK_1`` in dB (Eq. 48): ``alpha* (1.43 log R_delta*p - 5.29)`` below ``R_delta*p = 5000``, else 0."""
    a = sign_abs(alpha_deg)
    return piecewise(reynolds_delta_star_p, [5000.0], [lambda r: a * (1.43 * log10(r) - 5.29),
                                                       lambda r: 0.0 * r])


def _k2_parameters(mach):
    """``gamma, gamma_0, beta, beta_0`` (Eq. 50), deg and dB."""
    return 27.094 * mach + 3.31, 23.43 * mach + 4.651, 72.65 * mach + 10.74, -34.19 * mach - 13.82


def amplitude_k2_minus_k1(mach, alpha_deg):
    """``K_2 - K_1`` in dB (Eq. 49): -1000 below ``gamma_0 - gamma``, an ellipse, -12 above ``gamma_0 + gamma``."""
    a = sign_abs(alpha_deg)
    gamma, gamma0, beta, beta0 = _k2_parameters(mach)
    edges = [real_value(gamma0 - gamma), real_value(gamma0 + gamma)]

    def ellipse(x):
        slope = beta / gamma
        return sqrt(beta * beta - slope * slope * (x - gamma0) * (x - gamma0)) + beta0

    return piecewise(a, edges, [lambda x: -1000.0 + 0.0 * x, ellipse, lambda x: -12.0 + 0.0 * x])


def amplitude_k2(reynolds, mach, alpha_deg):
    """``K_2(R_c, M, alpha*)`` in dB (Eq. 49)."""
    return amplitude_k1(reynolds) + amplitude_k2_minus_k1(mach, alpha_deg)


def stall_angle_deg(mach):
    """``alpha*_0 = min(gamma_0, 12.5 deg)``, the angle above which the separation term takes over (real)."""
    return np.minimum(real_value(23.43 * mach + 4.651), STALL_ANGLE_CAP_DEG)


def tbl_te_pressure_squared(frequency, chord, span, speed, mach, alpha, reynolds, distance, d_high, d_low,
                            tripped=True):
    """TBL-TE pressure side, suction side and separation of a segment, 1/3-octave mean squares (Pa**2).

    Parameters
    ----------
    frequency : array or Jet
        Band centre frequency (Hz) at the source.
    chord, span : array or Jet
        Chord ``c`` and span ``L`` of the segment (m).
    speed, mach : array or Jet
        Flow speed ``U`` (m/s) and Mach number ``M = U / c_0``.
    alpha : array or Jet
        Angle of attack ``alpha*`` (rad).
    reynolds : array or Jet
        Chord Reynolds number ``R_c = U c / nu``.
    distance : array or Jet
        Observer distance ``r_e`` (m).
    d_high, d_low : array or Jet
        Directivities ``D_h`` and ``D_l`` (:mod:`~bild_mdo.acoustics.bpm.directivity`).
    tripped : bool
        Tripped or untripped boundary layer.

    Returns
    -------
    tuple
        ``(p2_pressure, p2_suction, p2_separation)`` in Pa**2, broadcast over all arguments.
    """
    alpha_deg = alpha * _DEG
    bl = boundary_layer(chord, reynolds, alpha, tripped)
    st_p = frequency * bl.delta_star_p / speed  # Eq. (28)
    st_s = frequency * bl.delta_star_s / speed
    st_1 = peak_strouhal_1(mach)
    st_2 = peak_strouhal_2(mach, alpha_deg)
    st_1bar = 0.5 * (st_1 + st_2)  # Eq. (32)
    k1 = amplitude_k1(reynolds)
    dk1 = amplitude_delta_k1(alpha_deg, reynolds * bl.delta_star_p / chord)
    k2 = k1 + amplitude_k2_minus_k1(mach, alpha_deg)
    scale = _P_REF2 * power(mach, 5.0) * span / (distance * distance)
    scale_p = scale * bl.delta_star_p * d_high
    scale_s = scale * bl.delta_star_s
    p2_p = scale_p * pow10(0.1 * (spectral_shape_a(st_p / st_1, reynolds) + k1 - 3.0 + dk1))  # Eq. (24)
    p2_s = scale_s * d_high * pow10(0.1 * (spectral_shape_a(st_s / st_1bar, reynolds) + k1 - 3.0))  # Eq. (25)
    stalled = real_value(sign_abs(alpha_deg)) > stall_angle_deg(mach)
    if np.any(stalled):
        ratio = where(stalled, st_s / st_2, 1.0)
        separated = scale_s * d_low * pow10(0.1 * (spectral_shape_a(ratio, 3.0 * reynolds) + k2))
        attached = scale_s * d_high * pow10(0.1 * (spectral_shape_b(where(stalled, 1.0, st_s / st_2), reynolds)
                                                   + k2))
        p2_alpha = where(stalled, separated, attached)
        p2_p, p2_s = where(stalled, 0.0, p2_p), where(stalled, 0.0, p2_s)
    else:
        p2_alpha = scale_s * d_high * pow10(0.1 * (spectral_shape_b(st_s / st_2, reynolds) + k2))  # Eq. (26)
    return p2_p, p2_s, p2_alpha
