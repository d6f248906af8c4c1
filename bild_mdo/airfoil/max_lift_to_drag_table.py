"""The maximum-L/D point of a polar at many Reynolds numbers, warm-started from a per-polar table.

:func:`~bild_mdo.airfoil.max_lift_to_drag.max_lift_to_drag` brackets the
maximum by a scan of ~140 angles per Reynolds number before its Newton solve:
most of the cost of BILD's reference airfoil when it runs once per design.
The maximum moves smoothly with ``Re``, so this module solves it once per
polar on a grid of ``ln Re`` (spacing :data:`LOG_RE_STEP`, nodes computed when
a query first needs them, by that exact solver) and starts the same exact
Newton iteration on ``g = cl_alpha cd - cl cd_alpha = 0`` from the cubic
Hermite interpolant of the nodes (values and exact slopes ``dalpha*/dln Re``).
The interpolant is within 1e-6 rad of the root (typically 1e-11 rad), so one
or two Newton passes converge; the point returned is the exact root of the
polar to round-off, with the same implicit-function derivatives
(:func:`~bild_mdo.airfoil.max_lift_to_drag.point_from_polar_values`), not an
interpolated value.

The first pass needs only the polar's first derivatives: its Newton step
divides by the nodes' curvature ``dg/dalpha`` interpolated linearly in
``ln Re`` (relative error below 2e-3 at 99 % of Reynolds numbers, 1.3e-2 at
most, on the built-in NACA 4412), and is applied to first order where it is
below ``STEP_TOL / 2`` (about 9 queries in 10), so the point differs from
the exact step's by that relative error times ``STEP_TOL / 2``: below
1e-12 rad (and below ``STEP_TOL / 2`` whatever the error); the other queries
continue with exact passes.  With ``derivatives=False`` the
second derivatives at the point, which only the Reynolds derivatives need,
come with the first pass where the polar shares their evaluation with the
values (:meth:`~bild_mdo.airfoil.polar.Polar.evaluate_with_second_derivatives`:
one spline evaluation of a tabulated polar, about a third dearer than the values
alone, against a second call of the same cost as the first) and are evaluated
when first used otherwise (:class:`TabulatedPoint`): a run of BILD without
derivatives evaluates the polar once per design.

Safeguards: a query falls back to the scan of the exact solver when its grid
interval is not smooth (a jump of the node values away from their slopes: the
largest-L/D maximum switches between two local maxima there), when a node
could not be solved, or when the warm-started iteration does not converge in
:data:`MAX_PASSES` passes to a maximum of ``cl/cd`` with ``cl > 0`` near the
interpolated angle.  Polars that vary with Mach number or along the span use
the exact solver directly.

The table is built from the polar's own ``evaluate``/``second_derivatives``
(through the exact solver) and kept per polar object in a module-level cache
that forgets a polar when it is garbage-collected.  The node solves run with
the polar's warnings silenced (a node just outside a polar's Reynolds range
must not warn about Reynolds numbers nobody asked for); each query evaluates
the polar at its own Reynolds numbers first, so those warnings are the same
as without the table.
"""
from __future__ import annotations

import warnings
import weakref

import numpy as np

from bild_mdo.airfoil.max_lift_to_drag import max_lift_to_drag, point_from_polar_values

#: Spacing of the table nodes in ``ln Re`` (1 %): the Hermite interpolant is then within ~1e-11 rad of the
#: root for most Reynolds numbers of the built-in polars (1e-6 rad next to their spline knots).
LOG_RE_STEP = 0.01
#: Nodes solved together when a query needs one of them (a factor of 1.9 in Re).
BLOCK = 64
#: Newton passes from the interpolated angle before a query falls back to the exact solver's scan.
MAX_PASSES = 4
#: A Newton correction below this (rad) ends the iteration; it is applied (error O(step**2)).
STEP_TOL = 1e-10
#: Largest distance (rad) of the root from the interpolated angle, and largest mismatch of a node with its
#: neighbour's slope (one local maximum throughout the interval, not a switch between two).
TRUST = 1e-3

