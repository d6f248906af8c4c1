"""SQLite results store of a verification sweep: one row per case, committed at once.

The parent process is the only writer; workers return their results to it.
Each row is committed as soon as its case finishes, so a sweep that is killed
loses at most the cases that were running, and a rerun resumes from
:meth:`ResultsStore.done_ids`.  One sweep writes to a file at a time (an
advisory lock on the file); every row carries a checksum of its values, so a
row damaged on disk is found (:meth:`ResultsStore.damaged_ids`) and recomputed.  The database runs in WAL mode with
``synchronous=NORMAL``: a committed row survives a crash or kill of the process
(it could only be lost by a power cut of the machine).  WAL needs a local file
system; don't put the store on a network share.
"""
import datetime
import hashlib
import json
import math
import os
import sqlite3
import time

import numpy as np

from bild_mdo import __version__
from bild_mdo.bem.metrics import VERIFIED_METRICS

from .starts import START_COLUMNS
from .store_file import (StoreBusyError, StoreError, StoreFullError, acquire_writer_lock, check_store_path,
                         full_error, is_disk_full, operational_error)

# Version 2 added the per-row checksum, version 3 the start columns; an older store is upgraded when a sweep
# opens it.
SCHEMA_VERSION = 3
META_TABLE = "meta"
RESULTS_TABLE = "results"

# Per-method results, stored as columns bild_<key> and opt_<key>.  The result
# dicts that bild_batch_fn and optimize_fn return use the same keys.  The
# scalars are the verified metrics of the registry (paper Table 3).
RESULT_QUANTITIES = VERIFIED_METRICS
RESULT_ARRAYS = ("chord", "twist")
RESULT_KEYS = RESULT_QUANTITIES + RESULT_ARRAYS

INPUT_COLUMNS = (
    ("advance_ratio", "REAL"),
    ("radius", "REAL"),
    ("altitude", "REAL"),
    ("reference_chord", "REAL"),
    ("rpm", "REAL"),
    ("v_axial", "REAL"),
    ("reference_radius", "REAL"),
    ("hub_radius", "REAL"),
    ("num_blades", "INTEGER"),
    ("num_radial", "INTEGER"),
    ("airfoil", "TEXT"),
)
METHODS = ("bild", "opt")

COLUMNS = (
    (("case_id", "INTEGER PRIMARY KEY"),)
    + INPUT_COLUMNS
    + tuple((f"{m}_{q}", "REAL") for m in METHODS for q in RESULT_QUANTITIES)
    + tuple((f"{m}_{a}", "TEXT") for m in METHODS for a in RESULT_ARRAYS)
    + (
        ("bild_converged", "INTEGER NOT NULL"),
        ("converged", "INTEGER NOT NULL"),
        ("status", "TEXT"),
        ("iterations", "INTEGER"),
        ("bild_time", "REAL"),
        ("opt_time", "REAL"),
        ("error", "TEXT"),
        ("finished_at", "REAL"),
    )
    # Version 3: the comparison of the optimiser's starts (verify --starts), NULL with one start.
    + tuple((name, "INTEGER" if name in ("starts_converged", "best_start") else "REAL") for name in START_COLUMNS)
)
COLUMN_NAMES = tuple(name for name, _ in COLUMNS)
# SHA-256 of the row's values (every column above), checked when a sweep opens the store.
CHECKSUM_COLUMN = "checksum"
_KINDS = dict(COLUMNS)
_ARRAY_COLUMNS = frozenset(f"{m}_{a}" for m in METHODS for a in RESULT_ARRAYS)
_BOOL_COLUMNS = frozenset(("bild_converged", "converged"))


__all__ = ["ResultsStore", "StoreError", "StoreBusyError", "StoreFullError", "RESULT_KEYS", "SCHEMA_VERSION"]


def row_checksum(values):
    """Checksum of one row: 16 hex digits of the SHA-256 of its values in column order.

    Floats enter exactly (``float.hex``), so any change of a stored bit changes it.  A start column
    (version 3) enters only when it holds a value, so a version-2 row keeps its checksum.

    Parameters
    ----------
    values : sequence
        The stored values of :data:`COLUMN_NAMES`, in that order.

    Returns
    -------
    str
    """
    parts = []
    for (name, kind), value in zip(COLUMNS, values):
        if value is None and name in START_COLUMNS:
            continue
        if value is None:
            parts.append("N")
        elif kind == "REAL" and isinstance(value, (int, float)) and not isinstance(value, bool):
            parts.append("f" + float(value).hex())
        elif isinstance(value, int):
            parts.append(f"i{value}")
        elif isinstance(value, bytes):
            parts.append("b" + value.hex())
        else:
            parts.append("s" + json.dumps(str(value)))
    return hashlib.sha256("|".join(parts).encode()).hexdigest()[:16]


