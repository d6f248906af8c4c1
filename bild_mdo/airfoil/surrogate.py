"""Smooth ``C_l(alpha, Re)``, ``C_d(alpha, Re)`` surrogate of tabulated polars (paper Sec. 3.2, App. 7.2)."""
from __future__ import annotations

import functools
import warnings
from pathlib import Path

import numpy as np

from bild_mdo.airfoil import cache, viterna
from bild_mdo.airfoil.polar import Polar, PolarSecondDerivatives, PolarValues
from bild_mdo.airfoil.sources.polar_data import PolarData
from bild_mdo.airfoil.sources.readers import read_polar_table, read_xfoil_polar
from bild_mdo.airfoil.viterna import (DEFAULT_CD_MAX, DEFAULT_CD_REVERSE, STALL_BLEND_HALF_WIDTH,
                                      default_alpha_grid, extend_polar)

_LN10 = np.log(10.0)
# Points per block in evaluation: keeps the gathered coefficients (32 floats per
# point) in cache-sized pieces.
_CHUNK = 8192

#: Version of the surrogate construction, part of every cache key (with a hash of
#: this module's and viterna's source, and scipy's version): bump it when the
#: numbers a TabulatedPolar gives change for the same data and settings.
SURROGATE_VERSION = 1

# Everything a TabulatedPolar needs to evaluate, as stored in the polar cache.
_STATE_ARRAYS = ("reynolds", "coef", "grid", "ext_cl", "ext_cd", "ext_dcl", "ext_dcd", "ext_stall",
                 "ext_stall_negative", "scalars", "name", "data_mach")


def _default_settings():
    return {"cd_max": DEFAULT_CD_MAX, "cd_reverse": DEFAULT_CD_REVERSE, "epsilon": STALL_BLEND_HALF_WIDTH,
            "pre_stall": "spline", "smoothing": None, "alpha_step_deg": 0.25}


@functools.lru_cache(maxsize=None)
def code_version():
    """Identifier of the code that builds surrogates: a key part of every cached surrogate.

    Returns
    -------
    str
        :data:`SURROGATE_VERSION`, scipy's version (its smoothing splines fit
        the data) and a hash of this module's and :mod:`~bild_mdo.airfoil.viterna`'s source.
    """
    import scipy

    sources = []
    for module_file in (__file__, viterna.__file__):
        try:
            sources.append(Path(module_file).read_bytes())
        except OSError:
            sources.append(b"")
    return f"{SURROGATE_VERSION}|scipy {scipy.__version__}|{cache.hash_key(*sources)[:16]}"


