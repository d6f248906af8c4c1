"""SQLite results store of a verification sweep: one row per case, committed at once.

The parent process is the only writer; workers return their results to it.
Each row is committed as soon as its case finishes, so a sweep that is killed
loses at most the cases that were running, and a rerun resumes from
:meth:`ResultsStore.done_ids`.  The database runs in WAL mode with
``synchronous=NORMAL``: a committed row survives a crash or kill of the process
(it could only be lost by a power cut of the machine).  WAL needs a local file
system; don't put the store on a network share.
"""
import datetime
import json
import math
import os
import sqlite3
import time

import numpy as np

from bild_mdo import __version__
from bild_mdo.bem.metrics import VERIFIED_METRICS

SCHEMA_VERSION = 1
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
)
COLUMN_NAMES = tuple(name for name, _ in COLUMNS)
_ARRAY_COLUMNS = frozenset(f"{m}_{a}" for m in METHODS for a in RESULT_ARRAYS)
_BOOL_COLUMNS = frozenset(("bild_converged", "converged"))


class StoreError(ValueError):
    """The results file cannot be used for this sweep; the message says why and what to do."""


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
    store of the same schema version and the same sweep.

    Parameters
    ----------
    path : str or os.PathLike
        Database file.
    spec : SweepSpec
        The sweep this store belongs to; its fingerprint is stored in the meta
        table and compared on every later open.

    Raises
    ------
    StoreError
        If the file is not an SQLite database or is damaged, belongs to another
        program (other tables), has another schema version, or was made for a
        different sweep.
    """

    def __init__(self, path, spec):
        self.path = os.fspath(path)
        self.spec = spec
        self.fingerprint = spec.fingerprint()
        self._conn = None
        try:
            self._conn = sqlite3.connect(self.path, timeout=30.0)
            self._open()
        except sqlite3.DatabaseError as exc:
            self.close()
            raise StoreError(
                f"'{self.path}' is not a usable bild-mdo results store: it is not an SQLite database or "
                f"it is damaged ({exc}). Move the file away or choose another path (--db); a new store is "
                "created when the file does not exist."
            ) from exc
        except StoreError:
            self.close()
            raise

    def _open(self):
        conn = self._conn
        tables = {r[0] for r in conn.execute("SELECT name FROM sqlite_master WHERE type='table'")}
        if not tables:
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
        if version != str(SCHEMA_VERSION):
            raise StoreError(
                f"'{self.path}' has results-store schema version {version!r}, this bild-mdo writes version "
                f"{SCHEMA_VERSION}. Start a new store (another --db path) or use the bild-mdo version that made it."
            )
        stored = meta.get("sweep_fingerprint")
        if stored != self.fingerprint:
            raise StoreError(
                f"'{self.path}' holds results of a different sweep (fingerprint {stored}, settings "
                f"{meta.get('sweep_spec')}); this run is fingerprint {self.fingerprint} with settings "
                f"{json.dumps(self.spec.to_dict(), sort_keys=True)}. Use another --db file for this sweep, "
                "or rerun with the settings the store was made with to resume it."
            )
        self._configure()

    def _configure(self):
        self._conn.execute("PRAGMA journal_mode=WAL")
        self._conn.execute("PRAGMA synchronous=NORMAL")

    def _create(self):
        self._configure()
        cols = ",\n  ".join(f"{name} {kind}" for name, kind in COLUMNS)
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

    def meta(self):
        """Return the meta table as a dict of strings (schema_version, sweep_fingerprint, sweep_spec, created_at, ...)."""
        return dict(self._conn.execute(f"SELECT key, value FROM {META_TABLE}").fetchall())

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
        """
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
            values.append(value)
        if row.get("finished_at") is None:
            values[COLUMN_NAMES.index("finished_at")] = time.time()
        placeholders = ", ".join("?" for _ in COLUMNS)
        try:
            with self._conn:
                self._conn.execute(
                    f"INSERT INTO {RESULTS_TABLE} ({', '.join(COLUMN_NAMES)}) VALUES ({placeholders})", values
                )
        except sqlite3.IntegrityError as exc:
            raise ValueError(f"case {row.get('case_id')} is already stored in '{self.path}' ({exc})") from exc

    def done_ids(self):
        """Return the set of case ids already stored."""
        return {r[0] for r in self._conn.execute(f"SELECT case_id FROM {RESULTS_TABLE}")}

    def count(self):
        """Return the number of stored cases."""
        return self._conn.execute(f"SELECT COUNT(*) FROM {RESULTS_TABLE}").fetchone()[0]

    def rows(self):
        """Return every stored case in id order.

        Returns
        -------
        list of dict
            Column name -> value; NULL reads as None, converged flags as bool,
            chord/twist as float ndarrays.
        """
        cursor = self._conn.execute(f"SELECT {', '.join(COLUMN_NAMES)} FROM {RESULTS_TABLE} ORDER BY case_id")
        out = []
        for record in cursor:
            row = dict(zip(COLUMN_NAMES, record))
            for name in _ARRAY_COLUMNS:
                row[name] = _decode_array(row[name])
            for name in _BOOL_COLUMNS:
                row[name] = bool(row[name])
            out.append(row)
        return out

    def close(self):
        """Close the connection (idempotent)."""
        if self._conn is not None:
            self._conn.close()
            self._conn = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False
