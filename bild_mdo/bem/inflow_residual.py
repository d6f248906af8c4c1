"""BEM inflow-angle residual and induced velocities (paper Eqs. (7)-(9), with Prandtl's F).

With ``sigma = B c / (2 pi r)``, ``C_x = cl cos(phi) - cd sin(phi)``,
``C_theta = cl sin(phi) + cd cos(phi)`` (Eq. 7) and ``V_theta = Omega r``,
equating the momentum thrust and torque (Eqs. 1, 2, both multiplied by ``F``)
with the blade-element ones (Eqs. 5, 6) and closing with the inflow geometry
``tan(phi) = u_axial / (V_theta - u_theta/2)`` gives Eq. (9) generalised by ``F``:

    R(phi) = (V_x/V_theta) (sigma C_theta + 4 F |sin| cos) + sigma C_x - 4 F sin |sin|

and the induced velocities (Eq. 8 with ``F``):

    u_theta = 2 sigma C_theta V_theta / D,   u_axial = V_x + sigma C_x V_theta / D,
    D = 4 F |sin(phi)| cos(phi) + sigma C_theta.

The momentum terms carry the mass flux ``rho |u_axial|`` (``F -> F sgn(sin phi)``), as
CCBlade.jl and AeroDyn do: for ``0 < phi < pi`` this is Eq. (9) unchanged; for ``phi < 0`` (flow
reversed through the annulus) it is the momentum balance of that reversed flow, and in hover its
root is the exact mirror image of a normal hovering annulus.  ``D > 0`` is equivalent to
``W > 0`` (``tan phi = u_axial / (V_theta - u_theta/2)`` holds at every root, so only the sign
of ``W`` can be wrong): a root with ``D <= 0`` is the 180-deg mirror image of a real flow
(:mod:`bild_mdo.bem.flow_states`).

Both forms stay regular at ``V_x = 0`` (hover).  The functions below take
``cl``, ``cd`` and ``F`` as independent arguments, so callers chain in their
own polar and loss model (the BEM inflow solve) or fixed coefficients (the
BILD reference station).  Partials are *explicit*: the phi partial holds
``cl``, ``cd`` and ``F`` fixed.

High-induction correction (``high_induction='buhl'``, CCBlade's and AeroDyn's): for ``V_x > 0``
the momentum thrust ``C_T = 4 F a (1 - a)`` of an annulus (``a = 1 - u_axial / V_x``, ``C_T`` the
turbine-signed thrust over ``1/2 rho V_x^2 2 pi r dr``) is replaced above ``a_c = 0.4`` by Buhl's
(2005, NREL/TP-500-36834, Eq. 19 with F) ``C_T = 8/9 + (4 F - 40/9) a + (50/9 - 4 F) a^2``, which
meets it with the same value and slope at ``a_c``.  The torque balance and the inflow geometry
give, at every angle, ``u_axial = 4 F sin|sin| V_theta / D`` (derived in
:func:`buhl_residual_term`), so the thrust balance in Buhl's form is the residual above plus

    Delta R = (2/9) max(3 E - 5 sin(phi), 0)^2,   E = V_x D / (4 F V_theta sin(phi)),

(``3 E > 5 sin`` is ``a > 0.4``; zero in hover, where ``E = 0``, and for ``sin(phi) <= 0``), which is
continuously differentiable in every argument.  At a root with ``Delta R > 0`` the axial velocity
at the disk is ``u_axial = V_x + sigma C_x V_theta / D + Delta R V_theta / D``.

All functions broadcast and accept complex input (complex step); the
returned partials are evaluated at the real parts.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
import openmdao.api as om

from bild_mdo.utils.complex_step import real_part as _real

#: Values of the ``high_induction`` option: the momentum thrust everywhere, or Buhl's above a = 0.4.
HIGH_INDUCTION = ("none", "buhl")


def resolve_high_induction(high_induction, rotor_type):
    """``high_induction``, or where it is None the default of ``rotor_type``: Buhl's correction for a turbine
    (as CCBlade and AeroDyn apply it), none for a propeller (whose annuli past ``a = 0.4`` are flagged)."""
    if high_induction is None:
        return "buhl" if rotor_type == "turbine" else "none"
    return high_induction


class BuhlTerm(NamedTuple):
    """``Delta R`` of Buhl's correction (module docstring) and its explicit partials (names as
    :class:`InflowResidual`'s)."""

    value: np.ndarray
    d_phi: np.ndarray
    d_v_axial: np.ndarray
    d_v_theta: np.ndarray
    d_sigma: np.ndarray
    d_cl: np.ndarray
    d_cd: np.ndarray
    d_F: np.ndarray


