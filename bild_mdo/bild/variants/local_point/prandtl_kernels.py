"""Prandtl's loss factor compiled for one station: its value, its phi derivatives and its partials in the radii.

The forms of :func:`factor_df` keep full accuracy over the whole range of the exponent (a series in
``exp(-f)`` far from the tip and the hub, ``acos`` in between, ``expm1``/``atan2`` next to them);
:func:`prandtl_one` and :func:`prandtl_value_one` serve the compiled solves
(:mod:`~bild_mdo.bild.variants.local_point.kernels`, the turbine's), :func:`prandtl_partials_one` the
compiled partials (:mod:`~bild_mdo.bild.variants.local_point.partials_kernel`).  The same factor as
:func:`bild_mdo.bem.prandtl.prandtl_loss_jet`, to round-off (``tests/bild/variants/test_partials_kernel.py``).
"""
from __future__ import annotations

import math

from bild_mdo.bem.prandtl import EXPONENT_MAX, EXPONENT_MIN, SIN_PHI_FLOOR
from bild_mdo.utils.compiled import kernel

_TWO_OVER_PI = 2.0 / math.pi
#: Hub exponent above which the hub factor is 1 (``1 - (2/pi) exp(-f)`` rounds to 1) and its derivatives
#: (``~ exp(-f) f cot(phi)**2``, below 1e-16 for ``phi > 2 deg``) are dropped: they change no result beyond round-off.
_HUB_UNITY = 48.0
#: Exponents of the three forms of :func:`factor_df`: series above the first, ``acos`` down to the second.
_SERIES_EXPONENT, _ATAN_EXPONENT = 4.0, 0.1


@kernel
def _series_value(g, g2):
    """``(2/pi) acos(g) = 1 - (2/pi) asin(g)`` from the series of ``asin`` (``g`` small, ``g2 = g**2``)."""
    return 1.0 - _TWO_OVER_PI * g * (1.0 + g2 * (1.0 / 6.0 + g2 * (3.0 / 40.0 + g2 * (
        5.0 / 112.0 + g2 * (35.0 / 1152.0 + g2 * (63.0 / 2816.0))))))


@kernel
def factor_df(f):
    """A Prandtl factor of exponent ``f``, ``P = (2/pi) acos(g)`` with ``g = exp(-f)``, and its first two
    ``f``-derivatives ``dP/df = (2/pi) g / sqrt(1 - g**2)``, ``d2P/df2 = -(dP/df) / (1 - g**2)`` (zero where ``f``
    is clipped to ``[EXPONENT_MIN, EXPONENT_MAX]``).

    Where ``g < 0.02`` (most of the span for the hub factor, the inner span for the tip factor), ``acos`` and
    ``1 / sqrt(1 - g**2)`` are their series in ``g**2`` (to ``g**12 < 1e-20``); where ``g > 0.9`` (by the tip and
    the hub), ``1 - g`` comes from ``expm1`` and the angle from ``atan2``, which keep full accuracy there."""
    inside = EXPONENT_MIN < f < EXPONENT_MAX
    if inside and f > _SERIES_EXPONENT:
        g = math.exp(-f)
        g2 = g * g
        value = _series_value(g, g2)
        a1 = _TWO_OVER_PI * g * (1.0 + g2 * (0.5 + g2 * (0.375 + g2 * (0.3125 + g2 * (0.2734375 + g2 * 0.24609375)))))
        q = 1.0 - g2
    elif inside and f > _ATAN_EXPONENT:
        g = math.exp(-f)
        q = (1.0 - g) * (1.0 + g)
        value = _TWO_OVER_PI * math.acos(g)
        a1 = _TWO_OVER_PI * g / math.sqrt(q)
    else:
        one_minus = -math.expm1(-min(max(f, EXPONENT_MIN), EXPONENT_MAX))
        g = 1.0 - one_minus
        q = one_minus * (1.0 + g)
        root = math.sqrt(q)
        value = _TWO_OVER_PI * math.atan2(root, g)
        if not inside:
            return value, 0.0, 0.0
        a1 = _TWO_OVER_PI * g / root
    return value, a1, -a1 / q


@kernel
def _factor(f, cot):
    """A Prandtl factor of exponent ``f = k / |sin phi|`` and its first two phi derivatives (:func:`factor_df`
    with ``df/dphi = -f cot``, ``d2f/dphi2 = f (1 + 2 cot**2)``)."""
    value, a1, a2 = factor_df(f)
    if a1 == 0.0:
        return value, 0.0, 0.0
    f1 = -f * cot
    return value, a1 * f1, a2 * f1 * f1 + a1 * (f * (1.0 + 2.0 * cot * cot))


