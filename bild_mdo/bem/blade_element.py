"""Blade-section kinematics, aerodynamics and loads with forward-mode partials.

Shared by :class:`~bild_mdo.bem.inflow.InflowComp` (residual and its
partials) and :class:`~bild_mdo.bem.loads.BladeElementLoadsComp` (loads and
their partials), so both components use one set of formulas.

Kinematics: ``V_theta = Omega r`` with ``Omega = rpm pi/30`` (:mod:`bild_mdo.constants`), local solidity
``sigma = B c / (2 pi r)``, angle of attack ``alpha = twist - phi``.  In inclined flow (precone, tilt,
yaw, shear, azimuth sectors: :mod:`bild_mdo.bem.wind_components`) the components take the freestream
velocity of every station instead, ``v_axial_local[nn, nr]`` and ``v_theta_local[nn, nr]`` (option
``station_velocities``): the same formulas with ``V_x`` and ``V_theta`` per station.

Reynolds number: ``Re = rho W0 c / mu`` with ``W0 = sqrt(V_x^2 + V_theta^2)``,
the local speed *without* induction (as CCBlade does).  This keeps ``Re``
independent of ``phi``, so the residual stays a function of ``phi`` alone and
the bracketed solve remains one-dimensional.  Induction typically changes the
local speed by a few per cent, and polars vary slowly with ``Re``.

Loads (blade element, Eqs. 5-7): ``W^2 = u_axial^2 + (V_theta - u_theta/2)^2``,
``dT/dr = 1/2 rho W^2 B c C_x`` and ``dQ/dr = 1/2 rho W^2 B c C_theta r``
(the printed Eq. (6) omits the moment arm ``r``).

Mach number: the polar is evaluated at ``W0 / a``, from the same speed without induction as
``Re`` (CCBlade.jl does the same for both).  The induced ``W`` depends on ``C_l, C_d`` at the root
(Eq. 8), so a polar Mach number from ``W`` would make the polar depend on itself and the solve
two-dimensional; with ``W0`` the residual stays a function of ``phi`` alone.  The reported local
Mach number (output ``mach``) is ``W / a`` with the induced inflow speed, the same definition as
BILD's.  The polar receives ``mach`` only where
``polar.varies_with_mach`` and ``radial_fraction = r/R`` only where ``polar.varies_along_span``,
so a uniform, Mach-independent polar is evaluated exactly as before.

Collective pitch: the blade pitch is ``twist + collective_pitch`` at every station, so
``alpha = twist + collective_pitch - phi``.

Every quantity is carried with a dict of partials with respect to the
component inputs ``phi, v_axial, rpm, radii, chord, twist, rho, mu, radius,
hub_radius, speed_of_sound, collective_pitch`` (arrays broadcast to the station shape).

BEM (:class:`~bild_mdo.bem.inflow.InflowComp`,
:class:`~bild_mdo.bem.loads.BladeElementLoadsComp`) and BILD's reference
station (:mod:`bild_mdo.bild.variants.reference_point.reference_station`) declare their options and
inputs here (:func:`declare_section_options`, :func:`add_section_inputs`).
"""
from __future__ import annotations

import numpy as np

from bild_mdo.airfoil.polar import Polar
from bild_mdo.bem.inflow_residual import (buhl_axial_velocity, buhl_term, force_coefficients, induced_velocities,
                                          inflow_residual, inflow_residual_value, sign_of_sine)
from bild_mdo.bem.prandtl import LOSS_MODELS, loss_inputs, loss_partials, prandtl_loss, prandtl_loss_and_dphi
from bild_mdo.bem.station_velocities import STATION_VELOCITIES, station_mode
from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.utils.complex_step import real_part as _real
from bild_mdo.utils.options import VARIABLES, add_inputs, declare_size_options

#: Inputs of the BEM blade element, in declaration order (collective pitch and the speed of sound
#: are the BEM's own: BILD designs the pitch and reads no speed of sound at its stations).
SECTION_INPUTS = ("v_axial", "rpm", "radius", "hub_radius", "radii", "chord", "twist", "rho", "mu",
                  "speed_of_sound", "collective_pitch")
