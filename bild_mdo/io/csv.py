"""Blade geometry as CSV (``.csv``): one row per station, metadata in comment lines.

Comment lines ``# key [unit]: value`` hold the metadata, then one header row and
one row per station::

    # bild-mdo rotor geometry, format 2
    # name: bild-mdo design (naca4412, B=3)
    # airfoil: naca4412
    # num_blades: 3
    # loss_model: tip_hub
    # radius [m]: 1.5
    # hub_radius [m]: 0.3
    # polar_file: blade.polar.json
    # design_point.v_axial [m/s]: 0
    # design_point.rpm [rpm]: 800
    ...
    r [m],chord [m],twist [deg],dr [m]
    0.32,0.1359434876,25.930843669,0.04
    ...

``dr`` is the width of the annulus each station stands for (the cells
between the midpoints of neighbouring stations, bounded by hub and tip, that
the BEM analysis integrates over); the widths tile hub to tip, so a file
that lost rows is refused (:func:`~bild_mdo.io.file_checks.check_stations`).
The first line gives the format version: a newer file than this reader
reads is refused; a format-1 file (no ``dr`` column) or a hand-made table
has its end stations checked instead (the gap to hub and tip at most one
station spacing, :func:`~bild_mdo.io.file_checks.check_end_gaps`).

The ``polar_file`` line is written for a polar that its name does not
rebuild (tables, a spanwise set): the polar file next to the CSV
(:mod:`bild_mdo.io.airfoil`) holds it, and the reader loads it from there.
On reading, the file may start with a UTF-8 byte-order mark (as spreadsheets
save it), the header may give lengths in m, cm, mm or in and the twist in
deg or rad; a file without ``radius``/``hub_radius`` lines gets them by
extending the first and last station half a spacing outwards (exact for
stations at the midpoints of equal annuli).
"""
from __future__ import annotations

import csv
import re
from pathlib import Path

import numpy as np

from bild_mdo.io.airfoil import (needs_polar_file, polar_description, polar_file_for, read_polar_file,
                                 write_polar_file)
from bild_mdo.io.file_checks import (FileMetadata, check_stations, check_version, file_errors, read_text,
                                     twist_to_radians)
from bild_mdo.io.geometry import (ANGLE_UNITS, FORMAT_NAME, FORMAT_VERSION, LENGTH_UNITS, as_geometry, design_point_key,
                                  format_number, split_key)

# The first line: '# bild-mdo rotor geometry, format 2'.
_FORMAT_LINE = re.compile(r"^#\s*" + re.escape(FORMAT_NAME) + r"\s*,\s*format\s+(?P<version>\S+)\s*$")
#: What to do with a file without widths whose end stations are far from hub or tip.
_FIX = "write the file again from the design (bild-mdo design --csv), or give each station's width in a 'dr [m]' column"


def write_csv(path, geometry):
    """Write a geometry as CSV (see the module docstring).

    Parameters
    ----------
    path : str or path
    geometry : RotorGeometry, dict or single-design DesignResult

    Returns
    -------
    pathlib.Path
    """
    geometry = as_geometry(geometry)
    path = Path(path)
    lines = [f"# {FORMAT_NAME}, format {FORMAT_VERSION}",
             f"# name: {geometry.name}",
             f"# airfoil: {geometry.airfoil or ''}",
             f"# num_blades: {geometry.num_blades}",
             f"# loss_model: {geometry.loss_model}",
             f"# radius [m]: {format_number(geometry.radius)}",
             f"# hub_radius [m]: {format_number(geometry.hub_radius)}"]
    description = polar_description(geometry.polar, geometry.airfoil)
    if needs_polar_file(description):
        lines.append(f"# polar_file: {write_polar_file(polar_file_for(path), description).name}")
    lines += [f"# design_point.{design_point_key(key)}: {format_number(value)}"
              for key, value in geometry.design_point.items()]
    lines.append("r [m],chord [m],twist [deg],dr [m]")
    lines += [f"{format_number(r)},{format_number(c)},{format_number(t)},{format_number(w)}"
              for r, c, t, w in zip(geometry.radii, geometry.chord, geometry.twist_deg, geometry.dr)]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def _column_scale(header):
    """Column of each quantity in a header row: name -> (column, units, key text)."""
    names = {}
    for column, text in enumerate(header):
        key, units = split_key(text)
        table = ANGLE_UNITS if key in ("twist", "beta") else LENGTH_UNITS
        if units not in table:
            raise ValueError(f"column {text!r}: unknown units {units!r}; use one of {', '.join(table)}")
        names["twist" if key == "beta" else key] = (column, units, text.strip())
    missing = {"r", "chord", "twist"} - set(names)
    if missing:
        raise ValueError(f"CSV header lacks column(s) {sorted(missing)}; expected 'r [m],chord [m],twist [deg]'")
    return names


