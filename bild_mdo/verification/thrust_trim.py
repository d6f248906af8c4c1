"""The collective-pitch trim of BILD's designs to their own thrust in the BEM model (:mod:`.optimality`, step 2).

One safeguarded secant iteration on a uniform pitch offset per case, all cases
of one configuration in one vectorised :func:`~bild_mdo.bem.analyze.analyze_rotor`
call per iteration; turbine rows (:mod:`~bild_mdo.verification.turbine_sweep`) in
the kernel's convention of :mod:`bild_mdo.optimization.turbine`.
"""
from __future__ import annotations

import numpy as np

from bild_mdo.airfoil.text import sweep_polar
from bild_mdo.atmosphere import isa
from bild_mdo.bem.analyze import analyze_rotor
from bild_mdo.bem.flow_states import INVALID_STATES
from bild_mdo.bem.turbine_polar import TurbinePolar
from bild_mdo.constants import RPM_TO_REV_PER_S
from bild_mdo.optimization.initial_design import CHORD_RATIO_BOUNDS

from .feathering import least_loss_twist

#: Loss model of the optimisation problem the optimum comes from.
LOSS_MODEL = "tip_hub"
CASE_KEYS = ("v_axial", "rpm", "radius", "hub_radius", "altitude")
MODEL_KEYS = ("num_radial", "num_blades", "airfoil")


def thrust_target(rows, rotor_type="propeller"):
    """``T* = C_T rho n^2 D^4`` of BILD's design (N; a turbine's ``C_T rho pi R^2 V^2 / 2``, in the kernel's
    sign: negative), rho from the ISA at each case's altitude."""
    c_t = np.array([row["bild_thrust_coefficient"] for row in rows], dtype=float)
    rho = np.asarray(isa(np.array([row["altitude"] for row in rows], dtype=float)).rho, dtype=float)
    radius = np.array([row["radius"] for row in rows], dtype=float)
    if rotor_type == "turbine":
        return -c_t * 0.5 * rho * np.pi * radius**2 * np.array([row["v_axial"] for row in rows], dtype=float)**2
    return c_t * rho * (np.array([row["rpm"] for row in rows], dtype=float) * RPM_TO_REV_PER_S)**2 * (2.0 * radius)**4


def trim_batch(rows, tol, max_iter, first_step, max_step, rotor_type):
    """Safeguarded secant iteration on the pitch offset of every row at once (one configuration)."""
    _, num_blades, airfoil = (rows[0][k] for k in MODEL_KEYS)
    polar = sweep_polar(airfoil)
    # A turbine in the kernel's convention (bild_mdo.optimization.turbine): its thrust falls with pitch.
    polar, sign = (TurbinePolar(polar), -1.0) if rotor_type == "turbine" else (polar, 1.0)
    chord = np.array([row["bild_chord"] for row in rows], dtype=float)
    twist = np.array([row["bild_twist"] for row in rows], dtype=float)
    case = {k: np.array([row[k] for row in rows], dtype=float) for k in CASE_KEYS}
    bound = CHORD_RATIO_BOUNDS[0] * case["radius"][:, None]
    raised = chord < bound
    chord = np.maximum(chord, bound)  # see trimmed_bild_energy_loss
    if np.any(raised):
        twist = least_loss_twist(chord, twist, raised, case, int(num_blades), polar, LOSS_MODEL)
    target = thrust_target(rows, rotor_type)

    def analyse(offset):
        result = analyze_rotor(chord, twist + offset[:, None], case["radius"], case["hub_radius"], case["rpm"],
                               case["v_axial"], int(num_blades), polar, altitude=case["altitude"],
                               loss_model=LOSS_MODEL, on_invalid="ignore")
        # The secant steps may pass through invalid flow states; the trimmed design's are counted below.
        invalid[:] = np.isin(np.rint(np.real(result.flow_state)), INVALID_STATES).sum(axis=-1)
        return np.asarray(result.thrust) / target - 1.0, np.asarray(result.energy_loss)

    size = len(rows)
    invalid = np.zeros(size, dtype=int)
    x = np.zeros(size)
    f, energy = analyse(x)
    untrimmed = f.copy()
    x_prev, f_prev = None, None
    # Thrust rises with collective pitch while the sections are not stalled; the first slope
    # comes from a small probe step, later ones from the last two iterates.
    slope = np.full(size, np.nan)
    iterations = 0
    while np.any(np.abs(f) > tol) and iterations < max_iter:
        active = np.abs(f) > tol
        if x_prev is None:
            step = np.where(active, -sign * np.sign(f) * first_step, 0.0)
        else:
            dx = x - x_prev
            with np.errstate(divide="ignore", invalid="ignore"):
                secant = (f - f_prev) / dx
            usable = (dx != 0.0) & np.isfinite(secant) & (sign * secant > 0.0)
            slope = np.where(usable, secant, slope)
            step = np.where(active & np.isfinite(slope), -f / slope, 0.0)
            # No usable slope yet (the probe did not move T): probe again.
            step = np.where(active & ~np.isfinite(slope), -sign * np.sign(f) * first_step, step)
        step = np.clip(step, -max_step, max_step)
        moved = step != 0.0
        if x_prev is None:
            x_prev, f_prev = x.copy(), f.copy()
        x_prev, f_prev = np.where(moved, x, x_prev), np.where(moved, f, f_prev)
        x = x + step
        f, energy = analyse(x)
        iterations += 1
    return dict(energy_loss=energy, thrust_residual=f, pitch_offset=x, untrimmed_thrust_error=untrimmed,
                converged=np.abs(f) <= tol, iterations=iterations, invalid_stations=invalid,
                twist=twist + x[:, None])
