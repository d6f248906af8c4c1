import functools
import io

import numpy as np
import pytest

from bild_mdo.verification import ResultsStore, SweepSpec, StoreError, run_sweep
from bild_mdo.verification.runner import format_duration, sweep_summary
from tests.verification import standins

SPEC = SweepSpec(levels=2)
ALL_IDS = set(range(16))
# Stand-in failure pattern (standins.py): raises for id % 11 == 4, not converged for id % 7 == 3.
RAISING = {4, 15}
NOT_CONVERGED = {3, 10}


def _rows(path, spec=SPEC):
    with ResultsStore(path, spec) as store:
        return store.rows()


def _comparable(row):
    """A row without its timings (the only fields that differ between executors)."""
    out = {}
    for key, value in row.items():
        if key in ("bild_time", "opt_time", "finished_at"):
            continue
        out[key] = value.tolist() if isinstance(value, np.ndarray) else value
    if out["error"]:
        out["error"] = out["error"].strip().splitlines()[-1]
    return out


def test_in_process_sweep_records_every_case_and_failures(tmp_path):
    path = tmp_path / "s.sqlite"
    result = run_sweep(SPEC, path, standins.bild_batch, standins.optimize, workers=1, progress=False)
    assert sorted(result.computed_ids) == sorted(ALL_IDS) and result.num_skipped == 0
    assert result.num_failed == len(RAISING | NOT_CONVERGED)
    rows = _rows(path)
    assert [r["case_id"] for r in rows] == sorted(ALL_IDS)
    for row in rows:
        cid = row["case_id"]
        assert row["bild_converged"] is True
        assert row["converged"] is (cid not in RAISING | NOT_CONVERGED)
        assert row["bild_time"] > 0 and row["opt_time"] >= 0
        if cid in RAISING:
            assert row["status"] == "exception"
            assert row["error"].strip().endswith(f"ValueError: stand-in failure in case {cid}")
            assert row["opt_thrust_coefficient"] is None
        else:
            assert row["error"] is None
            assert row["iterations"] == 10 + cid % 13
            # The stand-in optimum meets the BILD thrust exactly (its thrust_target).
            assert row["opt_thrust_coefficient"] == row["bild_thrust_coefficient"]
            assert len(row["opt_chord"]) == 30
        assert row["status"] == ("stand-in: iteration limit" if cid in NOT_CONVERGED else
                                 "exception" if cid in RAISING else "optimal")


def test_rerun_computes_nothing(tmp_path):
    path = tmp_path / "s.sqlite"
    run_sweep(SPEC, path, standins.bild_batch, standins.optimize, progress=False)
    calls = []

    def recording_bild(cases):
        calls.append(len(cases))
        return standins.bild_batch(cases)

    again = run_sweep(SPEC, path, recording_bild, standins.optimize, progress=False)
    assert again.computed_ids == [] and again.num_skipped == 16 and calls == []
    assert len(_rows(path)) == 16


def test_process_pool_matches_in_process(tmp_path):
    run_sweep(SPEC, tmp_path / "a.sqlite", standins.bild_batch, standins.optimize, workers=1, progress=False)
    slow = functools.partial(standins.optimize, sleep=0.01)
    result = run_sweep(SPEC, tmp_path / "b.sqlite", standins.bild_batch, slow, workers=2, progress=False)
    assert sorted(result.computed_ids) == sorted(ALL_IDS)
    assert [_comparable(r) for r in _rows(tmp_path / "a.sqlite")] == [_comparable(r) for r in _rows(tmp_path / "b.sqlite")]


def test_worker_crash_is_isolated_to_its_case(tmp_path):
    path = tmp_path / "s.sqlite"
    crashing = functools.partial(standins.optimize_crashing, crash_ids=frozenset({5}))
    result = run_sweep(SPEC, path, standins.bild_batch, crashing, workers=2, progress=False)
    assert sorted(result.computed_ids) == sorted(ALL_IDS)
    rows = {r["case_id"]: r for r in _rows(path)}
    assert rows[5]["converged"] is False and rows[5]["status"] == "worker failure"
    assert "worker process died while running this case alone" in rows[5]["error"]
    # Cases in flight with the crashing one were rerun, not blamed.
    for cid in ALL_IDS - {5} - RAISING - NOT_CONVERGED:
        assert rows[cid]["converged"] is True, cid


