"""Several optimiser starts per case: the best converged optimum is the reference, and the spread between starts."""
import math

import numpy as np
import pytest

from bild_mdo.verification.cases import START_KINDS, SweepSpec
from bild_mdo.verification.starts import START_COLUMNS, combine_starts, start_spread
from bild_mdo.verification.statistics import format_table3, table3
from bild_mdo.verification.store import COLUMNS, ResultsStore, row_checksum


def _result(energy, twist, chord, converged=True):
    return {"energy_loss": energy, "twist": np.asarray(twist, dtype=float), "chord": np.asarray(chord, dtype=float),
            "converged": converged, "status": "ok" if converged else "iteration limit"}


def test_spread_by_hand():
    # Hand derivation: twists (3, 4) and (0, 4) are 3 apart; the best (E = 10) has |(3, 4)| = 5, so 3/5.
    # Chords (1, 0) and (0, 1): sqrt(2) apart over |(1, 0)| = 1.  Energies 10 and 12: (12 - 10)/10.
    spread = start_spread([_result(10.0, [3.0, 4.0], [1.0, 0.0]), _result(12.0, [0.0, 4.0], [0.0, 1.0])])
    assert spread["start_spread_twist"] == pytest.approx(0.6)
    assert spread["start_spread_chord"] == pytest.approx(math.sqrt(2.0))
    assert spread["start_spread_energy"] == pytest.approx(0.2)
    # One start: no spread.
    assert set(start_spread([_result(10.0, [3.0, 4.0], [1.0, 0.0])]).values()) == {0.0}


def test_best_converged_start_is_the_reference():
    starts = [_result(12.0, [0.5, 0.4], [0.1, 0.1]), _result(10.0, [0.52, 0.41], [0.12, 0.09]),
              _result(5.0, [0.9, 0.9], [0.3, 0.3], converged=False)]
    best = combine_starts(starts)
    # Invariant: the reference energy is the minimum over the converged starts; the unconverged one does not count.
    assert best["energy_loss"] == min(r["energy_loss"] for r in starts if r["converged"]) == 10.0
    assert (best["best_start"], best["starts_converged"]) == (2, 2)
    np.testing.assert_array_equal(best["twist"], starts[1]["twist"])
    assert all(best[key] >= 0.0 for key in START_COLUMNS[:3])
    assert best["start_spread_energy"] == pytest.approx(0.2)


def test_no_converged_start_keeps_the_first():
    error = ValueError("boom")
    assert combine_starts([error, None]) is error
    failed = combine_starts([None, _result(5.0, [1.0], [1.0], converged=False)])
    assert failed["converged"] is False and failed["starts_converged"] == 0 and failed["start_spread_twist"] is None
    # A later converged start is used when the first raised.
    assert combine_starts([error, _result(7.0, [1.0], [1.0])])["best_start"] == 2


def test_spec_options_and_fingerprints():
    base = SweepSpec(levels=3)
    prints = {base.fingerprint(), SweepSpec(levels=3, section_point="local").fingerprint(),
              SweepSpec(levels=3, starts=2).fingerprint(), SweepSpec(levels=3, section_point="local", starts=2)
              .fingerprint()}
    assert len(prints) == 4
    # At their defaults the new settings stay out of the fingerprint: stores made before them still resume.
    assert SweepSpec(levels=3, section_point="reference", starts=1).fingerprint() == base.fingerprint()
    assert "starts" not in base.to_dict() and SweepSpec(starts=3).to_dict()["starts"] == 3
    case = SweepSpec(levels=2, section_point="local", starts=3).case(5)
    assert (case.section_point, case.starts) == ("local", 3)
    with pytest.raises(ValueError, match="section point must be one of reference, local, got 'middle'"):
        SweepSpec(section_point="middle")
    for bad in (0, len(START_KINDS) + 1, 1.5, True):
        with pytest.raises(ValueError, match="starts must be an integer from 1 to 3"):
            SweepSpec(starts=bad)


def test_store_keeps_the_start_columns_and_table_reports_them(tmp_path):
    spec = SweepSpec(levels=2, starts=2)
    with ResultsStore(tmp_path / "s.sqlite", spec) as store:
        for case_id in range(3):
            case = spec.case(case_id)
            row = {"case_id": case_id, **case.inputs, "bild_converged": True, "converged": True,
                   "bild_energy_loss": 100.0, "opt_energy_loss": 99.0, "bild_twist": [0.5, 0.4],
                   "opt_twist": [0.5, 0.41], "bild_chord": [0.1, 0.1], "opt_chord": [0.1, 0.1]}
            row.update(start_spread_twist=0.01 * case_id, start_spread_chord=0.02, start_spread_energy=0.0,
                       starts_converged=2 if case_id else 1, best_start=1 + case_id % 2)
            store.write(row)
        assert store.damaged_ids() == []
        rows = store.rows()
    assert rows[2]["start_spread_twist"] == 0.02 and rows[1]["best_start"] == 2
    table = table3(rows)
    # Cases 1 and 2 compared two converged starts: twist spreads 1 % and 2 %.
    assert table.start_spread["num_cases"] == 2 and table.start_spread["num_single"] == 1
    assert table.start_spread["twist"] == pytest.approx((1.5, 2.0))
    assert "Start spread (mean over the 2 cases with >= 2 converged starts" in format_table3(table)
    # One start: no start columns, no line.
    for row in rows:
        row.update({key: None for key in START_COLUMNS})
    assert table3(rows).start_spread is None and "Start spread" not in format_table3(table3(rows))


def test_version_2_store_is_upgraded_and_its_rows_stay_intact(tmp_path):
    spec = SweepSpec(levels=2)
    path = tmp_path / "s.sqlite"
    with ResultsStore(path, spec) as store:
        store.write({"case_id": 1, **spec.case(1).inputs, "bild_converged": True, "converged": True})
        with store._conn:
            for name in START_COLUMNS:
                store._conn.execute(f"ALTER TABLE results DROP COLUMN {name}")
            store._conn.execute("UPDATE meta SET value = '2' WHERE key = 'schema_version'")
    with ResultsStore(path, spec) as store:
        assert store.meta()["schema_version"] == "3"
        assert store.damaged_ids() == [] and store.rows()[0]["best_start"] is None


def test_a_schema_2_row_keeps_its_checksum():
    # Old rows must stay valid after the upgrade: the start columns, empty, stay out of the checksum.  The
    # pinned value is what the schema-2 store code (commit 0dc3209, before the start columns) gave this row.
    old_columns = [(name, kind) for name, kind in COLUMNS if name not in START_COLUMNS]
    kinds = {"REAL": lambda k: 0.125 * (k + 1), "INTEGER": lambda k: k, "TEXT": lambda k: f"t{k}",
             "BLOB": lambda k: bytes([k % 256, 7])}
    row = [kinds[kind.split()[0]](k) for k, (_, kind) in enumerate(old_columns)]
    assert len(old_columns) == 36
    assert row_checksum(row + [None] * len(START_COLUMNS)) == "69596242adcbd50e"