def _encode_array(value):
    if value is None:
        return None
    arr = np.asarray(value, dtype=float)
    if arr.ndim != 1:
        raise ValueError(f"chord/twist distributions must be 1-D, got shape {arr.shape}")
    # json writes NaN/Infinity tokens that json.loads reads back.
    return json.dumps(arr.tolist())


def _decode_array(text):
    if text is None:
        return None
    return np.asarray(json.loads(text), dtype=float)


def _decode_text(raw):
    return raw.decode("utf-8", "surrogateescape")


def _encode_real(value):
    if value is None:
        return None
    value = float(value)
    # SQLite stores NaN as NULL anyway; be explicit so rows read back the same.
    return None if math.isnan(value) else value


class ResultsStore:
    """Results of one sweep in an SQLite file.

    Opening creates the file (and its tables) when it does not exist or is an
    empty database; otherwise it checks that the file is a bild-mdo results
    store of the same schema version and the same sweep.  A writer (the
    default) holds the file's one-writer lock until :meth:`close`.

    Parameters
    ----------
    path : str or os.PathLike
        Database file.
    spec : SweepSpec
        The sweep this store belongs to; its fingerprint is stored in the meta
        table and compared on every later open.
    writer : bool
        Take the writer lock (needed by :meth:`write` and :meth:`drop`); a
        reader opens an existing store while a sweep writes to it.

    Raises
    ------
    StoreError
        If the path is a folder, its folder is missing or not writable, the
        disk is full, the file is not an SQLite database or is damaged,
        belongs to another program (other tables), has another schema
        version, or was made for a different sweep.
    StoreBusyError
        If ``writer`` and another sweep is writing to the file.
    """

    def __init__(self, path, spec, writer=True):
        self.path = os.fspath(path)
        self.spec = spec
        self.writer = bool(writer)
        self.fingerprint = spec.fingerprint()
        self._conn = None
        self._lock = None
        check_store_path(self.path)
        try:
            if self.writer:
                self._lock = acquire_writer_lock(self.path)
            self._conn = sqlite3.connect(self.path, timeout=30.0)
            # Text that is no longer UTF-8 (damaged on disk) reads back instead of raising; its row then
            # fails the checksum and is recomputed.
            self._conn.text_factory = _decode_text
            self._open()
        except sqlite3.OperationalError as exc:
            self.close()
            raise operational_error(self.path, exc) from exc
        except sqlite3.DatabaseError as exc:
            self.close()
            raise StoreError(
                f"'{self.path}' is not a usable bild-mdo results store: it is not an SQLite database or "
                f"it is damaged ({exc}). Move the file away or choose another path (--db); a new store is "
                "created when the file does not exist."
            ) from exc
        except BaseException:
            self.close()
            raise

    def _open(self):
        conn = self._conn
        tables = {r[0] for r in conn.execute("SELECT name FROM sqlite_master WHERE type='table'")}
        if not tables:
            if not self.writer:
                raise StoreError(f"'{self.path}' holds no results yet")
            self._create()
            return
        if META_TABLE not in tables or RESULTS_TABLE not in tables:
            raise StoreError(
                f"'{self.path}' is an SQLite database of another program (tables: {sorted(tables)}), "
                f"not a bild-mdo results store. Choose another path (--db) so it is not overwritten."
            )
        check = conn.execute("PRAGMA quick_check").fetchone()[0]
        if check != "ok":
            raise sqlite3.DatabaseError(f"integrity check failed: {check}")
        meta = dict(conn.execute(f"SELECT key, value FROM {META_TABLE}").fetchall())
        version = meta.get("schema_version")
        if version is None or "sweep_fingerprint" not in meta:
            raise sqlite3.DatabaseError(f"the meta table lacks its entries ({sorted(meta)})")
        # Checked before any upgrade: a store of another sweep is refused untouched.
        stored = meta.get("sweep_fingerprint")
        if stored != self.fingerprint:
            raise StoreError(
                f"'{self.path}' holds results of a different sweep (fingerprint {stored}, settings "
                f"{meta.get('sweep_spec')}); this run is fingerprint {self.fingerprint} with settings "
                f"{json.dumps(self.spec.to_dict(), sort_keys=True)}. Use another --db file for this sweep, "
                "or rerun with the settings the store was made with to resume it."
            )
        if version == "1" and self.writer:
            self._upgrade_from_1()
            self._upgrade_from_2()
        elif version == "2" and self.writer:
            self._upgrade_from_2()
        elif version != str(SCHEMA_VERSION):
            raise StoreError(
                f"'{self.path}' has results-store schema version {version!r}, this bild-mdo writes version "
                f"{SCHEMA_VERSION}. Start a new store (another --db path) or use the bild-mdo version that made it."
            )
        self._configure()

    def _configure(self):
        self._conn.execute("PRAGMA journal_mode=WAL")
        self._conn.execute("PRAGMA synchronous=NORMAL")

    def _create(self):
        self._configure()
        cols = ",\n  ".join(f"{name} {kind}" for name, kind in COLUMNS + ((CHECKSUM_COLUMN, "TEXT"),))
        meta = {
            "schema_version": str(SCHEMA_VERSION),
            "sweep_fingerprint": self.fingerprint,
            "sweep_spec": json.dumps(self.spec.to_dict(), sort_keys=True),
            "created_at": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "package_version": __version__,
        }
        with self._conn:
            self._conn.execute(f"CREATE TABLE {META_TABLE} (key TEXT PRIMARY KEY, value TEXT NOT NULL)")
            self._conn.execute(f"CREATE TABLE {RESULTS_TABLE} (\n  {cols}\n)")
            self._conn.executemany(f"INSERT INTO {META_TABLE} VALUES (?, ?)", sorted(meta.items()))

    def _upgrade_from_2(self):
        # The start columns are NULL in older rows, which leaves their checksums as they were.
        present = {record[1] for record in self._conn.execute(f"PRAGMA table_info({RESULTS_TABLE})")}
        with self._conn:
            for name in (n for n in START_COLUMNS if n not in present):
                self._conn.execute(f"ALTER TABLE {RESULTS_TABLE} ADD COLUMN {name} {_KINDS[name]}")
            self._conn.execute(f"UPDATE {META_TABLE} SET value = ? WHERE key = 'schema_version'",
                               (str(SCHEMA_VERSION),))

    def _upgrade_from_1(self):
        # Version 1 had no checksum: the rows are taken as they are and get one now.
        names = [name for name in COLUMN_NAMES if name not in START_COLUMNS]
        records = self._conn.execute(f"SELECT {', '.join(names)} FROM {RESULTS_TABLE}").fetchall()
        with self._conn:
            self._conn.execute(f"ALTER TABLE {RESULTS_TABLE} ADD COLUMN {CHECKSUM_COLUMN} TEXT")
            self._conn.executemany(f"UPDATE {RESULTS_TABLE} SET {CHECKSUM_COLUMN} = ? WHERE case_id = ?",
                                   [(row_checksum(r), r[0]) for r in records])
            self._conn.execute(f"UPDATE {META_TABLE} SET value = ? WHERE key = 'schema_version'",
                               (str(SCHEMA_VERSION),))

    def _read(self, sql):
        """All records of a query; SQLite errors from damage on disk become a StoreError."""
        try:
            return self._conn.execute(sql).fetchall()
        except sqlite3.OperationalError as exc:
            raise operational_error(self.path, exc) from exc
        except sqlite3.DatabaseError as exc:
            raise StoreError(f"the results store '{self.path}' is damaged ({exc}); move it away and rerun, "
                             "or choose another --db path") from exc

    def meta(self):
        """Return the meta table as a dict of strings (schema_version, sweep_fingerprint, sweep_spec, ...)."""
        return dict(self._read(f"SELECT key, value FROM {META_TABLE}"))

    def write(self, row):
        """Insert one finished case and commit it.

        Parameters
        ----------
        row : dict
            Column name -> value; ``case_id``, ``bild_converged`` and ``converged``
            are required, the rest default to NULL.  ``*_chord``/``*_twist`` take
            1-D sequences, the result quantities floats (NaN is stored as NULL).

        Raises
        ------
        ValueError
            On unknown columns or when the case is already stored.
        StoreFullError
            If the disk is full; the rows committed before stay.
        """
        self._require_writer()
        unknown = set(row) - set(COLUMN_NAMES)
        if unknown:
            raise ValueError(f"unknown result columns {sorted(unknown)}")
        values = []
        for name, kind in COLUMNS:
            value = row.get(name)
            if name in _ARRAY_COLUMNS:
                value = _encode_array(value)
            elif name in _BOOL_COLUMNS:
                value = int(bool(value))
            elif value is not None and kind == "REAL":
                value = _encode_real(value)
            elif value is not None and kind.startswith("INTEGER"):
                value = int(value)
            elif value is not None and kind == "TEXT":
                value = str(value)
            values.append(value)
        if row.get("finished_at") is None:
            values[COLUMN_NAMES.index("finished_at")] = time.time()
        values.append(row_checksum(values))
        names = COLUMN_NAMES + (CHECKSUM_COLUMN,)
        try:
            with self._conn:
                self._conn.execute(
                    f"INSERT INTO {RESULTS_TABLE} ({', '.join(names)}) VALUES ({', '.join('?' for _ in names)})",
                    values)
        except sqlite3.IntegrityError as exc:
            raise ValueError(f"case {row.get('case_id')} is already stored in '{self.path}' ({exc})") from exc
        except sqlite3.OperationalError as exc:
            if is_disk_full(exc):
                raise full_error(self.path, self._safe_count()) from exc
            raise operational_error(self.path, exc) from exc

    def _require_writer(self):
        if not self.writer:
            raise ValueError(f"the results store '{self.path}' was opened for reading (writer=False)")

    def _safe_count(self):
        try:
            return self.count()
        except (sqlite3.Error, StoreError):
            return None

    def damaged_ids(self):
        """Return the ids of stored cases whose values no longer match their checksum (damaged on disk).

        Returns
        -------
        list of int
            Sorted; empty when every row is intact.
        """
        names = COLUMN_NAMES + (CHECKSUM_COLUMN,)
        damaged = []
        for record in self._read(f"SELECT {', '.join(names)} FROM {RESULTS_TABLE}"):
            if record[-1] != row_checksum(record[:-1]):
                damaged.append(record[0])
        # A damaged id may not even be an integer any more.
        return sorted(damaged, key=lambda cid: (not isinstance(cid, int), cid if isinstance(cid, int) else 0, str(cid)))

    def drop(self, case_ids):
        """Delete the given cases (so that a resumed sweep computes them again).

        Parameters
        ----------
        case_ids : iterable of int
        """
        self._require_writer()
        try:
            with self._conn:
                self._conn.executemany(f"DELETE FROM {RESULTS_TABLE} WHERE case_id IS ?",
                                       [(cid,) for cid in case_ids])
        except sqlite3.OperationalError as exc:
            raise operational_error(self.path, exc) from exc

    def done_ids(self):
        """Return the set of case ids already stored."""
        return {r[0] for r in self._read(f"SELECT case_id FROM {RESULTS_TABLE}")}

    def count(self):
        """Return the number of stored cases."""
        return self._read(f"SELECT COUNT(*) FROM {RESULTS_TABLE}")[0][0]

    def rows(self):
        """Return every stored case in id order.

        Returns
        -------
        list of dict
            Column name -> value; NULL reads as None, converged flags as bool,
            chord/twist as float ndarrays.

        Raises
        ------
        StoreError
            If a row cannot be decoded (damage that :meth:`damaged_ids` reports).
        """
        out = []
        for record in self._read(f"SELECT {', '.join(COLUMN_NAMES)} FROM {RESULTS_TABLE} ORDER BY case_id"):
            row = dict(zip(COLUMN_NAMES, record))
            try:
                for name in _ARRAY_COLUMNS:
                    row[name] = _decode_array(row[name])
            except (ValueError, TypeError) as exc:
                raise StoreError(f"case {row['case_id']} in '{self.path}' is damaged ({exc}); rerun the sweep "
                                 "on this file to recompute it") from exc
            for name in _BOOL_COLUMNS:
                row[name] = bool(row[name])
            out.append(row)
        return out

    def close(self):
        """Close the connection, then release the writer lock (idempotent)."""
        if self._conn is not None:
            self._conn.close()
            self._conn = None
        if self._lock is not None:
            os.close(self._lock)
            self._lock = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False