#: Per-node inputs (shape (nn,)) of the section components; the others are per station (nn, nr).
NODE_INPUTS = tuple(name for name in SECTION_INPUTS if VARIABLES[name][0] == "node")
_SEA_LEVEL_SPEED_OF_SOUND = VARIABLES["speed_of_sound"][1]


def _lin(*terms):
    """Linear combination of partial dicts: ``_lin((a, da), (b, db))`` -> ``a*da + b*db``."""
    out = {}
    for coef, d in terms:
        for key, val in d.items():
            out[key] = out[key] + coef * val if key in out else coef * val
    return out


def reynolds_number(v_axial, v_theta, chord, rho, mu):
    """Chord Reynolds number from the speed without induction, ``rho W0 c / mu``."""
    return rho * np.sqrt(v_axial**2 + v_theta**2) * chord / mu


def polar_arguments(polar, w0, speed_of_sound, radii, radius):
    """``(mach, radial_fraction)`` for ``polar.evaluate``: ``W0 / a`` and ``r / R`` where the polar needs them.

    Each is None where the polar does not vary with it, so such a polar is evaluated as before.
    """
    mach = w0 / speed_of_sound if polar.varies_with_mach else None
    fraction = radii / radius if polar.varies_along_span else None
    return mach, fraction


def _at(value, idx):
    return None if value is None else value[idx]


def blade_speed(rpm, radii, v_theta=None):
    """The station's tangential freestream speed: ``Omega r`` (axial flow), or the given ``v_theta`` (m/s).

    ``v_theta`` is given by the per-station kinematics of inclined flow
    (:mod:`bild_mdo.bem.wind_components`); then ``rpm`` is not used.
    """
    return rpm * RPM_TO_RAD_PER_S * radii if v_theta is None else v_theta


def _station_setup(v_axial, rpm, radii, chord, twist, rho, mu, radius, num_blades, polar, speed_of_sound,
                   collective_pitch, v_theta=None):
    """What a station's residual needs besides phi: ``V_theta``, solidity, Re, pitch and the polar's M and r/R."""
    v_theta = blade_speed(rpm, radii, v_theta)
    sigma = num_blades * chord / (2.0 * np.pi * radii)
    reynolds = reynolds_number(v_axial, v_theta, chord, rho, mu)
    mach, fraction = polar_arguments(polar, np.sqrt(v_axial**2 + v_theta**2), speed_of_sound, radii, radius)
    return v_theta, sigma, reynolds, twist + collective_pitch, mach, fraction


