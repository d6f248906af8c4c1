"""The curves of stationary ``cd/cl`` along paths of fixed load, solved once per polar and interpolated.

The local-section-point variants of BILD need, at every station and every
trial inflow angle, the section point of least ``s = cd/cl`` along the
station's path of fixed load.  The stationary points of ``s`` along such
paths lie on curves that depend on the polar alone, not on the inflow angle
or the chord form (:mod:`bild_mdo.airfoil.load_path`), so
:class:`LoadPathTable` solves them once per polar on a uniform grid of the
load coordinate ``x0 = ln Re + ln cl`` (spacing :data:`X_STEP`) and represents
each curve (*sheet*) by cubic Hermite interpolants of the exact node values
and slopes ``d/dx0`` of ``s``, ``ln Re`` and ``alpha``.  A path with ``tau``
and load coordinate ``x = ln(Q / p)`` meets a sheet where ``x0 + ln(1 + tau
s(x0)) = x``.  The interpolants are the model the BILD components use: their
values and derivatives (to the second) are exact for it, and they are within
about 1e-9 of the exact curves in ``s`` (relative; with the built-in NACA 4412
1e-8 below Re = 5e4 and up to 1e-6 next to the join of its two splines at 5e4;
``tests/airfoil/test_load_path.py`` measures it).

Sheets.  At each node all stationary points in the polar's scan range are
kept (sorted by angle of attack); two of neighbouring nodes are one sheet
when each is the other's Hermite continuation (within :data:`LINK_TOL`) and
both are of one kind (a minimum or a maximum along the path at ``tau = 0``,
the sign of ``det``).  A sheet therefore ends a node before a fold, where a
minimum turns into a maximum.  Sheets are numbered by their angle of attack
(sheet 0 the lowest), so that a caller can report which one a station uses.

Building evaluates the polar once on a grid of ``(alpha, ln Re)``
(:data:`SCAN_STEP`, :data:`ELL_STEP`), interpolates ``H`` along every path to
bracket its roots, and refines every bracket by Newton's method on the polar
itself (:func:`~bild_mdo.airfoil.load_path.refine`): about a second.  The
table is kept per polar object and, for polars with a ``state()``
(:class:`~bild_mdo.airfoil.surrogate.TabulatedPolar`), on disk in the polar
cache (:mod:`bild_mdo.airfoil.cache`).
"""
from __future__ import annotations

import warnings
import weakref
from typing import NamedTuple

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from bild_mdo.airfoil import cache
from bild_mdo.airfoil.load_path import LIFT_FLOOR, path_point, refine, stationary_value
from bild_mdo.airfoil.max_lift_to_drag import DEFAULT_SCAN_RANGE

#: Version of the table construction, part of its cache key.
TABLE_VERSION = 1
#: Spacing of the nodes in x0 = ln Re + ln cl.
X_STEP = 0.001
#: Load coordinates of the grid: from ln(1e3) (next to no load; BILD leaves lighter annuli unloaded) to
#: :data:`REYNOLDS_SPAN` times the top of the polar's data (at least 1e7; 1e9 for a polar without a data range).
X_LOW = np.log(1e3)
REYNOLDS_SPAN = 20.0
#: The scan that brackets the roots: angle step (rad) and ln Re step of the polar's grid.
SCAN_STEP = np.radians(0.25)
ELL_STEP = 0.02
#: Stationary points kept per node (sorted by angle of attack).
SLOTS = 6
#: Largest mismatch of a neighbour's value with the Hermite continuation for two points to be one sheet.
LINK_TOL = 1e-3
#: Cells left out at a sheet's end inside the grid (a fold; module docstring).
FOLD_TRIM = 2
#: The interpolated quantities, in the order of :attr:`LoadPathTable.coef`.
QUANTITIES = ("s", "ell", "alpha")

# Cubic Hermite basis on [0, 1]: coefficients of u**j from (f0, f1, h f0', h f1').
_HERMITE = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [-3.0, 3.0, -2.0, -1.0], [2.0, -2.0, 1.0, 1.0]])

_TABLES = {}


