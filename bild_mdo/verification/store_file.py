"""The file behind a results store: path checks, the one-writer lock and what a full disk means.

Each failure gets its own message naming the fix: a missing folder, a folder
given where a file is expected, no write permission, another sweep writing to
the same file, a full disk.  These checks run before SQLite touches the file,
because SQLite reports most of them as "unable to open database file".
"""
import os
import shutil
import sqlite3

try:
    import fcntl
except ImportError:  # Windows: no advisory locks; one writer is then the user's responsibility
    fcntl = None


class StoreError(ValueError):
    """The results file cannot be used for this sweep; the message says why and what to do."""


class StoreBusyError(StoreError):
    """Another sweep holds the writer lock of the results file."""


class StoreFullError(StoreError):
    """The disk (or SQLite's page limit) holding the results file is full."""


def check_store_path(path):
    """Raise :class:`StoreError` if a results store cannot be created or written at ``path``.

    Parameters
    ----------
    path : str
        The ``--db`` file.

    Raises
    ------
    StoreError
        If ``path`` is a folder, its folder does not exist or is a file, or the
        file or its folder is not writable (the store writes its journal files
        ``FILE-wal`` and ``FILE-shm`` beside it).
    """
    full = os.path.abspath(path)
    folder = os.path.dirname(full)
    if os.path.isdir(full):
        raise StoreError(f"'{path}' is a folder; the results store (--db) is a file, for example "
                         f"'{os.path.join(path, 'bild-verify.sqlite')}'")
    if not os.path.exists(folder):
        raise StoreError(f"the folder '{folder}' of the results store '{path}' does not exist; create it or "
                         "choose another --db path")
    if not os.path.isdir(folder):
        raise StoreError(f"'{folder}' is a file, not a folder, so the results store '{path}' cannot be made there; "
                         "choose another --db path")
    if os.path.exists(full) and not os.access(full, os.R_OK | os.W_OK):
        raise StoreError(f"the results store '{path}' is not writable (permissions); make it writable "
                         "(chmod u+rw) or choose another --db path")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise StoreError(f"the folder '{folder}' is not writable (permissions); the results store '{path}' and "
                         "its journal files are written there: choose another --db path")


def acquire_writer_lock(path):
    """Take the one-writer lock of a results file (an advisory ``flock`` on the file itself).

    The lock is released when the returned descriptor is closed or the process
    dies (a killed sweep never leaves a stale lock).  Close it only after the
    SQLite connection: closing any descriptor of the file drops the process's
    POSIX locks, which SQLite uses.

    Parameters
    ----------
    path : str
        The database file; created empty when missing (an empty file becomes a store).

    Returns
    -------
    int or None
        The open descriptor holding the lock (None where ``fcntl`` does not exist).

    Raises
    ------
    StoreBusyError
        If another sweep holds the lock.
    """
    if fcntl is None:
        return None
    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        os.close(fd)
        raise StoreBusyError(f"another sweep is writing to '{path}'; wait until it finishes (its rows are kept "
                             "and this command then resumes from them) or use another --db") from None
    return fd


def is_disk_full(exc):
    """True if an SQLite error means the disk (or the connection's ``max_page_count``) is full."""
    return isinstance(exc, sqlite3.OperationalError) and "full" in str(exc).lower()


def free_space_text(path):
    """Free space on the file system holding ``path``, as ``'12.3 MB free'`` (``'free space unknown'``)."""
    try:
        free = shutil.disk_usage(os.path.dirname(os.path.abspath(path))).free
    except OSError:
        return "free space unknown"
    return f"{free / 1e6:.1f} MB free"


def full_error(path, stored):
    """The :class:`StoreFullError` of a full disk, saying what is kept and how to resume.

    Parameters
    ----------
    path : str
        The results file.
    stored : int or None
        Rows committed so far (None if unknown).
    """
    kept = "the rows committed so far are kept" if stored is None else f"the {stored} cases stored so far are kept"
    return StoreFullError(f"the disk holding the results store '{path}' is full ({free_space_text(path)}): {kept}; "
                          "free some space and rerun the same command to resume")


def operational_error(path, exc):
    """A :class:`StoreError` for an SQLite OperationalError (full disk, permissions, I/O, locks)."""
    if is_disk_full(exc):
        return full_error(path, None)
    return StoreError(f"cannot use the results store '{path}': {exc}; check the file, its folder and the disk, "
                      "or choose another --db path")
