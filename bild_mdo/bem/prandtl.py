"""Prandtl tip and hub loss factor with its partial derivatives.

The paper (Sec. 3) uses Prandtl's formulation in every result:

    F_tip = 2/pi * acos(exp(-f_tip)),  f_tip = B (R - r) / (2 r |sin phi|)
    F_hub = 2/pi * acos(exp(-f_hub)),  f_hub = B (r - r_hub) / (2 r_hub |sin phi|)
    F = F_tip * F_hub

Two guards keep the factor finite and its derivatives consistent:

* ``|sin phi|`` is floored at :data:`SIN_PHI_FLOOR` (the derivative with
  respect to ``phi`` is zero where the floor is active), so ``phi -> 0``
  gives a huge exponent instead of a division by zero.
* The exponent is clipped to ``[EXPONENT_MIN, EXPONENT_MAX]`` with zero
  derivative outside.  The upper clip avoids overflow in the derivative
  ``dF/df = 2/pi / sqrt(exp(2 f) - 1)`` (at ``f = 100`` the factor is 1 to
  round-off and the true derivative is 1e-44).  The lower clip keeps the
  derivative finite at ``r -> R`` (and ``r -> r_hub``), where the exact
  derivative ``~ 1/sqrt(2 f)`` is singular; there ``F ~ 1e-5``, i.e. the
  section carries essentially no load, which is the physical limit.

All functions accept real or complex arrays (complex step) and broadcast.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from bild_mdo.utils.complex_step import real_part as _real

#: Floor on ``|sin phi|`` (avoids 0/0 at phi = 0; the loss factor is 1 there anyway).
SIN_PHI_FLOOR = 1e-12
#: Clip range of the Prandtl exponent ``f``.
EXPONENT_MIN = 1e-10
EXPONENT_MAX = 100.0

#: Prandtl loss models: tip x hub factor, tip factor only, or no loss (F = 1).
LOSS_MODELS = ("tip_hub", "tip", "none")
#: Rotor radii the loss factor depends on (besides phi and the station radius) per loss model.
_LOSS_RADII = {"tip_hub": ("radius", "hub_radius"), "tip": ("radius",), "none": ()}


def loss_inputs(loss_model):
    """The rotor radii (``'radius'``, ``'hub_radius'``) that ``F`` depends on under ``loss_model``, for sparsity."""
    return _LOSS_RADII[loss_model]


def loss_partials(loss, loss_model, phi="phi", r="radii"):
    """Partials of ``F`` keyed by input name: ``phi`` and ``r`` always, the rotor radii ``F`` depends on.

    Parameters
    ----------
    loss : PrandtlLoss
        The loss factor and its partials.
    loss_model : str
        One of :data:`LOSS_MODELS`.
    phi, r : str
        The component's names of the inflow angle and of the station radius.
    """
    fields = {"radius": loss.dF_dradius, "hub_radius": loss.dF_dhub_radius}
    partials = {phi: loss.dF_dphi, r: loss.dF_dr}
    partials.update((name, fields[name]) for name in loss_inputs(loss_model))
    return partials


class PrandtlLoss(NamedTuple):
    """Loss factor ``F`` and its partial derivatives (all broadcast to a common shape).

    Attributes
    ----------
    F : ndarray
        Loss factor, in (0, 1].
    dF_dphi : ndarray
        Partial with respect to the inflow angle (1/rad).
    dF_dr : ndarray
        Partial with respect to the station radius (1/m).
    dF_dradius : ndarray
        Partial with respect to the tip radius (1/m).
    dF_dhub_radius : ndarray
        Partial with respect to the hub radius (1/m).
    """

    F: np.ndarray
    dF_dphi: np.ndarray
    dF_dr: np.ndarray
    dF_dradius: np.ndarray
    dF_dhub_radius: np.ndarray


def _abs_sin(phi):
    """Complex-safe ``|sin phi|`` floored at SIN_PHI_FLOOR, with its phi derivative."""
    s = np.sin(phi)
    sign = np.sign(_real(s))
    abs_s = sign * s
    dabs = sign * np.cos(phi)
    floored = _real(abs_s) < SIN_PHI_FLOOR
    abs_s = np.where(floored, SIN_PHI_FLOOR, abs_s)
    dabs = np.where(floored, 0.0, _real(dabs))
    return abs_s, dabs


def acos_factor(f):
    """``2/pi acos(exp(-f))`` with ``f`` clipped, and its derivative with respect to ``f``."""
    fr = _real(f)
    inside = (fr > EXPONENT_MIN) & (fr < EXPONENT_MAX)
    fc = np.where(fr <= EXPONENT_MIN, EXPONENT_MIN, np.where(fr >= EXPONENT_MAX, EXPONENT_MAX, f))
    value = 2.0 / np.pi * np.arccos(np.exp(-fc))
    # d/df acos(e^-f) = e^-f / sqrt(1 - e^-2f) = 1 / sqrt(e^2f - 1); expm1 keeps it accurate at small f.
    deriv = np.where(inside, 2.0 / np.pi / np.sqrt(np.expm1(2.0 * np.clip(fr, EXPONENT_MIN, EXPONENT_MAX))), 0.0)
    return value, deriv


def prandtl_loss(phi, r, radius, hub_radius, num_blades, loss_model="tip_hub"):
    """Prandtl tip/hub loss factor ``F(phi, r, R, r_hub)`` and its partials.

    Parameters
    ----------
    phi : array_like
        Inflow angle (rad).
    r : array_like
        Station radius (m), ``r_hub <= r <= R``.
    radius : array_like
        Tip radius R (m), broadcast against ``r``.
    hub_radius : array_like
        Hub radius r_hub (m); must be positive for ``loss_model='tip_hub'``.
    num_blades : int
        Number of blades B.
    loss_model : {'tip_hub', 'tip', 'none'}
        Which losses to include.

    Returns
    -------
    PrandtlLoss
        ``F`` and its partials with respect to phi, r, radius and hub_radius.
    """
    if loss_model not in LOSS_MODELS:
        raise ValueError(f"loss_model must be one of {LOSS_MODELS}, got {loss_model!r}")
    if loss_model != "none" and not any(np.iscomplexobj(x) for x in (phi, r, radius, hub_radius)):
        if loss_model == "tip" or np.all(np.asarray(hub_radius) > 0.0):
            return _prandtl_loss_real(phi, r, radius, hub_radius, num_blades, loss_model)
    phi, r, radius, hub_radius = np.broadcast_arrays(phi, r, radius, hub_radius)
    dtype = np.result_type(phi, r, radius, hub_radius, float)
    zero = np.zeros(phi.shape)
    if loss_model == "none":
        return PrandtlLoss(np.ones(phi.shape, dtype=dtype), zero, zero, zero, zero)

    if loss_model == "tip_hub" and np.any(_real(hub_radius) <= 0.0):
        raise ValueError("hub_radius must be positive for loss_model='tip_hub' "
                         "(use loss_model='tip' for a rotor without hub)")
    # Values carry complex parts (complex step); partials are always real.
    is_complex = np.iscomplexobj(dtype.type(0))
    F_tip, (dFt_dphi, dFt_dr, dFt_dR) = _tip_factor(*map(_real, (phi, r, radius)), num_blades)
    if is_complex:
        F_tip = _tip_factor(phi, r, radius, num_blades)[0]
    if loss_model == "tip":
        return PrandtlLoss(F_tip, dFt_dphi, dFt_dr, dFt_dR, zero)

    F_hub, (dFh_dphi, dFh_dr, dFh_drh) = _hub_factor(*map(_real, (phi, r, hub_radius)), num_blades)
    if is_complex:
        F_hub = _hub_factor(phi, r, hub_radius, num_blades)[0]
    F_tip_r, F_hub_r = _real(F_tip), _real(F_hub)
    return PrandtlLoss(
        F_tip * F_hub,
        F_hub_r * dFt_dphi + F_tip_r * dFh_dphi,
        F_hub_r * dFt_dr + F_tip_r * dFh_dr,
        F_hub_r * dFt_dR,
        F_tip_r * dFh_drh,
    )


def _factor_real(gap, base, half_b, abs_s, dlog):
    """Real :func:`_factor` from ``|sin phi|`` (floored) and ``dlog = d|sin phi|/dphi / |sin phi|``: the same
    formulas, clips and zero derivatives outside the clip, in fewer whole-array operations (ufuncs with
    ``where=`` instead of ``np.where``/``np.clip``); the caller silences floating-point warnings."""
    denominator = base * abs_s
    f = half_b * gap / denominator  # as _exponent: the same rounding, so F is bit-for-bit prandtl_loss's
    df_dgap = half_b / denominator
    clipped = np.minimum(np.maximum(f, EXPONENT_MIN), EXPONENT_MAX)
    value = np.arccos(np.exp(-clipped))
    value *= 2.0 / np.pi
    inside = (f > EXPONENT_MIN) & (f < EXPONENT_MAX)
    # dF/df = 2/pi / sqrt(exp(2 f) - 1) inside the clip, 0 outside (never evaluated there: no overflow).
    dF_df = np.zeros(inside.shape)
    np.divide(2.0 / np.pi, np.sqrt(np.expm1(2.0 * clipped)), out=dF_df, where=inside)
    d_phi = np.multiply(dF_df, clipped, out=np.zeros(inside.shape), where=inside)
    d_phi *= -dlog
    d_gap = np.multiply(dF_df, df_dgap, out=np.zeros(inside.shape), where=inside)
    d_base = np.zeros(inside.shape)
    np.divide(-dF_df * clipped, base, out=d_base, where=inside)
    return value, d_phi, d_gap, d_base


def _full(x, shape):
    return x if x.shape == shape else np.broadcast_to(x, shape)


def _prandtl_loss_real(phi, r, radius, hub_radius, num_blades, loss_model):
    """:func:`prandtl_loss` for real arguments (``loss_model`` 'tip' or 'tip_hub', positive hub radii):
    its values and partials to round-off at a fraction of its cost (component partials call it once per
    linearisation)."""
    shape = np.broadcast_shapes(np.shape(phi), np.shape(r), np.shape(radius), np.shape(hub_radius))
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        abs_s, dabs_dphi = _abs_sin(phi)
        dlog = dabs_dphi / abs_s
        half_b = 0.5 * num_blades
        tip, dt_phi, dt_gap, dt_base = _factor_real(radius - r, r, half_b, abs_s, dlog)
        if loss_model == "tip":
            return PrandtlLoss(_full(tip, shape), _full(dt_phi, shape), _full(dt_base - dt_gap, shape),
                               _full(dt_gap, shape), np.zeros(shape))
        hub, dh_phi, dh_gap, dh_base = _factor_real(r - hub_radius, hub_radius, half_b, abs_s, dlog)
        return PrandtlLoss(_full(tip * hub, shape), _full(hub * dt_phi + tip * dh_phi, shape),
                           _full(hub * (dt_base - dt_gap) + tip * dh_gap, shape), _full(hub * dt_gap, shape),
                           _full(tip * (dh_base - dh_gap), shape))


def _exponent(half_b, gap, base, abs_s):
    """Prandtl exponent ``f = B gap / (2 base |sin phi|)``, capped at :data:`EXPONENT_MAX`.

    Beyond the cap ``F = 1`` to round-off and ``dF/df = 0`` (:func:`_acos_factor` clips there anyway),
    so the cap changes no value; it keeps a tiny base (a hub radius of 1e-300 m) from carrying an
    overflowed exponent into the partials.
    """
    with np.errstate(over="ignore", divide="ignore"):
        f = half_b * gap / (base * abs_s)
    return np.where(_real(f) >= EXPONENT_MAX, EXPONENT_MAX, f)


def _where_loaded(dF_df, numerator, denominator):
    """``dF_df * numerator / denominator`` where ``dF/df != 0``, else 0 (no overflow where it would be discarded)."""
    num, den, d = np.broadcast_arrays(numerator, denominator, dF_df)
    ratio = np.divide(num, den, out=np.zeros(d.shape, dtype=np.result_type(num, den, float)), where=d != 0.0)
    return d * ratio


def _factor(phi, gap, base, num_blades):
    """Prandtl factor ``2/pi acos(exp(-f))``, ``f = B gap / (2 base |sin phi|)``, and its phi, gap, base partials."""
    abs_s, dabs_dphi = _abs_sin(phi)
    half_b = 0.5 * num_blades
    f = _exponent(half_b, gap, base, abs_s)
    value, dF_df = acos_factor(f)
    return value, (dF_df * (-f / abs_s * dabs_dphi), _where_loaded(dF_df, half_b, base * abs_s),
                   _where_loaded(dF_df, -f, base))


def _tip_factor(phi, r, radius, num_blades):
    """F_tip and its partials (phi, r, R): gap ``R - r`` over the station radius ``r``."""
    value, (d_phi, d_gap, d_base) = _factor(phi, radius - r, r, num_blades)
    return value, (d_phi, d_base - d_gap, d_gap)


def _hub_factor(phi, r, hub_radius, num_blades):
    """F_hub and its partials (phi, r, r_hub): gap ``r - r_hub`` over the hub radius."""
    value, (d_phi, d_gap, d_base) = _factor(phi, r - hub_radius, hub_radius, num_blades)
    return value, (d_phi, d_gap, d_base - d_gap)


def prandtl_loss_and_dphi(phi, r, radius, hub_radius, num_blades, loss_model="tip_hub"):
    """Real-valued fast path of :func:`prandtl_loss`: only ``F`` and ``dF/dphi`` (for the inflow solve).

    Returns
    -------
    F, dF_dphi : ndarray
    """
    if loss_model == "none":
        shape = np.broadcast(phi, r).shape
        return np.ones(shape), np.zeros(shape)
    abs_s, dabs_dphi = _abs_sin(phi)
    half_b = 0.5 * num_blades
    f = _exponent(half_b, radius - r, r, abs_s)
    F, dF_df = acos_factor(f)
    # df/dphi = -f/|sin| d|sin|/dphi for both exponents.
    dlog = -dabs_dphi / abs_s
    dF_dphi = dF_df * f * dlog
    if loss_model == "tip":
        return F, dF_dphi
    g = _exponent(half_b, r - hub_radius, hub_radius, abs_s)
    G, dG_dg = acos_factor(g)
    return F * G, dF_dphi * G + F * dG_dg * g * dlog


class PrandtlLossJet(NamedTuple):
    """``F``, its first and second ``phi`` derivatives and the mixed partials with the radii (complex-safe).

    The exact ideal loading (:mod:`bild_mdo.bild.annulus_stationarity`) is a stationarity condition in
    ``phi`` that contains ``dF/dphi``; its Newton slope needs ``d2F/dphi2`` and its partials need
    ``d2F/(dphi dx)`` for ``x`` in (``r``, ``R``, ``r_hub``).  Every field carries the complex-step part of
    its arguments (unlike :class:`PrandtlLoss`, whose partials are real).
    """

    F: np.ndarray
    dF_dphi: np.ndarray
    d2F_dphi2: np.ndarray
    dF_dr: np.ndarray
    d2F_dphi_dr: np.ndarray
    dF_dradius: np.ndarray
    d2F_dphi_dradius: np.ndarray
    dF_dhub_radius: np.ndarray
    d2F_dphi_dhub_radius: np.ndarray


def acos_factor_jet(f):
    """``2/pi acos(exp(-f))`` and its first two ``f`` derivatives (complex-safe, ``f`` clipped as there)."""
    fr = _real(f)
    inside = (fr > EXPONENT_MIN) & (fr < EXPONENT_MAX)
    fc = np.where(fr <= EXPONENT_MIN, EXPONENT_MIN, np.where(fr >= EXPONENT_MAX, EXPONENT_MAX, f))
    value = 2.0 / np.pi * np.arccos(np.exp(-fc))
    gap = np.expm1(2.0 * fc)  # exp(2 f) - 1, accurate at small f
    first = np.where(inside, 2.0 / np.pi / np.sqrt(gap), 0.0)
    second = np.where(inside, -(gap + 1.0) * first / gap, 0.0)
    return value, first, second


def _factor_jet(phi, gap, base, num_blades):
    """One Prandtl factor ``P(a/|sin phi|)``, ``a = B gap/(2 base)``: value, phi, phi-phi, a, phi-a derivatives.

    With ``c = cot phi``: ``f' = -f c`` and ``f'' = f (1 + 2 c**2)`` (zero where ``|sin phi|`` is floored).
    """
    sign = np.sign(_real(np.sin(phi)))
    floored = sign * _real(np.sin(phi)) < SIN_PHI_FLOOR
    abs_s = np.where(floored, SIN_PHI_FLOOR, sign * np.sin(phi))
    cot = np.where(floored, 0.0, np.cos(phi) / np.where(floored, 1.0, np.sin(phi)))
    f = _exponent(0.5 * num_blades, gap, base, abs_s)
    value, p1, p2 = acos_factor_jet(f)
    f1 = -f * cot
    f2 = np.where(floored, 0.0, f * (1.0 + 2.0 * cot * cot))
    f_a = 1.0 / abs_s
    f1_a = -cot / abs_s
    return value, p1 * f1, p2 * f1 * f1 + p1 * f2, p1 * f_a, p2 * f_a * f1 + p1 * f1_a


def prandtl_loss_jet(phi, r, radius, hub_radius, num_blades, loss_model="tip_hub"):
    """:class:`PrandtlLossJet` of ``F(phi, r, R, r_hub)`` (the same ``F`` as :func:`prandtl_loss`).

    Parameters are those of :func:`prandtl_loss`; real or complex arrays, broadcast.
    """
    if loss_model not in LOSS_MODELS:
        raise ValueError(f"loss_model must be one of {LOSS_MODELS}, got {loss_model!r}")
    phi, r, radius, hub_radius = np.broadcast_arrays(phi, r, radius, hub_radius)
    dtype = np.result_type(phi, r, radius, hub_radius, float)
    one, zero = np.ones(phi.shape, dtype=dtype), np.zeros(phi.shape, dtype=dtype)
    if loss_model == "none":
        return PrandtlLossJet(one, *([zero] * 8))
    half_b = 0.5 * num_blades
    # Tip: a = B (R - r)/(2 r), da/dr = -B R/(2 r**2), da/dR = B/(2 r).
    t, t1, t2, t_a, t1_a = _factor_jet(phi, radius - r, r, num_blades)
    ta_r, ta_R = -half_b * radius / (r * r), half_b / r
    if loss_model == "tip":
        return PrandtlLossJet(t, t1, t2, t_a * ta_r, t1_a * ta_r, t_a * ta_R, t1_a * ta_R, zero, zero)
    if np.any(_real(hub_radius) <= 0.0):
        raise ValueError("hub_radius must be positive for loss_model='tip_hub' "
                         "(use loss_model='tip' for a rotor without hub)")
    # Hub: a = B (r - r_hub)/(2 r_hub), da/dr = B/(2 r_hub), da/dr_hub = -B r/(2 r_hub**2).
    h, h1, h2, h_a, h1_a = _factor_jet(phi, r - hub_radius, hub_radius, num_blades)
    ha_r, ha_rh = half_b / hub_radius, -half_b * r / (hub_radius * hub_radius)

    def mixed(t_x, t1_x, h_x, h1_x):
        return t_x * h + t * h_x, t1_x * h + t1 * h_x + t_x * h1 + t * h1_x

    d_r = mixed(t_a * ta_r, t1_a * ta_r, h_a * ha_r, h1_a * ha_r)
    d_R = mixed(t_a * ta_R, t1_a * ta_R, zero, zero)
    d_rh = mixed(zero, zero, h_a * ha_rh, h1_a * ha_rh)
    return PrandtlLossJet(t * h, t1 * h + t * h1, t2 * h + 2.0 * t1 * h1 + t * h2, *d_r, *d_R, *d_rh)