def residual_function(v_axial, rpm, radii, chord, twist, rho, mu, radius, hub_radius,
                      num_blades, polar, loss_model, speed_of_sound=_SEA_LEVEL_SPEED_OF_SOUND,
                      collective_pitch=0.0, v_theta=None, high_induction="none"):
    """A real ``residual(phi, idx) -> (R, dR/dphi)`` over flat station indices for the solver.

    All inputs are real arrays already broadcast to the flat station shape; ``v_theta`` (optional)
    replaces ``Omega r`` by a given tangential freestream speed (:func:`blade_speed`);
    ``high_induction`` as :func:`~bild_mdo.bem.inflow_residual.inflow_residual`'s.
    ``dR/dphi`` is the total derivative along phi (through alpha and F; ``M`` and ``r/R`` do not
    depend on phi).
    """
    v_theta, sigma, reynolds, pitch, mach, fraction = _station_setup(
        v_axial, rpm, radii, chord, twist, rho, mu, radius, num_blades, polar, speed_of_sound, collective_pitch,
        v_theta)

    def residual(phi, idx):
        pv = polar.evaluate(pitch[idx] - phi, reynolds[idx], mach=_at(mach, idx), radial_fraction=_at(fraction, idx))
        F, dF_dphi = prandtl_loss_and_dphi(phi, radii[idx], radius[idx], hub_radius[idx], num_blades,
                                           loss_model)
        # Eq. (9) with F and its total phi derivative (through alpha = twist - phi and F);
        # the same formulas as inflow_residual, without the partials the solve does not need.
        lam = v_axial[idx] / v_theta[idx]
        sig = sigma[idx]
        s, c = np.sin(phi), np.cos(phi)
        sgn = sign_of_sine(phi)
        abs_s = sgn * s
        c_x = pv.cl * c - pv.cd * s
        c_theta = pv.cl * s + pv.cd * c
        value = lam * (sig * c_theta + 4.0 * F * abs_s * c) + sig * c_x - 4.0 * F * s * abs_s
        d_explicit = (lam * (sig * c_x + 4.0 * F * sgn * (c * c - s * s)) - sig * c_theta
                      - 8.0 * F * abs_s * c)
        d_cl = sig * (lam * s + c)
        d_cd = sig * (lam * c - s)
        d_F = 4.0 * abs_s * (lam * c - s)
        if high_induction == "buhl":
            t = buhl_term(phi, v_axial[idx], v_theta[idx], sig, pv.cl, pv.cd, F)
            value, d_explicit = value + t.value, d_explicit + t.d_phi
            d_cl, d_cd, d_F = d_cl + t.d_cl, d_cd + t.d_cd, d_F + t.d_F
        return value, d_explicit - d_cl * pv.dcl_dalpha - d_cd * pv.dcd_dalpha + d_F * dF_dphi

    return residual


def denominator_function(v_axial, rpm, radii, chord, twist, rho, mu, radius, hub_radius,
                         num_blades, polar, loss_model, speed_of_sound=_SEA_LEVEL_SPEED_OF_SOUND,
                         collective_pitch=0.0, v_theta=None):
    """A real ``admissible(phi, idx) -> bool`` over flat station indices: ``D > 0`` of Eq. (8), i.e. ``W > 0``.

    Arguments as in :func:`residual_function`.
    """
    v_theta, sigma, reynolds, pitch, mach, fraction = _station_setup(
        v_axial, rpm, radii, chord, twist, rho, mu, radius, num_blades, polar, speed_of_sound, collective_pitch,
        v_theta)

    def admissible(phi, idx):
        pv = polar.evaluate(pitch[idx] - phi, reynolds[idx], mach=_at(mach, idx), radial_fraction=_at(fraction, idx))
        F = prandtl_loss(phi, radii[idx], radius[idx], hub_radius[idx], num_blades, loss_model).F
        _, c_theta = force_coefficients(phi, pv.cl, pv.cd)
        return 4.0 * F * (sign_of_sine(phi) * np.sin(phi)) * np.cos(phi) + sigma[idx] * c_theta > 0.0

    return admissible


def inflow_angle_guess(v_axial, rpm, radii, chord, twist, num_blades, lift_slope=2.0 * np.pi, v_theta=None):
    """Small-angle estimate of the region-1 inflow angle (rad), a first iterate for the solve.

    With ``cl = a (twist - phi)``, no drag, ``F = 1`` and ``sin phi ~ phi``,
    ``cos phi ~ 1``, the residual becomes the quadratic
    ``(lam sigma a + 4) phi^2 - (lam sigma a twist + 4 lam - sigma a) phi - sigma a twist = 0``
    (``lam = V_x / V_theta``), whose non-negative root is returned.  It tends
    to ``V_x / V_theta`` for a lightly loaded blade and to the momentum-theory
    hover angle at ``V_x = 0``.  Only a starting point: the solve keeps its bracket.
    """
    v_theta = blade_speed(rpm, radii, v_theta)
    lam = v_axial / v_theta
    sa = num_blades * chord / (2.0 * np.pi * radii) * lift_slope
    a2 = lam * sa + 4.0
    b = lam * sa * twist + 4.0 * lam - sa
    disc = np.maximum(b * b + 4.0 * a2 * sa * twist, 0.0)
    return (b + np.sqrt(disc)) / (2.0 * a2)