def _extend_ends(radii):
    """Hub and tip radius by extending the end stations half a spacing outwards."""
    hub = max(radii[0] - 0.5 * (radii[1] - radii[0]), 0.0)
    tip = radii[-1] + 0.5 * (radii[-1] - radii[-2])
    return hub, tip


def read_csv(path, load_polar=True):
    """Read a geometry CSV (see the module docstring).

    Parameters
    ----------
    path : str or path
    load_polar : bool
        Read the polar file that a ``polar_file`` line names (``RotorGeometry.polar``);
        False skips it (when the polar is given otherwise).

    Returns
    -------
    RotorGeometry
        Hub and tip radius from the metadata, else extended from the end stations.

    Raises
    ------
    ValueError
        For a file that is not a geometry table, with ``path:line:`` and the reason.
    """
    path = Path(path)
    meta, rows, header = FileMetadata(path), [], None
    with file_errors(path):
        lines = read_text(path).splitlines()
    for line_no, line in enumerate(lines, start=1):
        with file_errors(path, line_no):
            header = _read_line(line, line_no, meta, rows, header)
    if header is None or not rows:
        raise ValueError(f"{path}: no geometry table found (need a header 'r [m],chord [m],twist [deg]' and rows)")
    if "num_blades" not in meta:
        raise ValueError(f"{path}: the number of blades is missing (a line '# num_blades: 3')")
    polar = None
    if load_polar and meta.text("polar_file"):
        polar = read_polar_file(path.parent / meta.text("polar_file"))
    with file_errors(path):
        data = np.array(rows)
        radii = data[:, 0] * LENGTH_UNITS[header["r"][1]]
        chord = data[:, 1] * LENGTH_UNITS[header["chord"][1]]
        twist = twist_to_radians(path, header["twist"][2], data[:, 2], header["twist"][1])
        dr = data[:, 3] * LENGTH_UNITS[header["dr"][1]] if "dr" in header else None
        hub, tip = _extend_ends(radii) if radii.size > 1 else (0.0, radii[-1])
        geometry = meta.geometry(radii, chord, twist, radius=meta.length("radius", tip),
                                 hub_radius=meta.length("hub_radius", hub), num_blades=meta.integer("num_blades"),
                                 name=meta.text("name", path.stem), polar=polar)
        return check_stations(path, geometry, dr, fix=_FIX)


def _read_line(line, line_no, meta, rows, header):
    """Take one line of a geometry CSV into ``meta`` or ``rows``; return the (new) header."""
    text = line.strip()
    if not text:
        return header
    if text.startswith("#"):
        version = _FORMAT_LINE.match(text)
        if version:
            # At once: a newer file may have columns this reader does not know.
            meta.add("format", version["version"])
            check_version(meta.path, _number(version["version"]))
            return header
        key_text, colon, value = text.lstrip("#").strip().partition(":")
        try:
            split_key(key_text)
        except ValueError:
            return header  # a free-text comment, not metadata
        if colon:
            meta.add(key_text, value)
        return header
    cells = next(csv.reader([text]))
    if header is None:
        return _column_scale(cells)
    try:
        rows.append([float(cells[header[k][0]]) for k in ("r", "chord", "twist", "dr") if k in header])
    except (ValueError, IndexError):
        raise ValueError(f"expected numbers in every column, got {text!r}") from None
    return header


def _number(text):
    """``float(text)``, or the text itself when it is not a number (for the message)."""
    try:
        return float(text)
    except ValueError:
        return text
