"""BPM's boundary-layer thickness fits for the NACA 0012 at the trailing edge (NASA RP-1218, Section 3).

The boundary-layer thickness ``delta`` and displacement thickness ``delta*`` at the trailing edge, as
fractions of the chord, from the chord Reynolds number ``R_c`` and the angle of attack ``alpha*``
(degrees in the fits, radians at this module's API):

* zero angle of attack, tripped (heavy trip) Eqs. (2)-(3), untripped (natural transition) Eqs. (5)-(6);
* pressure side, tripped and untripped alike, Eqs. (8)-(9);
* suction side, tripped Eqs. (11)-(12), untripped Eqs. (14)-(15).

The fits are for ``0 <= alpha* <= 25 deg``; a negative angle is taken by its magnitude (the pressure side
is then the other side, and BPM's directivities do not tell the sides apart), and the last branch is
kept above 25 deg.  Every function accepts arrays (real or complex) or :class:`~bild_mdo.utils.jet.Jet`.
"""
from __future__ import annotations

from collections import namedtuple

import numpy as np

from bild_mdo.acoustics.bpm.jet_math import log10, piecewise, pow10, power, sign_abs

#: Boundary-layer quantities at the trailing edge (m): pressure and suction side, thickness and displacement.
BoundaryLayer = namedtuple("BoundaryLayer", ["delta_p", "delta_star_p", "delta_s", "delta_star_s"])


def _log_quadratic(reynolds, c0, c1, c2):
    lr = log10(reynolds)
    return pow10(c0 + c1 * lr + c2 * lr * lr)


def zero_angle_thickness(reynolds, tripped=True):
    """``(delta_0 / c, delta*_0 / c)`` at zero angle of attack.

    Parameters
    ----------
    reynolds : array or Jet
        Chord Reynolds number ``R_c = U c / nu``.
    tripped : bool
        Heavily tripped (Eqs. 2-3) or untripped (Eqs. 5-6) boundary layer.
    """
    if tripped:
        delta0 = _log_quadratic(reynolds, 1.892, -0.9045, 0.0596)  # Eq. (2)
        delta_star0 = piecewise(reynolds, [0.3e6], [  # Eq. (3)
            lambda r: 0.0601 * power(r, -0.114),
            lambda r: _log_quadratic(r, 3.411, -1.5397, 0.1059)])
    else:
        delta0 = _log_quadratic(reynolds, 1.6569, -0.9045, 0.0596)  # Eq. (5)
        delta_star0 = _log_quadratic(reynolds, 3.0187, -1.5397, 0.1059)  # Eq. (6)
    return delta0, delta_star0


def pressure_side_ratios(alpha_deg):
    """``(delta_p / delta_0, delta*_p / delta*_0)``, Eqs. (8)-(9), tripped and untripped alike (``alpha*`` in deg)."""
    a = sign_abs(alpha_deg)
    return pow10(-0.04175 * a + 0.00106 * a * a), pow10(-0.0432 * a + 0.00113 * a * a)


def suction_side_ratios(alpha_deg, tripped=True):
    """``(delta_s / delta_0, delta*_s / delta*_0)``: Eqs. (11)-(12) tripped, Eqs. (14)-(15) untripped (deg)."""
    a = sign_abs(alpha_deg)
    if tripped:
        edges = [5.0, 12.5]
        delta = [lambda x: pow10(0.0311 * x), lambda x: 0.3468 * pow10(0.1231 * x),
                 lambda x: 5.718 * pow10(0.0258 * x)]
        delta_star = [lambda x: pow10(0.0679 * x), lambda x: 0.381 * pow10(0.1516 * x),
                      lambda x: 14.296 * pow10(0.0258 * x)]
    else:
        edges = [7.5, 12.5]
        delta = [lambda x: pow10(0.03114 * x), lambda x: 0.0303 * pow10(0.2336 * x),
                 lambda x: 12.0 * pow10(0.0258 * x)]
        delta_star = [lambda x: pow10(0.0679 * x), lambda x: 0.0162 * pow10(0.3066 * x),
                      lambda x: 52.42 * pow10(0.0258 * x)]
    return piecewise(a, edges, delta), piecewise(a, edges, delta_star)


def boundary_layer(chord, reynolds, alpha, tripped=True):
    """Trailing-edge boundary-layer thicknesses (m) of a NACA 0012 section.

    Parameters
    ----------
    chord : array or Jet
        Chord ``c`` (m).
    reynolds : array or Jet
        Chord Reynolds number ``R_c``.
    alpha : array or Jet
        Angle of attack ``alpha*`` (rad).
    tripped : bool
        Tripped or untripped boundary layer.

    Returns
    -------
    BoundaryLayer
        ``delta_p``, ``delta_star_p``, ``delta_s``, ``delta_star_s`` (m).
    """
    alpha_deg = alpha * (180.0 / np.pi)
    delta0, delta_star0 = zero_angle_thickness(reynolds, tripped)
    ratio_p, ratio_star_p = pressure_side_ratios(alpha_deg)
    ratio_s, ratio_star_s = suction_side_ratios(alpha_deg, tripped)
    return BoundaryLayer(chord * delta0 * ratio_p, chord * delta_star0 * ratio_star_p,
                         chord * delta0 * ratio_s, chord * delta_star0 * ratio_star_s)
