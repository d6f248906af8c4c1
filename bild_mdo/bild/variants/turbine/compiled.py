"""The turbine loading's per-station solve and station values, compiled (:mod:`~bild_mdo.bild.variants.turbine.kernel`).

The residual is the one of :func:`~bild_mdo.bild.variants.turbine.kernel._bracketed`, written for one
station: ``G - mu`` with ``G = (F p)' / (F t)'`` below the maximum of the annulus thrust, the barrier past
it, from the propeller's ``(F e)'``, ``(F t)'`` at ``-s`` (:mod:`bild_mdo.bild.annulus_stationarity`) and
Prandtl's factor with its first two ``phi`` derivatives.  The solver is
:func:`~bild_mdo.utils.compiled.bracketed_newton_for`, the whole-array
:func:`~bild_mdo.utils.newton.bracketed_newton` step for step, so the roots are those of the whole-array
solve to round-off (``tests/bild/variants/turbine/test_turbine_compiled.py``); the partials still come
from the whole-array terms.

The values of the loads, of the chord and twist and of the reference station's chord (and its solve for a
given chord) are here too: one pass per station, where the whole-array jets take tens of passes over the
stations and carry every partial along (``run_model`` of a batch of designs spends its time there).  The
components keep the jets for their partials and under complex step.
"""
from __future__ import annotations

import math

import numpy as np

# Prandtl's factor in the three exact forms the local-point kernels use (one implementation for all kernels).
from bild_mdo.bild.variants.local_point.kernels import prandtl_one as _loss, prandtl_value_one as _loss_value
from bild_mdo.utils.compiled import bracketed_newton_for, kernel

#: Stations of a design the start of the solve is extrapolated from (a cubic in ``r``).
_TRAIL = 4


@kernel
def _slopes(phi, v_axial, v_theta, ratio, k_tip, k_hub, loss):
    """``(F p)', (F t)'`` and their ``phi`` derivatives of one station (the kernel's :class:`TurbineTerms`)."""
    s = -ratio
    sn, cs = math.sin(phi), math.cos(phi)
    f, f1, f2 = _loss(sn, cs, k_tip, k_hub, loss)
    c_x, c_t = cs - s * sn, sn + s * cs
    a = v_axial * c_t + v_theta * c_x
    a1 = v_axial * c_x - v_theta * c_t
    u, w = a * sn, a * cs
    u1, w1 = a1 * sn + w, a1 * cs - u
    u2, w2 = 2.0 * w1, -2.0 * u1
    slope_u, gap = 2.0 * u - v_axial, v_theta - w
    t, t1, t2 = u * (u - v_axial), u1 * slope_u, u2 * slope_u + 2.0 * u1 * u1
    q, q1, q2 = u * gap, u1 * gap - u * w1, u2 * gap - 2.0 * u1 * w1 - u * w2
    e, e1, e2 = v_theta * q - v_axial * t, v_theta * q1 - v_axial * t1, v_theta * q2 - v_axial * t2
    n = f1 * e + f * e1
    d = f1 * t + f * t1
    n1 = f2 * e + 2.0 * f1 * e1 + f * e2
    d1 = f2 * t + 2.0 * f1 * t1 + f * t2
    return -n - v_axial * d, -d, -n1 - v_axial * d1, -d1


@kernel
def turbine_value(phi, state, params):
    """``(G - mu, dG/dphi, scale)`` of one station at ``phi`` (``params = (V, x, s, k_tip, k_hub, loss, mu,
    barrier)``, ``barrier`` the value past the maximum of the annulus thrust: the turbine kernel's ``BARRIER``)."""
    v_axial, v_theta, ratio, k_tip, k_hub, loss, mu, barrier = params
    power_slope, thrust_slope, power_curvature, thrust_curvature = _slopes(phi, v_axial, v_theta, ratio, k_tip,
                                                                           k_hub, int(loss))
    if not thrust_slope < 0.0:
        return barrier, 1.0, abs(power_slope) + abs(mu)
    inverse = 1.0 / thrust_slope
    g = power_slope * inverse
    return g - mu, (power_curvature - g * thrust_curvature) * inverse, abs(g) + abs(mu)


@kernel
def chord_value(phi, state, params):
    """``(c - c_ref, dc/dphi, 0)`` of the chord (T2) of one station (``params = (V, x, s, k_tip, k_hub, loss,
    8 pi r / (B C_l*), c_ref)``; the formula of :func:`~bild_mdo.bild.variants.turbine.kernel.chord_jet`)."""
    v, x, s, k_tip, k_hub, loss, scale, target = params
    sn, cs = math.sin(phi), math.cos(phi)
    f, f1, _ = _loss(sn, cs, k_tip, k_hub, int(loss))
    normal, normal1 = cs + s * sn, s * cs - sn
    big_a = v * (sn - s * cs) + x * normal
    big_a1 = v * normal + x * normal1
    u = big_a * sn
    u1 = big_a1 * sn + big_a * cs
    t, t1 = u * (v - u), u1 * (v - 2.0 * u)
    below = big_a * big_a * normal
    chord = scale * f * t / below
    slope = scale * ((f1 * t + f * t1) - f * t * (2.0 * big_a1 * normal + big_a * normal1) / (big_a * normal)) / below
    return chord - target, slope, 0.0


