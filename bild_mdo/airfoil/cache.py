"""The on-disk polar cache: numpy arrays (``.npz``, never pickle) keyed by a hash of what made them.

Building the smooth surrogate of a polar set takes seconds (smoothing-spline
fits with cross-validation), and generating polars with XFOIL takes tens of
seconds, while a design takes milliseconds.  Both are therefore stored once
per user in a cache folder and reused by every later process:

* the folder is ``platformdirs.user_cache_dir("bild-mdo")``, or the value of
  the environment variable ``BILD_MDO_CACHE_DIR`` when it is set (read at
  every call, so tests and batch jobs can point it elsewhere);
* an entry is a ``.npz`` file named ``<kind>/<label>-<key>.npz``, where
  ``key`` is a SHA-256 hash of the source data, the settings and the code
  version that built it (:func:`hash_key`).  A change of any of them gives a
  new key, so a stale entry is never read: it is rebuilt, and the old file
  is simply no longer used (:func:`clear_cache` removes everything);
* writes go to a temporary file in the same folder, then ``os.replace`` puts
  it in place atomically, so concurrent processes never read a half-written
  entry (the last writer wins; both wrote the same content);
* an entry that cannot be read (truncated, foreign, wrong format) counts as
  missing and is rebuilt; a folder that cannot be written disables the
  cache for the process with one warning, and nothing fails.
"""
from __future__ import annotations

import hashlib
import os
import re
import shutil
import tempfile
import warnings
import zipfile

from bild_mdo.utils.cache_folder import CACHE_ENV, cache_dir

import numpy as np

__all__ = ["CACHE_ENV", "cache_dir", "clear_cache", "hash_key", "load_arrays", "store_arrays"]

_warned_unwritable = set()


def _update(digest, item):
    """Feed one item of a key into the hash, with its type, so ``1`` and ``'1'`` differ."""
    if isinstance(item, np.ndarray):
        arr = np.ascontiguousarray(item)
        digest.update(f"array{arr.dtype.str}{arr.shape}".encode())
        digest.update(arr.tobytes())
    elif isinstance(item, (list, tuple)):
        digest.update(f"seq{len(item)}".encode())
        for sub in item:
            _update(digest, sub)
    elif isinstance(item, dict):
        digest.update(f"dict{len(item)}".encode())
        for k in sorted(item):
            _update(digest, str(k))
            _update(digest, item[k])
    elif isinstance(item, bytes):
        digest.update(b"bytes" + str(len(item)).encode() + item)
    elif isinstance(item, float):
        digest.update(b"float" + float(item).hex().encode())
    else:
        text = f"{type(item).__name__}:{item!r}"
        digest.update(str(len(text)).encode() + text.encode())


def hash_key(*parts):
    """Hex SHA-256 of ``parts`` (arrays, numbers, strings, bytes, nested lists and dicts).

    Returns
    -------
    str
        64 hexadecimal digits; equal parts give equal keys in every process.
    """
    digest = hashlib.sha256()
    _update(digest, parts)
    return digest.hexdigest()


def _entry(kind, label, key):
    safe = re.sub(r"[^A-Za-z0-9._-]+", "_", str(label))[:60] or "polar"
    return cache_dir() / kind / f"{safe}-{key[:32]}.npz"


def load_arrays(kind, label, key):
    """The arrays stored under ``key``, or ``None`` when there is no readable entry.

    Parameters
    ----------
    kind : str
        Sub-folder (``'surrogate'``, ``'polars'``).
    label : str
        Human-readable part of the file name (the airfoil name).
    key : str
        :func:`hash_key` of the source.

    Returns
    -------
    dict of str to ndarray, or None
    """
    path = _entry(kind, label, key)
    try:
        with np.load(path, allow_pickle=False) as data:
            arrays = {name: data[name] for name in data.files}
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
        return None
    if str(arrays.get("_key", "")) != key:
        return None
    return arrays


def store_arrays(kind, label, key, arrays):
    """Store ``arrays`` under ``key`` atomically (temporary file, then ``os.replace``).

    Never raises for file-system problems: a cache that cannot be written
    warns once per folder and the caller goes on without it.

    Parameters
    ----------
    kind, label, key : str
        As in :func:`load_arrays`.
    arrays : dict of str to array_like
        Numeric or string arrays (object arrays are refused by numpy's
        ``allow_pickle=False`` on load, so they must not be stored).

    Returns
    -------
    Path or None
        The entry written, or ``None`` if the cache folder is not writable.
    """
    path = _entry(kind, label, key)
    tmp = None
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=path.stem, suffix=".tmp", dir=path.parent)
        with os.fdopen(fd, "wb") as handle:
            np.savez(handle, _key=np.array(key), **arrays)
        os.replace(tmp, path)
        return path
    except OSError as exc:
        if tmp is not None:
            try:
                os.unlink(tmp)
            except OSError:
                pass
        folder = str(path.parent)
        if folder not in _warned_unwritable:
            _warned_unwritable.add(folder)
            warnings.warn(f"polar cache disabled: cannot write to {folder} ({exc.strerror or exc}); "
                          f"set {CACHE_ENV} to a writable folder to keep built polars between runs",
                          RuntimeWarning, stacklevel=3)
        return None


def clear_cache():
    """Delete every cached polar and surrogate (the folder of :func:`cache_dir`).

    Returns
    -------
    Path
        The folder that was removed (it may not have existed).
    """
    folder = cache_dir()
    shutil.rmtree(folder, ignore_errors=True)
    return folder