def evaluate_section(phi, v_axial, rpm, radii, chord, twist, rho, mu, radius, hub_radius,
                     num_blades, polar, loss_model, loads=True, partials=True, unloaded=None,
                     speed_of_sound=_SEA_LEVEL_SPEED_OF_SOUND, collective_pitch=0.0, v_theta=None,
                     high_induction="none"):
    """Residual, aerodynamics and (optionally) loads at every station, with partials.

    Parameters
    ----------
    phi, radii, chord, twist : ndarray
        Station arrays, shape (nn, nr) (rad, m, m, rad).
    v_axial, rpm, rho, mu, radius, hub_radius : ndarray
        Per-node arrays, shape (nn, 1) or broadcastable (m/s, rpm, kg/m^3, Pa s, m, m).
    num_blades : int
    polar : Polar
    loss_model : {'tip_hub', 'tip', 'none'}
    loads : bool
        Also compute induced velocities, inflow speed and loads.
    partials : bool
        Also compute the partials (else the second return value is empty).
    unloaded : ndarray of bool, optional
        Stations without a momentum solution (:data:`~bild_mdo.bem.flow_states.NO_SOLUTION`):
        there the loads take CCBlade's "zero loading" values ``u_axial = V_x``,
        ``u_theta = 0``, ``W = W0``, ``dT/dr = dQ/dr = 0`` (with their exact partials).
    speed_of_sound, collective_pitch : ndarray or float
        Per-node speed of sound (m/s) and collective pitch (rad), broadcastable like ``rpm``.
    v_theta : ndarray, optional
        Tangential freestream speed of each station (m/s), shape (nn, nr), instead of ``Omega r``
        (inclined flow, :mod:`bild_mdo.bem.wind_components`; ``v_axial`` is then per station too).
        Its partials are keyed ``'v_theta'`` (and none are keyed ``'rpm'``).
    high_induction : {'none', 'buhl'}
        Buhl's thrust above ``a = 0.4`` (:mod:`bild_mdo.bem.inflow_residual`): the residual and ``u_axial``.

    Returns
    -------
    values : dict
        'residual', 'alpha', 'reynolds', 'mach', 'lift_coefficient', 'drag_coefficient', 'loss_factor'
        and, with ``loads``,
        'u_axial', 'u_theta', 'inflow_speed', 'dthrust_dr', 'dtorque_dr' and the
        'denominator' ``D`` of Eq. (8) (``D > 0`` <=> ``W > 0``; no partials).
    partials : dict
        name -> {input name: array broadcastable to (nn, nr)} (real).
    """
    shape = np.broadcast_shapes(np.shape(phi), np.shape(v_axial), np.shape(radii))
    ones = np.ones(shape)
    if v_theta is None:
        omega = rpm * RPM_TO_RAD_PER_S
        v_theta = omega * radii
        d_vtheta = {"rpm": RPM_TO_RAD_PER_S * _real(radii) * ones, "radii": _real(omega) * ones}
    else:
        d_vtheta = {"v_theta": ones}
    sigma = num_blades * chord / (2.0 * np.pi * radii)
    alpha = (twist + collective_pitch) - phi
    w0 = np.sqrt(v_axial**2 + v_theta**2)
    reynolds = rho * w0 * chord / mu
    mach_arg, fraction = polar_arguments(polar, w0, speed_of_sound, radii, radius)
    pv = polar.evaluate(alpha, reynolds, mach=mach_arg, radial_fraction=fraction)
    loss = prandtl_loss(phi, radii, radius, hub_radius, num_blades, loss_model)
    mach = w0 / speed_of_sound
    values = {"residual": inflow_residual_value(phi, v_axial, v_theta, sigma, pv.cl, pv.cd, loss.F,
                                                high_induction),
              "alpha": alpha * ones, "reynolds": reynolds * ones, "mach": mach * ones, "lift_coefficient": pv.cl,
              "drag_coefficient": pv.cd,
              "loss_factor": loss.F * ones}
    if loads:
        c_x, c_theta = force_coefficients(phi, pv.cl, pv.cd)
        # Eq. (8) with F (mass flux rho |u_axial|: see bild_mdo.bem.inflow_residual)
        denom = 4.0 * loss.F * (sign_of_sine(phi) * np.sin(phi)) * np.cos(phi) + sigma * c_theta
        u_axial = v_axial + v_theta * sigma * c_x / denom
        if high_induction == "buhl":
            u_axial = u_axial + buhl_axial_velocity(phi, v_axial, v_theta, sigma, pv.cl, pv.cd, loss.F)
        u_theta = 2.0 * v_theta * sigma * c_theta / denom
        # Eq. (7): W^2 = u_axial^2 + (V_theta - u_theta/2)^2
        w2 = u_axial**2 + (v_theta - 0.5 * u_theta) ** 2
        # Eqs. (5), (6): dT/dr = 1/2 rho W^2 B c C_x, dQ/dr = 1/2 rho W^2 B c C_theta r
        q = 0.5 * rho * w2 * num_blades * chord
        values.update(u_axial=u_axial, u_theta=u_theta, inflow_speed=np.sqrt(w2),
                      dthrust_dr=q * c_x, dtorque_dr=q * c_theta * radii, denominator=denom * ones)
        if unloaded is not None and np.any(unloaded):
            zero = 0.0 * ones
            for name, value in (("u_axial", v_axial * ones), ("u_theta", zero), ("inflow_speed", w0 * ones),
                                ("dthrust_dr", zero), ("dtorque_dr", zero)):
                values[name] = np.where(unloaded, value, values[name])
        # The reported local Mach number uses the inflow speed with induction, W / a (as BILD's); the polar
        # above is evaluated at W0 / a, the speed of the Reynolds number, so the solve stays one-dimensional.
        values["mach"] = values["inflow_speed"] / speed_of_sound * ones
    if not partials:
        return values, {}
    d = _section_partials(phi, v_axial, v_theta, d_vtheta, radii, chord, sigma, w0,
                          reynolds, rho, mu, pv, loss, num_blades, loss_model, loads, ones,
                          mach, speed_of_sound, fraction, radius, high_induction)
    if loads and unloaded is not None and np.any(unloaded):
        d_w0 = _lin((_real(v_axial / w0), {"v_axial": ones}), (_real(v_theta / w0), d_vtheta))
        for name, fixed in (("u_axial", {"v_axial": ones}), ("u_theta", {}), ("inflow_speed", d_w0),
                            ("dthrust_dr", {}), ("dtorque_dr", {})):
            d[name] = {key: np.where(unloaded, fixed.get(key, 0.0), d[name].get(key, 0.0))
                       for key in set(d[name]) | set(fixed)}
    if loads:
        a = _real(speed_of_sound)
        d["mach"] = _lin((1.0 / a * ones, d["inflow_speed"]), (-_real(values["mach"]) / a, {"speed_of_sound": ones}))
    return values, d