_TABLES = {}


class _Table:
    """Nodes ``k`` (``ln Re = k LOG_RE_STEP``) from ``first``: angle, slope ``dalpha*/dln Re``, curvature
    ``dg/dalpha`` of ``g = cl_alpha cd - cl cd_alpha`` at the root, known, failed."""

    def __init__(self):
        self.first = 0
        self.alpha = np.zeros(0)
        self.slope = np.zeros(0)
        self.curvature = np.zeros(0)
        self.known = np.zeros(0, dtype=bool)
        self.failed = np.zeros(0, dtype=bool)

    def cover(self, k_lo, k_hi):
        """Grow the arrays to hold nodes ``k_lo ... k_hi``."""
        if self.alpha.size and self.first <= k_lo and k_hi < self.first + self.alpha.size:
            return
        first = min(k_lo, self.first) if self.alpha.size else k_lo
        last = max(k_hi, self.first + self.alpha.size - 1) if self.alpha.size else k_hi
        size = last - first + 1
        offset = self.first - first
        for name, dtype in (("alpha", float), ("slope", float), ("curvature", float), ("known", bool),
                            ("failed", bool)):
            grown = np.zeros(size, dtype=dtype)
            old = getattr(self, name)
            grown[offset:offset + old.size] = old
            setattr(self, name, grown)
        self.first = first


def _table_of(polar):
    """The table of ``polar`` (created empty at first use), or None if the polar cannot be weakly referenced."""
    key = id(polar)
    entry = _TABLES.get(key)
    if entry is not None and entry[0]() is polar:
        return entry[1]
    try:
        ref = weakref.ref(polar, lambda _, key=key: _TABLES.pop(key, None))
    except TypeError:
        return None
    table = _Table()
    _TABLES[key] = (ref, table)
    return table


