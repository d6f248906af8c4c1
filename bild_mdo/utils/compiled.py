"""Compiled per-element kernels: numba set-up and the scalar twin of the bracketed Newton solver.

Most of bild-mdo is whole-array NumPy.  A few solves make many small decisions
per element (which sheet of a load-path table, whether a bracket holds, when
to probe), where whole-array code spends its time on bookkeeping rather than
arithmetic; those run as numba-compiled loops over the elements instead
(:mod:`bild_mdo.bild.variants.local_point.kernels`).  This module

* points numba's on-disk cache of the package's compiled functions into its
  cache folder (:func:`bild_mdo.utils.cache_folder.cache_dir`, ``numba/<key>``)
  unless the user set ``NUMBA_CACHE_DIR``, so that compiling happens once per machine
  and never writes into the source tree.  The key hashes the source of every
  module in :data:`KERNEL_MODULES` and numba's version: numba checks only the
  file of a function itself, so a kernel would otherwise keep a stale copy of
  a changed kernel it calls from another file.  Numba is imported only by the
  modules that compile, so a design that does not need them never loads it;
* provides :func:`kernel`, the decorator of every compiled function
  (``nopython``, cached, NumPy's floating-point semantics: a division by zero
  gives inf, never an exception; LLVM may fuse a multiply and an add and multiply
  by a reciprocal, which changes round-off only: NaN, infinities and the sign of
  zero keep their meaning);
* provides :func:`run_in_threads`, which runs a compiled solve of many stations in chunks on several
  threads (:func:`num_threads`, the environment variable ``BILD_MDO_NUM_THREADS``), bit for bit the
  result of one call;
* provides :func:`bracketed_newton_for`, the algorithm of
  :func:`bild_mdo.utils.newton.bracketed_newton` for one element, step for
  step (the same Newton step, the same bisection fallback, the same
  convergence tests including ``quadratic_stop`` and ``xtol``), compiled for
  one residual function, for kernels that solve element by element.
"""
from __future__ import annotations

import hashlib
import math
import os
from importlib.metadata import version
from pathlib import Path

import numpy as np

from bild_mdo.utils.cache_folder import cache_dir

#: The modules of compiled functions (relative to the package), whose source keys the cache.
KERNEL_MODULES = ("utils/compiled.py", "bild/variants/local_point/kernels.py",
                  "bild/variants/local_point/paper_kernels.py", "bild/variants/local_point/sheet_solve.py",
                  "bild/variants/local_point/reference_kernel.py", "bild/variants/local_point/partials_kernel.py",
                  "bild/variants/local_point/prandtl_kernels.py",
                  "bild/variants/reynolds_exact/kernel.py", "bild/variants/local_paper/kernel.py", "bild/variants/paper/eta2.py",
                  "bild/variants/turbine/compiled.py")


def _cache_key():
    digest = hashlib.sha256(version("numba").encode())
    root = Path(__file__).resolve().parent.parent
    for name in KERNEL_MODULES:
        digest.update((root / name).read_bytes())
    return digest.hexdigest()[:16]


import numba  # noqa: E402
import numba.core.config  # noqa: E402

#: The folder of the compiled functions' cache (``NUMBA_CACHE_DIR`` where the user set it).
CACHE_FOLDER = os.environ.get("NUMBA_CACHE_DIR") or str(cache_dir() / "numba" / _cache_key())

_EPS = 2.220446049250313e-16


def kernel(function):
    """Compile ``function`` with numba (nopython, cached on disk in :data:`CACHE_FOLDER`, NumPy error model, the
    fast-math flags ``contract`` and ``arcp`` only)."""
    # Numba picks a function's cache folder when it is decorated, from its configuration (which another
    # library may have loaded already); it is set for these functions only.
    config = numba.core.config
    previous = config.CACHE_DIR
    config.CACHE_DIR = CACHE_FOLDER
    try:
        return numba.njit(cache=True, error_model="numpy", nogil=True, fastmath={"contract", "arcp"})(function)
    finally:
        config.CACHE_DIR = previous


@kernel
def _sign(value):
    if value > 0.0:
        return 1.0
    if value < 0.0:
        return -1.0
    return value  # 0.0, or NaN