def _section_partials(phi, v_axial, v_theta, d_vtheta, radii, chord, sigma, w0, reynolds, rho, mu,
                      pv, loss, num_blades, loss_model, loads, ones, mach, speed_of_sound, fraction, radius,
                      high_induction="none"):
    """Forward-mode partials of every section quantity with respect to the component inputs."""
    phi, v_axial, v_theta, radii, chord, sigma, w0, reynolds, rho, mu, mach, speed_of_sound, radius = map(
        _real, (phi, v_axial, v_theta, radii, chord, sigma, w0, reynolds, rho, mu, mach, speed_of_sound, radius))
    cl, cd = _real(pv.cl), _real(pv.cd)
    F = _real(loss.F)
    res = inflow_residual(phi, v_axial, v_theta, sigma, cl, cd, F, high_induction)

    d_phi = {"phi": ones}
    d_vx = {"v_axial": ones}
    d_sigma = {"chord": sigma / chord * ones, "radii": -sigma / radii * ones}
    d_alpha = {"twist": ones, "collective_pitch": ones, "phi": -ones}
    d_w0 = _lin((v_axial / w0, d_vx), (v_theta / w0, d_vtheta))
    d_re = _lin((reynolds / w0, d_w0), (reynolds / chord, {"chord": ones}),
                (reynolds / rho, {"rho": ones}), (-reynolds / mu, {"mu": ones}))
    d_mach = _lin((1.0 / speed_of_sound, d_w0), (-mach / speed_of_sound, {"speed_of_sound": ones}))
    cl_terms, cd_terms = [(pv.dcl_dalpha, d_alpha), (pv.dcl_dre, d_re)], [(pv.dcd_dalpha, d_alpha), (pv.dcd_dre, d_re)]
    if hasattr(pv, "dcl_dmach"):
        cl_terms.append((pv.dcl_dmach, d_mach))
        cd_terms.append((pv.dcd_dmach, d_mach))
    if fraction is not None:
        d_fraction = {"radii": ones / radius, "radius": -_real(fraction) / radius * ones}
        cl_terms.append((pv.dcl_dradial_fraction, d_fraction))
        cd_terms.append((pv.dcd_dradial_fraction, d_fraction))
    d_cl = _lin(*cl_terms)
    d_cd = _lin(*cd_terms)
    d_F = loss_partials(loss, loss_model)
    d_res = _lin((res.dR_dphi, d_phi), (res.dR_dv_axial, d_vx), (res.dR_dv_theta, d_vtheta),
                 (res.dR_dsigma, d_sigma), (res.dR_dcl, d_cl), (res.dR_dcd, d_cd),
                 (res.dR_dF, d_F))
    partials = {"residual": d_res, "alpha": d_alpha, "reynolds": d_re, "mach": d_mach, "lift_coefficient": d_cl,
                "drag_coefficient": d_cd, "loss_factor": d_F}
    if not loads:
        return partials

    ind = induced_velocities(phi, v_axial, v_theta, sigma, cl, cd, F, high_induction)
    d_ux = _lin((ind.du_axial_dphi, d_phi), (ind.du_axial_dv_axial, d_vx),
                (ind.du_axial_dv_theta, d_vtheta), (ind.du_axial_dsigma, d_sigma),
                (ind.du_axial_dcl, d_cl), (ind.du_axial_dcd, d_cd), (ind.du_axial_dF, d_F))
    d_ut = _lin((ind.du_theta_dphi, d_phi), (ind.du_theta_dv_theta, d_vtheta),
                (ind.du_theta_dsigma, d_sigma), (ind.du_theta_dcl, d_cl),
                (ind.du_theta_dcd, d_cd), (ind.du_theta_dF, d_F))

    v_tan = v_theta - 0.5 * ind.u_theta
    w2 = ind.u_axial**2 + v_tan**2
    d_vtan = _lin((1.0, d_vtheta), (-0.5, d_ut))
    d_w2 = _lin((2.0 * ind.u_axial, d_ux), (2.0 * v_tan, d_vtan))
    d_w = _lin((0.5 / np.sqrt(w2), d_w2))

    s, c = np.sin(phi), np.cos(phi)
    c_x, c_theta = force_coefficients(phi, cl, cd)
    d_cx = _lin((-c_theta, d_phi), (c, d_cl), (-s, d_cd))
    d_ctheta = _lin((c_x, d_phi), (s, d_cl), (c, d_cd))
    half_b = 0.5 * num_blades
    q = half_b * rho * w2 * chord
    d_q = _lin((half_b * rho * chord, d_w2), (half_b * w2 * chord, {"rho": ones}),
               (half_b * rho * w2, {"chord": ones}))
    d_dthrust = _lin((c_x, d_q), (q, d_cx))
    d_dtorque = _lin((c_theta * radii, d_q), (q * radii, d_ctheta), (q * c_theta, {"radii": ones}))
    partials.update(u_axial=d_ux, u_theta=d_ut, inflow_speed=d_w, dthrust_dr=d_dthrust,
                    dtorque_dr=d_dtorque)
    return partials