def data_reynolds_range(polar):
    """``(low, high)`` Reynolds numbers of a polar's data, or None where it has none."""
    reynolds = getattr(polar, "reynolds", None)
    if isinstance(reynolds, np.ndarray) and reynolds.size:
        return float(reynolds.min()), float(reynolds.max())
    return None


class CurveValues(NamedTuple):
    """A quantity of a sheet at query points: value, ``d/dx0``, ``d2/dx0**2`` (NaN off the sheet) and ``d3/dx0**3``
    with the local coordinate ``u`` in the cell (with ``third=True``: a cubic's Taylor series moves the point
    exactly within its cell)."""

    f: np.ndarray
    f1: np.ndarray
    f2: np.ndarray
    f3: object = None
    u: object = None


class SheetIndex(NamedTuple):
    """Sheets of query points prepared for lookups: ``label`` (-1 none), the first and one past the last cell
    covered, and the offset of the coefficient row from the cell."""

    label: np.ndarray
    low: np.ndarray
    high: np.ndarray
    offset: np.ndarray


class LoadPathTable:
    """Sheets of stationary ``cd/cl`` along paths of fixed load of one polar (module docstring).

    Attributes
    ----------
    x_first, nx : float, int
        First node and number of nodes (spacing :data:`X_STEP`).
    arrays : dict of str to ndarray
        Node data ``[nx, SLOTS]``: ``s, ell, alpha``, their slopes (suffix ``1``), ``det`` and ``label``.
    first, last : ndarray of int
        First and last node of every sheet; ``kind`` +1 for a minimum along the path at ``tau = 0``, -1 a
        maximum.
    """

    def __init__(self, polar, *, arrays=None):
        self.name = getattr(polar, "name", type(polar).__name__)
        if arrays is None:
            arrays = _build(polar)
        self.arrays = arrays
        grid = arrays["grid"]
        self.x_first, self.nx = float(grid[0]), int(grid[1])
        self.x_last = self.x_first + (self.nx - 1) * X_STEP
        label = arrays["label"]
        self.num_sheets = int(label.max()) + 1
        k, m = np.nonzero(label >= 0)
        lab = label[k, m]
        self.first = np.full(self.num_sheets, self.nx, dtype=np.int64)
        self.last = np.full(self.num_sheets, -1, dtype=np.int64)
        np.minimum.at(self.first, lab, k)
        np.maximum.at(self.last, lab, k)
        #: Slot of every sheet at every node of its range ([nx, sheets] would be large: per sheet offsets).
        sizes = self.last - self.first + 1
        self.row0 = np.concatenate(([0], np.cumsum(sizes)[:-1])).astype(np.int64)
        slot = np.full(int(sizes.sum()), -1, dtype=np.int64)
        slot[self.row0[lab] + k - self.first[lab]] = m
        self.slot = slot
        self.kind = np.zeros(self.num_sheets)
        self.kind[lab] = np.sign(arrays["det"][k, m])
        #: Cells of every sheet that the lookups use: :data:`FOLD_TRIM` fewer at an end inside the grid (a fold,
        #: where the curve's slopes grow without bound and the interpolant loses accuracy).
        self.cover_first = np.where(self.first > 0, self.first + FOLD_TRIM, self.first)
        self.cover_last = np.where(self.last < self.nx - 1, self.last - FOLD_TRIM, self.last)
        self.coef = self._coefficients()

    def _coefficients(self):
        """Cubic coefficients ``[3, 4, rows]`` of :data:`QUANTITIES` on every cell of every sheet (row of node i of
        sheet k: ``row0[k] + i - first[k]``; the last node's row is unused)."""
        rows = self.slot.size
        node = np.empty(rows, dtype=np.int64)
        for k in range(self.num_sheets):
            node[self.row0[k]:self.row0[k] + self.last[k] - self.first[k] + 1] = np.arange(self.first[k],
                                                                                            self.last[k] + 1)
        nxt = np.minimum(np.arange(rows) + 1, rows - 1)
        valid = np.concatenate([np.arange(self.last[k] - self.first[k]) + self.row0[k] for k in range(self.num_sheets)])
        coef = np.full((len(QUANTITIES), 4, rows), np.nan)
        m0, m1 = self.slot[valid], self.slot[nxt[valid]]
        n0, n1 = node[valid], node[valid] + 1
        for q, name in enumerate(QUANTITIES):
            f, d = self.arrays[name], self.arrays[f"{name}1"]
            data = np.stack([f[n0, m0], f[n1, m1], X_STEP * d[n0, m0], X_STEP * d[n1, m1]])
            coef[q][:, valid] = _HERMITE @ data
        return coef

    # ---------------------------------------------------------------- lookups
    def sheets(self, label):
        """:class:`SheetIndex` of sheets ``label`` (-1 none): for repeated lookups on fixed sheets."""
        if isinstance(label, SheetIndex):
            return label
        label = np.asarray(label)
        safe = np.maximum(label, 0)
        none = label < 0
        low = np.where(none, 1, self.cover_first.take(safe))
        high = np.where(none, 0, self.cover_last.take(safe))
        return SheetIndex(label, low, high, self.row0.take(safe) - self.first.take(safe))

    def locate(self, x0, label):
        """Coefficient row and local coordinate ``u`` of sheet ``label`` (or a :class:`SheetIndex`) at ``x0``, and
        where the sheet covers it (real or complex ``x0``: the cell from its real part; NaN is never covered)."""
        index = label if isinstance(label, SheetIndex) else self.sheets(label)
        t = (x0 - self.x_first) * (1.0 / X_STEP)
        real = t.real if np.iscomplexobj(t) else t
        # Cells from a clipped copy (a NaN or far coordinate is outside every sheet's cover anyway; a sheet
        # without cover, label -1, has low > high).
        i = np.fmin(np.fmax(real, -1.0), self.nx).astype(np.int64)
        ok = (i >= index.low) & (i < index.high)
        row = index.offset + i
        if not ok.all():
            row = np.where(ok, row, 0)
        return row, t - i, ok

    def curve(self, x0, label, quantities=QUANTITIES, third=False):
        """:class:`CurveValues` of ``quantities`` on sheets ``label`` at ``x0``: a dict (NaN off the sheet)."""
        row, u, ok = self.locate(x0, label)
        every = ok.all()
        out = {}
        for name in quantities:
            c = self.coef[QUANTITIES.index(name)]
            c0, c1, c2, c3 = c[0].take(row), c[1].take(row), c[2].take(row), c[3].take(row)
            f = c0 + u * (c1 + u * (c2 + u * c3))
            f1 = (c1 + u * (2.0 * c2 + 3.0 * u * c3)) * (1.0 / X_STEP)
            f2 = (2.0 * c2 + 6.0 * u * c3) * (1.0 / X_STEP ** 2)
            if not every:
                f, f1, f2 = (np.where(ok, g, np.nan) for g in (f, f1, f2))
            out[name] = CurveValues(f, f1, f2, c3 * (6.0 / X_STEP ** 3), u) if third else CurveValues(f, f1, f2)
        return out

    def labels_near(self, x0):
        """``[n, SLOTS]`` sheets (-1 none) whose cell holds ``x0`` (the sheets a path near ``x0`` can meet)."""
        real = np.asarray(np.real(x0))
        i = np.floor((real - self.x_first) / X_STEP)
        inside = np.isfinite(i) & (i >= 0) & (i <= self.nx - 2)
        i = np.where(inside, i, 0).astype(np.int64)
        labels = self.arrays["label"][i]
        safe = np.maximum(labels, 0)
        ok = (labels >= 0) & (i[:, None] >= self.cover_first[safe]) & (i[:, None] < self.cover_last[safe]) & inside[:, None]
        return np.where(ok, labels, -1)

    def meet(self, x, tau, label, passes=3):
        """``x0`` where a path ``(x, tau)`` meets sheet ``label`` (``x0 + ln(1 + tau s(x0)) = x``, Newton's method
        from ``x0 = x``), and whether the point is a minimum of ``cd/cl`` along that path; NaN where it does not
        meet the sheet nearby."""
        x0 = np.array(x, dtype=float)
        with np.errstate(invalid="ignore", divide="ignore"):
            for _ in range(passes):
                s = self.curve(x0, label, ("s",))["s"]
                ratio = 1.0 + tau * s.f
                step = (x0 + np.log(ratio) - x) / (1.0 + tau * s.f1 / ratio)
                x0 = x0 - np.minimum(np.maximum(step, -0.5), 0.5)
            s = self.curve(x0, label, ("s",))["s"]
            ratio = 1.0 + tau * s.f
            residual = x0 + np.log(ratio) - x
            minimum = self.kind[np.maximum(getattr(label, 'label', label), 0)] * (1.0 + tau * s.f1 / ratio) > 0.0
            good = (np.abs(residual) < 1e-9) & (ratio > 0.0)
        return np.where(good, x0, np.nan), good & minimum

    def node_slots(self):
        """``[nx, 6, SLOTS]``: per node and slot the sheet (-1 none), ``s``, ``ds/dx0``, the sheet's kind and the first
        and one past the last cell it covers (empty for none), for quick lookups of the sheets near a point."""
        if not hasattr(self, "_slots"):
            label = self.arrays["label"]
            safe = np.maximum(label, 0)
            none = label < 0
            self._slots = np.stack((label.astype(float), self.arrays["s"], self.arrays["s1"],
                                    np.where(none, 0.0, self.kind[safe]), np.where(none, 1.0, self.cover_first[safe]),
                                    np.where(none, 0.0, self.cover_last[safe])), axis=1)
        return self._slots

    def sheet_ends(self):
        """``(x0, label, inward)`` of every covered end of a sheet inside the grid (a fold), sorted by ``x0``;
        ``inward`` is +1 where the sheet lies at larger ``x0``."""
        if not hasattr(self, "_ends"):
            labels = np.arange(self.num_sheets)
            born, dies = self.first > 0, self.last < self.nx - 1
            cells = np.concatenate((self.cover_first[born], self.cover_last[dies]))
            order = np.argsort(cells, kind="stable")
            self._ends = (self.x_first + X_STEP * cells[order],
                          np.concatenate((labels[born], labels[dies]))[order],
                          np.concatenate((np.ones(born.sum()), -np.ones(dies.sum())))[order])
        return self._ends

    def reynolds_crossings(self, ell):
        """Where a sheet's chord Reynolds number is ``exp(ell)``: every ``(query, label, x0)`` (linear interpolation
        of the nodes on the runs of every sheet where ``ln Re`` is monotone; a start for Newton's method)."""
        ell = np.asarray(ell, dtype=float)
        if not hasattr(self, "_runs"):
            self._runs = self._reynolds_runs()
        found = [[], [], []]
        for label, xs, ells in self._runs:
            inside = (ell >= ells.min()) & (ell <= ells.max())
            at = np.flatnonzero(inside)
            if at.size:
                found[0].append(at)
                found[1].append(np.full(at.size, label))
                order = slice(None) if ells[-1] > ells[0] else slice(None, None, -1)
                found[2].append(np.interp(ell[at], ells[order], xs[order]))
        if not found[0]:
            empty = np.zeros(0, dtype=np.int64)
            return empty, empty, np.zeros(0)
        return tuple(np.concatenate(part) for part in found)

    def _reynolds_runs(self):
        runs = []
        for k in range(self.num_sheets):
            i = np.arange(self.first[k], self.last[k] + 1)
            ells = self.arrays["ell"][i, self.slot[self.row0[k] + i - self.first[k]]]
            rising = np.diff(ells) > 0.0
            breaks = np.flatnonzero(rising[1:] != rising[:-1]) + 1
            for run in np.split(np.arange(i.size), breaks):
                run = np.arange(run[0], min(run[-1] + 2, i.size))
                if run.size >= 2:
                    runs.append((k, self.x_first + X_STEP * i[run], ells[run]))
        return runs


