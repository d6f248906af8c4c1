"""A sweep under failure: damaged rows, a full disk, cases that cannot be set up, warnings from workers."""
import functools
import io
import warnings

import pytest

from bild_mdo.verification import ResultsStore, SweepSpec, run_sweep
from bild_mdo.verification.cases import CaseSetupError
from bild_mdo.verification.store import StoreFullError
from tests.verification import standins

SPEC = SweepSpec(levels=2)
ALL_IDS = set(range(16))


def _ids_once(path):
    with ResultsStore(path, SPEC, writer=False) as store:
        ids = [row["case_id"] for row in store.rows()]
    assert len(ids) == len(set(ids))
    return set(ids)


def test_workers_checked_before_the_store_exists(tmp_path):
    for workers in (0, -3, 1.5, True):
        with pytest.raises(ValueError, match="workers must be an integer >= 1"):
            run_sweep(SPEC, tmp_path / "s.sqlite", standins.bild_batch, standins.optimize, workers=workers,
                      progress=False)
    assert not (tmp_path / "s.sqlite").exists()


def test_damaged_row_is_recomputed_with_a_warning(tmp_path):
    path = tmp_path / "s.sqlite"
    run_sweep(SPEC, path, standins.bild_batch, standins.optimize, progress=False)
    with ResultsStore(path, SPEC) as store:
        before = {r["case_id"]: r for r in store.rows()}
        # Damage behind the store's back: a value changed without its checksum.
        with store._conn:
            store._conn.execute("UPDATE results SET opt_energy_loss = 1.0 WHERE case_id IN (5, 9)")
    with pytest.warns(RuntimeWarning, match=r"2 stored cases of .* failed their checksum .* computed again: 5, 9"):
        result = run_sweep(SPEC, path, standins.bild_batch, standins.optimize, progress=False)
    assert sorted(result.computed_ids) == [5, 9] and result.recomputed_ids == [5, 9]
    assert _ids_once(path) == ALL_IDS
    with ResultsStore(path, SPEC) as store:
        assert store.damaged_ids() == []
        after = {r["case_id"]: r for r in store.rows()}
    assert after[5]["opt_energy_loss"] == before[5]["opt_energy_loss"]


def test_full_disk_stops_the_sweep_and_the_resume_completes(tmp_path, monkeypatch):
    path = tmp_path / "s.sqlite"
    write = ResultsStore.write

    def filling(store, row):
        if store.count() == 6:
            # SQLite's page limit on this connection stands in for a disk that fills up.
            pages = store._conn.execute("PRAGMA page_count").fetchone()[0]
            store._conn.execute(f"PRAGMA max_page_count = {pages}").fetchall()
        return write(store, row)

    monkeypatch.setattr(ResultsStore, "write", filling)
    with pytest.raises(StoreFullError, match="is full") as info:
        run_sweep(SPEC, path, standins.bild_batch, standins.optimize, workers=2, progress=False)
    assert "\n" not in str(info.value)
    kept = _ids_once(path)
    assert 6 <= len(kept) < 16
    monkeypatch.setattr(ResultsStore, "write", write)
    result = run_sweep(SPEC, path, standins.bild_batch, standins.optimize, progress=False)
    assert set(result.computed_ids) == ALL_IDS - kept
    assert _ids_once(path) == ALL_IDS


def test_cases_that_cannot_be_set_up_are_not_stored(tmp_path):
    path = tmp_path / "s.sqlite"
    missing = functools.partial(standins.optimize_setup_error, missing_ids=(2, 7))
    with pytest.raises(CaseSetupError, match=r"2 of 16 cases could not be set up and are not stored \(a rerun "
                                             r"retries them\); case 2: ImportError: stand-in optimiser"):
        run_sweep(SPEC, path, standins.bild_batch, missing, progress=False)
    assert _ids_once(path) == ALL_IDS - {2, 7}
    result = run_sweep(SPEC, path, standins.bild_batch, standins.optimize, progress=False)
    assert sorted(result.computed_ids) == [2, 7]
    assert _ids_once(path) == ALL_IDS


@pytest.mark.parametrize("workers", [1, 2])
def test_worker_warnings_reach_the_user_once(tmp_path, workers):
    stream = io.StringIO()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = run_sweep(SPEC, tmp_path / "s.sqlite", standins.bild_batch, standins.optimize_warning,
                           workers=workers, progress=stream)
    shown = [str(w.message) for w in caught if "stand-in clamp" in str(w.message)]
    assert len(shown) == 1 and result.warnings == shown