def declare_section_options(options, radial=True, polar=True):
    """Options of a blade-element component: sizes, ``num_blades``, the ``polar`` and the ``loss_model``.

    Parameters
    ----------
    options : OptionsDictionary
        The component's ``self.options``.
    radial : bool
        Whether the component has radial stations (False for BILD's reference station).
    polar : bool
        Whether the component reads the polar (False where ``C_l*, C_d*`` are inputs).
    """
    declare_size_options(options, radial=radial)
    options.declare("num_blades", types=int, default=3, desc="number of blades B")
    if polar:
        options.declare("polar", types=Polar, recordable=False, desc="airfoil polar cl, cd (alpha, Re)")
    options.declare("loss_model", default="tip_hub", values=LOSS_MODELS,
                    desc="Prandtl loss factor: tip x hub, tip only, or none")


def add_section_inputs(comp, names=SECTION_INPUTS, **values):
    """Declare the blade-element inputs ``names`` on ``comp`` (BEM stations or BILD's reference station).

    Parameters
    ----------
    comp : openmdao.api.Component
        Called in its ``setup``.
    names : iterable of str
        Input names of :data:`bild_mdo.utils.options.VARIABLES`; by default the
        BEM section inputs :data:`SECTION_INPUTS`.
    **values
        Default values other than the catalogue's.
    """
    if "radii" in names and "radii" not in values:
        values["radii"] = np.linspace(0.2, 0.95, comp.options["num_radial"])
    add_inputs(comp, names, **values)


