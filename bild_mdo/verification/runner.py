"""Run the verification sweep: BILD for every case in one batch, then one optimisation per case.

The science is plugged in through two functions:

``bild_batch_fn(cases) -> list of dict``
    Vectorised BILD for a list of :class:`~bild_mdo.verification.cases.Case`;
    one dict per case with the keys of
    :data:`~bild_mdo.verification.store.RESULT_KEYS` (``thrust_coefficient``,
    ``torque_coefficient``, ``power_coefficient``, ``efficiency``,
    ``figure_of_merit``, ``energy_loss`` in W, ``chord`` in m and ``twist`` in rad
    as 1-D arrays; ``efficiency`` may be None/NaN at J = 0 and
    ``figure_of_merit`` for J > 0).  Optional keys: ``converged`` (default True),
    ``error`` (text, when not converged) and ``run_time`` (s; by default the
    batch time divided by the number of cases).  Any other keys (the thrust
    target, say) are passed on to ``optimize_fn`` untouched.
``optimize_fn(case, bild_result) -> dict``
    The reference BEM optimisation of one case, using ``case.optimizer``;
    returns the same result keys plus ``converged`` (bool, required),
    ``status`` (text), ``iterations`` (int) and optionally ``run_time`` (s; by
    default the wall time of the call, measured in the worker).

Both must be module-level functions (picklable) to run in worker processes or
on a Dask cluster.

A case whose optimisation could not even be set up (:class:`CaseSetupError`,
or an ImportError: a missing optimiser) is not stored, so a rerun retries it;
:func:`run_sweep` raises one error counting such cases after the others ran.
Warnings raised while a case runs, in this process or in a worker, are
collected and shown once per sweep (:mod:`~bild_mdo.verification.warning_relay`).
"""
import functools
import os
import sys
import time
import traceback
import warnings
from dataclasses import dataclass, field

import numpy as np

from .cases import CaseSetupError, check_workers
from .executors import check_picklable, connect_dask, run_tasks
from .report import progress_bar, default_db_path, format_duration, sweep_summary, verification_table  # noqa: F401
from .starts import START_COLUMNS
from .store import INPUT_COLUMNS, RESULT_ARRAYS, RESULT_KEYS, ResultsStore
from .warning_relay import WarningRelay, recorded_warnings

ERROR_TEXT_LIMIT = 4000

#: Cases per task of a chunked optimisation (run_sweep's optimize_chunk_fn).  Several lockstep batches
#: (64 cases) per chunk: the cases that need many iterations then run beside new cases instead of in a
#: batch of their own at the end of every chunk; a chunk is still only 10-20 s of work to lose to an interrupt.
DEFAULT_CHUNK_SIZE = 256


@dataclass
class SweepResult:
    """What one call of :func:`run_sweep` did.

    Attributes
    ----------
    db_path : str
        The results store.
    num_cases : int
        Cases in the sweep (or in the requested subset).
    num_skipped : int
        Cases already stored before this call (resume).
    computed_ids : list of int
        Cases computed and stored by this call, in completion order.
    num_failed : int
        Of those, cases whose optimisation (or BILD) did not converge or raised.
    setup_errors : dict
        Case id -> error text of cases not run because of a set-up error (not stored).
    recomputed_ids : list of int
        Stored cases whose row failed its checksum; they were deleted and computed again.
    warnings : list of str
        The distinct warnings shown during the sweep.
    bild_batch_time : float
        Wall time of the batched BILD call (s).
    wall_time : float
        Wall time of the whole call (s).
    """

    db_path: str
    num_cases: int
    num_skipped: int
    computed_ids: list = field(default_factory=list)
    num_failed: int = 0
    setup_errors: dict = field(default_factory=dict)
    recomputed_ids: list = field(default_factory=list)
    warnings: list = field(default_factory=list)
    bild_batch_time: float = 0.0
    wall_time: float = 0.0


def _error_text(exc):
    text = "".join(traceback.format_exception(type(exc), exc, exc.__traceback__))
    # Keep the end of long tracebacks: the raising frame and message are there.
    return text if len(text) <= ERROR_TEXT_LIMIT else "..." + text[-ERROR_TEXT_LIMIT:]


