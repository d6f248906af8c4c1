"""The ideal loading for energy extraction: each annulus makes its power minus mu times its thrust stationary.

Derivation (the turbine counterpart of :mod:`bild_mdo.bild.annulus_stationarity`)
---------------------------------------------------------------------------------
A turbine faces the wind ``V`` (m/s) and turns at ``Omega``; at radius ``r`` the
blade speed is ``x = Omega r``.  With the windmill-state axial induction ``a``
and the wake swirl ``a'`` (Burton et al., *Wind Energy Handbook*, Sec. 3.5;
Manwell et al., *Wind Energy Explained*, Sec. 3.5) the velocities at the disk
are ``u = V (1 - a)`` (axial) and ``w = x (1 + a')`` (tangential, relative to
the blade), ``tan(phi) = u / w``, ``W = sqrt(u**2 + w**2)``.  Momentum theory
with the Prandtl factor ``F`` gives, per unit span and for all blades::

    dT/dr = 4 pi rho r F t,     t = u (V - u) = V**2 a (1 - a)          (thrust, downwind, > 0)
    dQ/dr = 4 pi rho r**2 F q,  q = u (w - x) = V x a' (1 - a)           (driving torque, > 0)
    dP/dr = Omega dQ/dr = 4 pi rho r F p,  p = x q                       (power extracted, > 0)

and blade-element theory, with the normal and tangential force coefficients
``C_n = C_l (cos phi + s sin phi)``, ``C_t = C_l (sin phi - s cos phi)``
(``s = C_d / C_l``), ``dT/dr = 1/2 rho W**2 B c C_n``, ``dQ/dr = 1/2 rho W**2 B c
C_t r``.  Equating the ratios ``dT/(dQ/r)`` of the two theories,
``(V - u) C_t = (w - x) C_n``, and with ``u = W sin(phi)``, ``w = W cos(phi)``
(``C_t sin + C_n cos = C_l``)::

    W = A(phi) = V (sin phi - s cos phi) + x (cos phi + s sin phi),
    u = A sin(phi),  w = A cos(phi),                                    (T1)

so at a fixed section point every quantity of a station is explicit in its
inflow angle; the chord is what makes the blade element carry the load::

    c = 2 dT/dr / (rho W**2 B C_n) = 8 pi r F t / (B C_l A**2 (cos phi + s sin phi)).   (T2)

This is the propeller's BEM curve with the lift reversed (``s -> -s``,
``t -> -t_prop``, ``q -> -q_prop``), so the annulus functions of the exact
propeller loading are reused with ``drag_to_lift = -s``.  The loading runs from
``phi0 = atan(V/x)`` (unloaded: ``a = a' = 0``) down to ``phi_half``, where
``a = 1/2`` (``tan(phi_half)`` from ``(V/2 + x s) tau**2 + (x - V s) tau - V/2 = 0``).

Maximum power for a given thrust (Lagrange): with the chord free at every
station, each annulus is one design variable (its ``phi``), and the
Euler-Lagrange condition of ``max P - mu (T - T*)`` is, annulus by annulus::

    R(phi) = (F p)' - mu (F t)' = 0,   i.e.  mu = G(phi) = (F p)' / (F t)',   ' = d/dphi,   (T3)

with Prandtl's factor differentiated.  The multiplier ``mu`` (m/s, W/N) is the
marginal power per marginal thrust, the same at every station; the propeller's
energy loss is here ``E = V T - P`` and its constant is ``lambda = mu - V``.
``mu = 0`` is the design for maximum power at the tip-speed ratio (the thrust
free): every annulus at the maximum of its ``F p``.  ``mu > 0`` gives less
thrust (a thrust limit below the maximum-power thrust), ``mu < 0`` more.
Without drag and tip loss, (T3) with ``mu = 0`` is Glauert's optimum rotor
(``a' = (1 - 3a)/(4a - 1)``, ``a -> 1/3`` at high local speed ratio), so Betz
(``C_P = 16/27``) is its limit ``lambda -> inf``.

``G`` falls from ``G(phi0) = -x w'/u'`` (the lightest load; negative where
``x/V > C_l/C_d``, so that no load extracts power) through 0 (the maximum of
``F p``) to ``-inf`` at the maximum of ``F t``, which lies at or below
``a = 1/2`` (``t' = 0`` there and ``F' >= 0``).  A station with
``mu >= G(phi0)`` carries no load (``phi = phi0``, zero chord); otherwise the
root is bracketed on ``[phi_half, phi0]`` by ``G - mu`` with a barrier (a large
negative value) past the maximum of ``F t``.  At the optimum ``a`` stays near
1/3, so the momentum relation holds without Glauert's or Buhl's high-induction
correction; it stops holding where ``a > 0.4`` (the package's flow states,
:mod:`bild_mdo.bem.flow_states`): only a strongly negative ``mu`` (thrust far
above the maximum-power thrust) loads stations that far.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from bild_mdo.bem.prandtl import prandtl_loss
from bild_mdo.bild.annulus_stationarity import residual_partials, stationarity
from bild_mdo.utils.jet import Jet, variable

#: Value of the bracketed function past the maximum of the annulus thrust (m/s): negative, finite, large.
BARRIER = -1.0e6
_MAX_ITERATIONS = 100
#: Station status codes of :func:`solve_loading`.
LOADED, UNLOADED, FAILED = 0, 1, 4


def unloaded_angle(v_axial, v_theta):
    """``phi0 = atan(V/x)``: the unloaded station."""
    return np.arctan2(v_axial, v_theta)


def half_induction_angle(v_axial, v_theta, drag_to_lift):
    """Inflow angle where ``a = 1/2`` on the curve (T1) (the stable root of its quadratic in ``tan(phi)``)."""
    b = v_theta - v_axial * drag_to_lift
    return np.arctan(v_axial / (b + np.sqrt(b * b + v_axial * (v_axial + 2.0 * v_theta * drag_to_lift))))


class TurbineTerms(NamedTuple):
    """``(F p)'``, ``(F t)'`` and their ``phi`` derivatives (with the kinematic ``x``: ``p = x q``)."""

    power_slope: np.ndarray
    thrust_slope: np.ndarray
    power_curvature: np.ndarray
    thrust_curvature: np.ndarray


def turbine_terms(phi, v_axial, v_theta, drag_to_lift, r, radius, hub_radius, num_blades, loss_model):
    """:class:`TurbineTerms` at ``phi`` from the propeller's ``(F e)' = N``, ``(F t)' = D`` at ``-s``.

    ``t = -t_prop`` and ``p = V t - e``, so ``(F t)' = -D`` and ``(F p)' = -N - V D``.
    """
    st = stationarity(phi, v_axial, v_theta, -drag_to_lift, r, radius, hub_radius, num_blades, loss_model)
    return TurbineTerms(-st.N - v_axial * st.D, -st.D, -st.N1 - v_axial * st.D1, -st.D1)


def residual(phi, mu, *args):
    """``R = (F p)' - mu (F t)'`` of (T3) (real or complex)."""
    terms = turbine_terms(phi, *args)
    return terms.power_slope - mu * terms.thrust_slope


def residual_jacobian(phi, mu, v_axial, v_theta, drag_to_lift, r, radius, hub_radius, num_blades, loss_model):
    """Partials of ``R`` of (T3) at fixed ``phi``: a dict over ``phi, mu, v_axial, v_theta, drag_to_lift, r,
    radius, hub_radius`` (``R = -R_prop`` at ``lambda = mu - V`` and ``-s``)."""
    _, d, _ = residual_partials(phi, mu - v_axial, v_axial, v_theta, -drag_to_lift, r, radius, hub_radius,
                                num_blades, loss_model)
    out = {name: -d[name] for name in ("phi", "v_theta", "r", "radius", "hub_radius")}
    out["mu"] = -d["lam"]
    out["v_axial"] = d["lam"] - d["v_axial"]
    out["drag_to_lift"] = d["drag_to_lift"]
    return out


def implicit_sensitivities(phi, mu, status, *args):
    """``dphi/dx = -R_x / R_phi`` at loaded stations; at unloaded ones the partials of ``phi0``."""
    d = residual_jacobian(phi, mu, *args)
    loaded = status == LOADED
    slope = np.where(loaded, d["phi"], 1.0)
    sens = {name: np.where(loaded, -d[name] / slope, 0.0) for name in d if name != "phi"}
    v, x = args[0], args[1]
    q = v * v + x * x
    sens["v_axial"] = np.where(loaded, sens["v_axial"], x / q)
    sens["v_theta"] = np.where(loaded, sens["v_theta"], -v / q)
    return sens


def _bracketed(phi, mu, args):
    terms = turbine_terms(phi, *args)
    below = terms.thrust_slope < 0.0
    d = np.where(below, terms.thrust_slope, -1.0)
    g = terms.power_slope / d
    value = np.where(below, g - mu, BARRIER)
    slope = np.where(below, (terms.power_curvature - g * terms.thrust_curvature) / d, 1.0)
    return value, slope, np.abs(g) + np.abs(mu)


def solve_loading(mu, v_axial, v_theta, drag_to_lift, r, radius, hub_radius, num_blades, loss_model):
    """Inflow angle of (T3) at every station (real arrays that broadcast to one 1-D shape).

    Returns
    -------
    phi : ndarray
        The root; ``phi0`` at unloaded stations.
    status : ndarray of int
        :data:`LOADED`; :data:`UNLOADED` (``mu >= G(phi0)``: no load pays its thrust, zero chord);
        :data:`FAILED` (an input outside ``V, x, r > 0``, ``s >= 0``, not finite, or not converged).
    """
    shape = np.broadcast(mu, v_axial, v_theta, drag_to_lift, r, radius, hub_radius).shape
    flat = [np.broadcast_to(a, shape) for a in (mu, v_axial, drag_to_lift, radius, hub_radius, v_theta, r)]
    return _solve_compiled(*flat, 1, num_blades, loss_model)


def solve_designs(mu, v_axial, drag_to_lift, radius, hub_radius, v_theta, r, num_blades, loss_model):
    """:func:`solve_loading` of designs: ``mu, v_axial, drag_to_lift, radius, hub_radius`` per design (``[nn]``),
    ``v_theta`` and ``r`` per station (``[nn, nr]``); ``phi`` and ``status`` are ``[nn, nr]``."""
    shape = np.broadcast(v_theta, r).shape
    node = [np.broadcast_to(a, shape[:1]) for a in (mu, v_axial, drag_to_lift, radius, hub_radius)]
    return _solve_compiled(*node, np.broadcast_to(v_theta, shape), np.broadcast_to(r, shape), shape[1], num_blades,
                           loss_model)


def _solve_compiled(mu, v_axial, drag_to_lift, radius, hub_radius, v_theta, r, per, num_blades, loss_model):
    """:func:`~bild_mdo.bild.variants.turbine.compiled.solve_stations` of ``per`` stations a design."""
    from bild_mdo.bild.variants.local_point.kernels import LOSS_CODES
    from bild_mdo.bild.variants.turbine.compiled import solve_stations

    node = [np.ascontiguousarray(a, dtype=float) for a in (mu, v_axial, drag_to_lift, radius, hub_radius)]
    phi, status = np.empty(v_theta.shape), np.empty(v_theta.shape, dtype=np.int64)
    stations = [np.ascontiguousarray(a, dtype=float).ravel() for a in (v_theta, r)]
    solve_stations(*node, *stations, per, num_blades, LOSS_CODES[loss_model], _MAX_ITERATIONS,
                   (LOADED, UNLOADED, FAILED), BARRIER, phi.reshape(-1), status.reshape(-1))
    return phi, status


#: Names of the jet variables of :func:`station_jets`.
JET_NAMES = ("phi", "v_axial", "v_theta", "drag_to_lift", "r", "radius", "hub_radius")


def station_jets(phi, v_axial, v_theta, drag_to_lift, r, radius, hub_radius, num_blades, loss_model):
    """The station on the curve (T1) as :class:`~bild_mdo.utils.jet.Jet` s with partials over :data:`JET_NAMES`.

    Returns ``dict`` of jets: ``u`` (u_axial, m/s), ``w`` (m/s), ``W`` (m/s), ``F``, ``t`` and ``q`` (m**2/s**2)
    of the module docstring and ``normal = cos(phi) + s sin(phi)`` (``C_n / C_l``).  Complex-safe.
    """
    sn = Jet(np.sin(phi), {"phi": np.cos(phi)})
    cs = Jet(np.cos(phi), {"phi": -np.sin(phi)})
    v, x, s = variable(v_axial, "v_axial"), variable(v_theta, "v_theta"), variable(drag_to_lift, "drag_to_lift")
    normal = cs + s * sn
    big_a = v * (sn - s * cs) + x * normal
    u, w = big_a * sn, big_a * cs
    loss = prandtl_loss(phi, r, radius, hub_radius, num_blades, loss_model)
    f = Jet(loss.F, {"phi": loss.dF_dphi, "r": loss.dF_dr, "radius": loss.dF_dradius,
                     "hub_radius": loss.dF_dhub_radius})
    return {"u": u, "w": w, "W": big_a, "F": f, "t": u * (v - u), "q": u * (w - x), "normal": normal}


#: Outputs of :func:`station_loads`, in the order of the compiled kernel's arguments.
LOAD_NAMES = ("axial_induction", "tangential_induction", "u_axial", "inflow_speed", "loss_factor", "dthrust_dr",
              "dtorque_dr")
#: Outputs of :func:`station_chords`, in the order of the compiled kernel's arguments.
CHORD_NAMES = ("chord", "twist", "lift_coefficient", "drag_coefficient")


def _into(outputs, names, shape, fill):
    """``fill(arrays)`` on the output vector's views of ``names`` (C-contiguous ``[nn, nr]``, written in place),
    else on new arrays then copied into ``outputs``; returns what ``fill`` returns."""
    views = [outputs[name] for name in names]
    direct = all(view.flags.c_contiguous and view.flags.writeable and view.shape == shape for view in views)
    arrays = views if direct else [np.empty(shape) for _ in names]
    result = fill(arrays)
    if not direct:
        for name, value in zip(names, arrays):
            outputs[name] = value
    return result


def _node(*arrays):
    return [np.ascontiguousarray(a, dtype=float) for a in arrays]


def station_loads(phi, v_theta, r, v_axial, drag_to_lift, radius, hub_radius, rho, num_blades, loss_model, outputs):
    """Values of the loads of :class:`~bild_mdo.bild.variants.turbine.turbine_loads.TurbineLoadsComp` (those of
    :func:`station_jets`, compiled) written into ``outputs`` (:data:`LOAD_NAMES`, real ``[nn, nr]``); per-design
    ``v_axial, drag_to_lift, radius, hub_radius, rho`` (``[nn]``), the rest ``[nn, nr]``."""
    from bild_mdo.bild.variants.local_point.kernels import LOSS_CODES
    from bild_mdo.bild.variants.turbine.compiled import station_loads as compiled

    args = _node(phi, v_theta, r, v_axial, drag_to_lift, radius, hub_radius, rho)
    _into(outputs, LOAD_NAMES, np.shape(phi),
          lambda out: compiled(*args, num_blades, LOSS_CODES[loss_model], *out))


def station_chords(dthrust_dr, phi, inflow_speed, rho, alpha_star, cl_star, cd_star, num_blades, outputs):
    """Values of :class:`~bild_mdo.bild.variants.turbine.turbine_chord.TurbineChordComp`, compiled, written into
    ``outputs`` (:data:`CHORD_NAMES`); per-design ``rho, alpha_star, cl_star, cd_star``.  Returns False where a
    normal-force coefficient ``C_l* cos(phi) + C_d* sin(phi)`` is not positive."""
    from bild_mdo.bild.variants.turbine.compiled import station_chords as compiled

    args = _node(dthrust_dr, phi, inflow_speed, rho, alpha_star, cl_star, cd_star)
    return _into(outputs, CHORD_NAMES, np.shape(phi), lambda out: compiled(*args, num_blades, *out))


def reference_chord(phi, v_axial, v_theta, drag_to_lift, r, radius, hub_radius, cl, num_blades, loss_model):
    """Chord (T2) in m at ``phi`` of one station per design (real ``[nn]`` arrays; the value of :func:`chord_jet`,
    compiled)."""
    from bild_mdo.bild.variants.local_point.kernels import LOSS_CODES
    from bild_mdo.bild.variants.turbine.compiled import reference_chords

    args = _node(phi, v_axial, v_theta, drag_to_lift, r, radius, hub_radius, cl)
    chord = np.empty(args[0].shape)
    reference_chords(*args, num_blades, LOSS_CODES[loss_model], chord)
    return chord


def solve_reference_chord(v_axial, v_theta, drag_to_lift, r, radius, hub_radius, cl, ref_chord, num_blades,
                          loss_model):
    """``phi`` of one station per design (real ``[nn]`` arrays) whose chord (T2) is ``ref_chord``, solved on
    ``[phi_half, phi0]`` (the bracketed Newton solver from the midpoint, compiled), and ``G(phi)``.

    Returns ``(phi, mu, chord_half, status)``: ``chord_half`` the chord at ``phi_half``; ``status`` 0, 1 where
    ``ref_chord`` is not in ``(0, chord_half)``, 2 where the solve failed or ``phi`` lies past the maximum of the
    annulus thrust.
    """
    from bild_mdo.bild.variants.local_point.kernels import LOSS_CODES
    from bild_mdo.bild.variants.turbine.compiled import solve_reference_chords

    args = _node(v_axial, v_theta, drag_to_lift, r, radius, hub_radius, cl, ref_chord)
    phi, mu, chord_half = (np.empty(args[0].shape) for _ in range(3))
    status = np.empty(args[0].shape, dtype=np.int64)
    solve_reference_chords(*args, num_blades, LOSS_CODES[loss_model], _MAX_ITERATIONS, phi, mu, chord_half, status)
    return phi, mu, chord_half, status


def chord_jet(jets, r, num_blades, cl):
    """Chord (T2) in m as a jet (``r`` a jet or an array, ``cl`` the section's C_l*)."""
    return 8.0 * np.pi * jets["F"] * jets["t"] * r / (num_blades * cl * jets["W"] * jets["W"] * jets["normal"])


def station_angle(mu, v_axial, v_theta, drag_to_lift, r, radius, hub_radius, num_blades, loss_model):
    """:func:`solve_loading` on real parts, then (complex inputs) one complex Newton update carrying the
    derivative (loaded stations) or ``phi0`` in complex arithmetic (unloaded).  Returns ``(phi, status)``."""
    args = (v_axial, v_theta, drag_to_lift, r, radius, hub_radius)
    real = [np.real(a) for a in (mu,) + args]
    phi, status = solve_loading(*real, num_blades, loss_model)
    if not any(np.iscomplexobj(a) for a in (mu,) + args):
        return phi, status
    loaded = status == LOADED
    slope = np.where(loaded, residual_jacobian(phi, *real, num_blades, loss_model)["phi"], 1.0)
    update = phi - 1j * np.imag(residual(phi, mu, *args, num_blades, loss_model)) / slope
    return np.where(loaded, update, np.arctan(v_axial / v_theta)), status