class InflowResidual(NamedTuple):
    """Residual of Eq. (9) (with F) and its explicit partials (all dimensionless except as noted).

    Attributes
    ----------
    residual : ndarray
        R(phi).
    dR_dphi : ndarray
        Partial at fixed cl, cd, F (1/rad).
    dR_dv_axial, dR_dv_theta : ndarray
        Partials with respect to the velocities (s/m).
    dR_dsigma, dR_dcl, dR_dcd, dR_dF : ndarray
        Partials with respect to solidity, lift and drag coefficients and loss factor.
    """

    residual: np.ndarray
    dR_dphi: np.ndarray
    dR_dv_axial: np.ndarray
    dR_dv_theta: np.ndarray
    dR_dsigma: np.ndarray
    dR_dcl: np.ndarray
    dR_dcd: np.ndarray
    dR_dF: np.ndarray


class InducedVelocities(NamedTuple):
    """Induced velocities of Eq. (8) (with F) and their explicit partials.

    Attributes
    ----------
    u_axial, u_theta : ndarray
        Axial velocity at the disk ``u_axial`` and tangential induced velocity ``u_theta`` (m/s).
    du_axial_d<x>, du_theta_d<x> : ndarray
        Partials with respect to phi (m/s/rad), v_axial, v_theta (1), sigma, cl, cd and F (m/s).
    """

    u_axial: np.ndarray
    u_theta: np.ndarray
    du_axial_dphi: np.ndarray
    du_axial_dv_axial: np.ndarray
    du_axial_dv_theta: np.ndarray
    du_axial_dsigma: np.ndarray
    du_axial_dcl: np.ndarray
    du_axial_dcd: np.ndarray
    du_axial_dF: np.ndarray
    du_theta_dphi: np.ndarray
    du_theta_dv_axial: np.ndarray
    du_theta_dv_theta: np.ndarray
    du_theta_dsigma: np.ndarray
    du_theta_dcl: np.ndarray
    du_theta_dcd: np.ndarray
    du_theta_dF: np.ndarray


def force_coefficients(phi, cl, cd):
    """Axial and tangential force coefficients of Eq. (7).

    Returns
    -------
    c_x, c_theta : ndarray
        ``C_x = cl cos(phi) - cd sin(phi)``, ``C_theta = cl sin(phi) + cd cos(phi)``.
        Note ``dC_x/dphi = -C_theta`` and ``dC_theta/dphi = C_x`` at fixed cl, cd.
    """
    s, c = np.sin(phi), np.cos(phi)
    return cl * c - cd * s, cl * s + cd * c


def sign_of_sine(phi):
    """``sgn(sin phi)`` of the real part, +1 at ``sin phi = 0`` (the mass-flux sign of the momentum terms)."""
    return np.where(np.real(np.sin(phi)) < 0.0, -1.0, 1.0)


def _residual_value(phi, v_axial, v_theta, sigma, cl, cd, F):
    s, c = np.sin(phi), np.cos(phi)
    abs_s = sign_of_sine(phi) * s
    c_x, c_theta = cl * c - cd * s, cl * s + cd * c
    lam = v_axial / v_theta
    return lam * (sigma * c_theta + 4.0 * F * abs_s * c) + sigma * c_x - 4.0 * F * s * abs_s


