"""Polars tabulated at several Mach numbers: a smooth surrogate in ``(alpha, Re, M)`` with exact derivatives.

XFOIL computes compressible polars (its ``MACH`` command; the runner's
``--mach``).  Given tables at Mach numbers ``M_0 < M_1 < ...`` (each at one or
more Reynolds numbers), :class:`MachTabulatedPolar` fits one
:class:`~bild_mdo.airfoil.surrogate.TabulatedPolar` per Mach number and
interpolates across Mach numbers with cubic-spline cardinal functions
``w_k(M)`` (not-a-knot; straight lines for two Mach numbers, the parabola
through three)::

    c(alpha, Re, M) = sum_k w_k(M) c_k(alpha, Re)

Since ``sum_k w_k c_k`` of bicubic pieces is the tensor-product spline of
the data in ``(alpha, log Re, M)``, the surrogate is C^2 in ``M`` inside
the table and every derivative, including ``d/dM`` and ``d2/(dalpha dM)``,
is exact.  Reynolds numbers outside the tables are extrapolated by each
member, C^1 in log Re (:class:`~bild_mdo.airfoil.surrogate.TabulatedPolar`),
so the blend is C^1 there too.  Mach numbers outside ``[M_0, M_last]`` are
clamped (zero Mach derivative) with one warning per polar: past the last
table drag diverges, which a continuation of its slope would understate
(and tables usually start at ``M_0 = 0``).  Without a Mach number
(``evaluate(alpha, Re)``) the polar is the table at ``M_0``.
"""
from __future__ import annotations

import warnings

import numpy as np

from bild_mdo.airfoil.polar import MachPolarSecondDerivatives, MachPolarValues, Polar
from bild_mdo.airfoil.surrogate import TabulatedPolar

__all__ = ["MachTabulatedPolar", "tabulated_polar"]


def _cardinal_coefficients(machs):
    """Piecewise-cubic coefficients ``c[power 3..0, segment, k]`` of the cardinal splines ``w_k``."""
    k = machs.size
    if k == 2:
        c = np.zeros((4, 1, 2))
        h = machs[1] - machs[0]
        c[2, 0] = (-1.0 / h, 1.0 / h)
        c[3, 0] = (1.0, 0.0)
        return c
    from scipy.interpolate import CubicSpline

    return CubicSpline(machs, np.eye(k), bc_type="not-a-knot").c


