"""Polars generated on first use, with XFOIL or NeuralFoil, and kept in the polar cache.

``resolve_polar("naca2412")`` (or a coordinates file) runs XFOIL once per
machine: :func:`xfoil_polars` runs the Reynolds numbers (and Mach numbers) in
parallel XFOIL processes, stores the tables in the polar cache
(:mod:`bild_mdo.airfoil.cache`), keyed by the airfoil (its designation, or
the bytes of its coordinates file) and every setting, and later calls load
them in milliseconds.  :func:`neuralfoil_polars` does the same with the
optional NeuralFoil package.

The default settings suit rotors: chord Reynolds numbers from 5e4 (small
drones) to 5e6 (large helicopter and eVTOL blades), angles of attack from
-10 to 20 deg every 0.5 deg (attached flow, the drag bucket and stall, as
the surrogate's Eq. (33) construction needs), Mach 0 and Ncrit 9.
"""
from __future__ import annotations

import warnings
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from bild_mdo.airfoil import cache
from bild_mdo.airfoil.sources.coordinates import parse_airfoil
from bild_mdo.airfoil.sources.polar_data import MIN_POINTS, PolarData
from bild_mdo.utils.cpus import available_cpus

__all__ = ["DEFAULT_ALPHA_DEG", "DEFAULT_REYNOLDS", "neuralfoil_polars", "xfoil_polars"]

#: Chord Reynolds numbers of generated polars.
DEFAULT_REYNOLDS = (5e4, 1e5, 2e5, 5e5, 1e6, 2e6, 5e6)
#: Angles of attack (deg) of generated polars.
DEFAULT_ALPHA_DEG = tuple(np.round(np.arange(-10.0, 20.0 + 1e-9, 0.5), 3))


def _airfoil_key(airfoil):
    """``(kind, spec, label, identity)`` of an airfoil argument; a file is identified by its bytes."""
    kind, spec = parse_airfoil(airfoil)
    if kind == "naca":
        return kind, spec, f"naca{spec}", spec
    return kind, spec, spec.stem.lower(), spec.read_bytes()


def _pack(polars):
    counts = np.array([p.alpha_deg.size for p in polars])
    return {"reynolds": np.array([p.reynolds for p in polars]), "mach": np.array([p.mach for p in polars]),
            "ncrit": np.array([np.nan if p.ncrit is None else p.ncrit for p in polars]), "counts": counts,
            "alpha_deg": np.concatenate([p.alpha_deg for p in polars]), "cl": np.concatenate([p.cl for p in polars]),
            "cd": np.concatenate([p.cd for p in polars]), "source": np.array([p.source for p in polars])}


def _unpack(arrays):
    ends = np.cumsum(arrays["counts"])
    starts = ends - arrays["counts"]
    return [PolarData(reynolds=float(re), mach=float(m), alpha_deg=arrays["alpha_deg"][a:b],
                      cl=arrays["cl"][a:b], cd=arrays["cd"][a:b], source=str(src),
                      ncrit=None if np.isnan(nc) else float(nc))
            for re, m, nc, src, a, b in zip(arrays["reynolds"], arrays["mach"], arrays["ncrit"], arrays["source"],
                                            starts, ends)]


def _cached_polars(tool, airfoil, settings, generate):
    kind, spec, label, identity = _airfoil_key(airfoil)
    key = cache.hash_key(tool, kind, identity, settings)
    arrays = cache.load_arrays("polars", f"{tool}-{label}", key)
    if arrays is not None:
        return _unpack(arrays)
    polars = generate(airfoil, label)
    cache.store_arrays("polars", f"{tool}-{label}", key, _pack(polars))
    return polars


def _progress(iterable, total, desc):
    from tqdm import tqdm  # the bar is shown only on a terminal (disable=None)

    return tqdm(iterable, total=total, desc=desc, unit="polar", disable=None, leave=False)


def xfoil_polars(airfoil, reynolds=DEFAULT_REYNOLDS, alpha_deg=DEFAULT_ALPHA_DEG, mach=0.0, ncrit=9.0,
                 max_iter=200):
    """XFOIL polars of a NACA designation or coordinates file, generated once and then read from the cache.

    Parameters
    ----------
    airfoil : str or os.PathLike
        NACA 4- or 5-digit designation or a Selig coordinates file.
    reynolds : sequence of float
        Chord Reynolds numbers.
    alpha_deg : sequence of float
        Angles of attack (deg).
    mach : float or sequence of float
        Mach number(s); several give tables for a Mach-dependent surrogate.
    ncrit : float
        e^N transition amplification factor.
    max_iter : int
        XFOIL iteration limit per point.

    Returns
    -------
    list of PolarData
        One per (Mach, Reynolds) pair that converged at :data:`MIN_POINTS` or
        more angles (the others are dropped with a warning).

    Raises
    ------
    RuntimeError
        XFOIL is not installed, or no pair gave enough points.
    ValueError
        Invalid airfoil or settings.
    """
    from bild_mdo.airfoil.sources.xfoil import require_programs, run_xfoil

    machs = [float(m) for m in np.atleast_1d(mach)]
    reynolds = [float(r) for r in reynolds]
    alpha = np.asarray(alpha_deg, dtype=float)
    settings = {"reynolds": reynolds, "alpha_deg": alpha, "mach": machs, "ncrit": float(ncrit),
                "max_iter": int(max_iter)}

    def generate(spec, label):
        require_programs()

        def run(job):
            try:
                return run_xfoil(spec, [job[1]], alpha, mach=job[0], ncrit=ncrit, max_iter=max_iter)[0][0]
            except RuntimeError as exc:
                if "converged at no angle" not in str(exc):
                    raise
                return None

        jobs = [(m, r) for m in machs for r in reynolds]
        workers = max(1, min(len(jobs), available_cpus()))
        with ThreadPoolExecutor(max_workers=workers) as pool:
            polars = list(_progress(pool.map(run, jobs), len(jobs), f"XFOIL {label} (first use; cached)"))
        kept = [p for p in polars if p is not None and p.alpha_deg.size >= MIN_POINTS]
        if len(kept) < len(polars):
            thin = [f"Re={r:g} M={m:g}" for (m, r), p in zip(jobs, polars)
                    if p is None or p.alpha_deg.size < MIN_POINTS]
            warnings.warn(f"XFOIL {label}: fewer than {MIN_POINTS} converged angles at {', '.join(thin)}; "
                          "those tables are left out", RuntimeWarning, stacklevel=4)
        if not kept:
            raise RuntimeError(f"XFOIL {label}: no table with {MIN_POINTS} or more converged angles")
        return kept

    return _cached_polars("xfoil", airfoil, settings, generate)


def neuralfoil_polars(airfoil, reynolds=DEFAULT_REYNOLDS, alpha_deg=DEFAULT_ALPHA_DEG, model_size="large",
                      ncrit=9.0):
    """NeuralFoil polars of a NACA designation or coordinates file, cached like :func:`xfoil_polars`.

    Raises
    ------
    ImportError
        NeuralFoil is not installed (``pip install bild-mdo[neuralfoil]``).
    """
    from bild_mdo.airfoil.sources.neuralfoil import run_neuralfoil

    settings = {"reynolds": [float(r) for r in reynolds], "alpha_deg": np.asarray(alpha_deg, dtype=float),
                "model_size": str(model_size), "ncrit": float(ncrit)}
    return _cached_polars("neuralfoil", airfoil, settings,
                          lambda spec, label: run_neuralfoil(spec, reynolds, alpha_deg, model_size, ncrit))