def _buhl_gap(phi, v_axial, v_theta, sigma, cl, cd, F):
    """``(g, s, E, D, on)``: ``g = 3 E - 5 sin(phi)`` where Buhl's correction acts (``on``), 0 elsewhere."""
    s, _, _, _, _, _, _, denominator = _eq8_terms(phi, sigma, cl, cd, F)
    with np.errstate(divide="ignore", invalid="ignore"):
        excess = v_axial * denominator / (4.0 * F * v_theta * s)
        gap = 3.0 * excess - 5.0 * s
    on = (np.real(v_axial) > 0.0) & (np.real(s) > 0.0) & (np.real(F) > 0.0) & (np.real(gap) > 0.0) & np.isfinite(
        np.real(gap))
    return np.where(on, gap, 0.0), s, np.where(on, excess, 0.0), denominator, on


def buhl_residual_term(phi, v_axial, v_theta, sigma, cl, cd, F):
    """``Delta R`` of Buhl's high-induction correction (module docstring), real or complex, without partials.

    Derivation (propeller signs, ``s = sin(phi) > 0``): the torque balance with the blade element,
    ``u_theta = W^2 sigma C_theta / (2 F u_axial)``, and the geometry ``u_axial cos = (V_theta - u_theta/2)
    sin`` with ``W = u_axial / s`` give ``u_axial = 4 F s^2 V_theta / D``, so ``1 - a = s / E``.  The thrust
    balance ``-sigma C_x W^2 = V_x^2 C_T(a)`` is ``sigma C_x + E^2 C_T(a) = 0``; with ``C_T = 4 F a (1 - a)``
    that is ``R = 0`` (``E^2 4 F a s / E = lambda D a``), and Buhl's ``C_T`` exceeds it by
    ``(2/9)(5 a - 2)^2``, i.e. ``E^2 (2/9)(5 a - 2)^2 = (2/9)(3 E - 5 s)^2``.
    """
    gap = _buhl_gap(phi, v_axial, v_theta, sigma, cl, cd, F)[0]
    return (2.0 / 9.0) * gap * gap


def buhl_term(phi, v_axial, v_theta, sigma, cl, cd, F):
    """:class:`BuhlTerm`: ``Delta R`` and its explicit partials (at fixed ``cl, cd, F``), at the real parts."""
    value = buhl_residual_term(phi, v_axial, v_theta, sigma, cl, cd, F)
    phi, v_axial, v_theta, sigma, cl, cd, F = map(_real, (phi, v_axial, v_theta, sigma, cl, cd, F))
    gap, s, excess, denominator, on = _buhl_gap(phi, v_axial, v_theta, sigma, cl, cd, F)
    c = np.cos(phi)
    with np.errstate(divide="ignore", invalid="ignore"):
        # dDelta R = (4/9) g (3 dE - 5 ds); E = V_x D / (4 F V_theta s).
        lead = np.where(on, (4.0 / 9.0) * gap, 0.0)
        e_over_d = np.where(on, v_axial / (4.0 * F * v_theta * s), 0.0)
        e_over_s = np.where(on, excess / s, 0.0)
    d_D = _denominator_partials(phi, sigma, cl, cd, F)
    shape = np.broadcast(value, phi).shape

    def b(x):
        return np.broadcast_to(x, shape)

    with np.errstate(divide="ignore", invalid="ignore"):
        return BuhlTerm(
            value=value,
            d_phi=b(lead * (3.0 * (e_over_d * d_D["phi"] - e_over_s * c) - 5.0 * c)),
            d_v_axial=b(np.where(on, lead * 3.0 * excess / v_axial, 0.0)),
            d_v_theta=b(np.where(on, -lead * 3.0 * excess / v_theta, 0.0)),
            d_sigma=b(lead * 3.0 * e_over_d * d_D["sigma"]),
            d_cl=b(lead * 3.0 * e_over_d * d_D["cl"]),
            d_cd=b(lead * 3.0 * e_over_d * d_D["cd"]),
            d_F=b(np.where(on, lead * 3.0 * (e_over_d * d_D["F"] - excess / F), 0.0)),
        )


