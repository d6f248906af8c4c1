"""The turbine loading's per-station solve, compiled (:func:`~bild_mdo.bild.variants.turbine.kernel.solve_loading`).

The residual is the one of :func:`~bild_mdo.bild.variants.turbine.kernel._bracketed`, written for one
station: ``G - mu`` with ``G = (F p)' / (F t)'`` below the maximum of the annulus thrust, the barrier past
it, from the propeller's ``(F e)'``, ``(F t)'`` at ``-s`` (:mod:`bild_mdo.bild.annulus_stationarity`) and
Prandtl's factor with its first two ``phi`` derivatives
(:func:`~bild_mdo.bild.variants.local_point.kernels.prandtl_one`).  The solver is
:func:`~bild_mdo.utils.compiled.bracketed_newton_for`, the whole-array
:func:`~bild_mdo.utils.newton.bracketed_newton` step for step, so the roots are those of the whole-array
solve to round-off (``tests/bild/variants/turbine/test_turbine_compiled.py``); the partials still come
from the whole-array terms.
"""
from __future__ import annotations

import math

import numpy as np

from bild_mdo.bild.variants.local_point.kernels import prandtl_one, trail_prediction, trail_record
from bild_mdo.utils.compiled import bracketed_newton_for, kernel


@kernel
def turbine_value(phi, state, params):
    """``(G - mu, dG/dphi, scale)`` of one station at ``phi`` (``params = (V, x, s, k_tip, k_hub, loss, mu,
    barrier)``, ``barrier`` the value past the maximum of the annulus thrust: the turbine kernel's ``BARRIER``)."""
    v_axial, v_theta, ratio, k_tip, k_hub, loss, mu, barrier = params
    s = -ratio
    sn, cs = math.sin(phi), math.cos(phi)
    f, f1, f2 = prandtl_one(sn, cs, k_tip, k_hub, int(loss))
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
    thrust_slope, power_slope = -d, -n - v_axial * d
    if not thrust_slope < 0.0:
        return barrier, 1.0, abs(power_slope) + abs(mu)
    g = power_slope / thrust_slope
    return g - mu, ((-n1 - v_axial * d1) - g * (-d1)) / thrust_slope, abs(g) + abs(mu)


_solve = bracketed_newton_for(turbine_value)


@kernel
def solve_stations(mu, v_axial, v_theta, ratio, r, radius, hub_radius, lo, hi, start, num_blades, loss, max_iter,
                   codes, barrier, phi, status):
    """Solve every station (flat arrays of one length; ``loss``: 0 none, 1 tip, 2 tip and hub): writes ``phi``
    (``hi``, the unloaded angle, where not loaded) and ``status``, one of ``codes = (loaded, unloaded,
    failed)``: unloaded where ``G(hi) <= mu``, failed where that value is not finite or the solve did not
    converge."""
    loaded, unloaded, failed = codes
    state = np.zeros(1)
    half_b = 0.5 * num_blades
    # The loaded stations inward of this one in its design (one "sheet": label 0), as the local-point solves
    # keep them.
    trail = np.zeros(6)
    for i in range(mu.size):
        if not (i > 0 and r[i] > r[i - 1] and radius[i] == radius[i - 1] and mu[i] == mu[i - 1]
                and v_axial[i] == v_axial[i - 1]):
            trail_record(trail, -1, 0.0, 0.0)
        k_tip = half_b * (radius[i] - r[i]) / r[i]
        k_hub = half_b * (r[i] - hub_radius[i]) / hub_radius[i] if loss == 2 else 1.0
        params = (v_axial[i], v_theta[i], ratio[i], k_tip, k_hub, float(loss), mu[i], barrier)
        phi[i] = hi[i]
        f_hi = turbine_value(hi[i], state, params)[0]
        if not math.isfinite(f_hi):
            status[i] = failed
            trail_record(trail, -1, 0.0, 0.0)
        elif f_hi <= 0.0:
            status[i] = unloaded
            trail_record(trail, -1, 0.0, 0.0)
        else:
            # Where the offsets of the stations inward predict (changes where Newton's method begins only).
            offset = trail_prediction(trail, r[i])[1]
            x, ok, _, _, _ = _solve(state, params, lo[i], hi[i], -1.0, start[i] + offset, max_iter, 0.0)
            phi[i], status[i] = x, loaded if ok else failed
            trail_record(trail, 0 if ok else -1, x - start[i], r[i])
