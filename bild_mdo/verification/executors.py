"""Where the per-case optimisations run: in-process, local processes, or a Dask cluster.

Every backend takes ``fn`` and a list of ``(key, argument)`` tasks and yields
``(key, value, error)`` in completion order, so the caller can store each
result as soon as it exists.  ``error`` is None on success; otherwise it is the
text of a failure of the machinery itself (a worker process that died, a task
the cluster gave up on), and ``value`` is None.  Exceptions raised by ``fn``
propagate in-process and are reported as ``error`` by the parallel backends;
the runner's task wrapper catches the optimiser's own exceptions before that.

Local worker processes start from a fork server (spawn where there is none):
``fn`` must be importable in a fresh process, and a script that calls the
sweep must do so under ``if __name__ == '__main__':``.  On Dask, tasks wait
for workers: a cluster that has lost all its workers stalls the sweep until
workers join again (Dask's semantics); the rows stored so far stay valid.
"""
import functools
import multiprocessing
import os
import pickle
import threading
import uuid
from collections import deque
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool

DASK_MISSING = "running on a Dask cluster needs dask.distributed: pip install bild-mdo[dask]"

# Tasks queued per worker process: enough to keep workers busy, few enough that
# a crashing worker takes down only a handful of in-flight cases.
TASKS_PER_WORKER = 2


def run_tasks(fn, tasks, workers=1, scheduler=None):
    """Run ``fn(argument)`` for every task and yield results in completion order.

    Parameters
    ----------
    fn : callable
        Must be picklable (a module-level function, or a functools.partial of
        one) unless it runs in-process.
    tasks : list of (key, argument)
        Work items; ``key`` identifies the item in the output.
    workers : int
        1 runs in this process; more uses a ProcessPoolExecutor of that many processes.
        Ignored when ``scheduler`` is given.
    scheduler : str or dask.distributed.Client, optional
        Address of a Dask scheduler (``'tcp://host:port'``) or a connected client.

    Yields
    ------
    tuple
        ``(key, value, error)``.
    """
    tasks = list(tasks)
    if scheduler is not None:
        return _run_dask(fn, tasks, scheduler)
    workers = int(workers)
    if workers < 1:
        raise ValueError(f"workers must be >= 1, got {workers}")
    if workers == 1:
        return _run_inline(fn, tasks)
    return _run_processes(fn, tasks, workers)


def check_picklable(fn, where):
    """Raise a ValueError naming the fix when ``fn`` cannot be sent to ``where``."""
    try:
        pickle.dumps(fn)
    except Exception as exc:  # pickle raises several unrelated types
        raise ValueError(
            f"{getattr(fn, '__qualname__', fn)!r} cannot be sent to {where}: it is not picklable ({exc}). "
            "Pass a module-level function (or functools.partial of one), not a lambda or nested function."
        ) from exc


def _run_inline(fn, tasks):
    for key, arg in tasks:
        yield key, fn(arg), None


def _mp_context():
    # Forking a parent that runs threads (a Dask client, BLAS pools) can deadlock the
    # child; a fork server starts workers from a clean single-threaded process.
    if "forkserver" in multiprocessing.get_all_start_methods():
        return multiprocessing.get_context("forkserver")
    return multiprocessing.get_context("spawn")


def _one_thread_per_solve():
    """One thread per compiled solve unless the user set ``BILD_MDO_NUM_THREADS``: worker processes and Dask
    tasks already run side by side, one per core (:func:`bild_mdo.utils.compiled.num_threads`)."""
    os.environ.setdefault("BILD_MDO_NUM_THREADS", "1")


def _init_worker():
    """Worker initializer: :func:`_one_thread_per_solve` and :func:`_watch_parent`."""
    _one_thread_per_solve()
    _watch_parent()


def _watch_parent():
    """Exit when the sweep process is gone, so a killed sweep leaves no orphans."""
    parent = multiprocessing.parent_process()
    if parent is None:
        return

    def watch():
        # Returns once the parent's sentinel closes, i.e. the parent died.
        parent.join()
        os._exit(1)

    threading.Thread(target=watch, name="bild-parent-watch", daemon=True).start()


def _probe(pickled_fn):
    """Runs first in every new pool: proves workers start and can load ``fn``.

    ``fn`` comes as bytes so that a failure to load it is raised inside the task
    (and reported) instead of killing the worker while it reads its queue.
    """
    return pickle.loads(pickled_fn) is not None


def _start_pool(fn, workers):
    pool = ProcessPoolExecutor(max_workers=workers, mp_context=_mp_context(), initializer=_init_worker)
    try:
        pool.submit(_probe, pickle.dumps(fn)).result()
    except BrokenProcessPool as exc:
        pool.shutdown(wait=True, cancel_futures=True)
        raise RuntimeError(
            "worker processes could not start. If run_sweep is called from a script, put the call under "
            "`if __name__ == '__main__':` (workers re-import the main module); otherwise run with workers=1 "
            "to see the error in this process."
        ) from exc
    except Exception as exc:
        pool.shutdown(wait=True, cancel_futures=True)
        raise RuntimeError(
            f"worker processes cannot load {getattr(fn, '__qualname__', fn)!r}: {type(exc).__name__}: {exc}. "
            "Its module must be importable in a fresh Python process (installed, or on PYTHONPATH)."
        ) from exc
    return pool