def inflow_residual(phi, v_axial, v_theta, sigma, cl, cd, F, high_induction="none"):
    """Residual of Eq. (9) generalised by the loss factor, with explicit partials.

    Parameters
    ----------
    phi : array_like
        Inflow angle (rad).
    v_axial : array_like
        Freestream axial velocity V_x (m/s), >= 0.
    v_theta : array_like
        Blade rotational speed Omega r (m/s), > 0.
    sigma : array_like
        Local solidity ``B c / (2 pi r)``.
    cl, cd : array_like
        Section lift and drag coefficients.
    F : array_like
        Prandtl loss factor.
    high_induction : {'none', 'buhl'}
        Buhl's correction above ``a = 0.4`` (module docstring), or none.

    Returns
    -------
    InflowResidual

    Raises
    ------
    openmdao.api.AnalysisError
        Where the residual or a partial is not finite (inputs beyond the floating-point range).
    """
    # Extreme inputs (V_x / V_theta beyond 1e300) overflow here; they are reported once below as an
    # AnalysisError instead of NumPy warnings and silently infinite partials.
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        result = _inflow_residual(phi, v_axial, v_theta, sigma, cl, cd, F)
        if high_induction == "buhl":
            term = buhl_term(phi, v_axial, v_theta, sigma, cl, cd, F)
            result = InflowResidual(*(x + t for x, t in zip(result, term)))
    _require_finite(result, "inflow residual", v_axial, v_theta, sigma)
    return result


def _require_finite(result, what, v_axial, v_theta, sigma):
    """Raise AnalysisError where a value or partial of ``result`` is not finite."""
    if all(np.all(np.isfinite(np.real(x))) for x in result):
        return
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        ratio = np.max(np.real(v_axial) / np.real(v_theta))
    raise om.AnalysisError(f"BEM {what}: not finite (V_x / V_theta up to {ratio:.3g}, solidity up to "
                           f"{np.max(np.real(sigma)):.3g}); the inputs are beyond the floating-point range "
                           "of the momentum equations (check rpm, radii, chord and the number of blades)")


def _inflow_residual(phi, v_axial, v_theta, sigma, cl, cd, F):
    value = _residual_value(phi, v_axial, v_theta, sigma, cl, cd, F)
    phi, v_axial, v_theta, sigma, cl, cd, F = map(_real, (phi, v_axial, v_theta, sigma, cl, cd, F))
    s, c = np.sin(phi), np.cos(phi)
    sgn = sign_of_sine(phi)
    abs_s = sgn * s
    c_x, c_theta = cl * c - cd * s, cl * s + cd * c
    lam = v_axial / v_theta
    bracket = sigma * c_theta + 4.0 * F * abs_s * c
    shape = np.broadcast(value, phi).shape
    # d(|s| c)/dphi = sgn cos(2 phi), d(s |s|)/dphi = sgn sin(2 phi)
    return InflowResidual(
        residual=value,
        dR_dphi=np.broadcast_to(lam * (sigma * c_x + 4.0 * F * sgn * np.cos(2.0 * phi))
                                - sigma * c_theta - 4.0 * F * sgn * np.sin(2.0 * phi), shape),
        dR_dv_axial=np.broadcast_to(bracket / v_theta, shape),
        dR_dv_theta=np.broadcast_to(-lam * bracket / v_theta, shape),
        dR_dsigma=np.broadcast_to(lam * c_theta + c_x, shape),
        dR_dcl=np.broadcast_to(sigma * (lam * s + c), shape),
        dR_dcd=np.broadcast_to(sigma * (lam * c - s), shape),
        dR_dF=np.broadcast_to(4.0 * abs_s * (lam * c - s), shape),
    )