# ----------------------------------------------------------------------------- building
def _grid(polar):
    data = data_reynolds_range(polar)
    top = max(1e7, REYNOLDS_SPAN * data[1]) if data else 1e9
    return X_LOW, int(np.ceil((np.log(top) - X_LOW) / X_STEP)) + 1


def _build(polar):
    """Node arrays of the table (module docstring)."""
    x_first, nx = _grid(polar)
    x_nodes = x_first + X_STEP * np.arange(nx)
    low, high = getattr(polar, "alpha_scan_range", DEFAULT_SCAN_RANGE)
    alphas = np.linspace(low, high, max(int(np.ceil((high - low) / SCAN_STEP)) + 1, 3))
    # Paths need Re = exp(x0) / cl with cl between LIFT_FLOOR and about 2.5.
    ells = np.arange(x_nodes[0] - 1.5, x_nodes[-1] + np.log(1.0 / LIFT_FLOOR) + 0.5, ELL_STEP)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        aa, ll = np.meshgrid(alphas, ells, indexing="ij")
        v = polar.evaluate(aa.ravel(), np.exp(ll.ravel()))
        candidates = _scan(v, alphas, ells, x_nodes)
        points = _refine_candidates(polar, candidates, alphas, x_nodes)
    arrays = _nodes(points, nx)
    arrays["grid"] = np.array([x_first, nx], dtype=float)
    return arrays