def _clean_result(result, require_values):
    """Check one result dict and convert arrays to lists of float; returns (dict, error text)."""
    if not isinstance(result, dict):
        return None, f"expected a dict of results, got {type(result).__name__}"
    missing = [key for key in RESULT_KEYS if key not in result]
    if require_values and missing:
        return None, f"converged result lacks keys {missing}"
    clean = dict(result)
    for key in RESULT_ARRAYS:
        if clean.get(key) is not None:
            arr = np.asarray(clean[key], dtype=float)
            if arr.ndim != 1:
                return None, f"'{key}' must be a 1-D distribution, got shape {arr.shape}"
            clean[key] = arr.tolist()
    return clean, None


def optimize_task(optimize_fn, payload):
    """Run one optimisation in a worker: time it and turn exceptions into an error report.

    Parameters
    ----------
    optimize_fn : callable
        ``optimize_fn(case, bild_result) -> dict``.
    payload : tuple
        ``(case, bild_result)``.

    Returns
    -------
    dict
        ``{'result': dict or None, 'error': str or None, 'run_time': float,
        'setup_error': bool, 'warnings': list}``; ``setup_error`` marks a case
        that could not be set up (not to be stored), ``warnings`` holds the
        warnings the case raised as ``(category, message, filename, lineno)``.
    """
    with recorded_warnings() as caught:
        outcome = _optimize_outcome(optimize_fn, payload)
    outcome["warnings"] = caught
    return outcome


def optimize_chunk_task(optimize_chunk_fn, payloads):
    """Run a chunk of optimisations in a worker: :func:`optimize_task` for many cases in one call.

    Parameters
    ----------
    optimize_chunk_fn : callable
        ``optimize_chunk_fn(list of (case, bild_result)) -> list`` with, per
        case, a result dict or the exception of that case.
    payloads : list of tuple
        ``(case, bild_result)`` per case.

    Returns
    -------
    list of dict
        Per case, what :func:`optimize_task` returns; ``run_time`` is the
        chunk's wall time divided by its cases, and the chunk's warnings come
        with the first case.
    """
    with recorded_warnings() as caught:
        start = time.perf_counter()
        try:
            results = list(optimize_chunk_fn(payloads))
            if len(results) != len(payloads):
                raise ValueError(f"optimize_chunk_fn returned {len(results)} results for {len(payloads)} cases")
        except Exception as exc:  # the chunk's error is every case's error
            results = [exc] * len(payloads)
        share = (time.perf_counter() - start) / max(1, len(payloads))
        outcomes = [_outcome(result, share) for result in results]
    for k, outcome in enumerate(outcomes):
        outcome["warnings"] = caught if k == 0 else []
    return outcomes


def _optimize_outcome(optimize_fn, payload):
    case, bild_result = payload
    start = time.perf_counter()
    try:
        result = optimize_fn(case, bild_result)
    except Exception as exc:
        result = exc
    return _outcome(result, time.perf_counter() - start)


def _outcome(result, run_time):
    if isinstance(result, (CaseSetupError, ImportError)):
        return {"result": None, "error": f"{type(result).__name__}: {result}", "run_time": run_time,
                "setup_error": True}
    if isinstance(result, Exception):
        return {"result": None, "error": _error_text(result), "run_time": run_time}
    converged = isinstance(result, dict) and bool(result.get("converged", False))
    if isinstance(result, dict) and "converged" not in result:
        return {"result": None, "error": "optimize_fn result lacks the 'converged' flag", "run_time": run_time}
    clean, problem = _clean_result(result, require_values=converged)
    if problem:
        return {"result": None, "error": f"optimize_fn: {problem}", "run_time": run_time}
    return {"result": clean, "error": None, "run_time": run_time}


def _base_row(case, bild, bild_time):
    row = {"case_id": case.case_id}
    for name, _kind in INPUT_COLUMNS:
        row[name] = case.inputs[name]
    for key in RESULT_KEYS:
        row[f"bild_{key}"] = bild.get(key)
    row["bild_converged"] = bool(bild.get("converged", True))
    row["bild_time"] = bild_time
    return row