def inflow_residual_value(phi, v_axial, v_theta, sigma, cl, cd, F, high_induction="none"):
    """Only the residual of Eq. (9) with F (real or complex), without partials."""
    value = _residual_value(phi, v_axial, v_theta, sigma, cl, cd, F)
    if high_induction == "buhl":
        value = value + buhl_residual_term(phi, v_axial, v_theta, sigma, cl, cd, F)
    return value


def _denominator_partials(phi, sigma, cl, cd, F):
    """Partials of Eq. (8)'s ``D = 4 F |sin| cos + sigma C_theta`` (explicit: ``cl, cd, F`` fixed), by argument."""
    s, c, c_x, c_theta, _, _, _, _ = _eq8_terms(phi, sigma, cl, cd, F)
    return {"phi": 4.0 * F * sign_of_sine(phi) * np.cos(2.0 * phi) + sigma * c_x, "sigma": c_theta,
            "cl": sigma * s, "cd": sigma * c, "F": 4.0 * (sign_of_sine(phi) * s) * c}


def _eq8_terms(phi, sigma, cl, cd, F):
    """``sin, cos, C_x, C_theta`` and the terms ``P = 4 F |sin| cos``, ``N = sigma C_theta``,
    ``M = sigma C_x``, ``D = P + N`` of Eq. (8)."""
    s, c = np.sin(phi), np.cos(phi)
    c_x, c_theta = cl * c - cd * s, cl * s + cd * c
    P = 4.0 * F * (sign_of_sine(phi) * s) * c
    N = sigma * c_theta
    M = sigma * c_x
    return s, c, c_x, c_theta, P, N, M, P + N


def induced_velocities(phi, v_axial, v_theta, sigma, cl, cd, F, high_induction="none"):
    """Induced velocities of Eq. (8) generalised by the loss factor, with explicit partials.

    Parameters are those of :func:`inflow_residual`; with ``high_induction='buhl'`` the axial velocity
    gains ``Delta R V_theta / D`` (module docstring).

    Returns
    -------
    InducedVelocities
        ``u_axial = V_x + sigma C_x V_theta / D`` and
        ``u_theta = 2 sigma C_theta V_theta / D`` with
        ``D = 4 F |sin(phi)| cos(phi) + sigma C_theta`` (``D > 0`` <=> ``W > 0``).
    """
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        result = _induced_velocities(phi, v_axial, v_theta, sigma, cl, cd, F)
        if high_induction == "buhl":
            result = _buhl_velocity(result, phi, v_axial, v_theta, sigma, cl, cd, F)
    _require_finite(result, "induced velocities", v_axial, v_theta, sigma)
    return result


def buhl_axial_velocity(phi, v_axial, v_theta, sigma, cl, cd, F):
    """``Delta R V_theta / D``: what Buhl's correction adds to Eq. (8)'s ``u_axial`` (real or complex)."""
    _, _, _, _, _, _, _, D = _eq8_terms(phi, sigma, cl, cd, F)
    with np.errstate(divide="ignore", invalid="ignore"):
        return buhl_residual_term(phi, v_axial, v_theta, sigma, cl, cd, F) * v_theta / D


