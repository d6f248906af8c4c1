import json
import math
import random
import sqlite3
import struct

import numpy as np
import pytest

from bild_mdo.verification.cases import SweepSpec
from bild_mdo.verification.store import SCHEMA_VERSION, ResultsStore, StoreError, StoreFullError

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


def _double_offset(data, value):
    """Byte offset of the one big-endian IEEE double ``value`` in a file (SQLite stores REALs so)."""
    pattern = struct.pack(">d", value)
    assert data.count(pattern) == 1
    return data.index(pattern)


def test_row_damaged_on_disk_is_found_by_its_checksum(tmp_path):
    path = tmp_path / "s.sqlite"
    with ResultsStore(path, SPEC) as store:
        for case_id in range(6):
            store.write(_row(case_id, opt_energy_loss=1300.0 + 0.125 * case_id))
        assert store.damaged_ids() == []
        store._conn.execute("PRAGMA wal_checkpoint(TRUNCATE)")
    # Flip the lowest mantissa bit of case 4's stored E_opt: a valid SQLite file whose row no longer
    # holds what was written (the kind of damage SQLite's own integrity check cannot see).
    data = bytearray(path.read_bytes())
    offset = _double_offset(bytes(data), 1300.5) + 7
    data[offset] ^= 0x01
    path.write_bytes(bytes(data))
    with ResultsStore(path, SPEC) as store:
        assert store.damaged_ids() == [4]
        store.drop([4])
        assert store.done_ids() == {0, 1, 2, 3, 5} and store.damaged_ids() == []


def test_version_1_store_is_upgraded_with_checksums(tmp_path):
    path = tmp_path / "s.sqlite"
    with ResultsStore(path, SPEC) as store:
        store.write(_row(2))
        with store._conn:
            store._conn.execute("UPDATE meta SET value = '1' WHERE key = 'schema_version'")
            store._conn.execute("ALTER TABLE results DROP COLUMN checksum")
    with ResultsStore(path, SPEC) as store:
        assert store.meta()["schema_version"] == str(SCHEMA_VERSION)
        assert store.done_ids() == {2} and store.damaged_ids() == []


def test_full_disk_keeps_committed_rows(tmp_path):
    path = tmp_path / "s.sqlite"
    with ResultsStore(path, SPEC) as store:
        store.write(_row(0))
        # SQLite's page limit on this connection stands in for a full disk: the next page cannot be written.
        pages = store._conn.execute("PRAGMA page_count").fetchone()[0]
        store._conn.execute(f"PRAGMA max_page_count = {pages}")
        with pytest.raises(StoreFullError, match=r"disk holding the results store .* is full .*: the \d+ cases "
                                                 r"stored so far are kept; free some space and rerun"):
            for case_id in range(1, 16):
                store.write(_row(case_id, bild_chord=np.linspace(0.1, 0.3, 200)))
        kept = store.done_ids()
    with ResultsStore(path, SPEC) as store:
        assert store.done_ids() == kept and 0 in kept and store.damaged_ids() == []


def test_disk_full_when_creating(tmp_path, monkeypatch):
    def full(*args, **kwargs):
        raise sqlite3.OperationalError("database or disk is full")

    monkeypatch.setattr(ResultsStore, "_create", full)
    with pytest.raises(StoreFullError, match="is full"):
        ResultsStore(tmp_path / "s.sqlite", SPEC)


def test_reader_cannot_write(tmp_path):
    path = tmp_path / "s.sqlite"
    ResultsStore(path, SPEC).close()
    with ResultsStore(path, SPEC, writer=False) as store:
        with pytest.raises(ValueError, match="opened for reading"):
            store.write(_row(0))


def test_random_damage_is_found_or_refused(tmp_path):
    # Bit flips, overwritten and zeroed runs anywhere after the header: the store either refuses the file
    # with a StoreError or opens it, names the damaged rows, and every other row reads back as written.
    spec = SweepSpec(levels=3)
    base = tmp_path / "base.sqlite"
    with ResultsStore(base, spec) as store:
        for case_id in range(spec.num_cases):
            store.write({"case_id": case_id, "bild_converged": True, "converged": True, "status": "optimal",
                         "opt_energy_loss": 1000.0 + case_id, "bild_chord": np.linspace(0.1, 0.2, 30) + case_id})
        store._conn.execute("PRAGMA wal_checkpoint(TRUNCATE)")
        written = {r["case_id"]: (r["opt_energy_loss"], r["bild_chord"].tolist(), r["status"]) for r in store.rows()}
    data = base.read_bytes()
    rng = random.Random(2)
    refused = found = 0
    for trial in range(60):
        damaged = bytearray(data)
        start, length = rng.randrange(100, len(data) - 64), rng.randint(1, 64)
        if trial % 3 == 0:
            damaged[start] ^= 1 << rng.randrange(8)
        elif trial % 3 == 1:
            damaged[start:start + length] = rng.randbytes(length)
        else:
            damaged[start:start + length] = bytes(length)
        path = tmp_path / f"t{trial}.sqlite"
        path.write_bytes(bytes(damaged))
        try:
            with ResultsStore(path, spec) as store:
                bad = store.damaged_ids()
                store.drop(bad)
                rows = store.rows()
        except StoreError:
            refused += 1
            continue
        found += bool(bad)
        for row in rows:
            assert written[row["case_id"]] == (row["opt_energy_loss"], row["bild_chord"].tolist(), row["status"])
    assert refused > 0 and found > 0
