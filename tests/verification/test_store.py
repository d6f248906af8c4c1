import json
import math
import random
import sqlite3

import numpy as np
import pytest

from bild_mdo.verification.cases import SweepSpec
from bild_mdo.verification.store import SCHEMA_VERSION, ResultsStore, StoreError

SPEC = SweepSpec(levels=2)


def _row(case_id, **extra):
    case = SPEC.case(case_id)
    row = {"case_id": case_id, **{k: v for k, v in case.inputs.items()}}
    row.update(
        bild_thrust_coefficient=0.1 + case_id, opt_thrust_coefficient=0.1 + case_id,
        bild_efficiency=float("nan"), opt_efficiency=None,
        bild_energy_loss=1234.5, opt_energy_loss=1300.0,
        bild_chord=np.array([0.1, 0.2, 0.3]), opt_chord=[0.11, 0.21, 0.31],
        bild_twist=[0.5, float("nan"), 0.1], opt_twist=None,
        bild_converged=True, converged=False, status="iteration limit", iterations=42,
        bild_time=0.01, opt_time=2.5, error=None,
    )
    row.update(extra)
    return row


def test_round_trip(tmp_path):
    path = tmp_path / "store.sqlite"
    with ResultsStore(path, SPEC) as store:
        assert store.count() == 0 and store.done_ids() == set()
        store.write(_row(3))
        store.write(_row(1, error="boom"))
        meta = store.meta()
    assert meta["schema_version"] == str(SCHEMA_VERSION)
    assert meta["sweep_fingerprint"] == SPEC.fingerprint()
    assert json.loads(meta["sweep_spec"])["levels"] == 2
    assert meta["created_at"].endswith("+00:00")
    # Reopening reads back what was committed.
    with ResultsStore(path, SPEC) as store:
        assert store.count() == 2
        assert store.done_ids() == {1, 3}
        rows = store.rows()
        journal = store._conn.execute("PRAGMA journal_mode").fetchone()[0]
    assert journal == "wal"
    assert [r["case_id"] for r in rows] == [1, 3]
    row = rows[1]
    assert row["advance_ratio"] == SPEC.case(3).inputs["advance_ratio"]
    assert row["airfoil"] == "naca4412" and row["num_radial"] == 30
    assert row["bild_thrust_coefficient"] == 3.1
    # NaN and None both read back as None (NULL).
    assert row["bild_efficiency"] is None and row["opt_efficiency"] is None
    np.testing.assert_array_equal(row["bild_chord"], [0.1, 0.2, 0.3])
    np.testing.assert_array_equal(row["opt_chord"], [0.11, 0.21, 0.31])
    assert math.isnan(row["bild_twist"][1]) and row["opt_twist"] is None
    assert row["bild_converged"] is True and row["converged"] is False
    assert (row["status"], row["iterations"], row["opt_time"]) == ("iteration limit", 42, 2.5)
    assert row["finished_at"] > 0
    assert rows[0]["error"] == "boom"


def test_each_case_once(tmp_path):
    with ResultsStore(tmp_path / "s.sqlite", SPEC) as store:
        store.write(_row(0))
        with pytest.raises(ValueError, match="case 0 is already stored"):
            store.write(_row(0))
        with pytest.raises(ValueError, match="unknown result columns"):
            store.write(_row(1, bogus=1))
        assert store.count() == 1


def test_empty_file_becomes_a_store(tmp_path):
    path = tmp_path / "empty.sqlite"
    path.write_bytes(b"")
    with ResultsStore(path, SPEC) as store:
        assert store.count() == 0


def test_random_bytes_are_refused(tmp_path):
    path = tmp_path / "junk.sqlite"
    path.write_bytes(random.Random(0).randbytes(8192))
    with pytest.raises(StoreError, match="not a usable bild-mdo results store.*Move the file away"):
        ResultsStore(path, SPEC)
    # The file is left as it was: never overwritten.
    assert path.read_bytes() == random.Random(0).randbytes(8192)


def test_damaged_store_is_refused(tmp_path):
    path = tmp_path / "damaged.sqlite"
    spec = SweepSpec(levels=4)
    with ResultsStore(path, spec) as store:
        for case_id in range(spec.num_cases):
            store.write({"case_id": case_id, "bild_converged": True, "converged": True,
                         "bild_chord": np.linspace(0, 1, 30), "opt_chord": np.linspace(0, 1, 30)})
        store._conn.execute("PRAGMA wal_checkpoint(TRUNCATE)")
    data = bytearray(path.read_bytes())
    assert len(data) > 5 * 4096
    # Overwrite the middle pages (b-tree pages of the results table), keep the header page.
    data[2 * 4096:4 * 4096] = random.Random(1).randbytes(2 * 4096)
    path.write_bytes(bytes(data))
    with pytest.raises(StoreError, match="damaged"):
        ResultsStore(path, spec)


def test_foreign_database_is_refused(tmp_path):
    path = tmp_path / "other.sqlite"
    conn = sqlite3.connect(path)
    conn.execute("CREATE TABLE users (name TEXT)")
    conn.commit()
    conn.close()
    with pytest.raises(StoreError, match=r"another program \(tables: \['users'\]\)"):
        ResultsStore(path, SPEC)
    conn = sqlite3.connect(path)
    assert conn.execute("SELECT name FROM sqlite_master").fetchall() == [("users",)]
    conn.close()


def test_store_of_a_different_sweep_is_refused(tmp_path):
    path = tmp_path / "s.sqlite"
    ResultsStore(path, SPEC).close()
    for other in (SweepSpec(levels=3), SweepSpec(levels=2, optimizer="ipopt")):
        with pytest.raises(StoreError, match="different sweep.*Use another --db file"):
            ResultsStore(path, other)
    assert issubclass(StoreError, ValueError)


def test_other_schema_version_is_refused(tmp_path):
    path = tmp_path / "s.sqlite"
    with ResultsStore(path, SPEC) as store:
        with store._conn:
            store._conn.execute("UPDATE meta SET value = '999' WHERE key = 'schema_version'")
    with pytest.raises(StoreError, match="schema version '999'"):
        ResultsStore(path, SPEC)