_solve = bracketed_newton_for(turbine_value)
_solve_chord = bracketed_newton_for(chord_value)


@kernel
def _extrapolate(radii, offsets, known, r, work):
    """The polynomial through the ``known`` latest ``(radii, offsets)`` (newest first) at ``r`` (Neville's
    scheme in ``work``)."""
    for a in range(known):
        work[a] = offsets[a]
    for k in range(1, known):
        for a in range(known - k):
            work[a] = ((r - radii[a + k]) * work[a] + (radii[a] - r) * work[a + 1]) / (radii[a] - radii[a + k])
    return work[0]


@kernel
def solve_stations(mu, v_axial, ratio, radius, hub_radius, v_theta, r, per, num_blades, loss, max_iter, codes,
                   barrier, phi, status):
    """Solve every station (flat ``x = Omega r`` and ``r``, ``per`` stations a design, hub to tip; ``mu, V, s, R,
    r_hub`` per design; ``loss``: 0 none, 1 tip, 2 tip and hub).  Writes ``phi`` (the unloaded angle
    ``atan(V/x)`` where not loaded) and ``status``, one of ``codes = (loaded, unloaded, failed)``: failed
    outside ``V, x, r > 0, s >= 0`` or where the solve did not converge, unloaded where ``G(phi0) <= mu``.

    The first iterate is Glauert's optimum rotor with wake rotation, ``phi = (2/3) atan(V/x)`` (the member
    ``mu = 0`` without drag and tip loss), plus its offset from the root extrapolated from the loaded
    stations solved before in the design (changes where Newton's method begins only): from a quarter of the
    stations out to the tip, then from there in to the hub, where the hub loss bends the offset most."""
    loaded, unloaded, failed = codes
    state = np.zeros(1)
    half_b = 0.5 * num_blades
    trail_r, trail_offset, work = np.zeros(_TRAIL), np.zeros(_TRAIL), np.zeros(_TRAIL)
    first_out = per // 4
    outward = per - first_out
    known = 0
    for i in range(r.size):
        n, k = i // per, i % per
        first = n * per
        if k == 0:
            known = 0
        elif k == outward:
            # The trail inward begins at the stations the outward one began with.
            known = 0
            while known < min(_TRAIL, outward) and status[first + first_out + known] == loaded:
                m = first + first_out + known
                trail_r[known] = r[m]
                trail_offset[known] = phi[m] - (2.0 / 3.0) * math.atan2(v_axial[n], v_theta[m])
                known += 1
        i = first + (first_out + k if k < outward else per - 1 - k)
        v, s, x, radial = v_axial[n], ratio[n], v_theta[i], r[i]
        hi = math.atan2(v, x)
        b = x - v * s
        lo = math.atan(v / (b + math.sqrt(b * b + v * (v + 2.0 * x * s))))
        phi[i] = hi
        k_tip = half_b * (radius[n] - radial) / radial
        k_hub = half_b * (radial - hub_radius[n]) / hub_radius[n] if loss == 2 else 1.0
        if not (v > 0.0 and x > 0.0 and s >= 0.0 and radial > 0.0 and math.isfinite(lo + hi)
                and k_tip == k_tip and k_hub == k_hub):
            phi[i], status[i], known = 0.0, failed, 0
            continue
        # At phi0 the annulus carries no load (u = V, w = x: t = q = 0), so G(phi0) = -x w'/u' does not depend
        # on F: x (V - s x) / (x + s V).
        value = x * (v - s * x) / (x + s * v) - mu[n]
        if not value > 0.0:
            status[i], known = unloaded if math.isfinite(value) else failed, 0
            continue
        start = (2.0 / 3.0) * hi
        if known:
            start += _extrapolate(trail_r, trail_offset, known, radial, work)
        params = (v, x, s, k_tip, k_hub, float(loss), mu[n], barrier)
        root, ok, _, _, _ = _solve(state, params, lo, hi, -1.0, start, max_iter, 0.0)
        phi[i], status[i] = root, loaded if ok else failed
        if not ok:
            known = 0
            continue
        for a in range(_TRAIL - 1, 0, -1):
            trail_r[a], trail_offset[a] = trail_r[a - 1], trail_offset[a - 1]
        trail_r[0], trail_offset[0] = radial, root - (2.0 / 3.0) * hi
        known = min(known + 1, _TRAIL)


