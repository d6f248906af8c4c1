"""run_sweep with chunks of cases per task (optimize_chunk_fn): the same rows as one task per case.

Source of the expected rows: the same sweep run one case per task (the
chunking changes where cases run, never what is stored).
"""
import functools

from bild_mdo.verification import ResultsStore, SweepSpec, run_sweep
from bild_mdo.verification.cases import CaseSetupError
from tests.verification import standins
from tests.verification.test_runner import _comparable

import pytest

SPEC = SweepSpec(levels=2)


def _rows(path):
    with ResultsStore(path, SPEC) as store:
        return [_comparable(r) for r in store.rows()]


@pytest.mark.parametrize("workers, chunk_size", [(1, 5), (2, 3), (1, 100)])
def test_chunked_sweep_stores_the_rows_of_the_per_case_sweep(tmp_path, workers, chunk_size):
    run_sweep(SPEC, tmp_path / "a.sqlite", standins.bild_batch, standins.optimize, progress=False)
    result = run_sweep(SPEC, tmp_path / "b.sqlite", standins.bild_batch, standins.optimize, workers=workers,
                       progress=False, optimize_chunk_fn=standins.optimize_chunk, chunk_size=chunk_size)
    assert sorted(result.computed_ids) == list(range(16)) and result.num_failed == 4
    assert _rows(tmp_path / "a.sqlite") == _rows(tmp_path / "b.sqlite")


def test_chunked_sweep_resumes_case_by_case(tmp_path):
    path = tmp_path / "s.sqlite"
    run_sweep(SPEC, path, standins.bild_batch, standins.optimize, progress=False, case_ids=[0, 1, 2, 7])
    result = run_sweep(SPEC, path, standins.bild_batch, standins.optimize, progress=False,
                       optimize_chunk_fn=standins.optimize_chunk, chunk_size=4)
    assert result.num_skipped == 4 and sorted(result.computed_ids) == sorted(set(range(16)) - {0, 1, 2, 7})


def test_setup_errors_of_a_chunk_are_not_stored(tmp_path):
    path = tmp_path / "s.sqlite"
    chunk_fn = functools.partial(standins.optimize_chunk, missing_ids=frozenset({2, 9}))
    with pytest.raises(CaseSetupError, match="2 of 16 cases could not be set up"):
        run_sweep(SPEC, path, standins.bild_batch, standins.optimize, progress=False, optimize_chunk_fn=chunk_fn,
                  chunk_size=6)
    with ResultsStore(path, SPEC) as store:
        assert store.done_ids() == set(range(16)) - {2, 9}


def test_a_chunk_that_raises_fails_its_cases(tmp_path):
    path = tmp_path / "s.sqlite"
    result = run_sweep(SPEC, path, standins.bild_batch, standins.optimize, progress=False,
                       optimize_chunk_fn=_raising_chunk, chunk_size=8)
    assert result.num_failed == 16
    with ResultsStore(path, SPEC) as store:
        rows = store.rows()
    assert all(r["status"] == "exception" and "chunk stand-in" in r["error"] for r in rows)


def _raising_chunk(payloads):
    raise RuntimeError("chunk stand-in failure")
