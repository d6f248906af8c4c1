"""Smooth ``C_l(alpha, Re)``, ``C_d(alpha, Re)`` surrogate of tabulated polars (paper Sec. 3.2, App. 7.2)."""
from __future__ import annotations

import warnings

import numpy as np

from bild_mdo.airfoil.polar import Polar, PolarSecondDerivatives, PolarValues
from bild_mdo.airfoil.sources.polar_data import PolarData
from bild_mdo.airfoil.sources.readers import read_polar_table, read_xfoil_polar
from bild_mdo.airfoil.surrogate_spline import (LOW_ENDS, LOW_REYNOLDS_BOUNDS, LOW_REYNOLDS_DRAG_FACTOR,
                                              LOW_REYNOLDS_LIFT_CHANGE, physical_low_slope, reynolds_spline,
                                              split_index)
from bild_mdo.airfoil.surrogate_state import SURROGATE_VERSION, CachedSurrogate, code_version
from bild_mdo.airfoil.surrogate_terms import EXTRAPOLATED_ROWS, extrapolate_log_reynolds, per_reynolds, spline_terms
from bild_mdo.airfoil.viterna import (DEFAULT_CD_MAX, DEFAULT_CD_REVERSE, STALL_BLEND_HALF_WIDTH,
                                      default_alpha_grid, extend_polar)

__all__ = ["LOW_REYNOLDS_DRAG_FACTOR", "LOW_REYNOLDS_LIFT_CHANGE", "SURROGATE_VERSION", "TabulatedPolar",
           "code_version", "extrapolate_log_reynolds"]