def _fill(polar, table, nodes):
    """Solve the missing nodes of every block of :data:`BLOCK` nodes that holds one of ``nodes``, exactly.

    Whole blocks: one vectorised solve costs about the same for one node as for a block, and the
    next designs nearby need no solve.  Nodes whose solve fails are marked failed.
    """
    blocks = np.unique(nodes // BLOCK)
    nodes = (blocks[:, None] * BLOCK + np.arange(BLOCK)).ravel()
    table.cover(int(nodes.min()), int(nodes.max()))
    index = nodes - table.first
    missing = np.unique(index[~table.known[index]])
    if missing.size == 0:
        return
    reynolds = np.exp((missing + table.first) * LOG_RE_STEP)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            point = max_lift_to_drag(polar, reynolds)
        except ValueError:
            table.known[missing] = True
            table.failed[missing] = True
            return
        v = polar.evaluate(point.alpha, reynolds)
        second = polar.second_derivatives(point.alpha, reynolds)
    table.alpha[missing] = point.alpha
    table.slope[missing] = point.dalpha_dre * reynolds
    table.curvature[missing] = second.d2cl_dalpha2 * v.cd - v.cl * second.d2cd_dalpha2
    table.known[missing] = True


def _interpolate(table, log_re):
    """Hermite interpolant of the table at ``ln Re``, the linear one of its curvature, and whether the interval
    may be used."""
    t = log_re / LOG_RE_STEP
    k = np.floor(t)
    u = t - k
    i = k.astype(np.intp) - table.first
    a0, a1 = table.alpha[i], table.alpha[i + 1]
    m0, m1 = table.slope[i] * LOG_RE_STEP, table.slope[i + 1] * LOG_RE_STEP
    v = 1.0 - u
    alpha = (1.0 + 2.0 * u) * v * v * a0 + u * v * v * m0 + u * u * (3.0 - 2.0 * u) * a1 - u * u * v * m1
    smooth = ~(table.failed[i] | table.failed[i + 1])
    smooth &= (np.abs(a1 - a0 - m0) <= TRUST) & (np.abs(a1 - a0 - m1) <= TRUST)
    return alpha, v * table.curvature[i] + u * table.curvature[i + 1], smooth


def _newton_pass(polar, alpha, reynolds, v=None):
    """Polar values at ``alpha`` (``v`` if given), the Newton correction of ``g = 0`` and whether it is a
    maximum with lift."""
    if v is None:
        v = polar.evaluate(alpha, reynolds)
    s = polar.second_derivatives(alpha, reynolds)
    g = v.dcl_dalpha * v.cd - v.cl * v.dcd_dalpha
    dg = s.d2cl_dalpha2 * v.cd - v.cl * s.d2cd_dalpha2
    with np.errstate(divide="ignore", invalid="ignore"):
        step = -g / dg
    good = np.isfinite(step) & (dg < 0.0) & (v.cl > 0.0) & (v.cd > 0.0)
    return v, s, step, good


def _taken(values, index):
    return type(values)(*(x[index] for x in values))


def _scattered(values, index, n):
    """``values`` at the flat positions ``index`` of ``n`` (zero elsewhere)."""
    full = type(values)(*(np.zeros(n) for _ in values))
    _put(full, index, values)
    return full


def _put(target, index, values):
    for field, x in zip(target, values):
        field[index] = x


class TabulatedPoint:
    """A maximum-L/D point whose Reynolds derivatives are evaluated on first use.

    ``alpha, cl, cd`` (and ``dalpha_dre, dcl_dre, dcd_dre``) as in
    :class:`~bild_mdo.airfoil.max_lift_to_drag.MaxLiftToDrag`.  The derivatives need the
    polar's second derivatives at the point, one more polar call, which a run without
    derivatives does not pay; :meth:`full` gives the complete point (computed once).
    """

    def __init__(self, polar, alpha, values, reynolds, correction, inputs, second=None):
        self._state = (polar, alpha, values, reynolds, correction, inputs, second)
        self._full = None
        # As point_from_polar_values: the last Newton correction applied to first order.
        self.alpha = np.reshape(alpha + correction, inputs.shape)
        self.cl = np.reshape(values.cl + values.dcl_dalpha * correction, inputs.shape)
        self.cd = np.reshape(values.cd + values.dcd_dalpha * correction, inputs.shape)

    def full(self):
        """The point with its derivatives, a :class:`~bild_mdo.airfoil.max_lift_to_drag.MaxLiftToDrag`."""
        if self._full is None:
            polar, alpha, values, reynolds, correction, inputs, second = self._state
            if second is None:
                second = polar.second_derivatives(alpha, reynolds)
            self._full = point_from_polar_values(alpha, values, second, [inputs], [], inputs.shape, correction)
        return self._full

    dalpha_dre = property(lambda self: self.full().dalpha_dre)
    dcl_dre = property(lambda self: self.full().dcl_dre)
    dcd_dre = property(lambda self: self.full().dcd_dre)


def max_lift_to_drag_tabulated(polar, reynolds, derivatives=True):
    """:func:`~bild_mdo.airfoil.max_lift_to_drag.max_lift_to_drag` (Reynolds number only), warm-started.

    Parameters
    ----------
    polar : Polar
        Any polar with first and second derivatives; polars that vary with
        Mach number or along the span are solved by the exact solver directly.
    reynolds : array_like
        Chord Reynolds numbers, any shape; complex values (complex step) are
        carried to first order with the exact derivatives.
    derivatives : bool
        False: real Reynolds numbers may return a :class:`TabulatedPoint`,
        whose derivatives cost one more polar call when first used.

    Returns
    -------
    MaxLiftToDrag or TabulatedPoint
        As :func:`~bild_mdo.airfoil.max_lift_to_drag.max_lift_to_drag`: the
        same root of the polar (to round-off) and the same derivatives.

    Raises
    ------
    ValueError
        As :func:`~bild_mdo.airfoil.max_lift_to_drag.max_lift_to_drag`.
    """
    reynolds = np.asarray(reynolds)
    table = None
    if not (polar.varies_with_mach or polar.varies_along_span):
        table = _table_of(polar)
    re_flat = np.asarray(np.real(reynolds), dtype=float).ravel()
    if table is None or not (np.isfinite(re_flat).all() and (re_flat > 0.0).all()):
        return max_lift_to_drag(polar, reynolds)
    log_re = np.log(re_flat)
    k = np.floor(log_re / LOG_RE_STEP).astype(np.intp)
    nodes = np.concatenate([k, k + 1])
    lo, hi = nodes.min() - table.first, nodes.max() - table.first
    if lo < 0 or hi >= table.alpha.size or not table.known[nodes - table.first].all():
        # The polar's own warnings (a Reynolds number outside its data) come from the queried values.
        polar.evaluate(np.zeros_like(re_flat), re_flat)
        _fill(polar, table, nodes)
    guess, curvature, smooth = _interpolate(table, log_re)

    n = re_flat.size
    alpha = guess.copy()
    correction = np.zeros(n)
    v = None
    ok = np.zeros(n, dtype=bool)
    active = np.flatnonzero(smooth)
    # Second derivatives at each query's final angle, where they come with its values at no extra polar call
    # (a polar that shares them, and the exact passes); the others are evaluated when first used.
    s = None
    have_second = np.zeros(n, dtype=bool)
    if active.size:
        # First pass without second derivatives: the Newton step with the table's curvature dg/dalpha
        # (linear in ln Re; module docstring) is applied where it is below STEP_TOL / 2.
        if polar.shares_second_derivatives:
            v, s = polar.evaluate_with_second_derivatives(guess[active], re_flat[active])
            have_second[active] = True
        else:
            v = polar.evaluate(guess[active], re_flat[active])
        with np.errstate(divide="ignore", invalid="ignore"):
            step = -(v.dcl_dalpha * v.cd - v.cl * v.dcd_dalpha) / curvature[active]
        last = (np.abs(step) <= 0.5 * STEP_TOL) & (curvature[active] < 0.0) & (v.cl > 0.0) & (v.cd > 0.0)
        if active.size != n:
            v = _scattered(v, active, n)
            s = _scattered(s, active, n) if s is not None else None
        correction[active[last]] = step[last]
        ok[active[last]] = True
        active = active[~last]
    # The others: exact Newton passes, the first with the values already found at the guess.
    known = v is not None
    for _ in range(MAX_PASSES):
        if active.size == 0:
            break
        va, sa, step, good = _newton_pass(polar, alpha[active], re_flat[active],
                                          _taken(v, active) if known else None)
        known = False
        _put(v, active, va)
        if s is None:
            s = _scattered(sa, active, n)
        else:
            _put(s, active, sa)
        have_second[active] = True
        good &= np.abs(alpha[active] + step - guess[active]) <= TRUST
        last = good & (np.abs(step) <= STEP_TOL)
        correction[active[last]] = step[last]
        ok[active[last]] = True
        keep = good & ~last
        alpha[active[keep]] += step[keep]
        active = active[keep]
    fallback = np.flatnonzero(~ok)
    if fallback.size == n:
        return max_lift_to_drag(polar, reynolds)
    if fallback.size:
        exact = max_lift_to_drag(polar, re_flat[fallback])
        alpha[fallback] = exact.alpha
        correction[fallback] = 0.0
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            _put(v, fallback, polar.evaluate(exact.alpha, re_flat[fallback]))
        have_second[fallback] = False
    point = TabulatedPoint(polar, alpha, v, re_flat, correction, reynolds, s if have_second.all() else None)
    return point.full() if derivatives or np.iscomplexobj(reynolds) else point
