"""BPM's directivity functions with convective amplification (NASA RP-1218, Appendix B, Eqs. B1-B2).

In the frame of the trailing edge (``x`` along the chord, downstream; ``y`` along the span; ``z`` normal
to both), an observer at distance ``r_e`` sits at the angles ``Theta_e`` (from ``+x``) and ``Phi_e``
(from ``+y`` in the ``y-z`` plane)::

    D_h = 2 sin^2(Theta_e/2) sin^2(Phi_e) / ((1 + M cos Theta_e) (1 + (M - M_c) cos Theta_e)^2)   (B1)
    D_l = sin^2(Theta_e) sin^2(Phi_e) / (1 + M cos Theta_e)^4                                      (B2)

with the convection Mach number ``M_c = 0.8 M``.  ``D_h`` (a half-baffled trailing edge) holds for the
high-frequency sources and ``D_l`` (a compact dipole) for the low-frequency stalled separation.  Both are
1 at ``Theta_e = Phi_e = 90 deg``, the report's observer.  The ``*_from_cosines`` forms take
``cos Theta_e`` and ``sin^2 Phi_e`` (and ``sin^2 Theta_e sin^2 Phi_e``), which a component gets from
the observer's coordinates without inverse trigonometry.

Eqs. (B1)-(B2) are the wind tunnel's: airfoil and observer at rest, the air moving past them.  A rotor
blade moves through still air towards or away from an observer at rest in it; Brooks and Burley (AIAA
2001-2210, Eqs. 19-20) keep the angular factors and replace both convective factors by the moving
source's Doppler amplification::

    D_h = 2 sin^2(Theta_e/2) sin^2(Phi_e) / (1 - M_tot cos xi_r)^4
    D_l = sin^2(Theta_e) sin^2(Phi_e) / (1 - M_tot cos xi_r)^4

with ``M_tot cos xi_r = V_tot . r_hat / c_0`` the Mach number of the segment relative to the local air
(rotation, flight and induced velocity, their Eq. 14) towards the observer
(:func:`moving_source_directivities`).
"""
from __future__ import annotations

import numpy as np

#: Convection Mach number over the flow Mach number, ``M_c / M`` (Appendix B).
CONVECTION_RATIO = 0.8


def high_frequency_directivity_from_cosines(cos_theta, sin2_phi, mach):
    """``D_h`` (Eq. B1) from ``cos Theta_e``, ``sin^2 Phi_e`` and the Mach number ``M`` (arrays or jets)."""
    convective = 1.0 + mach * cos_theta
    relative = 1.0 + (1.0 - CONVECTION_RATIO) * mach * cos_theta
    return (1.0 - cos_theta) * sin2_phi / (convective * relative * relative)


def low_frequency_directivity_from_cosines(sin2_theta_sin2_phi, cos_theta, mach):
    """``D_l`` (Eq. B2) from ``sin^2 Theta_e sin^2 Phi_e``, ``cos Theta_e`` and ``M`` (arrays or jets)."""
    convective = 1.0 + mach * cos_theta
    c2 = convective * convective
    return sin2_theta_sin2_phi / (c2 * c2)


def high_frequency_directivity(theta_e, phi_e, mach):
    """``D_h`` (Eq. B1) of the angles ``Theta_e``, ``Phi_e`` (rad) and the Mach number ``M``."""
    return high_frequency_directivity_from_cosines(np.cos(theta_e), np.sin(phi_e) ** 2, mach)


def low_frequency_directivity(theta_e, phi_e, mach):
    """``D_l`` (Eq. B2) of the angles ``Theta_e``, ``Phi_e`` (rad) and the Mach number ``M``."""
    return low_frequency_directivity_from_cosines((np.sin(theta_e) * np.sin(phi_e)) ** 2, np.cos(theta_e), mach)


def moving_source_directivities(cos_theta, sin2_phi, sin2_theta_sin2_phi, mach_towards_observer):
    """``(D_h, D_l)`` of a segment moving through still air (Brooks & Burley, AIAA 2001-2210, Eqs. 19-20).

    Parameters
    ----------
    cos_theta, sin2_phi, sin2_theta_sin2_phi : array or Jet
        ``cos Theta_e``, ``sin^2 Phi_e`` and ``sin^2 Theta_e sin^2 Phi_e`` in the segment's frame.
    mach_towards_observer : array or Jet
        ``M_tot cos xi_r``: the segment's velocity relative to the local air, over ``c_0``, projected on
        the unit vector from the segment to the observer (positive when approaching).
    """
    convective = 1.0 - mach_towards_observer
    c2 = convective * convective
    amplification = 1.0 / (c2 * c2)
    return (1.0 - cos_theta) * sin2_phi * amplification, sin2_theta_sin2_phi * amplification