class TabulatedPolar(Polar):
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
    smoothing spline in ``alpha``, drag in log space) does the same job with
    four advantages:

    * it is C^2 everywhere, including across the stall blends and at
      +-180 deg (periodic end condition), so an optimiser sees no noise and
      Newton's method in the BEM solve sees continuous Jacobians;
    * it reproduces the Eq. (33) curves exactly at the table's Reynolds
      numbers and grid angles (no second fit that could drift from the data),
      and ``log10 Re`` is the variable in which polars change evenly;
    * first and second derivatives in ``alpha`` and ``Re`` are analytic and
      cheap (the spline is stored cell by cell as bicubic polynomials);
    * evaluation is a table look-up on a uniform grid plus Horner sums, fully
      vectorised: about 300,000 points in a few tens of milliseconds.

    The pre-stall model defaults to the smoothing spline rather than the
    paper's line-and-quartic fit (``pre_stall='polynomial'``): on the built-in
    NACA 4412 XFOIL data the spline keeps the maximum ``cl/cd`` within 1 % of
    XFOIL's for Re >= 1e5, while the line and quartic under-predict it by 7 to
    20 % (a quartic cannot follow the drag bucket).

    Reynolds numbers outside the table are clamped to the nearest tabulated
    Reynolds number (the Re derivatives are zero there) and one warning per
    polar object is issued.  All tables must share one Mach number
    (:attr:`data_mach`); the polar does not depend on Mach number (tables at
    several Mach numbers: :class:`~bild_mdo.airfoil.mach_surrogate.MachTabulatedPolar`;
    a correction of single-Mach data: :class:`~bild_mdo.airfoil.compressibility.CompressiblePolar`).

    Building takes about 0.3 s per Reynolds number (the smoothing-spline
    fits); :meth:`cached` stores the result on disk
    (:mod:`bild_mdo.airfoil.cache`) so that later processes load it in
    milliseconds.

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
        The constructor settings (``cd_max`` ... ``alpha_step_deg``).
    """

    name = "tabulated"

    def __init__(self, polars, *, cd_max=DEFAULT_CD_MAX, cd_reverse=DEFAULT_CD_REVERSE,
                 epsilon=STALL_BLEND_HALF_WIDTH, pre_stall="spline", smoothing=None,
                 alpha_step_deg=0.25, name=None):
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
        self.settings = {"cd_max": cd_max, "cd_reverse": cd_reverse, "epsilon": epsilon, "pre_stall": pre_stall,
                         "smoothing": smoothing, "alpha_step_deg": alpha_step_deg}
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
            c_re = CubicSpline(self._log_re, c_alpha, axis=2, bc_type="not-a-knot").c
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

    # ------------------------------------------------------------ the disk cache
    @classmethod
    def cache_key(cls, polars, **kwargs):
        """Hash of the data, the settings and :func:`code_version` (the polar cache key).

        Parameters
        ----------
        polars : sequence of PolarData
        **kwargs
            Constructor settings (``name`` is not part of the key).

        Returns
        -------
        str
        """
        settings = {k: v for k, v in kwargs.items() if k != "name"}
        data = [(float(p.reynolds), float(p.mach), p.alpha_deg, p.cl, p.cd)
                for p in sorted(polars, key=lambda p: (p.mach, p.reynolds))]
        return cache.hash_key("TabulatedPolar", code_version(), settings, data)

    @classmethod
    def cached(cls, polars, **kwargs):
        """:class:`TabulatedPolar` of ``polars``, loaded from the polar cache or built and stored there.

        The same numbers as ``TabulatedPolar(polars, **kwargs)``, bit for bit
        (the cache holds the spline coefficients themselves).  A change of the
        data, the settings or the surrogate code changes the key, so the
        surrogate is rebuilt (see :mod:`bild_mdo.airfoil.cache`).

        Parameters
        ----------
        polars : sequence of PolarData
        **kwargs
            Passed to :class:`TabulatedPolar`.

        Returns
        -------
        TabulatedPolar
        """
        polars = list(polars)
        key = cls.cache_key(polars, **kwargs)
        label = kwargs.get("name") or cls.name
        state = cache.load_arrays("surrogate", label, key)
        if state is not None and all(k in state for k in _STATE_ARRAYS):
            polar = cls.from_state(state)
            if kwargs.get("name") is not None:
                polar.name = str(kwargs["name"])
            polar.data = tuple(sorted(polars, key=lambda p: p.reynolds))
            polar.settings = dict(_default_settings(), **{k: v for k, v in kwargs.items() if k != "name"})
            return polar
        polar = cls(polars, **kwargs)
        cache.store_arrays("surrogate", label, key, polar.state())
        return polar

    def state(self):
        """The arrays that define this surrogate (stored by :meth:`cached`, read by :meth:`from_state`).

        Returns
        -------
        dict of str to ndarray
        """
        ext = self.extended
        return {
            "reynolds": self.reynolds, "coef": self._coef, "grid": ext[0].alpha,
            "ext_cl": np.stack([e.cl for e in ext]), "ext_cd": np.stack([e.cd for e in ext]),
            "ext_dcl": np.stack([e.dcl_dalpha for e in ext]), "ext_dcd": np.stack([e.dcd_dalpha for e in ext]),
            "ext_stall": np.array([e.alpha_stall for e in ext]),
            "ext_stall_negative": np.array([e.alpha_stall_negative for e in ext]),
            "scalars": np.array([self._alpha0, self._alpha_step, *self.alpha_scan_range]),
            "name": np.array(self.name), "data_mach": np.array(self.data_mach),
        }

    @classmethod
    def from_state(cls, state):
        """A surrogate from the arrays of :meth:`state` (no fitting).

        Parameters
        ----------
        state : mapping of str to ndarray

        Returns
        -------
        TabulatedPolar
        """
        polar = cls.__new__(cls)
        polar.name = str(state["name"])
        polar.reynolds = np.asarray(state["reynolds"], dtype=float)
        polar.data_mach = float(state["data_mach"])
        grid = np.asarray(state["grid"], dtype=float)
        polar.extended = [
            viterna.ExtendedPolar(grid, *(np.asarray(state[k][i]) for k in ("ext_cl", "ext_cd", "ext_dcl",
                                                                              "ext_dcd")),
                                  float(state["ext_stall"][i]), float(state["ext_stall_negative"][i]), float(re))
            for i, re in enumerate(polar.reynolds)]
        scalars = np.asarray(state["scalars"], dtype=float)
        polar.alpha_scan_range = (float(scalars[2]), float(scalars[3]))
        polar._set_grid(grid)
        polar._alpha0, polar._alpha_step = float(scalars[0]), float(scalars[1])
        polar._coef = np.ascontiguousarray(state["coef"], dtype=float)
        polar._warned = False
        polar.data = polar.settings = None
        return polar

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
        """Validated ``log10 Re`` clamped to the table, and the in-range mask; warns once."""
        if not np.all(np.isfinite(reynolds)) or not np.all(reynolds > 0.0):
            raise ValueError(f"{self.name}: Reynolds numbers must be finite and > 0, got min "
                             f"{np.min(reynolds)!r}")
        log_re = np.log10(reynolds)
        lo, hi = self._log_re[0], self._log_re[-1]
        inside = (log_re >= lo) & (log_re <= hi)
        if not self._warned and not np.all(inside):
            self._warned = True
            # stacklevel: _compute -> _evaluate_real -> Polar.evaluate -> the caller.
            warnings.warn(
                f"{self.name}: Reynolds numbers outside the tabulated range "
                f"{self.reynolds[0]:.4g}..{self.reynolds[-1]:.4g} are clamped to it "
                f"(seen {reynolds.min():.4g}..{reynolds.max():.4g}); lift and drag do not "
                "change with Re beyond the table (warned once per polar)", stacklevel=5)
        return np.clip(log_re, lo, hi), inside

    def _locate(self, alpha, log_re):
        """Flat cell index and local coordinates ``(alpha - alpha_i, log10 Re - log10 Re_j)``."""
        j = np.searchsorted(self._log_re, log_re, side="right") - 1
        np.clip(j, 0, self._n_re_cells - 1, out=j)
        u = log_re - self._log_re[j]
        # Wrap onto [-pi, pi): the spline is periodic.
        x = alpha - self._alpha0
        if x.min() < 0.0 or x.max() >= 2.0 * np.pi:
            x = np.mod(x, 2.0 * np.pi)
        i = np.minimum((x / self._alpha_step).astype(np.intp), self._n_alpha_cells - 1)
        t = x - i * self._alpha_step
        return i * self._n_re_cells + j, t, u

    def _compute(self, alpha, reynolds, second):
        shape = alpha.shape
        a = alpha.ravel()
        r = reynolds.ravel()
        if not np.all(np.isfinite(a)):
            raise ValueError(f"{self.name}: angle of attack must be finite")
        log_re, inside = self._log_reynolds(r)
        # d/dRe = d/dlog10(Re) / (Re ln 10); zero where Re is clamped.
        re_scale = np.where(inside, 1.0 / (r * _LN10), 0.0)
        n = a.size
        out = np.empty((2 if second else 3, 2, n))
        for start in range(0, n, _CHUNK):
            sl = slice(start, min(start + _CHUNK, n))
            cell, t, u = self._locate(a[sl], log_re[sl])
            c = np.take(self._coef, cell, axis=0).reshape(-1, 2, 4, 4)
            # c[point, q, alpha power, log-Re power]; Horner in log Re, then in alpha.
            uu = u[:, None, None]
            c_u = c[..., 0] + uu * (c[..., 1] + uu * (c[..., 2] + uu * c[..., 3]))
            c_du = c[..., 1] + uu * (2.0 * c[..., 2] + 3.0 * uu * c[..., 3])
            tt = t[:, None]
            if second:
                out[0, :, sl] = (2.0 * c_u[..., 2] + 6.0 * tt * c_u[..., 3]).T
                dre = c_du[..., 1] + tt * (2.0 * c_du[..., 2] + 3.0 * tt * c_du[..., 3])
            else:
                out[0, :, sl] = (c_u[..., 0] + tt * (c_u[..., 1] + tt * (c_u[..., 2]
                                                                         + tt * c_u[..., 3]))).T
                out[1, :, sl] = (c_u[..., 1] + tt * (2.0 * c_u[..., 2] + 3.0 * tt * c_u[..., 3])).T
                dre = c_du[..., 0] + tt * (c_du[..., 1] + tt * (c_du[..., 2] + tt * c_du[..., 3]))
            out[-1, :, sl] = dre.T * re_scale[sl]
        return [x.reshape(shape) for x in out[:, 0]], [x.reshape(shape) for x in out[:, 1]]

    def _evaluate_real(self, alpha, reynolds):
        (cl, dcl_da, dcl_dre), (cd, dcd_da, dcd_dre) = self._compute(alpha, reynolds, second=False)
        return PolarValues(cl, cd, dcl_da, dcl_dre, dcd_da, dcd_dre)

    def _second_derivatives_real(self, alpha, reynolds):
        (d2cl, d2cl_dre), (d2cd, d2cd_dre) = self._compute(alpha, reynolds, second=True)
        return PolarSecondDerivatives(d2cl, d2cl_dre, d2cd, d2cd_dre)
