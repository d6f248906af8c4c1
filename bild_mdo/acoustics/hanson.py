r"""Compact-chord, far-field tonal noise of a rotor in axial flight or hover: the kernel functions.

Model
-----
Hanson's helicoidal-surface theory (D. B. Hanson, "Helicoidal surface theory for harmonic noise
of propellers in the far field", AIAA J. 18(10), 1980; D. B. Hanson and D. J. Parzych, NASA
CR-4499, 1993) in its compact-chord limit: the chordwise source transforms
:math:`\Psi_V, \Psi_L, \Psi_D \to` their values at zero wavenumber and the face-alignment and sweep
phases vanish, so every blade element is a point force and a point volume on its radius.  The
same result follows from the Ffowcs Williams-Hawkings equation with the convected Green's function
of a uniform stream (derivation in the tests' docstrings); it reduces to Gutin's loading noise
(L. Gutin, 1936, NACA TM 1195) and Deming's thickness noise (A. F. Deming, 1937/1938) in hover.

Frame (bild-mdo's noise layer): ``x`` along the rotor axis in the direction of the thrust, the
rotor centre at the origin, the blades turning about ``+x``, the rotor moving along ``+x`` at
``V = v_axial`` (flight Mach number ``M = V / c0``); the observer at ``(x, y, z)`` moves with the
rotor (a wind-tunnel microphone, or a chase observer), as in Hanson's and Garrick & Watkins'
far-field formulas.  Hence every harmonic is heard at ``f_m = m B Omega / (2 pi)`` (no Doppler
shift of frequency); the convective amplification is in the amplitudes.  Hanson measures his
radiation angle from the flight direction, which for a propeller is the thrust direction and here
``+x``, so his ``theta`` is our polar angle from ``+x``; his formulas hold in *retarded* (emission)
coordinates, obtained from the observer's present position relative to the rotor by

.. math::

    \rho_o = \sqrt{y^2 + z^2},\quad \sigma = \sqrt{x^2 + (1 - M^2)\rho_o^2},\quad
    r_e = \frac{M x + \sigma}{1 - M^2},\quad r_e\cos\theta_e = x + M r_e,\quad
    r_e \sin\theta_e = \rho_o,\quad D \equiv 1 - M\cos\theta_e = \sigma / r_e .

Harmonic ``m`` (order ``n = m B``, ``k = n Omega / c0``), stations ``j`` of width ``dr_j``, loads of
all blades per unit span ``T'_j = dthrust_dr``, ``Q'_j = dtorque_dr``, Bessel argument
``z_j = k r_j sin(theta_e) / D = k r_j rho_o / sigma``:

.. math::

    p_m(t) = 2\,\mathrm{Re}\left[(i a_L - a_T)\, e^{i(k r_e - n\pi/2 - n\Omega t)}\right]
    \text{ (up to a common phase)},

    a_L = \frac{k}{4\pi r_e D^2}\sum_j J_n(z_j)\left[T'_j\cos\theta_e - \frac{Q'_j c_0 D}{\Omega r_j^2}\right] dr_j
        = \frac{k}{4\pi\sigma^2}\sum_j J_n(z_j)
          \left[T'_j (x + M r_e) - \frac{Q'_j c_0 \sigma}{\Omega r_j^2}\right] dr_j,

    a_T = \frac{\rho_0 B (n\Omega)^2}{4\pi r_e D^3}\sum_j J_n(z_j)\, \kappa\, (t/c)_j c_j^2\, dr_j ,

with ``kappa`` the section-area coefficient, area ``= kappa (t/c) c**2`` (:data:`AREA_COEFFICIENT`,
0.685 for the NACA four-digit thickness form).  The harmonic's mean square is
``2 a_L**2`` (loading), ``2 a_T**2`` (thickness) and ``2 (a_L**2 + a_T**2)`` (both: in the compact
limit the two are in quadrature, so their complex sum adds the mean squares).  In hover (``M = 0``,
``r_e = r``, ``D = 1``) the loading term is Gutin's
``p_rms = n Omega / (2 sqrt(2) pi c0 r) |sum (T' cos(theta) - Q' c0 / (Omega r_j**2)) J_n dr|`` and
the thickness term Deming's.  Behind the disc (``cos(theta) < 0``) thrust and torque add: loading
noise peaks below a lifting rotor.  On the axis ``z = 0`` and ``J_n(0) = 0`` for ``n >= 1``.

Where it stops holding: near field (``r`` not much larger than the radius ``R`` and the acoustic
wavelength; the far-field expansion drops terms of order ``R / r`` and ``1 / (k r)``); tip or
helical Mach numbers near or above 1 (chord non-compactness, ``k c / D`` not small, grows with the
harmonic; ``D -> 0`` makes the formulas singular; transonic and quadrupole noise are absent;
``J_n(z)`` with ``z ~ n`` is no longer small, so high harmonics stop decaying); non-axial inflow
(edgewise flight, incidence, unsteady loading, blade-vortex interaction) is not represented;
``M < 1`` is required.

Complex step: scipy's ``jv`` evaluates complex arguments through AMOS, which loses an imaginary part
of ``1e-40``; :func:`bessel_j` therefore expands ``J_n(a + ib) = J_n(a) + i b J_n'(a)`` (exact to first
order in ``b``, what a complex-step derivative uses).
"""
from __future__ import annotations