def _scan(values, alphas, ells, x_nodes):
    """Brackets ``(a, k, alpha0, ell0)``: ``H`` changes sign between scan angles ``a, a + 1`` on the path of
    ``x_k`` (``tau = 0``), with a false-position start."""
    na, nl = alphas.size, ells.size
    v = type(values)(*(f.reshape(na, nl) for f in values))
    re = np.exp(ells)[None, :]
    ok = (v.cl > LIFT_FLOOR) & (v.cd > 0.0) & (v.cl + re * v.dcl_dre > 0.0)
    h = stationary_value(v, re)
    with np.errstate(invalid="ignore", divide="ignore"):
        big_x = ells[None, :] + np.log(np.where(ok, v.cl, 1.0))
    h_path = np.full((na, x_nodes.size), np.nan)
    l_path = np.full((na, x_nodes.size), np.nan)
    for a in range(na):
        good = np.flatnonzero(ok[a])
        if good.size < 2:
            continue
        xs = big_x[a, good]
        run = np.concatenate(([True], (np.diff(good) == 1) & (np.diff(xs) > 0.0)))
        piece = max(np.split(np.arange(good.size), np.flatnonzero(~run)), key=len)
        if piece.size < 2:
            continue
        sel = good[piece]
        h_path[a] = np.interp(x_nodes, big_x[a, sel], h[a, sel], left=np.nan, right=np.nan)
        l_path[a] = np.interp(x_nodes, big_x[a, sel], ells[sel], left=np.nan, right=np.nan)
    h0, h1 = h_path[:-1], h_path[1:]
    with np.errstate(invalid="ignore"):
        a_idx, k_idx = np.nonzero(np.sign(h0) * np.sign(h1) < 0.0)
    frac = h0[a_idx, k_idx] / (h0[a_idx, k_idx] - h1[a_idx, k_idx])
    alpha0 = alphas[a_idx] + frac * (alphas[a_idx + 1] - alphas[a_idx])
    ell0 = l_path[a_idx, k_idx] + frac * (l_path[a_idx + 1, k_idx] - l_path[a_idx, k_idx])
    return a_idx, k_idx, alpha0, ell0


