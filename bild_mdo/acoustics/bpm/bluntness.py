"""Trailing-edge bluntness vortex-shedding noise (TEB-VS) of a segment (NASA RP-1218, Sec. 5.4).

A trailing edge of thickness ``h`` sheds vortices at a Strouhal number ``St''' = f h / U`` (Eq. 71); the
one-third-octave band level of a segment of span ``L`` is, Eq. (70)::

    SPL_BLUNT = 10 log(h M^5.5 L D_h / r_e^2) + G_4(h / delta*_avg, Psi) + G_5(h / delta*_avg, Psi, St''' / St'''_peak)

with ``delta*_avg = (delta*_p + delta*_s) / 2`` (Eq. 73, the displacement thicknesses of both sides at the
trailing edge, :mod:`~bild_mdo.acoustics.bpm.boundary_layer`), ``Psi`` the solid angle between the two
surfaces just upstream of the edge (deg: 14 for a NACA 0012, 0 for a flat plate), the peak Strouhal number
``St'''_peak`` (Eq. 72), the level ``G_4`` (Eq. 74) and the shape ``G_5`` (Eqs. 75-82): interpolated
linearly in ``Psi`` between the shape for ``Psi = 14`` (Eqs. 76-81) and for ``Psi = 0`` (the same
function of the modified ratio of Eq. 82).  As in the report's code listing (its appendix), ``m`` is kept
non-negative, ``G_5`` at most 0 dB and at most the ``Psi = 14`` shape at ``h / delta*_avg = 0.25``.

Every function accepts arrays (real or complex) or :class:`~bild_mdo.utils.jet.Jet`; the branch switches
use real parts, so complex step and the jets' partials agree (kinks at the report's breakpoints).
"""
from __future__ import annotations

import numpy as np

from bild_mdo.acoustics.bands import REFERENCE_PRESSURE
from bild_mdo.acoustics.bpm.boundary_layer import boundary_layer
from bild_mdo.acoustics.bpm.jet_math import log10, piecewise, pow10, power, real_value, sqrt, square, where

#: ``Psi`` (deg) of a NACA 0012 trailing edge, the report's bluntness cases (figures 98, 99).
NACA0012_TRAILING_EDGE_ANGLE = 14.0
#: The largest ``Psi`` (deg) accepted: the fits span 0-14 deg; Pettingill et al. (2021) use 16; Eq. (72) gives
#: a negative peak Strouhal number beyond 39 deg.
MAX_TRAILING_EDGE_ANGLE = 30.0


def peak_strouhal_3(ratio, psi_deg):
    """``St'''_peak(h / delta*_avg, Psi)`` (Eq. 72, ``Psi`` in deg)."""
    return piecewise(ratio, [0.2], [
        lambda x: 0.1 * x + 0.095 - 0.00243 * psi_deg,
        lambda x: (0.212 - 0.0045 * psi_deg) / (1.0 + 0.235 / x - 0.0132 / (x * x))])


def shape_g4(ratio, psi_deg):
    """``G_4(h / delta*_avg, Psi)`` in dB (Eq. 74): ``17.5 log(ratio) + 157.5 - 1.114 Psi`` up to 5, then flat."""
    return piecewise(ratio, [5.0], [lambda x: 17.5 * log10(x) + 157.5 - 1.114 * psi_deg,
                                    lambda x: 169.7 - 1.114 * psi_deg + 0.0 * x])


def _mu(ratio):
    """``mu(h / delta*_avg)`` of Eq. (78)."""
    return piecewise(ratio, [0.25, 0.62, 1.15], [
        lambda x: 0.1211 + 0.0 * x, lambda x: -0.2175 * x + 0.1755, lambda x: -0.0308 * x + 0.0596,
        lambda x: 0.0242 + 0.0 * x])


def _slope(ratio):
    """``m(h / delta*_avg)`` of Eq. (79), kept non-negative (the report's code listing)."""
    m = piecewise(ratio, [0.02, 0.5, 0.62, 1.15, 1.2], [
        lambda x: 0.0 * x, lambda x: 68.724 * x - 1.35, lambda x: 308.475 * x - 121.23,
        lambda x: 224.811 * x - 69.354, lambda x: 1583.28 * x - 1631.592, lambda x: 268.344 + 0.0 * x])
    return where(real_value(m) < 0.0, 0.0 * m, m)