@kernel
def station_loads(phi, v_theta, r, v_axial, ratio, radius, hub_radius, rho, num_blades, loss, axial, tangential,
                  u_axial, inflow_speed, loss_factor, dthrust_dr, dtorque_dr):
    """Values of :class:`~bild_mdo.bild.variants.turbine.turbine_loads.TurbineLoadsComp` (per-design ``V, s, R,
    r_hub, rho`` ``[nn]``, the rest ``[nn, nr]``), the formulas of
    :func:`~bild_mdo.bild.variants.turbine.kernel.station_jets` station by station, written into the outputs."""
    half_b = 0.5 * num_blades
    for i in range(phi.shape[0]):
        v, s, four_pi_rho = v_axial[i], ratio[i], 4.0 * math.pi * rho[i]
        for j in range(phi.shape[1]):
            x, radial = v_theta[i, j], r[i, j]
            sn, cs = math.sin(phi[i, j]), math.cos(phi[i, j])
            normal = cs + s * sn
            big_a = v * (sn - s * cs) + x * normal
            u, w = big_a * sn, big_a * cs
            k_hub = half_b * (radial - hub_radius[i]) / hub_radius[i] if loss == 2 else 1.0
            f = _loss_value(sn, half_b * (radius[i] - radial) / radial, k_hub, loss)
            axial[i, j], tangential[i, j] = 1.0 - u / v, w / x - 1.0
            u_axial[i, j], inflow_speed[i, j], loss_factor[i, j] = u, big_a, f
            dthrust_dr[i, j] = four_pi_rho * radial * f * (u * (v - u))
            dtorque_dr[i, j] = four_pi_rho * radial * radial * f * (u * (w - x))


@kernel
def station_chords(dthrust_dr, phi, inflow_speed, rho, alpha, cl, cd, num_blades, chord, twist, lift, drag):
    """Values of :class:`~bild_mdo.bild.variants.turbine.turbine_chord.TurbineChordComp` (per-design ``rho,
    alpha*, C_l*, C_d*`` ``[nn]``, the rest ``[nn, nr]``) written into the outputs; returns False where a normal-force
    coefficient is not positive (the outputs are then incomplete)."""
    for i in range(phi.shape[0]):
        c_l, c_d = cl[i], cd[i]
        for j in range(phi.shape[1]):
            normal = c_l * math.cos(phi[i, j]) + c_d * math.sin(phi[i, j])
            if not normal > 0.0:
                return False
            speed = inflow_speed[i, j]
            chord[i, j] = 2.0 / (rho[i] * (speed * speed) * num_blades) * dthrust_dr[i, j] / normal
            twist[i, j], lift[i, j], drag[i, j] = phi[i, j] - alpha[i], c_l, c_d
    return True


@kernel
def reference_chords(phi, v_axial, v_theta, ratio, r, radius, hub_radius, cl, num_blades, loss, chord):
    """Chord (T2) of one station a design at its ``phi`` (``[nn]`` each) into ``chord``."""
    half_b, state = 0.5 * num_blades, np.zeros(1)
    for i in range(phi.size):
        k_hub = half_b * (r[i] - hub_radius[i]) / hub_radius[i] if loss == 2 else 1.0
        params = (v_axial[i], v_theta[i], ratio[i], half_b * (radius[i] - r[i]) / r[i], k_hub, float(loss),
                  8.0 * math.pi * r[i] / (num_blades * cl[i]), 0.0)
        chord[i] = chord_value(phi[i], state, params)[0]


@kernel
def solve_reference_chords(v_axial, v_theta, ratio, r, radius, hub_radius, cl, ref_chord, num_blades, loss, max_iter,
                           phi, multiplier, chord_lo, status):
    """``phi`` of the reference station with the chord (T2) ``ref_chord`` and the multiplier ``G(phi)`` there
    (``[nn]`` each), bracketed on ``[phi_half, phi0]`` from the chord ``chord_lo`` at ``phi_half``; ``status`` 0,
    or 1 where ``ref_chord`` is not in ``(0, chord_lo)``, 2 where the solve failed or ``phi`` lies past the
    maximum of the annulus thrust."""
    half_b, state = 0.5 * num_blades, np.zeros(1)
    for i in range(phi.size):
        v, x, s = v_axial[i], v_theta[i], ratio[i]
        b = x - v * s
        lo = math.atan(v / (b + math.sqrt(b * b + v * (v + 2.0 * x * s))))
        k_tip = half_b * (radius[i] - r[i]) / r[i]
        k_hub = half_b * (r[i] - hub_radius[i]) / hub_radius[i] if loss == 2 else 1.0
        params = (v, x, s, k_tip, k_hub, float(loss), 8.0 * math.pi * r[i] / (num_blades * cl[i]), ref_chord[i])
        f_lo = chord_value(lo, state, params)[0]
        chord_lo[i] = f_lo + ref_chord[i]
        phi[i], multiplier[i] = lo, math.nan
        if not (f_lo > 0.0 and ref_chord[i] > 0.0):
            status[i] = 1
            continue
        root, ok, _, _, _ = _solve_chord(state, params, lo, math.atan2(v, x), f_lo, math.nan, max_iter, 0.0)
        power_slope, thrust_slope, _, _ = _slopes(root, v, x, s, k_tip, k_hub, loss)
        phi[i], multiplier[i] = root, power_slope / thrust_slope
        status[i] = 0 if ok and thrust_slope < 0.0 else 2
