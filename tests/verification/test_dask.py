"""The sweep on a real dask.distributed LocalCluster with worker processes."""
import functools
import os
import sys

import pytest

from bild_mdo.verification import ResultsStore, SweepSpec, run_sweep
from bild_mdo.verification.executors import DASK_MISSING, _dask_results
from tests.verification import standins

SPEC = SweepSpec(levels=2)
# Stand-in failure pattern (standins.py): raises for id % 11 == 4, not converged for id % 7 == 3.
RAISING = {4, 15}
NOT_CONVERGED = {3, 10}


@pytest.fixture(scope="module")
def cluster_address(tmp_path_factory):
    distributed = pytest.importorskip("dask.distributed", reason="dask[distributed] is not installed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  worker_dashboard_address=None, silence_logs=50,
                                  local_directory=str(tmp_path_factory.mktemp("dask"))) as cluster:
        yield cluster.scheduler_address


def test_sweep_through_scheduler_address(tmp_path, cluster_address):
    db = tmp_path / "dask.sqlite"
    assert cluster_address.startswith("tcp://")
    slow = functools.partial(standins.optimize, sleep=0.02)
    result = run_sweep(SPEC, db, standins.bild_batch, slow, scheduler=cluster_address, progress=False)
    assert sorted(result.computed_ids) == list(range(16))
    # A second pass over the same store finds nothing left to do.
    again = run_sweep(SPEC, db, standins.bild_batch, slow, scheduler=cluster_address, progress=False)
    assert again.computed_ids == [] and again.num_skipped == 16
    with ResultsStore(db, SPEC) as store:
        rows = store.rows()
    assert [r["case_id"] for r in rows] == list(range(16))
    for row in rows:
        assert row["converged"] is (row["case_id"] not in RAISING | NOT_CONVERGED)
        if row["case_id"] in RAISING:
            assert "stand-in failure" in row["error"]
        else:
            assert row["opt_time"] >= 0.02  # the sleep ran on a worker and was timed there


def test_dask_tasks_solve_on_one_thread_each(cluster_address):
    # A Dask worker runs as many tasks side by side as it has threads: unless its environment says otherwise,
    # a task's compiled solves use one thread (bild_mdo.utils.compiled.num_threads).
    from bild_mdo.verification.executors import run_tasks

    expected = os.environ.get("BILD_MDO_NUM_THREADS", "1")  # the workers inherit this process's environment
    results = list(run_tasks(standins.thread_setting, [(0, 0), (1, 1)], scheduler=cluster_address))
    assert sorted(value for _, value, _ in results) == [expected, expected]


def test_chunked_sweep_through_scheduler_address(tmp_path, cluster_address):
    # Source: the same sweep run in this process, one case per task (chunking never changes a stored row).
    from tests.verification.test_runner import _comparable

    reference = run_sweep(SPEC, tmp_path / "a.sqlite", standins.bild_batch, standins.optimize, progress=False)
    result = run_sweep(SPEC, tmp_path / "b.sqlite", standins.bild_batch, standins.optimize, scheduler=cluster_address,
                       progress=False, optimize_chunk_fn=standins.optimize_chunk, chunk_size=5)
    assert sorted(result.computed_ids) == sorted(reference.computed_ids) == list(range(16))
    rows = []
    for db in ("a.sqlite", "b.sqlite"):
        with ResultsStore(tmp_path / db, SPEC) as store:
            rows.append([_comparable(r) for r in store.rows()])
    assert rows[0] == rows[1]


class KilledWorker(Exception):
    """Stands for distributed.KilledWorker (matched by name, as the executor does)."""


class FakeFuture:
    def __init__(self, fn, arg, dies):
        self.fn, self.arg, self.dies = fn, arg, dies

    def result(self):
        if self.dies:
            raise KilledWorker(f"task {self.arg} was on a worker that died")
        return self.fn(self.arg)

    def release(self):
        pass


class FakeClient:
    """A cluster where one task kills its worker and takes the tasks queued beside it down too."""

    def __init__(self, crashing, bystanders):
        self.crashing, self.bystanders = crashing, bystanders
        self.alone, self.closed = [], False

    def map(self, fn, args, key, pure):
        assert pure is False and len(set(key)) == len(key)
        return [FakeFuture(fn, a, a in self.crashing | self.bystanders) for a in args]

    def submit(self, fn, arg, key, pure):
        self.alone.append(arg)
        return FakeFuture(fn, arg, arg in self.crashing)

    def cancel(self, futures):
        pass

    def close(self):
        self.closed = True


def test_cases_killed_beside_a_crashing_one_are_rerun_alone():
    # Dask declares a task failed after its workers died too often, counting deaths against the tasks
    # queued on the same worker as well (seen on a LocalCluster); only the real crasher must fail.
    client = FakeClient(crashing={5}, bystanders={6})
    tasks = [(cid, cid) for cid in range(8)]
    results = {key: (value, error) for key, value, error in
               _dask_results(client, True, lambda x: 10 * x, tasks, as_completed=iter)}
    assert sorted(client.alone) == [5, 6]
    assert results[6] == (60, None)
    assert results[5][0] is None
    assert results[5][1].startswith("KilledWorker") and results[5][1].endswith("rerun alone on the cluster)")
    assert all(results[cid] == (10 * cid, None) for cid in range(8) if cid not in (5, 6))
    assert client.closed


def test_missing_dask_names_the_extra(tmp_path, monkeypatch):
    # A None entry in sys.modules makes the import fail as if dask were not installed.
    monkeypatch.setitem(sys.modules, "dask.distributed", None)
    with pytest.raises(ImportError, match=r"pip install bild-mdo\[dask\]") as info:
        run_sweep(SPEC, tmp_path / "s.sqlite", standins.bild_batch, standins.optimize,
                  scheduler="tcp://127.0.0.1:8786", progress=False)
    assert str(info.value) == DASK_MISSING
    # Refused before any work: no results store is left behind.
    assert not (tmp_path / "s.sqlite").exists()


def test_a_refused_scheduler_leaves_no_store(tmp_path, monkeypatch):
    def refuse(scheduler):
        raise OSError(f"Timed out trying to connect to {scheduler} after 30 s")

    monkeypatch.setattr("bild_mdo.verification.runner.connect_dask", refuse)
    with pytest.raises(OSError, match="Timed out trying to connect"):
        run_sweep(SPEC, tmp_path / "s.sqlite", standins.bild_batch, standins.optimize,
                  scheduler="tcp://127.0.0.1:1", progress=False)
    assert not (tmp_path / "s.sqlite").exists()
