"""Resume after a real SIGKILL of a running sweep; a second sweep on the same file while one runs."""
import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest

from bild_mdo.verification import ResultsStore, SweepSpec, run_sweep
from bild_mdo.verification.store import StoreBusyError
from tests.verification import standins

REPO_ROOT = Path(__file__).resolve().parents[2]
SPEC = SweepSpec(levels=3)
ALL_IDS = set(range(81))

SWEEP_SCRIPT = """
import functools, sys
from bild_mdo.verification import SweepSpec, run_sweep
from tests.verification import standins
run_sweep(SweepSpec(levels=3), sys.argv[1], standins.bild_batch, functools.partial(standins.optimize, sleep=0.05),
          workers=int(sys.argv[2]), progress=False)
"""


def _stored_ids(db):
    if not db.exists():
        return set()
    conn = sqlite3.connect(f"file:{db}?mode=ro", uri=True, timeout=5)
    try:
        return {r[0] for r in conn.execute("SELECT case_id FROM results")}
    except sqlite3.OperationalError:  # tables not created yet
        return set()
    finally:
        conn.close()


def _descendants(pid):
    parents = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                stat = Path(f"/proc/{entry}/stat").read_text()
            except OSError:
                continue
            parents[int(entry)] = int(stat.rsplit(")", 1)[1].split()[1])
    found, frontier = set(), {pid}
    while frontier:
        frontier = {child for child, parent in parents.items() if parent in frontier} - found
        found |= frontier
    return found


def _alive(pid):
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"


@pytest.mark.parametrize("workers", [1, 2])
def test_sigkill_then_resume_stores_every_case_once(tmp_path, workers):
    db = tmp_path / "sweep.sqlite"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [str(REPO_ROOT), os.environ.get("PYTHONPATH")])))
    proc = subprocess.Popen([sys.executable, "-c", SWEEP_SCRIPT, str(db), str(workers)], cwd=tmp_path, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
    try:
        deadline = time.monotonic() + 30
        while len(_stored_ids(db)) < 10:
            assert proc.poll() is None, proc.communicate()[1].decode()[-2000:]
            assert time.monotonic() < deadline, "the sweep stored no 10 rows within 30 s"
            time.sleep(0.05)
        helpers = _descendants(proc.pid)
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=10)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == -signal.SIGKILL
    if workers > 1:
        # Worker processes notice that the sweep process died and exit instead of lingering.
        assert helpers, "expected worker processes"
        deadline = time.monotonic() + 10
        while any(_alive(p) for p in helpers) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not any(_alive(p) for p in helpers)

    with ResultsStore(db, SPEC) as store:
        before = {r["case_id"]: r for r in store.rows()}
    # Killed part-way: some rows committed, not all.
    assert 10 <= len(before) < len(ALL_IDS)
    missing = ALL_IDS - set(before)

    bild_seen, optimize_seen = [], []

    def recording_bild(cases):
        bild_seen.extend(c.case_id for c in cases)
        return standins.bild_batch(cases)

    def recording_optimize(case, bild_result):
        optimize_seen.append(case.case_id)
        return standins.optimize(case, bild_result)

    result = run_sweep(SPEC, db, recording_bild, recording_optimize, workers=1, progress=False)
    # The resumed run computed only the missing cases, each once.
    assert sorted(bild_seen) == sorted(missing)
    assert sorted(optimize_seen) == sorted(missing)
    assert sorted(result.computed_ids) == sorted(missing) and result.num_skipped == len(before)

    conn = sqlite3.connect(db)
    (count, distinct), = conn.execute("SELECT COUNT(*), COUNT(DISTINCT case_id) FROM results").fetchall()
    conn.close()
    assert count == distinct == len(ALL_IDS)
    with ResultsStore(db, SPEC) as store:
        after = {r["case_id"]: r for r in store.rows()}
    assert set(after) == ALL_IDS
    # Rows committed before the kill are unchanged.
    for cid, row in before.items():
        assert after[cid]["finished_at"] == row["finished_at"]
        assert after[cid]["opt_power_coefficient"] == row["opt_power_coefficient"]


def test_second_sweep_on_the_same_file_exits_at_once_and_loses_nothing(tmp_path):
    db = tmp_path / "sweep.sqlite"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [str(REPO_ROOT), os.environ.get("PYTHONPATH")])))
    proc = subprocess.Popen([sys.executable, "-c", SWEEP_SCRIPT, str(db), "1"], cwd=tmp_path, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
    try:
        deadline = time.monotonic() + 30
        while len(_stored_ids(db)) < 5:
            assert proc.poll() is None, proc.communicate()[1].decode()[-2000:]
            assert time.monotonic() < deadline, "the sweep stored no 5 rows within 30 s"
            time.sleep(0.05)
        start = time.monotonic()
        with pytest.raises(StoreBusyError, match=f"another sweep is writing to '{db}'"):
            run_sweep(SPEC, db, _never_called, _never_called, progress=False)
        assert time.monotonic() - start < 5.0
        _out, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == 0, err.decode()[-2000:]
    again = run_sweep(SPEC, db, _never_called, _never_called, progress=False)
    assert again.computed_ids == [] and again.num_skipped == len(ALL_IDS)
    conn = sqlite3.connect(db)
    (count, distinct), = conn.execute("SELECT COUNT(*), COUNT(DISTINCT case_id) FROM results").fetchall()
    conn.close()
    assert count == distinct == len(ALL_IDS)


def _never_called(*args):
    raise AssertionError("the second sweep must not compute anything")
