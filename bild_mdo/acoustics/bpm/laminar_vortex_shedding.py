"""Laminar-boundary-layer vortex-shedding noise (LBL-VS) of an untripped section (NASA RP-1218, Sec. 5.2).

One-third-octave band level of a segment of span ``L``, Eq. (53)::

    SPL_LBL-VS = 10 log(delta_p M^5 L D_h / r_e^2) + G_1(St' / St'_peak) + G_2(R_c / (R_c)_0) + G_3(alpha*)

with ``St' = f delta_p / U`` (Eq. 54), the reference Strouhal number ``St'_1(R_c)`` (Eq. 55), its peak
``St'_peak = St'_1 10^(-0.04 alpha*)`` (Eq. 56), the spectral shape ``G_1`` (Eq. 57), the Reynolds-number
dependence ``G_2`` (Eq. 58) about ``(R_c)_0(alpha*)`` (Eq. 59) and the angle dependence
``G_3 = 171.04 - 3.03 alpha*`` (Eq. 60).  ``delta_p`` is the untripped pressure-side thickness
(:mod:`~bild_mdo.acoustics.bpm.boundary_layer`); the mechanism exists only for an untripped boundary
layer.  Every function accepts arrays (real or complex) or :class:`~bild_mdo.utils.jet.Jet`.
"""
from __future__ import annotations

import numpy as np

from bild_mdo.acoustics.bands import REFERENCE_PRESSURE
from bild_mdo.acoustics.bpm.boundary_layer import boundary_layer
from bild_mdo.acoustics.bpm.jet_math import log10, piecewise, pow10, power, sign_abs, sqrt, univariate

_DEG = 180.0 / np.pi


def reference_strouhal(reynolds):
    """``St'_1(R_c)`` (Eq. 55): 0.18, ``0.001756 R_c^0.3931``, 0.28."""
    return piecewise(reynolds, [1.3e5, 4.0e5], [lambda r: 0.18 + 0.0 * r,
                                               lambda r: 0.001756 * power(r, 0.3931),
                                               lambda r: 0.28 + 0.0 * r])


def peak_strouhal(reynolds, alpha_deg):
    """``St'_peak = St'_1 10^(-0.04 alpha*)`` (Eq. 56, ``alpha*`` in deg)."""
    return reference_strouhal(reynolds) * pow10(-0.04 * sign_abs(alpha_deg))


def shape_g1(e):
    """``G_1(e)`` in dB, ``e = St' / St'_peak`` (Eq. 57)."""
    def log_e(branch):
        return lambda x: branch(log10(x))
    return piecewise(e, [0.5974, 0.8545, 1.17, 1.674], [
        log_e(lambda le: 39.8 * le - 11.12),
        log_e(lambda le: 98.409 * le + 2.0),
        log_e(lambda le: sqrt(2.484 - 506.25 * le * le) - 5.076),
        log_e(lambda le: -98.409 * le + 2.0),
        log_e(lambda le: -39.8 * le - 11.12)], pure=True)


def reference_reynolds(alpha_deg):
    """``(R_c)_0(alpha*)`` (Eq. 59): ``10^(0.215 alpha* + 4.978)`` up to 3 deg, ``10^(0.120 alpha* + 5.263)`` above."""
    a = sign_abs(alpha_deg)
    return piecewise(a, [3.0], [lambda x: pow10(0.215 * x + 4.978), lambda x: pow10(0.120 * x + 5.263)])


def shape_g2(d):
    """``G_2(d)`` in dB, ``d = R_c / (R_c)_0`` (Eq. 58)."""
    def log_d(branch):
        return lambda x: branch(log10(x))
    return piecewise(d, [0.3237, 0.5689, 1.7579, 3.0889], [
        log_d(lambda ld: 77.852 * ld + 15.328),
        log_d(lambda ld: 65.188 * ld + 9.125),
        log_d(lambda ld: -114.052 * ld * ld),
        log_d(lambda ld: -65.188 * ld + 9.125),
        log_d(lambda ld: -77.852 * ld + 15.328)], pure=True)


def shape_g3(alpha_deg):
    """``G_3(alpha*) = 171.04 - 3.03 alpha*`` in dB (Eq. 60)."""
    return 171.04 - 3.03 * sign_abs(alpha_deg)


def lbl_vs_pressure_squared(frequency, chord, span, speed, mach, alpha, reynolds, distance, d_high):
    """LBL-VS 1/3-octave mean-square pressure (Pa**2) of an untripped segment (Eq. 53).

    Parameters
    ----------
    frequency : array or Jet
        Band centre frequency (Hz) at the source.
    chord, span : array or Jet
        Chord ``c`` and span ``L`` (m).
    speed, mach : array or Jet
        Flow speed ``U`` (m/s) and Mach number ``M``.
    alpha : array or Jet
        Angle of attack ``alpha*`` (rad).
    reynolds : array or Jet
        Chord Reynolds number ``R_c``.
    distance, d_high : array or Jet
        Observer distance ``r_e`` (m) and high-frequency directivity ``D_h``.
    """
    alpha_deg = alpha * _DEG
    delta_p = boundary_layer(chord, reynolds, alpha, tripped=False).delta_p
    st = frequency * delta_p / speed  # Eq. (54)
    # G_1 is evaluated on every band, azimuth and station: with jets, once with one seed (jet_math.univariate).
    level = (univariate(shape_g1, st / peak_strouhal(reynolds, alpha_deg))
             + shape_g2(reynolds / reference_reynolds(alpha_deg)) + shape_g3(alpha_deg))
    scale = REFERENCE_PRESSURE ** 2 * delta_p * power(mach, 5.0) * span * d_high / (distance * distance)
    return scale * pow10(0.1 * level)