def _refine_candidates(polar, candidates, alphas, x_nodes):
    """Exact stationary points from the scan's brackets, with their slopes (duplicates removed)."""
    a, k, alpha0, ell0 = candidates
    step = alphas[1] - alphas[0]
    bounds = (alphas[a] - step, alphas[a + 1] + step)
    alpha, ell, ok = refine(polar, x_nodes[k], alpha0, ell0, alpha_bounds=bounds)
    point = path_point(polar, alpha[ok], ell[ok])
    keep = np.isfinite(point.alpha1) & np.isfinite(point.ell1) & np.isfinite(point.s1) & (point.det != 0.0)
    fields = {name: getattr(point, name)[keep] for name in point._fields}
    fields["k"] = k[ok][keep]
    order = np.lexsort((fields["alpha"], fields["k"]))
    fields = {name: value[order] for name, value in fields.items()}
    same = np.concatenate(([False], (np.diff(fields["k"]) == 0) & (np.abs(np.diff(fields["alpha"])) < 1e-9)))
    return {name: value[~same] for name, value in fields.items()}


def _nodes(points, nx):
    """Slot arrays ``[nx, SLOTS]`` (sorted by alpha within a node), links between nodes and sheet labels."""
    k = points["k"]
    first = np.searchsorted(k, k)
    rank = np.arange(k.size) - first
    keep = rank < SLOTS
    arrays = {}
    for name in ("s", "ell", "alpha", "s1", "ell1", "alpha1", "det"):
        arr = np.full((nx, SLOTS), np.nan)
        arr[k[keep], rank[keep]] = points[name][keep]
        arrays[name] = arr
    present = np.isfinite(arrays["s"])
    mismatch = np.zeros((nx - 1, SLOTS, SLOTS))
    for name in QUANTITIES:
        f0, f1 = arrays[name][:-1, :, None], arrays[name][1:, None, :]
        d0, d1 = arrays[f"{name}1"][:-1, :, None], arrays[f"{name}1"][1:, None, :]
        gap = np.abs(f1 - f0 - 0.5 * X_STEP * (d0 + d1))
        scale = np.maximum(np.abs(f0), 1e-6) if name == "s" else 1.0
        mismatch = np.maximum(mismatch, np.where(np.isfinite(gap), gap / scale, np.inf))
    same_kind = np.sign(arrays["det"][:-1, :, None]) == np.sign(arrays["det"][1:, None, :])
    mismatch = np.where(present[:-1, :, None] & present[1:, None, :] & same_kind, mismatch, np.inf)
    best = np.argmin(mismatch, axis=-1)
    ok = np.take_along_axis(mismatch, best[..., None], axis=-1)[..., 0] <= LINK_TOL
    back = np.argmin(mismatch, axis=-2)
    ok &= np.take_along_axis(back, best, axis=-1) == np.arange(SLOTS)
    i, m = np.nonzero(ok)
    flat = np.arange(nx * SLOTS).reshape(nx, SLOTS)
    rows, cols = flat[i, m], flat[i + 1, best[i, m]]
    graph = coo_matrix((np.ones(rows.size), (rows, cols)), shape=(flat.size, flat.size))
    _, component = connected_components(graph, directed=False)
    component = component.reshape(nx, SLOTS)
    # Sheets of at least two nodes, numbered by angle of attack (the median over their nodes).
    comp = np.where(present, component, -1)
    ids, counts = np.unique(comp[comp >= 0], return_counts=True)
    ids = ids[counts >= 2]
    median = np.array([np.median(arrays["alpha"][comp == c]) for c in ids])
    number = np.full(flat.size, -1)
    number[ids[np.argsort(median, kind="stable")]] = np.arange(ids.size)
    arrays["label"] = np.where(present, number[np.maximum(comp, 0)], -1)
    return arrays