class MachTabulatedPolar(Polar):
    """Smooth surrogate of polars tabulated at several Mach numbers (module docstring).

    Parameters
    ----------
    members : sequence of TabulatedPolar
        One surrogate per Mach number (``data_mach`` distinct, at least two).
    name : str, optional

    Attributes
    ----------
    machs : ndarray
        The tabulated Mach numbers, increasing.
    members : tuple of TabulatedPolar
    """

    varies_with_mach = True

    def __init__(self, members, name=None):
        members = sorted(members, key=lambda p: p.data_mach)
        machs = np.array([p.data_mach for p in members], dtype=float)
        if machs.size < 2 or np.any(np.diff(machs) <= 0.0):
            raise ValueError(f"MachTabulatedPolar needs tables at two or more distinct Mach numbers, got "
                             f"{machs.tolist()}")
        self.members = tuple(members)
        self.machs = machs
        self.data_mach = float(machs[0])
        self.name = name or members[0].name
        self._coef = _cardinal_coefficients(machs)
        self.data = None if any(p.data is None for p in members) else tuple(d for p in members for d in p.data)
        self.settings = members[0].settings
        self._warned = False
        self.alpha_scan_range = (min(p.alpha_scan_range[0] for p in members),
                                 max(p.alpha_scan_range[1] for p in members))

    def __repr__(self):
        return f"MachTabulatedPolar(name={self.name!r}, Mach {self.machs.tolist()})"

    def mach_weights(self, mach):
        """Cardinal weights ``w_k(M)`` and ``dw_k/dM``, shape (n_mach, n) for the raveled ``M``; complex-step safe."""
        mach = np.asarray(mach).ravel()
        real = np.real(mach)
        inside = (real >= self.machs[0]) & (real <= self.machs[-1])
        if not self._warned and not np.all(inside):
            self._warned = True
            warnings.warn(f"{self.name}: Mach numbers outside the tabulated range {self.machs[0]:g}..."
                          f"{self.machs[-1]:g} are clamped to it (seen {real.min():.3g}..{real.max():.3g}; "
                          "warned once per polar)", RuntimeWarning, stacklevel=5)
        m = np.where(real < self.machs[0], self.machs[0], np.where(real > self.machs[-1], self.machs[-1], mach))
        seg = np.clip(np.searchsorted(self.machs, np.real(m), side="right") - 1, 0, self.machs.size - 2)
        t = m - self.machs[seg]
        c = self._coef[:, seg, :]                       # [power, point, k]
        w = ((c[0] * t[:, None] + c[1]) * t[:, None] + c[2]) * t[:, None] + c[3]
        dw = (3.0 * c[0] * t[:, None] + 2.0 * c[1]) * t[:, None] + c[2]
        return w.T, np.where(inside, dw.T, 0.0)

    def _evaluate_real(self, alpha, reynolds):
        return self.members[0]._evaluate_real(alpha, reynolds)

    def _second_derivatives_real(self, alpha, reynolds):
        return self.members[0]._second_derivatives_real(alpha, reynolds)

    def _evaluate_mach_real(self, alpha, reynolds, mach):
        shape = alpha.shape
        w, dw = self.mach_weights(mach)
        vals = np.array([tuple(p._evaluate_real(alpha.ravel(), reynolds.ravel())) for p in self.members])
        total = np.einsum("kn,kfn->fn", w, vals)                 # vals[k, field, point]
        slope = np.einsum("kn,kfn->fn", dw, vals[:, :2])
        return MachPolarValues(*(v.reshape(shape) for v in (*total, *slope)))

    def _second_derivatives_mach_real(self, alpha, reynolds, mach):
        shape = alpha.shape
        a, r = alpha.ravel(), reynolds.ravel()
        w, dw = self.mach_weights(mach)
        second = np.array([tuple(p._second_derivatives_real(a, r)) for p in self.members])
        first = np.array([tuple(p._evaluate_real(a, r)) for p in self.members])
        total = np.einsum("kn,kfn->fn", w, second)
        # d2c/(dalpha dM) = sum_k w_k'(M) dc_k/dalpha (fields 2 and 4: dcl/dalpha, dcd/dalpha).
        slope = np.einsum("kn,kfn->fn", dw, first[:, [2, 4]])
        return MachPolarSecondDerivatives(*(v.reshape(shape) for v in (*total, *slope)))


def tabulated_polar(polars, cached=True, name=None, **kwargs):
    """The surrogate of any set of tables: :class:`TabulatedPolar` for one Mach number, else :class:`MachTabulatedPolar`.

    Parameters
    ----------
    polars : sequence of PolarData
        Tables at one or several Reynolds and Mach numbers (one per pair).
    cached : bool
        Load and store each surrogate in the polar cache (:meth:`TabulatedPolar.cached`).
    name : str, optional
    **kwargs
        Surrogate settings, passed to :class:`TabulatedPolar`.

    Returns
    -------
    TabulatedPolar or MachTabulatedPolar
    """
    groups = {}
    for p in polars:
        groups.setdefault(float(p.mach), []).append(p)
    if not groups:
        raise ValueError("no polar tables given")
    build = TabulatedPolar.cached if cached else TabulatedPolar
    members = [build(groups[m], name=name, **kwargs) for m in sorted(groups)]
    if len(members) == 1:
        return members[0]
    return MachTabulatedPolar(members, name=name)
