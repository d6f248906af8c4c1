"""The twist of a zero-chord BILD station held at the optimiser's chord bound, for the optimality check's trim."""
import numpy as np

from bild_mdo.bem.analyze import analyze_rotor, station_radii
from bild_mdo.bem.flow_states import INVALID_STATES
from bild_mdo.bild.annulus_stationarity import unloaded_angle
from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.optimization.initial_design import TWIST_LIMITS

#: Angles of attack (at the unloaded inflow angle) scanned for the twist of a station raised to the chord bound.
FEATHER_ANGLES = np.radians(np.arange(-20.0, 20.0 + 0.25, 0.5))
#: Rotors per BEM analysis of the scan (its memory grows with them: about 0.6 GB at 30 stations).
ROTORS_PER_ANALYSIS = 8000


def least_loss_twist(chord, twist, raised, case, num_blades, polar, loss_model):
    """Twist of least BEM energy loss at the stations ``raised`` to the chord bound (the others unchanged).

    BILD gives no blade, so no twist, where its chord is zero; at the
    optimiser's chord bound such a station still carries a load, and with a
    tabulated polar extrapolated far below its Reynolds range (Re of order
    1e2 at c/R = 1e-4) that load can be large.  The optimiser is free to set
    the twist there; so is this trim: each raised station gets, from a scan
    of :data:`FEATHER_ANGLES` about its unloaded inflow angle
    ``atan(V_x/(Omega r))``, clipped to the optimiser's twist limits
    (:data:`~bild_mdo.optimization.initial_design.TWIST_LIMITS`, so that the
    trimmed design stays a point the optimiser could reach), and BILD's own
    twist, the twist whose own energy loss ``Omega dQ/dr - V_x dT/dr`` is least
    (BEM stations are independent at a given chord and twist; flow states
    without a momentum solution are left out).

    Parameters
    ----------
    chord, twist : ndarray, shape (nn, nr)
        The design (m, rad), with the raised chords already at the bound.
    raised : ndarray of bool, shape (nn, nr)
        The stations whose twist is chosen.
    case : dict
        ``v_axial, rpm, radius, hub_radius, altitude`` arrays ``(nn,)``.
    num_blades : int
    polar : Polar
    loss_model : str
        Of the optimisation problem.

    Returns
    -------
    ndarray, shape (nn, nr)
        ``twist`` with the raised stations' twists replaced.
    """
    nn, nr = chord.shape
    out = twist.copy()
    rows = np.flatnonzero(np.any(raised, axis=1))
    # The designs with a raised station, in batches of at most ROTORS_PER_ANALYSIS rotors (each of them makes
    # FEATHER_ANGLES.size + 1 rotors of the analysis).
    per_batch = max(1, ROTORS_PER_ANALYSIS // (FEATHER_ANGLES.size + 1))
    for start in range(0, rows.size, per_batch):
        part = rows[start:start + per_batch]
        out[part] = _least_loss_twist(chord[part], twist[part], raised[part], {k: v[part] for k, v in case.items()},
                                      num_blades, polar, loss_model)
    return out


def _least_loss_twist(chord, twist, raised, case, num_blades, polar, loss_model):
    nn, nr = chord.shape
    k = FEATHER_ANGLES.size + 1
    radii = station_radii(case["radius"], case["hub_radius"], nr)
    omega = case["rpm"] * RPM_TO_RAD_PER_S
    phi0 = unloaded_angle(case["v_axial"][:, None], omega[:, None] * radii)
    # BILD's own twist is the first candidate (ties keep it), then the scan.
    scan = np.clip(phi0[:, None, :] + FEATHER_ANGLES[None, :, None], *TWIST_LIMITS)
    trial = np.concatenate([twist[:, None, :], scan], axis=1)
    trial = np.where(raised[:, None, :], trial, twist[:, None, :]).reshape(nn * k, nr)

    def repeat(x):
        return np.repeat(x, k, axis=0)

    result = analyze_rotor(repeat(chord), trial, repeat(case["radius"]), repeat(case["hub_radius"]),
                           repeat(case["rpm"]), repeat(case["v_axial"]), num_blades, polar,
                           altitude=repeat(case["altitude"]), loss_model=loss_model, on_invalid="ignore")
    loss = (repeat(omega)[:, None] * np.asarray(result.dtorque_dr)
            - repeat(case["v_axial"])[:, None] * np.asarray(result.dthrust_dr))
    invalid = np.isin(np.rint(np.real(result.flow_state)), INVALID_STATES)
    loss = np.where(invalid | ~np.isfinite(loss), np.inf, loss).reshape(nn, k, nr)
    best = np.argmin(loss, axis=1)
    chosen = np.take_along_axis(trial.reshape(nn, k, nr), best[:, None, :], axis=1)[:, 0, :]
    return np.where(raised, chosen, twist)
