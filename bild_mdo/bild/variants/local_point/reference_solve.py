"""The reference station of the local-section-point variants: its BEM state with ``c_ref`` at its own section point.

At the reference station the chord is given, so ``Re_ref = rho W0 c_ref / mu`` is
known and the load follows.  Its section point is a minimum of ``cd/cl`` along
its own path of fixed load with that Reynolds number, so a station placed at
``r_ref`` gets the same load, the same point and the chord ``c_ref``.

On the table (:mod:`bild_mdo.airfoil.load_path_table`) the state is ``(phi,
x0)`` on a sheet with::

    R2   = x_m(phi, s(x0)) - x0 - ln(1 + tau(phi) s(x0)) = 0    the blade element carries the momentum load,
    Rell = ell(x0) - ln Re_ref = 0                              at the chord Reynolds number of c_ref,

(``x_m`` the momentum ``ln(Q / p)`` of :mod:`~bild_mdo.bild.variants.local_point.load_path_model`), the same
residual ``R2`` as a station's, so a station of that model placed at ``r_ref`` has the same state and the
chord ``c_ref``.  The candidates are the sheets whose Reynolds number passes through ``Re_ref``
(:meth:`~bild_mdo.airfoil.load_path_table.LoadPathTable.reynolds_crossings`), each solved by Newton's method
on ``(R2, Rell)`` from a first angle (the reference station's BEM closed form at ``cl = 1``); of those that
are a minimum of ``cd/cl`` along their path the lowest ``cd/cl`` is taken.

The Reynolds gap (limitation).  With the NACA 4412 surrogate no minimum has a
chord Reynolds number between about 1.9e5 and 2.2e5: those are the optimum of
no path, so a ``c_ref`` whose ``Re_ref`` lies there is a chord no station
chooses.  There the reference station takes the stationary point with the
lowest ``cd/cl``, which is a maximum along its path (continuous in
``c_ref``, so lambda stays continuous), and a station placed at ``r_ref`` takes
a minimum of the same path instead, so its chord differs from ``c_ref``.  Where
no sheet of the table covers ``Re_ref`` (next to a fold) the state is solved
on the polar itself (:mod:`~bild_mdo.bild.variants.local_point.gap`).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from bild_mdo.bild.variants.local_point.load_path_model import (
    StationFlow,
    _curve_jets,
    _exp,
    _log,
    annulus_jets,
    constants,
    loading_jets,
)
from bild_mdo.bild.variants.local_point.gap import _reynolds_jet, gap_solve, reference_reynolds, take_reference
from bild_mdo.utils.jet import variable

#: cd/cl and cl of the first angle.
_START_CL, _START_RATIO = 1.0, 0.015
_PASSES = 40
_PHI_STEP_MAX, _X_STEP_MAX = 0.05, 0.5
_TOL = 1e-13
#: Added to cd/cl of a stationary point that is not a minimum along its path, so any minimum ranks first.
_GAP_RANK = 1.0e3


class ReferenceFlow(NamedTuple):
    """Per-design inputs of the reference station (flat arrays) and the options."""

    v_axial: np.ndarray
    v_theta: np.ndarray
    r: np.ndarray
    chord: np.ndarray
    radius: np.ndarray
    hub_radius: np.ndarray
    rho: np.ndarray
    mu: np.ndarray
    num_blades: int
    loss_model: str
    chord_form: str


def station_flow(ref):
    """The :class:`StationFlow` of the reference station (``lam`` unused: zeros)."""
    return StationFlow(np.zeros(np.shape(ref.r)), ref.v_axial, ref.v_theta, ref.r, ref.radius, ref.hub_radius,
                       ref.rho, ref.mu, ref.num_blades, ref.loss_model, ref.chord_form)


class ReferenceSolution(NamedTuple):
    """Per design: ``phi``, ``x0``, ``s``, ``alpha`` and the sheet ``label`` (table states), ``on_table``
    (False: no sheet covers ``Re_ref``, exact states ``phi, alpha``), ``ok`` (a converged state) and, on the
    table, ``N_tot, D_tot`` of the reference annulus (the exact loading's lambda is their ratio), and a station's
    test of that state as its own ideal load at lambda: ``slope``, ``d(N_tot/D_tot)/dphi`` along the path (> 0:
    a minimum of ``Phi``), and ``objective``, ``Phi = F (e - lambda t)`` (< 0: better than no load); NaN off the
    table."""

    phi: np.ndarray
    x0: np.ndarray
    s: np.ndarray
    alpha: np.ndarray
    label: np.ndarray
    on_table: np.ndarray
    ok: np.ndarray
    n_tot: np.ndarray
    d_tot: np.ndarray
    slope: np.ndarray
    objective: np.ndarray


def first_angle(ref):
    """The reference station's BEM closed form at ``cl = 1`` (``cos(phi_g + 2 delta) = cos(phi_g) - 2 q``)."""
    sigma = ref.num_blades * ref.chord / (2.0 * np.pi * ref.r)
    geometric = np.arctan2(ref.v_axial, ref.v_theta)
    q = 0.25 * sigma * _START_CL
    return 0.5 * (geometric + np.arccos(np.clip(np.cos(geometric) - 2.0 * q, -1.0, 1.0)))


def solve_reference(table, polar, ref, exclude=None, gap=True):
    """:class:`ReferenceSolution` of every design (flat real inputs; module docstring); ``exclude[n]``
    (int64, optional): bit ``k`` set, sheet ``k`` is no candidate of that design; ``gap=False``: a design with
    no minimum on the table is not solved on the polar (``ok`` False)."""
    from bild_mdo.bild.variants.local_point.kernels import LOSS_CODES, table_arrays
    from bild_mdo.bild.variants.local_point.reference_kernel import reference_all, reference_arrays

    n = ref.r.size
    ell_ref = np.log(reference_reynolds(ref))
    guess = first_angle(ref)
    c = constants(station_flow(ref))
    k_hub = c.k_hub if c.k_hub is not None else np.ones(n)
    out = np.full((n, 10), np.nan)
    if not hasattr(table, "_reference_arrays"):
        table._reference_arrays = reference_arrays(table)
    with np.errstate(all="ignore"):
        reference_all(table_arrays(table), table._reference_arrays,
                      np.column_stack((c.log_k, c.k_tip, k_hub, c.v_axial, c.v_theta)), guess, ell_ref,
                      ref.chord_form == "torque", LOSS_CODES[ref.loss_model],
                      np.array([_PASSES, _TOL, _PHI_STEP_MAX, _X_STEP_MAX]), _GAP_RANK,
                      np.zeros(n, dtype=np.int64) if exclude is None else exclude, out)
    on_table = out[:, 5] > 0.0
    phi = np.where(on_table, out[:, 0], guess)
    x0, s, alpha = np.where(on_table, out[:, 1], 0.0), np.where(on_table, out[:, 2], _START_RATIO), \
        np.where(on_table, out[:, 3], 0.1)
    label = np.where(on_table, out[:, 4], -1).astype(int)
    ok = on_table.copy()
    gap = np.flatnonzero(~on_table) if gap else np.zeros(0, dtype=int)
    if gap.size:
        phi_g, alpha_g, ok_g = gap_solve(polar, take_reference(ref, gap), guess[gap])
        phi[gap], alpha[gap], ok[gap] = phi_g, alpha_g, ok_g
    return ReferenceSolution(phi, x0, s, alpha, label, on_table, ok, out[:, 6], out[:, 7], out[:, 8], out[:, 9])


def table_jets(table, ref, phi, x0, label):
    """Jets of the table state: ``(R2, Rell)`` in the states ``(phi, x0)``, the annulus, ``s`` and ``s'``, and the
    section point ``alpha, cl, cd, Re C`` (module docstring)."""
    ph, xj = variable(phi, "phi"), variable(x0, "x0")
    flow = station_flow(ref)
    point = table.curve(x0, label)
    s, s1 = _curve_jets(point["s"], xj)
    ell = _curve_jets(point["ell"], xj)[0]
    alpha = _curve_jets(point["alpha"], xj)[0]
    ring = annulus_jets(flow, ph, s)
    r2, _, n_tot, d_tot = loading_jets(ring, xj, s, s1)
    cl = _exp(xj - ell)
    load = ring.p * _exp(xj) * (1.0 + ring.tau * s)
    return (r2, ell - _log(_reynolds_jet(ref))), (n_tot, d_tot), alpha, cl, cl * s, load
