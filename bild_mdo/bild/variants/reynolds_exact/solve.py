"""Solve the Reynolds-aware exact ideal loading at every station, in the load-path table's model.

Each annulus minimises ``Phi(phi) = F (e - lambda t)`` with its section point
at the least ``cd/cl`` of its path of fixed load
(:mod:`~bild_mdo.bild.variants.local_point.load_path_model`): on a sheet of the
polar's load-path table, a root of ``f = N_tot / D_tot - lambda`` where ``f``
goes from - to +.  Per station, independently of the others and of the other
designs (so a design in a batch is the design alone, bit for bit), compiled
(:mod:`~bild_mdo.bild.variants.reynolds_exact.kernel`):

1. The candidates are the sheets that the station's path meets as a minimum
   of ``cd/cl`` at a first angle, the paper loading's (Eq. (27)) at
   ``cd/cl =`` :data:`START_RATIO`, lowest ``cd/cl`` first.  On each the
   bracketed Newton solver
   (:func:`~bild_mdo.bild.variants.local_point.sheet_solve.sheet_solve`) solves
   ``f = 0`` on ``[phi0, phi(eta2 = 1/2)]`` (``phi0 = atan(V_x / V_theta)``
   unloaded) with the sheet coordinate ``x0`` carried along, beginning, on
   the sheet of the stations inward, where their solutions predict; a root off the
   sheet is no candidate.  The next sheet is tried only where a sheet gave no
   load.
2. A station without a candidate at the first angle is searched on a grid of
   :data:`SEARCH_POINTS` angles.
3. The other sheets next to the solution are candidates too: those its path
   meets there, and those that end at a fold within :data:`FOLD_WINDOW` of its
   coordinate (probed where the coordinate reaches them).  Unless its ``cd/cl``
   where it is met lies more than :data:`NEAR_RATIO` above the solution's, or a
   Newton model of its ``Phi`` shows it cannot reach the best ``Phi``
   (:data:`PRUNE_FACTOR`), each is bracketed from there (probing at
   :data:`PROBE_STEPS`) and solved.  The lowest ``Phi`` of all candidates is
   kept: it is a minimum of ``cd/cl`` along its path there, and the lowest
   one, since ``Phi`` grows with ``cd/cl`` at a fixed inflow angle.  Where two
   are nearly equal the choice switches as the inputs move: a jump in the
   design (``section_branch`` says which sheet each station uses).
4. A station whose best loaded ``Phi`` is not below the unloaded value 0 is
   unloaded (zero chord); where ``f < 0`` up to the top of the bracket it is
   overloaded.  The chosen state gets one more Newton step on ``R2`` in ``x0``.

Limitation: the candidates are stationary points of ``Phi``.  Where a sheet
ends at a fold, ``Phi`` on it can be lowest at that end, which is no root of
``f``; such a value is not taken (a lightly loaded station whose only state
below the unloaded 0 lies there stays unloaded; the brute-force test of
``tests/bild/variants/test_local_stations.py`` meets one such station in 60).

On the levels-10 sweep of the paper (300,000 stations) this finds the same
section points as a search of every station on a grid of 40 angles with every
sheet solved at each (``tests/bild/variants/test_local_stations.py`` checks
the definition by brute force on a sample), with 3.0 evaluations of the residual per
station (2.3 in the first solve, which begins where the stations inward predict; counted on
all 10,000 designs; 4.5 and 2.7 on the smallest reference chord's 1,000, at the lowest Reynolds numbers).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from bild_mdo.bild.variants.local_point.load_path_model import BARRIER, FLOW_ARRAYS

#: Status of a station: loaded, unloaded, overloaded, failed (an input outside its domain, or no converged
#: solve), load Reynolds number beyond the table.
LOADED, UNLOADED, OVERLOADED, FAILED, ABOVE_TABLE = 0, 1, 3, 4, 5
#: ``cd/cl`` of the paper-loading start and of the first load coordinate.
START_RATIO = 0.015
_MAX_ITERATIONS = 100
#: Inflow-angle tolerance (rad) of the solves: Newton's method stops once its predicted error is below it.
ANGLE_TOL = 1e-13
#: Largest last Newton step (rad) of a root (a jump of ``f`` closed by bisection has a large one).
ROOT_STEP = 1e-5
#: Angles of the search for a station without a candidate at its first angle.
SEARCH_POINTS = 24
#: Steps (rad) from a solution to bracket the minimum of another sheet next to it.
PROBE_STEPS = tuple(0.004 * 2.0 ** np.arange(7))
#: A sheet is skipped where its Phi stays above the best Phi by more than this multiple of its Newton model's
#: drop (the model is quadratic in phi).  On the levels-10 sweep (300,000 stations) 15,303 stations took a
#: sheet next to the first solution; on every one its Phi had stayed within 1.008 times its drop (at most 0.88
#: on the levels-3 sweep).
PRUNE_FACTOR = 1.25
#: Ends of sheets (folds) within this distance in ``x0`` of a solution are probed; the probe lies this many
#: cells inside the sheet.
FOLD_WINDOW = 0.05
FOLD_MARGIN = 3
#: A sheet next to the solution is skipped where its cd/cl at the coordinate where it is met exceeds the
#: solution's by more than this factor (``Phi`` grows with ``cd/cl`` at a fixed inflow angle).  Measured on every
#: tenth design of the levels-10 sweep: the sheets that won lay at most 1.045 times above it, and the ratios of the
#: others cluster below 1.05 or lie above 1.35.
NEAR_RATIO = 1.2


class StationSolution(NamedTuple):
    """Per station: the inflow angle, the sheet coordinate ``x0``, the sheet (``label``, -1 unloaded), the
    status (module constants) and, where loaded, the values a station passes on (``[n, 6]``: ``eta2, alpha,
    cl, cd, Re, Re C``; NaN elsewhere)."""

    phi: np.ndarray
    x0: np.ndarray
    label: np.ndarray
    status: np.ndarray
    values: np.ndarray = None


def solve_stations(table, flow, start=None, first_label=None):
    """:class:`StationSolution` of the Reynolds-aware exact loading at every station (flat real inputs).

    ``start, first_label`` (optional): a warm start, e.g. the last pass of a thrust-target solve: on sheet
    ``first_label`` the solve begins at the angle ``start`` (NaN, -1: none).
    """
    from bild_mdo.bild.variants.local_point.kernels import LOSS_CODES, design_starts, table_arrays
    from bild_mdo.bild.variants.reynolds_exact.kernel import solve_all
    from bild_mdo.utils.compiled import run_in_threads

    n = flow.v_theta.size
    if start is None:  # no warm start anywhere: empty arrays
        guess, first = np.empty(0), np.empty(0, dtype=np.int64)
    else:
        guess = np.asarray(start, dtype=float)
        first = np.full(n, -1, dtype=np.int64) if first_label is None else np.asarray(first_label, dtype=np.int64)
        if guess.shape != (n,) or first.shape != (n,):
            raise ValueError(f"solve_stations: start and first_label must have one value per station ({n})")
    out = np.empty((11, n))
    settings = np.array([BARRIER, _MAX_ITERATIONS, ANGLE_TOL, ROOT_STEP, START_RATIO, PRUNE_FACTOR, FOLD_WINDOW,
                         FOLD_MARGIN, NEAR_RATIO])
    frac = np.linspace(0.0, 1.0, SEARCH_POINTS + 2)[1:-1]
    rows, arrays, probes = flow_rows(flow), table_arrays(table), np.array(PROBE_STEPS)
    torque, loss = flow.chord_form == "torque", LOSS_CODES[flow.loss_model]
    run_in_threads(lambda begin, end: solve_all(arrays, rows, flow.num_blades, guess, first, torque, loss, settings,
                                                probes, frac, begin, end, out), design_starts(rows), n)
    return StationSolution(out[0], out[1], out[2].astype(int), out[3].astype(int), out[5:].T)


def flow_rows(flow):
    """The arrays of a :class:`~bild_mdo.bild.variants.local_point.load_path_model.StationFlow` as the rows the
    kernels read (the block the arrays are rows of, where they are: :class:`~bild_mdo.bild.variants.local_point.
    station.LocalStationComp` builds them so)."""
    arrays = [getattr(flow, name) for name in FLOW_ARRAYS]
    base = arrays[0].base
    if (isinstance(base, np.ndarray) and base.dtype == float and base.shape == (len(arrays), arrays[0].size)
            and base.flags.c_contiguous and all(a.base is base and a.dtype == float for a in arrays)
            and all(np.shares_memory(a, base[k]) and a.ctypes.data == base[k].ctypes.data
                    for k, a in enumerate(arrays))):
        return base
    return np.stack([np.asarray(a, dtype=float) for a in arrays])
