"""Several optimiser starts per sweep case: the best optimum and the spread between the starts.

With a Reynolds-dependent polar the energy-loss optimum is not unique: runs
from different starts end at different geometries with nearly equal energy
losses, so a geometry error measured against one run has a floor of that
size.  ``bild-mdo verify --starts N`` runs the optimiser from the first N
starts of :data:`~bild_mdo.verification.cases.START_KINDS`; :func:`combine_starts`
keeps the lowest-energy converged optimum as the reference of Table 3 and
measures how far apart the converged starts ended (:data:`START_COLUMNS`).

Spread definitions (fractions, over the converged starts; 0 with one):

- ``start_spread_twist``, ``start_spread_chord``: the largest distance between
  two starts' distributions, ``max_ij ||x_i - x_j||_2 / ||x_best||_2``: the same
  norm as Table 3's geometry error, so the two read side by side;
- ``start_spread_energy``: ``(max_i E_i - min_i E_i) / min_i E_i``.
"""
import math

import numpy as np

#: Columns one case's start comparison adds to its results-store row.
START_COLUMNS = ("start_spread_twist", "start_spread_chord", "start_spread_energy", "starts_converged", "best_start")


def _converged(result):
    return (isinstance(result, dict) and bool(result.get("converged"))
            and result.get("energy_loss") is not None and math.isfinite(float(result["energy_loss"])))


def start_spread(results):
    """Spread between converged optimiser results of one case (see the module docstring).

    Parameters
    ----------
    results : list of dict
        Converged results (``chord``, ``twist`` 1-D, ``energy_loss`` in W), at least one.

    Returns
    -------
    dict
        ``start_spread_twist``, ``start_spread_chord``, ``start_spread_energy`` (-), each >= 0.
    """
    energy = np.array([float(r["energy_loss"]) for r in results])
    best = results[int(np.argmin(energy))]
    out = {"start_spread_energy": float((energy.max() - energy.min()) / abs(energy.min()))}
    for name in ("twist", "chord"):
        values = np.array([np.asarray(r[name], dtype=float) for r in results])
        gaps = np.linalg.norm(values[:, None, :] - values[None, :, :], axis=-1)
        out[f"start_spread_{name}"] = float(gaps.max() / np.linalg.norm(np.asarray(best[name], dtype=float)))
    return out


def combine_starts(results):
    """One case's optimum from its starts: the lowest-energy converged one, with the spread.

    Parameters
    ----------
    results : list
        Per start, in :data:`~bild_mdo.verification.cases.START_KINDS` order:
        the result dict of the optimisation, the exception it raised, or None
        (the start could not be made, e.g. the other section point's BILD design failed).

    Returns
    -------
    dict or Exception
        The best converged result with :data:`START_COLUMNS` added
        (``best_start`` counts from 1); without a converged start, the first
        start's result or exception (the spread columns None,
        ``starts_converged`` 0).
    """
    converged = [(k, r) for k, r in enumerate(results) if _converged(r)]
    if not converged:
        first = next((r for r in results if r is not None), None)
        if not isinstance(first, dict):
            return first if first is not None else ValueError("no optimiser start could be made")
        out = dict(first)
        out.update({key: None for key in START_COLUMNS}, starts_converged=0)
        return out
    best_index, best = min(converged, key=lambda item: float(item[1]["energy_loss"]))
    out = dict(best)
    out.update(start_spread([r for _, r in converged]), starts_converged=len(converged), best_start=best_index + 1)
    return out