def bracketed_newton_for(function):
    """The compiled bracketed Newton solver of one element for ``function`` (numba caches a function that calls
    a compiled function it receives as an argument only in memory, so each residual gets its own solver).

    ``function(x, state, params)`` returns ``(f, df/dx, scale)`` and may update the float array ``state``
    (the caller's record of its last trials); ``params`` holds its constants.  The solver,
    ``solve(state, params, lo, hi, f_lo, x0, max_iter, xtol)``, is
    :func:`~bild_mdo.utils.newton.bracketed_newton` (``quadratic_stop=True``, ``atol = 0``, ``x_scale = 1e-3``)
    for one element and returns ``(x, converged, residual, slope, iterations)`` as the fields of
    :class:`~bild_mdo.utils.newton.NewtonResult`.
    """

    def solve(state, params, lo, hi, f_lo, x0, max_iter, xtol):
        sign_lo = _sign(f_lo)
        x = 0.5 * (lo + hi)
        if (x0 - lo) * (x0 - hi) <= 0.0:
            x = x0
        if lo > hi:
            lo_w, hi_w, sign_w = hi, lo, -sign_lo
        else:
            lo_w, hi_w, sign_w = lo, hi, sign_lo
        f_prev = math.inf
        step_prev = 0.0
        fa = math.nan
        da = math.nan
        for count in range(1, max_iter + 2):
            fa, da, scale = function(x, state, params)
            if _sign(fa) == sign_w:
                lo_w = x
            else:
                hi_w = x
            step = fa / da
            abs_step = abs(step)
            roundoff = 4.0 * _EPS * max(abs(x), 1e-3)
            abs_f = abs(fa)
            at_root = abs_f <= 4.0 * _EPS * scale
            cube = abs_step * abs_step * abs_step
            small = (abs_step <= roundoff) or (cube <= 0.0625 * roundoff * step_prev * step_prev) or (
                cube <= xtol * step_prev * step_prev and abs_step * abs_step <= xtol)
            small_step = small and not at_root
            finite = math.isfinite(fa)
            if finite and (at_root or small_step or (hi_w - lo_w <= roundoff)):
                if small_step:
                    x = min(max(x - step, lo_w), hi_w)
                return x, True, fa, da, count
            if not finite:
                return x, False, fa, da, count
            newton = x - step
            bisect = not ((newton > lo_w) and (newton < hi_w)) or (abs_f > 0.5 * f_prev)
            f_prev = abs_f
            step_prev = 0.0 if bisect else abs_step
            x = 0.5 * (lo_w + hi_w) if bisect else newton
        return x, False, fa, da, max_iter + 1

    return kernel(solve)


#: Stations a thread of :func:`run_in_threads` gets at least (fewer, and the solve stays on the calling thread:
#: about 4 ms of work at 2 us a station, against some 0.1 ms to hand a chunk to a thread).
MIN_CHUNK = 2048


#: Environment variables in which MPI launchers give the number of ranks on this machine (Open MPI, MPICH and
#: Intel MPI) or in the whole run.
_MPI_RANKS = ("OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS", "OMPI_COMM_WORLD_SIZE", "PMI_SIZE")


def num_threads():
    """Threads a compiled solve of many stations may use: the environment variable ``BILD_MDO_NUM_THREADS``
    where it is set (1: never a thread), else the CPUs this process may run on, at most 8, shared among the
    MPI ranks of a run under ``mpirun`` (one each where they are as many as the CPUs)."""
    setting = os.environ.get("BILD_MDO_NUM_THREADS", "").strip()
    if setting:
        try:
            count = int(setting)
        except ValueError:
            count = 0
        if count < 1:
            raise ValueError(f"BILD_MDO_NUM_THREADS must be a whole number >= 1, not {setting!r}")
        return count
    try:
        available = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        available = os.cpu_count() or 1
    for name in _MPI_RANKS:
        ranks = os.environ.get(name, "").strip()
        if ranks.isdigit() and int(ranks) > 1:
            available //= int(ranks)
            break
    return max(1, min(available, 8))


#: The thread pools of :func:`run_in_threads`, by their number of threads.
_POOL = {}


def run_in_threads(solve, starts, count):
    """Call ``solve(begin, end)`` on chunks of the ``count`` stations, one per thread (:func:`num_threads`), each
    beginning at one of the sorted indices ``starts`` (where a solve may begin without changing any result: the
    first station of a design), and wait for all; one call on the calling thread where the stations are too few
    for two chunks of :data:`MIN_CHUNK`.  The compiled solves release the GIL (``nogil``), so the chunks run in
    parallel; each writes only its own stations, so the result is the one of a single call, bit for bit."""
    threads = min(num_threads(), count // MIN_CHUNK)
    bounds = [0]
    if threads > 1 and starts.size:
        targets = (np.arange(1, threads) * count) // threads
        bounds += [b for b in np.unique(starts[np.minimum(np.searchsorted(starts, targets), starts.size - 1)])
                   if 0 < b < count]
    bounds.append(count)
    chunks = list(zip(bounds[:-1], bounds[1:]))
    if len(chunks) == 1:
        solve(0, count)
        return
    pool = _POOL.get(len(chunks))
    if pool is None:
        from concurrent.futures import ThreadPoolExecutor

        pool = _POOL[len(chunks)] = ThreadPoolExecutor(len(chunks), thread_name_prefix="bild-mdo")
    for future in [pool.submit(solve, begin, end) for begin, end in chunks]:
        future.result()