@kernel
def prandtl_one(sn, cs, k_tip, k_hub, loss):
    """``F, dF/dphi, d2F/dphi2`` of one station (``loss``: 0 none, 1 tip, 2 tip and hub)."""
    if loss == 0:
        return 1.0, 0.0, 0.0
    inverse = 1.0 / max(sn, SIN_PHI_FLOOR)
    cot = cs * inverse
    t, t1, t2 = _factor(k_tip * inverse, cot)
    f_hub = k_hub * inverse
    if loss == 1 or f_hub > _HUB_UNITY:
        return t, t1, t2
    h, h1, h2 = _factor(f_hub, cot)
    return t * h, t1 * h + t * h1, t2 * h + 2.0 * t1 * h1 + t * h2


@kernel
def _factor_value(f):
    """The value of :func:`_factor` alone, in its three forms."""
    if _SERIES_EXPONENT < f < EXPONENT_MAX:
        g = math.exp(-f)
        return _series_value(g, g * g)
    if f > _ATAN_EXPONENT:
        return _TWO_OVER_PI * math.acos(math.exp(-min(f, EXPONENT_MAX)))
    one_minus = -math.expm1(-max(f, EXPONENT_MIN))
    g = 1.0 - one_minus
    return _TWO_OVER_PI * math.atan2(math.sqrt(one_minus * (1.0 + g)), g)


@kernel
def prandtl_value_one(sn, k_tip, k_hub, loss):
    """Prandtl's ``F`` alone (the value of :func:`prandtl_one`)."""
    if loss == 0:
        return 1.0
    inverse = 1.0 / max(sn, SIN_PHI_FLOOR)
    value = _factor_value(k_tip * inverse)
    f_hub = k_hub * inverse
    if loss == 2 and f_hub <= _HUB_UNITY:
        value *= _factor_value(f_hub)
    return value


@kernel
def _one_factor(numerator, inv_s, cot):
    """One factor ``P(a / |sin phi|)``: value, ``d/dphi``, ``d2/dphi2``, ``d/da``, ``d2/(dphi da)``."""
    f = numerator * inv_s
    p, a1, a2 = factor_df(f)
    f1 = -f * cot
    f2 = f * (1.0 + 2.0 * cot * cot)
    f1_a = -cot * inv_s
    return p, a1 * f1, a2 * f1 * f1 + a1 * f2, a1 * inv_s, a2 * inv_s * f1 + a1 * f1_a


@kernel
def prandtl_partials_one(sn, cs, r, radius, hub, num_blades, loss):
    """``F, F_phi, F_phiphi, F_r, F_phir, F_R, F_phiR, F_hub, F_phihub`` of one station (``loss``: 0 none,
    1 tip, 2 tip and hub); ``|sin phi|`` floored as in ``prandtl._factor_jet``."""
    if loss == 0:
        return 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    if sn < SIN_PHI_FLOOR:
        inv_s, cot = 1.0 / SIN_PHI_FLOOR, 0.0
    else:
        inv_s, cot = 1.0 / sn, cs / sn
    half_b = 0.5 * num_blades
    # Tip: a = B (R - r) / (2 r), da/dr = -B R / (2 r**2), da/dR = B / (2 r).
    t, t1, t2, t_a, t1_a = _one_factor(half_b * (radius - r) / r, inv_s, cot)
    ta_r, ta_big = -half_b * radius / (r * r), half_b / r
    if loss == 1:
        return t, t1, t2, t_a * ta_r, t1_a * ta_r, t_a * ta_big, t1_a * ta_big, 0.0, 0.0
    # Hub: a = B (r - r_hub) / (2 r_hub), da/dr = B / (2 r_hub), da/dr_hub = -B r / (2 r_hub**2).
    h, h1, h2, h_a, h1_a = _one_factor(half_b * (r - hub) / hub, inv_s, cot)
    ha_r, ha_hub = half_b / hub, -half_b * r / (hub * hub)
    tr, t1r, hr, h1r = t_a * ta_r, t1_a * ta_r, h_a * ha_r, h1_a * ha_r
    tb, t1b = t_a * ta_big, t1_a * ta_big
    hh, h1h = h_a * ha_hub, h1_a * ha_hub
    return (t * h, t1 * h + t * h1, t2 * h + 2.0 * t1 * h1 + t * h2,
            tr * h + t * hr, t1r * h + t1 * hr + tr * h1 + t * h1r,
            tb * h, t1b * h + tb * h1,
            t * hh, t1 * hh + t * h1h)