import numpy as np
from scipy.special import jv

#: Section area / (t c**2) of the NACA four-digit thickness form (2 * integral of y_t / (t c) over the chord).
AREA_COEFFICIENT = 2.0 * 5.0 * (0.2969 * 2.0 / 3.0 - 0.1260 / 2.0 - 0.3516 / 3.0 + 0.2843 / 4.0 - 0.1015 / 5.0)


def bessel_j(order, z):
    """``J_order(z)`` for real ``z``, or complex-step-safe for complex ``z`` (first order in ``Im z``)."""
    z = np.asarray(z)
    if np.iscomplexobj(z):
        return jv(order, z.real) + 1j * z.imag * bessel_j_derivative(order, z.real)
    return jv(order, z)


def bessel_j_derivative(order, z):
    """``J'_order(z) = (J_{order-1}(z) - J_{order+1}(z)) / 2``."""
    return 0.5 * (bessel_j(order - 1, z) - bessel_j(order + 1, z))


def observer_coordinates(position):
    """Axial coordinate ``x``, distance from the axis ``rho_o`` and ``d rho_o / d (y, z)`` of observers.

    ``position[..., 3]`` (m).  On the axis the derivative is set to 0 (``rho_o`` has a kink there).
    """
    x, y, z = position[..., 0], position[..., 1], position[..., 2]
    rho_o = np.sqrt(y * y + z * z)
    off_axis = np.real(rho_o) > 0.0
    safe = np.where(off_axis, rho_o, 1.0)
    return x, rho_o, np.where(off_axis, y / safe, 0.0), np.where(off_axis, z / safe, 0.0)


def retarded_geometry(x, rho_o, mach):
    """Emission-time geometry of an observer moving with the rotor, with partials wrt ``(x, rho_o, mach)``.

    Returns
    -------
    dict
        ``sigma`` (``= r_e D``), ``r_e`` (emission distance), ``axial`` (``= r_e cos(theta_e)``), ``zeta``
        (``= sin(theta_e) / D = rho_o / sigma``), and for each of them ``name + '_' + q`` with
        ``q in ('x', 'rho', 'mach')``: the partial derivatives.
    """
    beta2 = 1.0 - mach * mach
    sigma = np.sqrt(x * x + beta2 * rho_o * rho_o)
    r_e = (mach * x + sigma) / beta2
    g = {"sigma": sigma, "r_e": r_e, "axial": x + mach * r_e, "zeta": rho_o / sigma}
    g["sigma_x"], g["sigma_rho"], g["sigma_mach"] = x / sigma, beta2 * rho_o / sigma, -mach * rho_o ** 2 / sigma
    g["r_e_x"] = (mach + g["sigma_x"]) / beta2
    g["r_e_rho"] = g["sigma_rho"] / beta2
    g["r_e_mach"] = (x + g["sigma_mach"] + 2.0 * mach * r_e) / beta2
    g["axial_x"] = 1.0 + mach * g["r_e_x"]
    g["axial_rho"] = mach * g["r_e_rho"]
    g["axial_mach"] = r_e + mach * g["r_e_mach"]
    g["zeta_x"] = -rho_o * g["sigma_x"] / sigma ** 2
    g["zeta_rho"] = 1.0 / sigma - rho_o * g["sigma_rho"] / sigma ** 2
    g["zeta_mach"] = -rho_o * g["sigma_mach"] / sigma ** 2
    return g