# ------------------------------------------------------------------------------ lookup
def _cache_key(polar):
    state = polar.state()
    arrays = [state[name] for name in sorted(state)]
    settings = (TABLE_VERSION, X_STEP, X_LOW, REYNOLDS_SPAN, SCAN_STEP, ELL_STEP, SLOTS, LINK_TOL, LIFT_FLOOR)
    return cache.hash_key("LoadPathTable", settings, arrays)


def load_path_table(polar):
    """The :class:`LoadPathTable` of ``polar``: kept per polar object, and on disk where the polar has a state."""
    key = id(polar)
    entry = _TABLES.get(key)
    if entry is not None and entry[0]() is polar:
        return entry[1]
    table = None
    disk_key = None
    if hasattr(polar, "state"):
        disk_key = _cache_key(polar)
        stored = cache.load_arrays("load-path", polar.name, disk_key)
        if stored is not None and "grid" in stored:
            table = LoadPathTable(polar, arrays=dict(stored))
    if table is None:
        table = LoadPathTable(polar)
        if disk_key is not None:
            cache.store_arrays("load-path", polar.name, disk_key, table.arrays)
    try:
        ref = weakref.ref(polar, lambda _, key=key: _TABLES.pop(key, None))
    except TypeError:
        return table
    _TABLES[key] = (ref, table)
    return table