def _finish_row(row, outcome, error):
    """Fill the optimisation columns from a task outcome (or an executor error)."""
    if error is not None:
        row.update(converged=False, status="worker failure", error=error)
        return row
    row["opt_time"] = outcome["run_time"]
    if outcome["error"] is not None:
        row.update(converged=False, status="exception", error=outcome["error"])
        return row
    result = outcome["result"]
    for key in RESULT_KEYS:
        row[f"opt_{key}"] = result.get(key)
    row["converged"] = bool(result["converged"])
    row["status"] = None if result.get("status") is None else str(result["status"])
    row["iterations"] = result.get("iterations")
    row.update({key: result.get(key) for key in START_COLUMNS})
    if result.get("run_time") is not None:
        row["opt_time"] = float(result["run_time"])
    return row


def _bild_results(bild_batch_fn, cases):
    start = time.perf_counter()
    results = list(bild_batch_fn(cases))
    elapsed = time.perf_counter() - start
    if len(results) != len(cases):
        raise ValueError(f"bild_batch_fn returned {len(results)} results for {len(cases)} cases")
    per_case = elapsed / len(cases)
    cleaned = []
    for case, result in zip(cases, results):
        converged = isinstance(result, dict) and bool(result.get("converged", True))
        clean, problem = _clean_result(result, require_values=converged)
        if problem:
            raise ValueError(f"bild_batch_fn, case {case.case_id}: {problem}")
        run_time = clean.get("run_time")
        # optimize_fn gets the result as the model returned it; the store gets the checked copy.
        cleaned.append((result, clean, per_case if run_time is None else float(run_time)))
    return cleaned, elapsed