def _run_processes(fn, tasks, workers):
    """Process pool with a sliding window and crash isolation.

    When a worker process dies (a segfault in a native optimiser, the OOM
    killer), the pool breaks and every in-flight task fails with it.  Those
    tasks are rerun one at a time in a fresh pool; the one that breaks the
    pool again while running alone is reported as failed, the others complete.
    """
    check_picklable(fn, "worker processes")
    pending = deque(tasks)
    suspects = deque()
    window = workers * TASKS_PER_WORKER
    while pending or suspects:
        pool = _start_pool(fn, workers)
        inflight = {}
        isolated = False
        broken = False
        try:
            while (pending or suspects or inflight) and not broken:
                try:
                    if suspects:
                        if not inflight:
                            task = suspects.popleft()
                            isolated = True
                            inflight[pool.submit(fn, task[1])] = task
                    else:
                        isolated = False
                        while pending and len(inflight) < window:
                            task = pending.popleft()
                            inflight[pool.submit(fn, task[1])] = task
                except BrokenProcessPool:
                    # The task whose submit failed never ran: queue it again.
                    (suspects if isolated else pending).appendleft(task)
                    broken = True
                    break
                done, _ = wait(list(inflight), return_when=FIRST_COMPLETED)
                for future in done:
                    error = future.exception()
                    if isinstance(error, BrokenProcessPool):
                        broken = True
                        continue
                    key, _arg = inflight.pop(future)
                    if error is None:
                        yield key, future.result(), None
                    else:
                        yield key, None, f"{type(error).__name__}: {error}"
            if broken:
                # Keep whatever finished before the break, then rerun the rest in isolation.
                lost = []
                for future, task in inflight.items():
                    if future.done() and future.exception() is None:
                        yield task[0], future.result(), None
                    else:
                        lost.append(task)
                if isolated and len(lost) == 1:
                    yield lost[0][0], None, (
                        "a worker process died while running this case alone (a crash or kill inside the "
                        "optimiser); the case was retried in isolation to make sure it is the cause"
                    )
                else:
                    suspects.extend(lost)
        finally:
            pool.shutdown(wait=True, cancel_futures=True)


def connect_dask(scheduler):
    """Connect to a Dask scheduler.

    Parameters
    ----------
    scheduler : str or dask.distributed.Client
        Address such as ``'tcp://host:8786'``, or a connected client (returned as is).

    Returns
    -------
    tuple
        ``(client, owned)``; ``owned`` is True when this call made the client
        (the caller closes it).
    """
    try:
        from dask.distributed import Client
    except ImportError as exc:
        raise ImportError(DASK_MISSING) from exc
    if isinstance(scheduler, Client):
        return scheduler, False
    return Client(check_scheduler_address(scheduler), timeout="30s"), True


def check_scheduler_address(scheduler):
    """The address text of a Dask scheduler, or ValueError in one line when it cannot be one."""
    address = str(scheduler)
    if ":" not in address:
        raise ValueError(f"scheduler must be an address like 'tcp://host:8786', got {address!r}")
    return address


def _one_thread_each(fn, argument):
    """``fn(argument)`` on a Dask worker, after :func:`_one_thread_per_solve` (a worker runs as many tasks side by
    side as it has threads)."""
    _one_thread_per_solve()
    return fn(argument)


def _run_dask(fn, tasks, scheduler):
    check_picklable(fn, "a Dask cluster")
    client, owned = connect_dask(scheduler)
    from dask.distributed import as_completed

    return _dask_results(client, owned, functools.partial(_one_thread_each, fn), tasks, as_completed)


def _dask_results(client, own_client, fn, tasks, as_completed):
    """Yield results in completion order; tasks killed with their worker are rerun alone at the end.

    Dask counts a worker death against every task that was assigned to that
    worker, so a case queued beside a crashing one can be declared failed
    (KilledWorker) too.  Rerunning such cases one at a time, with nothing else
    on the cluster, leaves only the case that really kills its worker failed.
    """
    futures = {}
    suspects = []
    # A token per run keeps keys apart from a previous run's leftovers on a shared scheduler.
    token = uuid.uuid4().hex[:8]
    try:
        if tasks:
            # Short task names: a chunk's key is the tuple of its case ids.
            keys = [f"bild-verify-{token}-{_key_text(key)}" for key, _ in tasks]
            submitted = client.map(fn, [arg for _, arg in tasks], key=keys, pure=False)
            futures = dict(zip(submitted, tasks))
        for future in as_completed(list(futures)):
            key, arg = futures.pop(future)
            try:
                value = future.result()
            except Exception as exc:  # KilledWorker, lost worker, unpicklable result ...
                if type(exc).__name__ == "KilledWorker":
                    suspects.append((key, arg))
                else:
                    yield key, None, f"{type(exc).__name__}: {exc}"
            else:
                yield key, value, None
            future.release()
        for key, arg in suspects:
            future = client.submit(fn, arg, key=f"bild-verify-{token}-{_key_text(key)}-alone", pure=False)
            futures = {future: (key, arg)}
            try:
                value = future.result()
            except Exception as exc:
                yield key, None, f"{type(exc).__name__}: {exc} (the case was rerun alone on the cluster)"
            else:
                yield key, value, None
            futures = {}
            future.release()
    finally:
        if futures:
            client.cancel(list(futures))
        if own_client:
            client.close()


def _key_text(key):
    """A task key as a short name: ``'17'`` for a case, ``'17+63'`` for a chunk of 64 cases from case 17."""
    if isinstance(key, tuple):
        return f"{key[0]}+{len(key) - 1}" if key else "empty"
    return str(key)