class TabulatedPolar(CachedSurrogate, Polar):
    """Bicubic-spline surrogate of polars tabulated at several Reynolds numbers.

    Construction (paper Appendix 7.2, Eq. 33): every Reynolds number's data are
    smoothed, extended to the whole circle with the stall blend and the
    Viterna-Corrigan extrapolation (:func:`bild_mdo.airfoil.viterna.extend_polar`)
    and sampled on one uniform angle grid from -180 to 180 deg.  The grid
    values are then interpolated by a tensor-product cubic spline in
    ``(alpha, log10 Re)``: periodic in ``alpha``, not-a-knot in ``log10 Re``.

    Why this surrogate.  The paper trains SMT's RMTS (regularised minimal-energy
    tensor-product splines) on the same kind of data; SMT is not a dependency
    here.  A cubic spline interpolant of data that are already smooth (the
    XFOIL scatter is removed per Reynolds number, before the extension, by a
    smoothing spline in ``alpha``, drag in log space) does the same job: it is
    C^2 everywhere within the table (stall blends and +-180 deg included; C^1 in Re at a
    ``split_reynolds``), so optimisers and
    the BEM Newton solve see continuous Jacobians; it reproduces the Eq. (33)
    curves at the table's Reynolds numbers and grid angles; its derivatives
    are analytic and cheap (bicubic pieces), and evaluation is a look-up on a
    uniform grid plus Horner sums (300,000 points in some tens of ms).

    The pre-stall model defaults to the smoothing spline rather than the
    paper's line-and-quartic fit (``pre_stall='polynomial'``): on the built-in
    NACA 4412 XFOIL data the spline keeps the maximum ``cl/cd`` within 1 % of
    XFOIL's for Re >= 1e5, while the line and quartic under-predict it by 7 to
    20 % (a quartic cannot follow the drag bucket).

    Past the table, beyond an edge ``L_e`` of ``L = log10 Re``, the spline is
    continued C^1 in ``L`` from the edge's value ``f(alpha)`` and slope
    ``s = df/dL`` (:func:`extrapolate_log_reynolds`; ``d = L - L_e``).  Above
    the table::

        cl = f + d s           linear in log Re
        cd = f exp(d m)        m = s / f: log cd linear in log Re, a power law cd ~ Re^(m / ln 10),
                               the form of skin-friction laws (Re^-1/2 laminar, Re^-1/5 turbulent)

    Below the table the same lines saturate (``C`` = :data:`LOW_REYNOLDS_LIFT_CHANGE`,
    ``K = ln`` :data:`LOW_REYNOLDS_DRAG_FACTOR`)::

        cl = f + C tanh(d s / C)        |cl - f| < C
        cd = f exp(K tanh(d m / K))     f / 3 < cd < 3 f

    so lift and drag stay bounded and monotone in Re however low the Reynolds
    number (each in the direction of its slope at the edge), instead of lines
    that leave the physical range (a lift that changes sign, a drag of 0.5,
    as the paper's tables from 5e4 gave at 1e4); to first order in ``d`` it is
    the same as above the table (``tanh x = x - x**3/3 ...``).

    Values, Re slopes, alpha derivatives up to the second and the cross terms
    ``d2/(dalpha dRe)`` are continuous at the edges, and so are the maximum-L/D
    point and its derivatives; ``d2/dRe2`` jumps there (the continuation is C^1:
    at the edge ``d2cl/dL2 = 0`` and ``d2(log cd)/dL2 = 0`` on the outside).  ``cd > 0``
    past the table: the positive edge value times an exponential (ValueError if
    the edge value is not positive).
    (Clamped instead, the zero Re slope past the edge made Ipopt cycle there.)
    One warning per polar object says that Re is extrapolated.  All tables must
    share one Mach number (:attr:`data_mach`; tables at several Mach numbers:
    :class:`~bild_mdo.airfoil.mach_surrogate.MachTabulatedPolar`; a correction of
    single-Mach data: :class:`~bild_mdo.airfoil.compressibility.CompressiblePolar`).

    Building takes about 0.3 s per Reynolds number (smoothing-spline fits);
    :meth:`cached` stores the result on disk for later processes (:mod:`bild_mdo.airfoil.cache`).

    Parameters
    ----------
    polars : sequence of PolarData
        One polar per Reynolds number (distinct Reynolds numbers, any order).
    cd_max : float
        Flat-plate drag coefficient at 90 deg of the Viterna extrapolation.
    cd_reverse : float
        Drag coefficient at +-180 deg.
    epsilon : float
        Half width of the cubic stall blends (rad); the paper's 1.5 deg.
    pre_stall : {'spline', 'polynomial'}
        Pre-stall model of Eq. (33); see :func:`bild_mdo.airfoil.viterna.extend_arrays`.
    smoothing : float, optional
        Smoothing-spline penalty; default chosen by generalised cross-validation.
    alpha_step_deg : float
        Spacing of the angle grid (deg).
    split_reynolds : float, optional
        A tabulated Reynolds number (not the first or last) where the spline
        in ``log10 Re`` is split: the tables from it up get their own
        not-a-knot spline (bit for bit the surrogate of those tables alone),
        the tables below one joined C^1 to it (``d2/dRe2`` jumps there).  The
        built-in NACA 4412 splits at 5e4 (bild_mdo/airfoil/data/README.md).
    low_end : {'not-a-knot', 'physical'}
        End condition in ``log10 Re`` at the lowest table: not-a-knot
        (default), or slopes clamped to lift flat in Re and ``log cd`` falling
        with one power law of Re times ``cos(alpha)**2``
        (:func:`~bild_mdo.airfoil.surrogate_spline.physical_low_slope`), so
        that below the table lift stays and drag rises as Re drops.
    name : str, optional
        Name used in messages.

    Attributes
    ----------
    reynolds : ndarray, shape (n_re,)
        Tabulated Reynolds numbers, increasing.
    extended : list of ExtendedPolar
        The Eq. (33) curves the spline interpolates.
    alpha_scan_range : tuple of float
        ``(min negative stall, max positive stall)`` angle (rad): where the
        maximum-L/D search looks.
    data_mach : float
        Mach number of the tables.
    data : tuple of PolarData or None
        The tables it was built from (``None`` when made by :meth:`from_state` alone).
    settings : dict or None
        The constructor settings (``cd_max`` ... ``split_reynolds``).
    """

    name = "tabulated"

    def __init__(self, polars, *, cd_max=DEFAULT_CD_MAX, cd_reverse=DEFAULT_CD_REVERSE,
                 epsilon=STALL_BLEND_HALF_WIDTH, pre_stall="spline", smoothing=None,
                 alpha_step_deg=0.25, split_reynolds=None, low_end="not-a-knot", name=None):
        from scipy.interpolate import CubicSpline  # only when building: a cached load needs numpy only

        polars = sorted(polars, key=lambda p: p.reynolds)
        if not polars:
            raise ValueError("TabulatedPolar needs at least one polar")
        machs = sorted({float(p.mach) for p in polars})
        if len(machs) > 1:
            raise ValueError(f"TabulatedPolar: the tables have several Mach numbers {machs}; use "
                             "bild_mdo.airfoil.mach_surrogate.MachTabulatedPolar for Mach-dependent data")
        reynolds = np.array([p.reynolds for p in polars], dtype=float)
        if np.any(np.diff(reynolds) <= 0):
            raise ValueError(f"TabulatedPolar: Reynolds numbers must be distinct, got {reynolds.tolist()}")
        self.data_mach = machs[0]
        self.data = tuple(polars)
        split = split_index(reynolds, split_reynolds)
        if low_end not in LOW_ENDS:
            raise ValueError(f"TabulatedPolar: low_end must be one of {', '.join(LOW_ENDS)}, got {low_end!r}")
        self.settings = {"cd_max": cd_max, "cd_reverse": cd_reverse, "epsilon": epsilon, "pre_stall": pre_stall,
                         "smoothing": smoothing, "alpha_step_deg": alpha_step_deg,
                         "split_reynolds": None if split_reynolds is None else float(split_reynolds),
                         "low_end": low_end}
        if name is not None:
            self.name = str(name)
        grid = default_alpha_grid(alpha_step_deg)
        self.extended = [extend_polar(p, alpha_grid=grid, cd_max=cd_max, cd_reverse=cd_reverse,
                                      epsilon=epsilon, pre_stall=pre_stall, smoothing=smoothing)
                         for p in polars]
        self.reynolds = reynolds
        self.alpha_scan_range = (min(e.alpha_stall_negative for e in self.extended),
                                 max(e.alpha_stall for e in self.extended))
        self._set_grid(grid)
        self._warned = False

        values = np.stack([np.stack([e.cl for e in self.extended], axis=1),
                           np.stack([e.cd for e in self.extended], axis=1)], axis=-1)
        # values[i_alpha, i_re, q]: q = 0 lift, 1 drag.  Periodic in alpha; the grid
        # ends are the same angle, and Eq. (33) makes them equal.
        values[-1] = values[0]
        c_alpha = CubicSpline(grid, values, axis=0, bc_type="periodic").c
        # c_alpha[m, i, r, q]: power 3 - m of (alpha - grid[i]).
        if reynolds.size == 1:
            # A single table: the polar does not depend on Re (constant term only).
            coef = np.zeros((grid.size - 1, 1, 2, 4, 4))
            coef[:, 0, :, :, 3] = np.transpose(c_alpha[:, :, 0, :], (1, 2, 0))
            self._n_re_cells = 1
        else:
            low_slope = physical_low_slope(grid, values, self._log_re) if low_end == "physical" else None
            c_re = reynolds_spline(self._log_re, c_alpha, split, low_slope)
            # c_re[k, j, m, i, q]: power 3 - k of (log10 Re - log_re[j]).
            self._n_re_cells = reynolds.size - 1
            coef = np.transpose(c_re, (3, 1, 4, 2, 0))           # [i, j, q, m, k]
        # Increasing powers in both local coordinates, cells flattened for one gather.
        coef = coef[:, :, :, ::-1, ::-1]
        # Rows of 32 numbers: np.take on a 2-D table is several times faster than
        # fancy indexing of a 4-D one.
        self._coef = np.ascontiguousarray(coef.reshape(-1, 32))

    def _set_grid(self, grid):
        self._alpha0 = grid[0]
        self._alpha_step = grid[1] - grid[0]
        self._n_alpha_cells = grid.size - 1
        self._log_re = np.log10(self.reynolds)
        self._n_re_cells = max(self.reynolds.size - 1, 1)

    # ----------------------------------------------------------------- builders
    @classmethod
    def from_files(cls, paths, **kwargs):
        """Surrogate of XFOIL polar files (``PACC`` output), one per Reynolds number.

        Parameters
        ----------
        paths : sequence of str or os.PathLike
            XFOIL polar files, read with :func:`~bild_mdo.airfoil.sources.readers.read_xfoil_polar`.
        **kwargs
            Passed to :class:`TabulatedPolar`.

        Returns
        -------
        TabulatedPolar
        """
        return cls([read_xfoil_polar(p) for p in paths], **kwargs)

    @classmethod
    def from_tables(cls, paths, **kwargs):
        """:meth:`from_files` for plain tables (columns ``alpha_deg, cl, cd``, a ``# reynolds =`` line).

        The files are read with :func:`~bild_mdo.airfoil.sources.readers.read_polar_table`.
        """
        return cls([read_polar_table(p) for p in paths], **kwargs)

    @classmethod
    def from_arrays(cls, reynolds, alpha_deg, cl, cd, **kwargs):
        """Surrogate of in-memory tables.

        Parameters
        ----------
        reynolds : sequence of float, length n_re
            Reynolds number of each table.
        alpha_deg, cl, cd : sequence of array_like, length n_re
            Angle of attack (deg, increasing), lift and drag of each table.
        **kwargs
            Passed to :class:`TabulatedPolar`.

        Returns
        -------
        TabulatedPolar
        """
        if not len(reynolds) == len(alpha_deg) == len(cl) == len(cd):
            raise ValueError("reynolds, alpha_deg, cl, cd must have the same length")
        return cls([PolarData(re, 0.0, a, l, d, source=f"table {i} (Re={re:g})")
                    for i, (re, a, l, d) in enumerate(zip(reynolds, alpha_deg, cl, cd))], **kwargs)

    def __repr__(self):
        return (f"TabulatedPolar(name={self.name!r}, {self.reynolds.size} Reynolds numbers "
                f"{self.reynolds[0]:g}..{self.reynolds[-1]:g})")

    # --------------------------------------------------------------- evaluation
    def _log_reynolds(self, reynolds):
        """Validated ``log10 Re``, the same clamped to the table (its edge), and the in-range mask; warns once."""
        real = np.real(reynolds)
        if not np.all(np.isfinite(real)) or not np.all(real > 0.0):
            raise ValueError(f"{self.name}: Reynolds numbers must be finite and > 0, got min "
                             f"{np.min(real)!r}")
        log_re = np.log10(reynolds)
        lo, hi = self._log_re[0], self._log_re[-1]
        inside = (np.real(log_re) >= lo) & (np.real(log_re) <= hi)
        if not self._warned and not np.all(inside):
            self._warned = True
            how = ("are evaluated at it (one table: lift and drag do not change with Re)" if lo == hi else
                   "are extrapolated from the table's edge (above: lift linear in log Re, drag a power of Re; "
                   "below: the same, bounded)")
            # stacklevel: _rows -> _compute -> _evaluate_real -> Polar.evaluate -> the caller.
            warnings.warn(f"{self.name}: Reynolds numbers outside the tabulated range {self.reynolds[0]:.4g}.."
                          f"{self.reynolds[-1]:.4g} {how}; seen {real.min():.4g}..{real.max():.4g} "
                          "(warned once per polar)", stacklevel=6)
        return log_re, np.where(inside, log_re, np.clip(np.real(log_re), lo, hi)), inside

    def _terms(self, alpha, log_re, rows):
        """Rows ``rows`` of the spline's terms (:data:`~bild_mdo.airfoil.surrogate_terms.SPLINE_ROWS`)."""
        grid = (self._alpha0, self._alpha_step, self._n_alpha_cells, self._n_re_cells)
        return spline_terms(self._coef, grid, self._log_re, alpha, log_re, rows)

    def _rows(self, alpha, reynolds, rows):
        """Rows ``rows`` (:data:`~bild_mdo.airfoil.surrogate_terms.SPLINE_ROWS`) of the terms of cl and cd at flat
        ``alpha, reynolds``, continued past the table, shape ``(len(rows), 2, n)``."""
        a, r = alpha.ravel(), reynolds.ravel()
        if not np.all(np.isfinite(a)):
            raise ValueError(f"{self.name}: angle of attack must be finite")
        log_re, edge, inside = self._log_reynolds(r)
        out = self._terms(a, edge, rows)
        # Past the table: the C^1 continuation (class docstring); one table is constant in Re as it is.
        past = np.flatnonzero(~inside) if self.reynolds.size > 1 else ()
        if len(past):
            terms = self._terms(a[past], edge[past], range(6))
            if not np.all(np.real(terms[0, 1]) > 0.0):
                bad = past[np.argmin(np.real(terms[0, 1]))]
                raise ValueError(f"{self.name}: cd <= 0 at the table edge Re = {10.0 ** np.real(edge[bad]):.4g}, "
                                 f"alpha = {np.degrees(np.real(a[bad])):.4g} deg: cannot extrapolate it to Re = "
                                 f"{np.real(r[bad]):.4g}")
            below = np.real(log_re[past]) < self._log_re[0]
            extrapolated = np.empty((6, 2, len(past)), dtype=terms.dtype)
            for side, bounds in ((below, LOW_REYNOLDS_BOUNDS), (~below, None)):
                if np.any(side):
                    extrapolated[:, :, side] = extrapolate_log_reynolds(
                        terms[:, :, side], log_re[past][side] - edge[past][side], bounds)
            if not np.all(np.isfinite(extrapolated[0][1])):
                raise ValueError(f"{self.name}: cd extrapolated to Re = {np.real(r[past]).min():.4g}.."
                                 f"{np.real(r[past]).max():.4g} overflows: too far from the table's Reynolds numbers")
            out[:, :, past] = [extrapolated[EXTRAPOLATED_ROWS.index(row)] for row in rows]
        return out

    @staticmethod
    def _first(out, reynolds):
        """``(c, c_alpha, c_Re)`` from rows ``(f, f_a, f_L)``."""
        return out[0], out[1], per_reynolds({"f_L": out[2]}, reynolds)["f_Re"]

    @staticmethod
    def _second(out, reynolds):
        """``(c_alpha2, c_alpha_Re, c_Re2)`` from rows ``(f_aa, f_aL, f_L, f_LL)``."""
        to_re = per_reynolds({"f_aL": out[1], "f_L": out[2], "f_LL": out[3]}, reynolds)
        return out[0], to_re["f_aRe"], to_re["f_ReRe"]

    def _compute(self, alpha, reynolds, second):
        """``[c, c_alpha, c_Re]`` (or with ``second`` ``[c_alpha2, c_alpha_Re, c_Re2]``) of cl and of cd.

        Complex-step safe in ``alpha`` and ``reynolds``: the tests check the derivatives with it.
        """
        shape = alpha.shape
        # f_aa, f_aL, f_L, f_LL or f, f_a, f_L (rows of surrogate_terms.SPLINE_ROWS).
        out = self._rows(alpha, reynolds, (2, 4, 3, 6) if second else (0, 1, 3))
        out = (self._second if second else self._first)(out, reynolds.ravel())
        return [x[0].reshape(shape) for x in out], [x[1].reshape(shape) for x in out]

    def _compute_both(self, alpha, reynolds):
        """:meth:`_compute` without and with ``second`` from one evaluation of the spline."""
        shape, r = alpha.shape, reynolds.ravel()
        out = self._rows(alpha, reynolds, (0, 1, 3, 2, 4, 6))
        first, second = self._first(out[:3], r), self._second(out[[3, 4, 2, 5]], r)
        return tuple(([x[0].reshape(shape) for x in part], [x[1].reshape(shape) for x in part])
                     for part in (first, second))

    def _evaluate_with_second_real(self, alpha, reynolds):
        ((cl, dcl_da, dcl_dre), (cd, dcd_da, dcd_dre)), ((cl_aa, cl_are, cl_rere), (cd_aa, cd_are, cd_rere)) = \
            self._compute_both(alpha, reynolds)
        return (PolarValues(cl, cd, dcl_da, dcl_dre, dcd_da, dcd_dre),
                PolarSecondDerivatives(cl_aa, cl_are, cd_aa, cd_are, cl_rere, cd_rere))

    def _evaluate_real(self, alpha, reynolds):
        (cl, dcl_da, dcl_dre), (cd, dcd_da, dcd_dre) = self._compute(alpha, reynolds, second=False)
        return PolarValues(cl, cd, dcl_da, dcl_dre, dcd_da, dcd_dre)

    def _second_derivatives_real(self, alpha, reynolds):
        (cl_aa, cl_are, cl_rere), (cd_aa, cd_are, cd_rere) = self._compute(alpha, reynolds, second=True)
        return PolarSecondDerivatives(cl_aa, cl_are, cd_aa, cd_are, cl_rere, cd_rere)