def run_sweep(spec, db_path, bild_batch_fn, optimize_fn, workers=1, scheduler=None, progress=True, case_ids=None,
              optimize_chunk_fn=None, chunk_size=DEFAULT_CHUNK_SIZE):
    """Run (or resume) a verification sweep into an SQLite results store.

    Cases already in the store are skipped; stored rows that fail their
    checksum are deleted and computed again (with a warning naming them).
    BILD runs once for all remaining cases (one batched call); then
    ``optimize_fn`` runs per case through the chosen executor and each row is
    committed as soon as its case returns.  An optimisation that raises is
    stored with ``converged=False`` and the error text; it never stops the
    sweep.  A case that fails to set up is not stored (see the module docstring).

    Parameters
    ----------
    spec : SweepSpec
        The sweep.
    db_path : str or os.PathLike
        Results store; created if missing, resumed if it holds this sweep.
    bild_batch_fn : callable
        ``bild_batch_fn(list of Case) -> list of dict`` (see the module docstring).
    optimize_fn : callable
        ``optimize_fn(case, bild_result) -> dict``; module-level unless ``workers=1``.
    workers : int
        1 runs in this process, more uses that many local worker processes
        (a script calling this must then guard the call with
        ``if __name__ == '__main__':``).
    scheduler : str or dask.distributed.Client, optional
        Dask scheduler address (``'tcp://host:port'``); overrides ``workers``.
    progress : bool or file-like
        Progress report to stderr (True), to the given stream, or none (False).
    case_ids : iterable of int, optional
        Only these cases (default: the whole sweep).
    optimize_chunk_fn : callable, optional
        ``optimize_chunk_fn(list of (case, bild_result)) -> list`` (a result
        dict or an exception per case): optimises chunks of up to
        ``chunk_size`` cases per task instead of ``optimize_fn`` per case
        (fewer for local workers when the cases would not fill them all;
        every n-th case per chunk); the rows of a chunk are stored when it returns.
    chunk_size : int
        Cases per task of ``optimize_chunk_fn``.

    Returns
    -------
    SweepResult

    Raises
    ------
    ValueError
        If ``workers`` is not an integer >= 1 (before the store is opened).
    StoreError
        If ``db_path`` is not a results store of this sweep, cannot be written,
        or the disk fills up (``StoreFullError``: the rows stored so far stay,
        a rerun resumes); ``StoreBusyError`` if another sweep writes to it.
    CaseSetupError
        After the sweep, if cases could not be set up (they are not stored).
    """
    start = time.perf_counter()
    if scheduler is None:
        workers = check_workers(workers)
    cases = spec.cases(case_ids)
    stream = None if progress is True else progress
    task_fn = functools.partial(optimize_task, optimize_fn)
    if optimize_chunk_fn is not None:
        task_fn = functools.partial(optimize_chunk_task, optimize_chunk_fn)
    relay = WarningRelay()
    # Executor problems surface before the store file exists and before the BILD batch: a refused cluster
    # leaves nothing behind.
    client, owned = None, False
    if scheduler is not None:
        check_picklable(task_fn, "a Dask cluster")
        client, owned = connect_dask(scheduler)
    elif workers != 1:
        check_picklable(task_fn, "worker processes")
    try:
        with ResultsStore(db_path, spec) as store:
            damaged = store.damaged_ids()
            if damaged:
                store.drop(damaged)
                shown = ", ".join(str(cid) for cid in damaged[:10]) + (" ..." if len(damaged) > 10 else "")
                warnings.warn(f"{len(damaged)} stored cases of '{os.fspath(db_path)}' failed their checksum (damaged "
                              f"on disk) and are computed again: {shown}", RuntimeWarning, stacklevel=2)
            done = store.done_ids()
            remaining = [case for case in cases if case.case_id not in done]
            result = SweepResult(db_path=os.fspath(db_path), num_cases=len(cases),
                                 num_skipped=len(cases) - len(remaining),
                                 recomputed_ids=sorted(set(damaged) & {c.case_id for c in remaining}))
            if remaining:
                chunk = None
                if optimize_chunk_fn is not None:
                    share = -(-len(remaining) // workers) if client is None else len(remaining)
                    chunk = max(1, min(int(chunk_size), share))
                _compute(store, remaining, bild_batch_fn, task_fn, workers, client, progress, stream, result, relay,
                         chunk)
    finally:
        if owned:
            client.close()
    result.warnings = relay.shown
    result.wall_time = time.perf_counter() - start
    if result.setup_errors:
        ids = sorted(result.setup_errors)
        first = " ".join(result.setup_errors[ids[0]].split())
        raise CaseSetupError(
            f"{len(ids)} of {len(remaining)} cases could not be set up and are not stored (a rerun retries them); "
            f"case {ids[0]}: {first}")
    return result


def _compute(store, remaining, bild_batch_fn, task_fn, workers, client, progress, stream, result, relay, chunk):
    with recorded_warnings() as caught:
        bild, result.bild_batch_time = _bild_results(bild_batch_fn, remaining)
    relay.show(caught)
    if progress:
        print(f"BILD: {len(remaining)} cases in {result.bild_batch_time:.2f} s; {result.num_skipped} already stored",
              file=stream or sys.stderr)
    bar = progress_bar(len(remaining), stream) if progress else None
    try:
        with relay.above(bar):
            tasks, pending_rows = [], {}
            for case, (bild_result, bild_clean, bild_time) in zip(remaining, bild):
                row = _base_row(case, bild_clean, bild_time)
                if row["bild_converged"]:
                    pending_rows[case.case_id] = row
                    tasks.append((case.case_id, (case, bild_result)))
                else:
                    # Without a BILD design there is no thrust target for the optimisation.
                    row.update(converged=False, status="BILD failed",
                               error=str(bild_result.get("error") or "BILD did not converge"))
                    _store(store, row, result, bar)
            if chunk is not None:
                # Every count-th case per chunk: neighbouring cases of a sweep are alike (the same rotor size,
                # the same advance ratio), so striding spreads the hard ones over the chunks.
                count = -(-len(tasks) // chunk)
                tasks = [(tuple(key for key, _ in tasks[k::count]), [arg for _, arg in tasks[k::count]])
                         for k in range(count)]
            for key, outcome, error in run_tasks(task_fn, tasks, workers=workers, scheduler=client):
                if chunk is None:
                    key, outcome = (key,), [outcome]
                for case_id, case_outcome in zip(key, outcome if outcome is not None else [None] * len(key)):
                    _finish(store, pending_rows.pop(case_id), case_outcome, error, result, bar, relay)
    finally:
        if bar is not None:
            bar.close()


def _finish(store, row, outcome, error, result, bar, relay):
    if outcome is not None:
        relay.show(outcome.get("warnings", ()))
        if outcome.get("setup_error"):
            result.setup_errors[row["case_id"]] = outcome["error"]
            if bar is not None:
                bar.update()
            return
    _store(store, _finish_row(row, outcome, error), result, bar)


def _store(store, row, result, bar):
    store.write(row)
    result.computed_ids.append(row["case_id"])
    if not (row["converged"] and row["bild_converged"]):
        result.num_failed += 1
    if bar is not None:
        bar.update()
