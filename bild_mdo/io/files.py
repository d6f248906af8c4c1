"""Read and write a blade geometry file in the format its name says (:func:`read_geometry`, :func:`write_geometry`).

``.csv`` is :mod:`bild_mdo.io.csv`, ``.json`` is :mod:`bild_mdo.io.json`, any
other name is a QPROP propeller file (:mod:`bild_mdo.io.qprop`).
"""
from __future__ import annotations

import os
from pathlib import Path

from bild_mdo.io.csv import read_csv, write_csv
from bild_mdo.io.json import read_json, write_json
from bild_mdo.io.qprop import read_qprop, write_qprop

FORMATS = ("csv", "json", "qprop")
_SUFFIXES = {".csv": "csv", ".json": "json"}


def _format_of(path, fmt):
    if fmt is None:
        return _SUFFIXES.get(Path(path).suffix.lower(), "qprop")
    if fmt not in FORMATS:
        raise ValueError(f"unknown geometry format {fmt!r}; use one of {', '.join(FORMATS)}")
    return fmt


def write_geometry(path, geometry, fmt=None, **kwargs):
    """Write a geometry; the format comes from ``fmt`` or the suffix (.csv, .json, anything else QPROP).

    Parameters
    ----------
    path : str or path
    geometry : RotorGeometry, dict or single-design DesignResult
    fmt : {'csv', 'json', 'qprop'}, optional
    **kwargs
        Passed to the writer (:func:`~bild_mdo.io.qprop.write_qprop` takes ``polar`` and ``reynolds``).

    Returns
    -------
    pathlib.Path
    """
    writer = {"csv": write_csv, "json": write_json, "qprop": write_qprop}[_format_of(path, fmt)]
    return writer(path, geometry, **kwargs)


def read_geometry(path, fmt=None, design=0, load_polar=True):
    """Read a geometry file written by bild-mdo (or any QPROP propeller file).

    Parameters
    ----------
    path : str or path
    fmt : {'csv', 'json', 'qprop'}, optional
        Default: from the suffix (``.csv``, ``.json``, anything else QPROP).
    design : int
        Design of a multi-design JSON file.
    load_polar : bool
        Rebuild the polar the file carries (JSON ``"polar"``, the polar file a
        CSV or QPROP file names) into ``RotorGeometry.polar``; False skips it.

    Returns
    -------
    RotorGeometry

    Raises
    ------
    FileNotFoundError
        If the file does not exist: ``geometry file not found: PATH``.
    ValueError
        One line, if it cannot be read as a geometry or would lie: stations
        that do not tile hub to tip (a cut file), a format version newer than
        this reader, a twist in rad that looks like degrees, a file that is not
        text (:func:`~bild_mdo.io.file_checks.check_stations`).
    """
    path = Path(path)
    if path.is_dir():
        raise ValueError(f"{path}: is a folder, not a geometry file")
    if not path.is_file():
        raise FileNotFoundError(f"geometry file not found: {path}")
    kind = _format_of(path, fmt)
    if kind == "json":
        return read_json(path, design=design, load_polar=load_polar)
    return (read_csv if kind == "csv" else read_qprop)(path, load_polar=load_polar)


def check_output_file(path, option="output file"):
    """Check, before any work, that a file can be written at ``path`` (nothing is created).

    Parameters
    ----------
    path : str or path
        The file to be written.
    option : str
        What asks for it (``'--csv'``), used in the message.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ValueError
        If ``path`` is a folder, its folder does not exist (or is a file), or it
        cannot be written; one line naming ``option`` and the path.
    """
    path = Path(path)
    if str(path) in ("", "."):
        raise ValueError(f"{option}: give a file name")
    if path.is_dir():
        raise ValueError(f"{option} {path}: is a folder; give a file name in it")
    folder = path.parent
    if not folder.exists():
        raise ValueError(f"{option} {path}: folder {folder} does not exist")
    if not folder.is_dir():
        raise ValueError(f"{option} {path}: {folder} is not a folder")
    if path.exists():
        if not os.access(path, os.W_OK):
            raise ValueError(f"{option} {path}: the file is not writable")
    elif not os.access(folder, os.W_OK | os.X_OK):
        raise ValueError(f"{option} {path}: folder {folder} is not writable")
    return path
