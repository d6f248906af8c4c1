"""The paper's ideal loading with each station's own section point, solved per station on the load-path table.

The paper's loading (Eq. (22), the quartic (27)) gives a station's annular
efficiency ``eta2`` from ``lambda`` and its profile-loss ratio ``s = cd/cl``;
with the local section point ``s`` is that of the least ``cd/cl`` along the
station's own path of fixed load, which follows from the load.  On a sheet of
the polar's load-path table (:mod:`bild_mdo.airfoil.load_path_table`) at the
coordinate ``x0`` (``s = s(x0)``) the station's loading is::

    eta2 = eta2(lambda, V_x, V_theta, s)            the quartic (27),
    u_axial from Eq. (26), w = eta2 V_theta,  phi = atan2(u_axial, w),

and its blade element carries that load where (as for the exact loading,
:mod:`~bild_mdo.bild.variants.local_point.load_path_model`)::

    R(x0) = x_m(phi, s) - x0 - ln(1 + tau(phi) s) = 0.

That is the state of the component (one residual ``R`` in ``x0``, whose jets
give the partials).  The solve (:func:`solve_stations`, compiled:
:mod:`~bild_mdo.bild.variants.local_paper.kernel`) works in the inflow angle
instead, as the exact loading's does: on the BEM curve at ``(phi, s)`` the
annulus has ``eta2 = w / V_theta`` and ``u_axial = A sin(phi)``, which satisfy
Eq. (25), so the paper's loading is the root of the quartic's physical factor
``h = N - u_axial M`` (:mod:`bild_mdo.bild.variants.paper.quartic`) along ``R = 0``, bracketed
between the unloaded angle and ``eta2 = 1/2``.  It is solved on each sheet that
the station's path meets as a minimum at a first angle (the paper loading at a
typical ``cd/cl``); of the solutions the one with the least ``cd/cl`` is kept,
and it must be the least ``cd/cl`` of every minimum that its own path meets
(else the station is solved again on that lower sheet, :data:`SWITCHES`
times at most): the section point of the station's own load.  Where two
sheets are nearly equal the choice can switch as the inputs move
(``section_branch``).  A station that the quartic leaves unloaded (hover,
``lambda <= V_theta s / 2`` at every ``s`` the path can reach) has no section
point: zero chord.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from bild_mdo.bild.variants.paper.eta2 import solve_eta2
from bild_mdo.bild.variants.paper.quartic import quartic, quartic_and_partials
from bild_mdo.bild.variants.local_point.load_path_model import BARRIER, _curve_jets, _log, annulus_jets
from bild_mdo.bild.variants.reynolds_exact.solve import ANGLE_TOL, ROOT_STEP, flow_rows
from bild_mdo.utils.jet import Jet, variable

#: Status of a station: loaded, unloaded (no load, or no section point), failed (an input outside its domain),
#: load Reynolds number beyond the table.
LOADED, UNLOADED, FAILED, ABOVE_TABLE = 0, 1, 4, 5
#: ``cd/cl`` of the first load, and the lowest ``cd/cl`` tried where the quartic leaves a hover station unloaded.
START_RATIO, LOWEST_RATIO = 0.015, 0.002
_MAX_ITERATIONS = 100
#: Times a station is solved again on a lower sheet that its own path meets.
SWITCHES = 3


class PaperSolution(NamedTuple):
    """Per station: the sheet coordinate ``x0``, the sheet ``label`` (-1 unloaded), the status and, where
    loaded, the values a station passes on (``[n, 6]``: ``eta2, alpha, cl, cd, Re, Re C``; NaN elsewhere)."""

    x0: np.ndarray
    label: np.ndarray
    status: np.ndarray
    values: np.ndarray = None


def _sqrt(jet):
    value = np.sqrt(jet.v)
    return Jet(value, {k: 0.5 * x / value for k, x in jet.d.items()})


def _atan2(num, den):
    """``atan2(num, den)`` for ``den > 0`` (complex-safe: ``atan(num / den)``)."""
    value = np.arctan(num.v / den.v)
    r2 = num.v * num.v + den.v * den.v
    keys = set(num.d) | set(den.d)
    return Jet(value, {k: (den.v * num.partial(k) - num.v * den.partial(k)) / r2 for k in keys})


class PaperJets(NamedTuple):
    """Jets of a station of the local point with the paper's loading: the residual ``R``, ``eta2``, ``phi``, the
    state ``x0``, ``s`` and the annulus (:class:`~bild_mdo.bild.variants.local_point.load_path_model.AnnulusJets`)."""

    r: Jet
    eta2: Jet
    phi: Jet
    x0: Jet
    s: Jet
    ring: object


def loading(flow, s, seed=True):
    """``(eta2, u_axial, phi)`` jets of the paper's loading at the ratio jet ``s`` (real ``s.v``).

    ``eta2`` from the quartic (27) by :func:`~bild_mdo.bild.variants.paper.eta2.solve_eta2`, its partials by the
    implicit-function theorem; complex inputs are carried by one Newton update in complex arithmetic.
    """
    var = variable if seed else (lambda value, name: Jet(value, {}))
    vx, vt, lam = var(flow.v_axial, "v_axial"), var(flow.v_theta, "v_theta"), var(flow.lam, "lam")
    real = [np.real(x) for x in (flow.v_axial, flow.v_theta, flow.lam)]
    eta = solve_eta2(*real, 1.0, np.real(s.v))
    value, partials = quartic_and_partials(eta, *real, np.real(s.v))
    slope = partials["eta"]
    if np.iscomplexobj(flow.v_axial) or np.iscomplexobj(s.v):
        eta = eta - quartic(eta, flow.v_axial, flow.v_theta, flow.lam, s.v) / slope
    d = {}
    for jet, name in ((vx, "v_axial"), (vt, "v_theta"), (lam, "lam"), (s, "drag_to_lift")):
        for k, x in jet.d.items():
            d[k] = d.get(k, 0.0) - partials[name] * x / slope
    eta_jet = Jet(eta, d)
    b = 0.5 * (vx - vt * s)
    c = eta_jet * vt * (vt * (1.0 - eta_jet) + vx * s)
    root = _sqrt(b * b + c)
    positive = np.real(b.v) >= 0.0
    u = (b + root) if np.all(positive) else _select(positive, b + root, c / (root - b))
    return eta_jet, u, _atan2(u, eta_jet * vt)


def _select(mask, a, b):
    keys = set(a.d) | set(b.d)
    return Jet(np.where(mask, a.v, b.v), {k: np.where(mask, a.partial(k), b.partial(k)) for k in keys})


def paper_jets(table, flow, x0, label, seed=True):
    """:class:`PaperJets` at the coordinates ``x0`` on sheets ``label`` (``seed``: partials with respect to the
    inputs of :class:`~bild_mdo.bild.variants.local_point.load_path_model.StationFlow` too, else ``x0`` only)."""
    xj = variable(x0, "x0")
    s, _ = _curve_jets(table.curve(x0, label, ("s",))["s"], xj)
    eta, _, phi = loading(flow, s, seed=seed)
    ring = annulus_jets(flow, phi, s, seed=seed)
    return PaperJets(ring.x - xj - _log(1.0 + ring.tau * s), eta, phi, xj, s, ring)


def solve_stations(table, flow):
    """:class:`PaperSolution` at every station (flat real inputs; module docstring)."""
    from bild_mdo.bild.variants.local_paper.kernel import solve_all
    from bild_mdo.bild.variants.local_point.kernels import LOSS_CODES, design_starts, table_arrays
    from bild_mdo.utils.compiled import run_in_threads

    out = np.empty((10, flow.r.size))
    settings = np.array([BARRIER, _MAX_ITERATIONS, ANGLE_TOL, ROOT_STEP, START_RATIO, LOWEST_RATIO, SWITCHES])
    rows, arrays = flow_rows(flow), table_arrays(table)
    torque, loss = flow.chord_form == "torque", LOSS_CODES[flow.loss_model]
    run_in_threads(lambda begin, end: solve_all(arrays, rows, flow.num_blades, torque, loss, settings, begin, end,
                                                out), design_starts(rows), flow.r.size)
    return PaperSolution(out[1], out[2].astype(int), out[3].astype(int), out[4:].T)