def tonal_amplitudes(radii, dr, chord, thickness_ratio, dthrust_dr, dtorque_dr, omega, speed_of_sound, rho,
                     mach, geometry, orders, num_blades, area_coefficient=AREA_COEFFICIENT, partials=False):
    """Loading and thickness amplitudes ``a_L, a_T`` (Pa) of the module docstring, and their partials.

    Parameters
    ----------
    radii, dr, chord, thickness_ratio, dthrust_dr, dtorque_dr : ndarray, shape ``(nn, nr)``
        Stations (SI; loads of all blades per unit span).
    omega, speed_of_sound, rho, mach : ndarray, shape ``(nn,)``
        Rotor speed (rad/s), speed of sound (m/s), density (kg/m**3), flight Mach number.
    geometry : dict
        :func:`retarded_geometry` of the observers, arrays of shape ``(nn, no)``.
    orders : ndarray of int, shape ``(nh,)``
        Bessel orders ``n = m B``.
    num_blades : int
    area_coefficient : float
    partials : bool
        Also return the partial derivatives.

    Returns
    -------
    a_loading, a_thickness : ndarray, shape ``(nn, no, nh)``
    d : dict, only with ``partials``
        ``d[amp][name]`` for ``amp in ('loading', 'thickness')``: wrt station inputs shape
        ``(nn, no, nh, nr)``, wrt ``'omega', 'speed_of_sound', 'rho', 'mach', 'x', 'rho_o'`` shape ``(nn, no, nh)``
        (``speed_of_sound`` at fixed ``mach``).
    """
    st = (slice(None), None, None, slice(None))          # (nn, nr) -> (nn, 1, 1, nr)
    nd = (slice(None), None, None)                       # (nn,) -> (nn, 1, 1)
    r, w = radii[st], dr[st]
    om, c = omega[nd], speed_of_sound[nd]
    n = np.asarray(orders, dtype=float)[None, None, :]
    k = n * om / c                                        # (nn, 1, nh)
    sigma, r_e, axial, zeta = (geometry[name][:, :, None] for name in ("sigma", "r_e", "axial", "zeta"))
    z = (k * zeta)[..., None] * r                         # (nn, no, nh, nr)
    order = np.asarray(orders)[None, None, :, None]
    bj = bessel_j(order, z)
    torque_arm = c[..., None] / (om[..., None] * r * r)   # c0 / (Omega r^2), (nn, 1, 1, nr)
    bracket = dthrust_dr[st] * axial[..., None] - dtorque_dr[st] * torque_arm * sigma[..., None]
    e_l = k / (4.0 * np.pi * sigma ** 2)
    s_l = np.sum(bj * bracket * w, axis=-1)
    a_l = e_l * s_l
    area = area_coefficient * thickness_ratio[st] * chord[st] ** 2
    e_t = rho[nd] * num_blades * (n * om) ** 2 * r_e ** 2 / (4.0 * np.pi * sigma ** 3)
    s_t = np.sum(bj * area * w, axis=-1)
    a_t = e_t * s_t
    if not partials:
        return a_l, a_t

    dbj = bessel_j_derivative(order, z)
    el, et = e_l[..., None], e_t[..., None]
    dl = {"dthrust_dr": el * bj * axial[..., None] * w,
          "dtorque_dr": -el * bj * torque_arm * sigma[..., None] * w,
          "dr": el * bj * bracket,
          "radii": el * w * (dbj * (k * zeta)[..., None] * bracket
                             + 2.0 * bj * dtorque_dr[st] * torque_arm * sigma[..., None] / r)}
    dt = {"thickness_ratio": et * bj * area_coefficient * chord[st] ** 2 * w,
          "chord": et * bj * area_coefficient * thickness_ratio[st] * 2.0 * chord[st] * w,
          "dr": et * bj * area,
          "radii": et * dbj * (k * zeta)[..., None] * area * w}
    # Station sums that the node and observer partials share.
    sum_dbj_l = np.sum(dbj * r * bracket * w, axis=-1)              # sum J' r G dr
    sum_thrust = np.sum(bj * dthrust_dr[st] * w, axis=-1)            # sum J T' dr
    sum_torque = np.sum(bj * dtorque_dr[st] * torque_arm * w, axis=-1)   # sum J Q' c0 / (Omega r^2) dr
    sum_dbj_t = np.sum(dbj * r * area * w, axis=-1)                 # sum J' r A dr
    # d/dk at fixed Omega (the Bessel argument and the prefactor k), then the chain to Omega and c0.
    dl_dk = a_l / k + e_l * zeta * sum_dbj_l
    dt_dk = e_t * zeta * sum_dbj_t
    dl["omega"] = dl_dk * k / om + e_l * sigma * sum_torque / om
    dl["speed_of_sound"] = -dl_dk * k / c - e_l * sigma * sum_torque / c
    dt["omega"] = dt_dk * k / om + 2.0 * a_t / om
    dt["speed_of_sound"] = -dt_dk * k / c
    dt["rho"] = a_t / rho[nd]
    for q, name in (("x", "x"), ("rho", "rho_o"), ("mach", "mach")):
        s_q, ax_q, r_q, z_q = (geometry[f"{g}_{q}"][:, :, None] for g in ("sigma", "axial", "r_e", "zeta"))
        dl[name] = (-2.0 * a_l * s_q / sigma
                    + e_l * (k * z_q * sum_dbj_l + ax_q * sum_thrust - s_q * sum_torque))
        dt[name] = a_t * (2.0 * r_q / r_e - 3.0 * s_q / sigma) + e_t * k * z_q * sum_dbj_t
    return a_l, a_t, {"loading": dl, "thickness": dt}
