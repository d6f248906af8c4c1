import sys
import types

import pytest

from bild_mdo.verification import SweepSpec, run_sweep
from bild_mdo.verification.executors import run_tasks
from tests.verification import standins


def test_in_process_runs_in_order_and_propagates():
    tasks = [("a", ("A", 0.0)), ("b", ("B", 0.0))]
    assert list(run_tasks(standins.sleep_echo, tasks, workers=1)) == [("a", "A", None), ("b", "B", None)]
    with pytest.raises(TypeError):
        list(run_tasks(standins.sleep_echo, [("x", None)], workers=1))


def test_process_pool_yields_in_completion_order(tmp_path):
    # The first task cannot finish before this process has received a result: it waits for a file
    # created only then.  So with two workers the second task's result must come back first.  (A file
    # created by the second task itself left a race: the first could return before the second's
    # result reached this process.)
    marker = str(tmp_path / "first-result-received")
    tasks = [("slow", ("S", marker, None)), ("fast", ("F", None, None))]
    results = run_tasks(standins.echo_after_file, tasks, workers=2)
    first = next(results)
    open(marker, "w").close()
    assert [first, *results] == [("fast", "F", None), ("slow", "S", None)]


def test_exceptions_in_workers_are_reported_not_raised():
    results = dict((k, (v, e)) for k, v, e in run_tasks(standins.sleep_echo, [("x", None), ("y", (1, 0))], workers=2))
    assert results["y"] == (1, None)
    assert results["x"][0] is None and results["x"][1].startswith("TypeError:")


def test_workers_that_cannot_import_the_function_fail_clearly(tmp_path, monkeypatch):
    # A module that exists only in this process: it pickles by reference, but workers cannot import it.
    ghost = types.ModuleType("bild_h6_ghost_module")
    exec("def optimize(case, bild_result):\n    return {'converged': False}\n", ghost.__dict__)
    monkeypatch.setitem(sys.modules, ghost.__name__, ghost)
    with pytest.raises(RuntimeError, match="worker processes cannot load.*ModuleNotFoundError.*importable"):
        run_sweep(SweepSpec(levels=2), tmp_path / "s.sqlite", standins.bild_batch, ghost.optimize, workers=2,
                  progress=False)


def test_invalid_workers():
    with pytest.raises(ValueError, match="workers must be >= 1"):
        run_tasks(standins.sleep_echo, [], workers=0)


def test_worker_processes_solve_on_one_thread_each():
    # The workers share the cores already: unless the environment says otherwise, their compiled solves use one
    # thread each (bild_mdo.utils.compiled.num_threads).
    import os

    expected = os.environ.get("BILD_MDO_NUM_THREADS", "1")
    results = list(run_tasks(standins.thread_setting, [(0, 0), (1, 1)], workers=2))
    assert sorted(value for _, value, _ in results) == [expected, expected]
