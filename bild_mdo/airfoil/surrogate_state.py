"""The disk-cache side of :class:`~bild_mdo.airfoil.surrogate.TabulatedPolar`: its key, its state arrays, and
the code version that is part of both (:mod:`bild_mdo.airfoil.cache`)."""
from __future__ import annotations

import functools
from pathlib import Path

import numpy as np

from bild_mdo.airfoil import cache, surrogate_spline, surrogate_terms, viterna
from bild_mdo.airfoil.viterna import DEFAULT_CD_MAX, DEFAULT_CD_REVERSE, STALL_BLEND_HALF_WIDTH

_HERE = Path(__file__).parent

#: Version of the surrogate construction, part of every cache key (with a hash of
#: the surrogate modules' and viterna's source, and scipy's version): bump it when the
#: numbers a TabulatedPolar gives change for the same data and settings.
SURROGATE_VERSION = 3

# Everything a TabulatedPolar needs to evaluate, as stored in the polar cache.
_STATE_ARRAYS = ("reynolds", "coef", "grid", "ext_cl", "ext_cd", "ext_dcl", "ext_dcd", "ext_stall",
                 "ext_stall_negative", "scalars", "name", "data_mach", "code_version")


def _default_settings():
    """The constructor settings of a :class:`~bild_mdo.airfoil.surrogate.TabulatedPolar` left at their defaults."""
    return {"cd_max": DEFAULT_CD_MAX, "cd_reverse": DEFAULT_CD_REVERSE, "epsilon": STALL_BLEND_HALF_WIDTH,
            "pre_stall": "spline", "smoothing": None, "alpha_step_deg": 0.25, "split_reynolds": None,
            "low_end": "not-a-knot"}


@functools.lru_cache(maxsize=None)
def code_version():
    """Identifier of the code that builds and evaluates surrogates, part of every cache key: a ``str`` of
    :data:`SURROGATE_VERSION`, scipy's version (its smoothing splines fit the data) and a hash of the source
    of :mod:`~bild_mdo.airfoil.surrogate`, this module, :mod:`~bild_mdo.airfoil.surrogate_spline`,
    :mod:`~bild_mdo.airfoil.surrogate_terms` (the continuation past the table) and
    :mod:`~bild_mdo.airfoil.viterna`.  :meth:`CachedSurrogate.state` holds it, so the tables built from a
    polar's values (the load-path table) get a new key when the evaluation changes."""
    import scipy

    sources = []
    for module_file in (_HERE / "surrogate.py", __file__, surrogate_spline.__file__, surrogate_terms.__file__,
                        viterna.__file__):
        try:
            sources.append(Path(module_file).read_bytes())
        except OSError:
            sources.append(b"")
    return f"{SURROGATE_VERSION}|scipy {scipy.__version__}|{cache.hash_key(*sources)[:16]}"


class CachedSurrogate:
    """Mixin of :class:`~bild_mdo.airfoil.surrogate.TabulatedPolar`: :meth:`cache_key`, :meth:`cached`,
    :meth:`state` and :meth:`from_state`."""

    @classmethod
    def cache_key(cls, polars, **kwargs):
        """The polar cache key (str): a hash of ``polars``, the constructor settings ``**kwargs`` but
        ``name``, and :func:`code_version`."""
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
        """The arrays (dict of str to ndarray) that define this surrogate: :meth:`cached` stores them,
        :meth:`from_state` reads them."""
        ext = self.extended
        return {
            "reynolds": self.reynolds, "coef": self._coef, "grid": ext[0].alpha,
            "ext_cl": np.stack([e.cl for e in ext]), "ext_cd": np.stack([e.cd for e in ext]),
            "ext_dcl": np.stack([e.dcl_dalpha for e in ext]), "ext_dcd": np.stack([e.dcd_dalpha for e in ext]),
            "ext_stall": np.array([e.alpha_stall for e in ext]),
            "ext_stall_negative": np.array([e.alpha_stall_negative for e in ext]),
            "scalars": np.array([self._alpha0, self._alpha_step, *self.alpha_scan_range]),
            "name": np.array(self.name), "data_mach": np.array(self.data_mach),
            "code_version": np.array(code_version()),
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