def test_case_subset_and_bild_failures(tmp_path):
    path = tmp_path / "s.sqlite"
    optimised = []

    def bild_failing_for_case_2(cases):
        out = standins.bild_batch(cases)
        for case, res in zip(cases, out):
            if case.case_id == 2:
                res.update(converged=False, error="ideal loading: no root of the quartic")
        return out

    def recording_optimize(case, bild_result):
        optimised.append(case.case_id)
        return standins.optimize(case, bild_result)

    result = run_sweep(SPEC, path, bild_failing_for_case_2, recording_optimize, case_ids=[0, 1, 2], progress=False)
    assert sorted(result.computed_ids) == [0, 1, 2]
    # Without a BILD design there is no thrust target: case 2 is stored, not optimised.
    assert sorted(optimised) == [0, 1]
    row = _rows(path)[2]
    assert (row["bild_converged"], row["converged"], row["status"]) == (False, False, "BILD failed")
    assert row["error"] == "ideal loading: no root of the quartic"


def test_plug_in_errors_are_clear(tmp_path):
    with pytest.raises(ValueError, match="returned 15 results for 16 cases"):
        run_sweep(SPEC, tmp_path / "a.sqlite", lambda cases: standins.bild_batch(cases)[1:], standins.optimize,
                  progress=False)

    def no_chord(cases):
        out = standins.bild_batch(cases)
        del out[0]["chord"]
        return out

    with pytest.raises(ValueError, match=r"case 0: converged result lacks keys \['chord'\]"):
        run_sweep(SPEC, tmp_path / "b.sqlite", no_chord, standins.optimize, progress=False)
    with pytest.raises(ValueError, match="not picklable.*module-level function"):
        run_sweep(SPEC, tmp_path / "c.sqlite", standins.bild_batch, lambda c, b: {}, workers=2, progress=False)
    # A run refused before any work leaves no store behind.
    assert not (tmp_path / "c.sqlite").exists()
    with pytest.raises(StoreError, match="different sweep"):
        run_sweep(SweepSpec(levels=3), tmp_path / "b.sqlite", standins.bild_batch, standins.optimize, progress=False)


def test_malformed_optimize_results_become_failed_rows(tmp_path):
    def sloppy(case, bild_result):
        if case.case_id == 0:
            return {"converged": True}
        if case.case_id == 1:
            return [1, 2]
        return {"converged": False}

    run_sweep(SPEC, tmp_path / "s.sqlite", standins.bild_batch, sloppy, case_ids=[0, 1, 2], progress=False)
    rows = _rows(tmp_path / "s.sqlite")
    assert "converged result lacks keys" in rows[0]["error"]
    assert "expected a dict of results, got list" in rows[1]["error"]
    # A non-converged result may omit the values.
    assert (rows[2]["converged"], rows[2]["error"], rows[2]["opt_efficiency"]) == (False, None, None)


def test_progress_goes_to_the_given_stream(tmp_path):
    stream = io.StringIO()
    result = run_sweep(SPEC, tmp_path / "s.sqlite", standins.bild_batch, standins.optimize, progress=stream)
    text = stream.getvalue()
    assert text.startswith("BILD: 16 cases in ") and text.splitlines()[0].endswith("s; 0 already stored")
    # Not a terminal: plain text (no bar redrawn in place), ending with the final count.
    final = text.replace("\r", "\n").rstrip().splitlines()[-1]
    assert final.startswith("optimise: 100%") and "16/16" in final
    assert sweep_summary(SPEC, tmp_path / "s.sqlite", result).startswith(
        f"Sweep of 16 cases in {tmp_path / 's.sqlite'}: 0 resumed, 16 computed in ")


def test_format_duration():
    assert [format_duration(s) for s in (None, float("nan"), 42.4, 185, 7620)] == ["?", "?", "42s", "3m05s", "2h07m"]