def _buhl_velocity(result, phi, v_axial, v_theta, sigma, cl, cd, F):
    """``result`` with ``u_axial`` and its partials gaining ``Delta R V_theta / D``."""
    u_axial = result.u_axial + buhl_axial_velocity(phi, v_axial, v_theta, sigma, cl, cd, F)
    term = buhl_term(phi, v_axial, v_theta, sigma, cl, cd, F)
    phi, v_axial, v_theta, sigma, cl, cd, F = map(_real, (phi, v_axial, v_theta, sigma, cl, cd, F))
    D = _eq8_terms(phi, sigma, cl, cd, F)[-1]
    # d(dR V / D) = (V / D) d(dR) + (dR / D) dV - (dR V / D^2) dD, at the real parts
    value = _real(term.value)
    ratio, scaled = v_theta / D, value * v_theta / D**2
    d_D = _denominator_partials(phi, sigma, cl, cd, F)
    return result._replace(
        u_axial=u_axial,
        du_axial_dphi=result.du_axial_dphi + ratio * term.d_phi - scaled * d_D["phi"],
        du_axial_dv_axial=result.du_axial_dv_axial + ratio * term.d_v_axial,
        du_axial_dv_theta=result.du_axial_dv_theta + ratio * term.d_v_theta + value / D,
        du_axial_dsigma=result.du_axial_dsigma + ratio * term.d_sigma - scaled * d_D["sigma"],
        du_axial_dcl=result.du_axial_dcl + ratio * term.d_cl - scaled * d_D["cl"],
        du_axial_dcd=result.du_axial_dcd + ratio * term.d_cd - scaled * d_D["cd"],
        du_axial_dF=result.du_axial_dF + ratio * term.d_F - scaled * d_D["F"],
    )


def _induced_velocities(phi, v_axial, v_theta, sigma, cl, cd, F):
    _, _, _, _, P, N, M, D = _eq8_terms(phi, sigma, cl, cd, F)
    u_theta = 2.0 * v_theta * N / D
    u_axial = v_axial + v_theta * M / D

    # Partials are real: the same terms from the real parts.
    phi, v_axial, v_theta, sigma, cl, cd, F = map(_real, (phi, v_axial, v_theta, sigma, cl, cd, F))
    s, c, c_x, c_theta, P, N, M, D = _eq8_terms(phi, sigma, cl, cd, F)
    shape = np.broadcast(u_axial, u_theta, phi).shape

    # Intermediate partials: P(phi, F), N(phi, sigma, cl, cd), M(phi, sigma, cl, cd).
    sgn = sign_of_sine(phi)
    dP_dphi, dP_dF = 4.0 * F * sgn * np.cos(2.0 * phi), 4.0 * (sgn * s) * c
    dN_dphi, dN_dsigma, dN_dcl, dN_dcd = sigma * c_x, c_theta, sigma * s, sigma * c
    dM_dphi, dM_dsigma, dM_dcl, dM_dcd = -sigma * c_theta, c_x, sigma * c, -sigma * s

    # u_theta = 2 V N / (P + N)
    ut_N = 2.0 * v_theta * P / D**2
    ut_P = -2.0 * v_theta * N / D**2
    # u_axial = V_x + V M / (P + N)
    ux_M = v_theta / D
    ux_D = -v_theta * M / D**2

    def b(x):
        return np.broadcast_to(x, shape)

    return InducedVelocities(
        u_axial=u_axial,
        u_theta=u_theta,
        du_axial_dphi=b(ux_M * dM_dphi + ux_D * (dP_dphi + dN_dphi)),
        du_axial_dv_axial=b(np.ones(shape)),
        du_axial_dv_theta=b(M / D),
        du_axial_dsigma=b(ux_M * dM_dsigma + ux_D * dN_dsigma),
        du_axial_dcl=b(ux_M * dM_dcl + ux_D * dN_dcl),
        du_axial_dcd=b(ux_M * dM_dcd + ux_D * dN_dcd),
        du_axial_dF=b(ux_D * dP_dF),
        du_theta_dphi=b(ut_N * dN_dphi + ut_P * dP_dphi),
        du_theta_dv_axial=b(np.zeros(shape)),
        du_theta_dv_theta=b(2.0 * N / D),
        du_theta_dsigma=b(ut_N * dN_dsigma),
        du_theta_dcl=b(ut_N * dN_dcl),
        du_theta_dcd=b(ut_N * dN_dcd),
        du_theta_dF=b(ut_P * dP_dF),
    )