def shape_g5_psi14(ratio, eta):
    """``G_5`` for ``Psi = 14 deg`` in dB (Eqs. 76-81), ``eta = log10(St''' / St'''_peak)`` (Eq. 77)."""
    mu, m = _mu(ratio), _slope(ratio)
    # Eqs. (80), (81) with m >= 0 and mu > 0: eta_0 = -m mu^2 / S and k = S - 2.5, S = sqrt(6.25 + m^2 mu^2)
    # (the same numbers, with finite partials at m = 0).
    root = sqrt(6.25 + square(m * mu))
    eta0, k = -m * mu * mu / root, root - 2.5
    # Eq. (76); each branch sees only points of its own interval (piecewise), so the square roots stay real
    # (the third's radicand is floored: 1194.99 * 0.03616^2 exceeds 1.5625 by 6e-6, a rounding of the report's;
    # the fit itself has a vertical tangent there, so its derivative grows large within about 1e-6 of the edge).
    return piecewise(eta, [real_value(eta0), 0.0, 0.03616], [
        lambda e: m * e + k,
        lambda e: 2.5 * sqrt(1.0 - square(e / mu)) - 2.5,
        lambda e: sqrt(_floored(1.5625 - 1194.99 * e * e)) - 1.25,
        lambda e: -155.543 * e + 4.375])


def _floored(x, floor=1e-12):
    return where(real_value(x) < floor, floor + 0.0 * x, x)


def shape_g5(ratio, psi_deg, strouhal_ratio):
    """``G_5(h / delta*_avg, Psi, St''' / St'''_peak)`` in dB (Eq. 75 with Eq. 82), with the report's two caps."""
    eta = log10(strouhal_ratio)
    g5_14 = shape_g5_psi14(ratio, eta)
    g5_0 = shape_g5_psi14(6.724 * ratio * ratio - 4.019 * ratio + 1.107, eta)  # Eq. (82)
    g5 = g5_0 + 0.0714 * psi_deg * (g5_14 - g5_0)
    g5 = where(real_value(g5) > 0.0, 0.0 * g5, g5)
    # The report's listing evaluates the cap with its branch 'ratio >= 0.25' of Eq. (78) (mu = 0.121125), where
    # piecewise would put 0.25 itself in the lower one (0.1211): the next float above 0.25 takes that branch.
    cap = shape_g5_psi14(np.nextafter(0.25, 1.0) + 0.0 * real_value(eta), eta)
    return where(real_value(g5) > real_value(cap), cap, g5)


def bluntness_pressure_squared(frequency, chord, span, speed, mach, alpha, reynolds, distance, d_high, thickness,
                               psi_deg=NACA0012_TRAILING_EDGE_ANGLE, tripped=True):
    """TEB-VS 1/3-octave mean-square pressure (Pa**2) of a segment (Eq. 70).

    Parameters
    ----------
    frequency, chord, span, speed, mach, alpha, reynolds, distance, d_high : array or Jet
        As in :func:`~bild_mdo.acoustics.bpm.laminar_vortex_shedding.lbl_vs_pressure_squared` (source frequency
        in Hz, chord and span in m, ``U`` in m/s, ``M``, ``alpha*`` in rad, ``R_c``, ``r_e`` in m, ``D_h``);
        ``alpha*`` and ``R_c`` set the displacement thicknesses.
    thickness : array or Jet
        Trailing-edge thickness ``h`` (m), positive.
    psi_deg : float or array
        Trailing-edge solid angle ``Psi`` (deg, 0 ... 14 in the report's fits).
    tripped : bool
        Boundary-layer fits of a tripped (default) or untripped section.
    """
    if not np.all(np.asarray(real_value(thickness)) > 0.0):
        raise ValueError("the trailing-edge thickness h must be positive (a sharp edge has no bluntness noise: "
                         "leave the mechanism out)")
    layer = boundary_layer(chord, reynolds, alpha, tripped=tripped)
    ratio = thickness / (0.5 * (layer.delta_star_p + layer.delta_star_s))  # Eq. (73)
    strouhal = frequency * thickness / speed  # Eq. (71)
    level = shape_g4(ratio, psi_deg) + shape_g5(ratio, psi_deg, strouhal / peak_strouhal_3(ratio, psi_deg))
    scale = REFERENCE_PRESSURE ** 2 * thickness * power(mach, 5.5) * span * d_high / (distance * distance)
    return scale * pow10(0.1 * level)