def add_station_section_inputs(comp):
    """Declare the section inputs of ``comp``: :data:`SECTION_INPUTS`, or, with ``station_velocities``,
    those without ``v_axial`` and ``rpm`` plus ``v_axial_local`` and ``v_theta_local`` (nn, nr) (m/s)."""
    if not station_mode(comp.options):
        add_section_inputs(comp)
        return
    add_section_inputs(comp, tuple(name for name in SECTION_INPUTS if name not in ("v_axial", "rpm")))
    shape = (comp.options["num_nodes"], comp.options["num_radial"])
    comp.add_input("v_axial_local", val=np.full(shape, 10.0), units="m/s", desc=STATION_VELOCITIES["v_axial_local"][1])
    comp.add_input("v_theta_local", val=np.full(shape, 50.0), units="m/s", desc=STATION_VELOCITIES["v_theta_local"][1])


def section_input_names(loss_model, polar, station_velocities=False):
    """Inputs the residual and the polar depend on.

    ``radius`` and ``hub_radius`` enter through the loss factor, ``radius`` also through ``r/R``
    of a polar that varies along the span; ``speed_of_sound`` only through the Mach number of a
    polar that varies with it.  With ``station_velocities`` ``v_axial_local`` and ``v_theta_local``
    replace ``v_axial`` and ``rpm``.
    """
    names = ["v_axial", "rpm", "radii", "chord", "twist", "collective_pitch", "rho", "mu"]
    if station_velocities:
        names[:2] = list(STATION_VELOCITIES)
    names += list(loss_inputs(loss_model))
    if polar.varies_with_mach:
        names.append("speed_of_sound")
    if polar.varies_along_span and "radius" not in names:
        names.append("radius")
    return names


def section_arguments(inputs, options):
    """Keyword arguments for :func:`evaluate_section` from component inputs (node inputs as (nn, 1))."""
    if station_mode(options):
        kw = {name: inputs[name][:, None] for name in NODE_INPUTS if name not in ("v_axial", "rpm")}
        kw.update(v_axial=inputs["v_axial_local"], rpm=None, v_theta=inputs["v_theta_local"])
    else:
        kw = {name: inputs[name][:, None] for name in NODE_INPUTS}
    kw.update(radii=inputs["radii"], chord=inputs["chord"], twist=inputs["twist"],
              num_blades=options["num_blades"], polar=options["polar"],
              loss_model=options["loss_model"],
              high_induction=options["high_induction"] if "high_induction" in options else "none")
    return kw
