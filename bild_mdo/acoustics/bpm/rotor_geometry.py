"""Where a rotating blade segment sits relative to an observer, in BPM's frame: distance, directivities, Doppler.

Rotor frame of the noise layer: ``x`` along the rotor axis (thrust direction), the blades turning about
``+x`` at ``Omega``, the rotor moving along ``+x`` at ``v_axial`` through still air, the observers moving
with the rotor.  A segment at radius ``r`` and azimuth ``psi`` sits at ``p = r (0, cos psi, sin psi)``
and moves through the air at ``V = (v_axial, -Omega r sin psi, Omega r cos psi)``.  BPM's trailing-edge
frame of the segment (Appendix B): ``x_e = -(cos theta e_theta + sin theta e_x)`` along the chord from the
leading to the trailing edge, ``theta = phi + alpha`` the section's pitch from the disc plane (its inflow
angle plus its angle of attack: the twist the blade is built with, collective included) and ``e_theta = (0,
-sin psi, cos psi)`` the direction of rotation; ``y_e = (0, cos psi, sin psi)`` (the span), ``z_e = x_e x
y_e`` (normal to the chord).  An observer in the disc plane of a hovering rotor is thus ``theta`` off the
chord plane, not in it.
With ``d = X_obs - p`` and its components ``d_x, d_y, d_z`` in that frame::

    r_e = |d|,  cos Theta_e = d_x / r_e,  sin^2 Phi_e = d_z^2 / (d_y^2 + d_z^2),
    sin^2 Theta_e sin^2 Phi_e = d_z^2 / r_e^2,

the directivities are Brooks and Burley's for a source moving through still air (AIAA 2001-2210, Eqs.
19-20; :func:`~bild_mdo.acoustics.bpm.directivity.moving_source_directivities`) with the segment's
velocity relative to the local air ``V_tot = W (cos phi e_theta + sin phi e_x)`` (their Eq. 14: rotation,
flight and induced velocity; ``W`` the inflow speed and ``phi`` the inflow angle of the blade-element
analysis), ``M_tot cos xi_r = V_tot . d / (c_0 r_e)``, and the Doppler factor of the source frequency is
``f_source / f_observer = 1 - M_r``, ``M_r = V_rot . d / (c_0 r_e)`` with ``V_rot`` the rotational part of
the segment's velocity (the observer moves with the hub, so only the rotation moves the source relative to
the observer).  All quantities are evaluated at the emission geometry (the source's position at the
emission time; the observer is at rest relative to the hub).
"""
from __future__ import annotations

import numpy as np

from bild_mdo.acoustics.bpm.directivity import moving_source_directivities
from bild_mdo.acoustics.bpm.jet_math import cos, sin, sqrt

#: Names of the geometric quantities :func:`segment_geometry` returns.
GEOMETRY_NAMES = ("distance", "d_high", "d_low", "shift")


def segment_geometry(radius, omega, inflow_speed, inflow_angle, speed_of_sound, observer, azimuth, pitch):
    """Observer distance, ``D_h``, ``D_l`` and the Doppler factor ``1 - M_r`` of rotating segments.

    Parameters
    ----------
    radius : array or Jet
        Segment radius ``r`` (m).
    omega : array or Jet
        Rotor speed ``Omega`` (rad/s).
    inflow_speed : array or Jet
        Speed ``W`` of the segment relative to the local air (m/s).
    inflow_angle : array or Jet
        Inflow angle ``phi`` of that velocity from the disc plane (rad).
    speed_of_sound : array or Jet
        ``c_0`` (m/s).
    observer : tuple of (array or Jet)
        ``(x, y, z)`` of the observer (m).
    azimuth : ndarray
        Azimuth ``psi`` of the segment (rad), a constant.
    pitch : array or Jet
        Pitch ``theta = phi + alpha`` of the chord from the disc plane (rad).

    Returns
    -------
    dict
        ``{name: value}`` for the names of :data:`GEOMETRY_NAMES`, broadcast over all arguments.
    """
    cos_psi, sin_psi = np.cos(azimuth), np.sin(azimuth)
    tangential = omega * radius
    ox, oy, oz = observer
    dx, dy, dz = ox, oy - radius * cos_psi, oz - radius * sin_psi
    # Components of d along the span (y_e) and the chord (x_e, towards the trailing edge).
    d_span = dy * cos_psi + dz * sin_psi
    d_tangential = -dy * sin_psi + dz * cos_psi  # along e_theta = (0, -sin psi, cos psi)
    cos_pitch, sin_pitch = cos(pitch), sin(pitch)
    d_flow = -(sin_pitch * dx + cos_pitch * d_tangential)
    # z_e = x_e x y_e is the unit vector normal to the chord in the (e_x, e_theta) plane.
    d_normal = -sin_pitch * d_tangential + cos_pitch * dx
    distance2 = dx * dx + dy * dy + dz * dz
    distance = sqrt(distance2)
    cos_theta = d_flow / distance
    dn2 = d_normal * d_normal
    sin2_phi = dn2 / (d_span * d_span + dn2)
    # V_tot . d: the segment moves along e_theta and, relative to the air, along +e_x at W sin phi.
    approach = inflow_speed * (cos(inflow_angle) * d_tangential + sin(inflow_angle) * dx)
    d_high, d_low = moving_source_directivities(cos_theta, sin2_phi, dn2 / distance2,
                                                approach / (speed_of_sound * distance))
    return {
        "distance": distance,
        "d_high": d_high,
        "d_low": d_low,
        "shift": 1.0 - tangential * d_tangential / (speed_of_sound * distance),
    }
