"""Blade geometries as JSON (``.json``): one file, one or more designs.

One object with ``"format": "bild-mdo rotor geometry"``, ``"version": 2`` and a
list ``"designs"`` of objects with the keys ``"name"``, ``"airfoil"``,
``"num_blades"``, ``"loss_model"``, ``"radius [m]"``, ``"hub_radius [m]"``,
``"r [m]"``, ``"chord [m]"``, ``"twist [deg]"``, ``"dr [m]"`` (lists; ``dr``
the width of the annulus each station stands for, which tile hub to tip) and
``"design_point"`` (``{"v_axial [m/s]": ..., "rpm [rpm]": ...}``), and
``"polar"``: the description of the design's polar
(:func:`~bild_mdo.airfoil.serialize.polar_to_dict`: tables, analytic
parameters or a spanwise set); a file without it names a built-in airfoil in
``"airfoil"``, or needs the polar given when read.  Floats are written with
every digit (Python's shortest round-trip form), so the polar and the
stations read back are the same numbers (the twist, kept in degrees, to the
last bit of the conversion).  Other keys
(:meth:`~bild_mdo.results.design.DesignResult.to_json` adds ``"performance"``
and ``"distributions"``) are ignored by the reader.

The reader refuses a file of a newer ``"version"`` than it reads, stations
whose widths do not tile hub to tip, and, for a version-1 file (no
``"dr [m]"``), end stations farther from hub or tip than one station spacing
(:func:`~bild_mdo.io.file_checks.check_stations`); a twist declared in rad whose
values look like degrees is refused with that said.  A UTF-8 byte-order mark
is skipped.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from bild_mdo import validation
from bild_mdo.io.airfoil import polar_description, polar_from_description
from bild_mdo.io.file_checks import check_stations, check_version, file_errors, read_text, twist_to_radians
from bild_mdo.io.geometry import (ANGLE_UNITS, FORMAT_NAME, FORMAT_VERSION, LENGTH_UNITS, RotorGeometry, as_geometry,
                                  design_point_key, split_key, unit_key)

#: What to do with a file without widths whose end stations are far from hub or tip.
_FIX = "write the file again from the design (bild-mdo design --json), or give each station's width in a 'dr [m]' list"


def _geometry_entry(geometry):
    return {
        "name": geometry.name,
        "airfoil": geometry.airfoil,
        "num_blades": geometry.num_blades,
        "loss_model": geometry.loss_model,
        unit_key("radius", "m"): geometry.radius,
        unit_key("hub_radius", "m"): geometry.hub_radius,
        unit_key("r", "m"): geometry.radii.tolist(),
        unit_key("chord", "m"): geometry.chord.tolist(),
        unit_key("twist", "deg"): geometry.twist_deg.tolist(),
        unit_key("dr", "m"): geometry.dr.tolist(),
        "design_point": {design_point_key(k): v for k, v in geometry.design_point.items()},
    }


def _plain(obj):
    """``obj`` with NumPy scalars as Python numbers; floats keep every digit (json writes their shortest repr)."""
    if isinstance(obj, (float, np.floating)):
        return float(obj)
    if isinstance(obj, dict):
        return {k: _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple, np.ndarray)):
        return [_plain(v) for v in obj]
    if isinstance(obj, np.integer):
        return int(obj)
    return obj


def write_json(path, geometries, extras=None):
    """Write one or more geometries to a JSON file (see the module docstring).

    Parameters
    ----------
    path : str or path
    geometries : RotorGeometry, dict, single-design DesignResult, or a list of them
    extras : list of dict, optional
        Additional keys merged into each design's entry.

    Returns
    -------
    pathlib.Path
    """
    if not isinstance(geometries, (list, tuple)):
        geometries = [geometries]
    geometries = [as_geometry(g) for g in geometries]
    entries = [_geometry_entry(g) for g in geometries]
    for entry, extra in zip(entries, extras or []):
        entry.update(extra)
    doc = _plain({"format": FORMAT_NAME, "version": FORMAT_VERSION,
                  "units": {"r": "m", "chord": "m", "twist": "deg", "dr": "m", "radius": "m", "hub_radius": "m"},
                  "designs": entries})
    descriptions = {}
    for entry, geometry in zip(doc["designs"], geometries):
        if geometry.polar is not None:
            if id(geometry.polar) not in descriptions:
                descriptions[id(geometry.polar)] = polar_description(geometry.polar, geometry.airfoil)
            if descriptions[id(geometry.polar)] is not None:
                entry["polar"] = descriptions[id(geometry.polar)]
    path = Path(path)
    path.write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")
    return path


def _lookup(entry, name, default_units, path, scalar=False, required=True):
    """Value of ``name [units]`` in a JSON entry, converted to SI (lengths) or rad (angles).

    None when absent and not ``required``.
    """
    for key, value in entry.items():
        try:
            base, units = split_key(key)
        except ValueError:
            continue
        if base != name:
            continue
        table = ANGLE_UNITS if name == "twist" else LENGTH_UNITS
        if units not in table:
            raise ValueError(f"{path}: {key!r} has unknown units; use one of {', '.join(table)}")
        what = "a number" if scalar else "a list of numbers"
        values = validation.real_array(f"{path}: {key!r}", value, requirement=what, ndim=(0,) if scalar else (1,))
        if name == "twist":
            return twist_to_radians(path, key, values, units)
        return values * table[units]
    if not required:
        return None
    raise ValueError(f"{path}: design entry lacks '{name} [{default_units}]'")


def _load(path):
    try:
        doc = json.loads(read_text(path))
    except json.JSONDecodeError as err:
        raise ValueError(f"{path}:{err.lineno}: not valid JSON ({err.msg}, column {err.colno})") from None
    if not isinstance(doc, dict) or doc.get("format") != FORMAT_NAME or "designs" not in doc:
        raise ValueError(f"{path}: not a {FORMAT_NAME!r} JSON file")
    # Files from before the version key are version 1.
    check_version(path, doc.get("version", 1))
    designs = doc["designs"]
    if not isinstance(designs, list) or not designs:
        raise ValueError(f"{path}: 'designs' must be a non-empty list of design entries, got {_short(designs)}")
    return doc


def _short(value):
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def read_json(path, design=0, load_polar=True):
    """Read design ``design`` of a geometry JSON file.

    Parameters
    ----------
    path : str or path
    design : int
        Index into the file's ``"designs"`` list (negative counts from the end).
    load_polar : bool
        Rebuild the design's polar from its ``"polar"`` entry (``RotorGeometry.polar``);
        False skips it (when the polar is given otherwise).

    Returns
    -------
    RotorGeometry

    Raises
    ------
    ValueError
        One line naming the file and what is wrong, if the file is not a
        readable geometry file or ``design`` is not in it.
    """
    path = Path(path)
    with file_errors(path):
        designs = _load(path)["designs"]
        design = validation.integer("design", design, minimum=0)
        if not design < len(designs):
            raise ValueError(f"{path}: holds {len(designs)} design(s); design {design} does not exist")
        entry = designs[design]
        if not isinstance(entry, dict):
            raise ValueError(f"{path}: design {design} must be an object of 'key [unit]' entries, got {_short(entry)}")
        if "num_blades" not in entry:
            raise ValueError(f"{path}: design {design} lacks 'num_blades'")
        raw_point = entry.get("design_point") or {}
        if not isinstance(raw_point, dict):
            raise ValueError(f"{path}: 'design_point' must be an object of 'name [unit]': number entries, "
                             f"got {_short(raw_point)}")
        point = {split_key(key)[0]: value for key, value in raw_point.items()}
        polar = None
        if load_polar and entry.get("polar") is not None:
            polar = polar_from_description(entry["polar"], f"{path}: design {design}")
        geometry = RotorGeometry(radii=_lookup(entry, "r", "m", path), chord=_lookup(entry, "chord", "m", path),
                                 twist=_lookup(entry, "twist", "deg", path),
                                 radius=float(_lookup(entry, "radius", "m", path, scalar=True)),
                                 hub_radius=float(_lookup(entry, "hub_radius", "m", path, scalar=True)),
                                 num_blades=entry["num_blades"], airfoil=entry.get("airfoil"),
                                 loss_model=entry.get("loss_model", "tip_hub"), design_point=point,
                                 name=entry.get("name", path.stem), polar=polar)
        dr = _lookup(entry, "dr", "m", path, required=False)
        return check_stations(f"{path}: design {design}" if len(designs) > 1 else path, geometry, dr, fix=_FIX)
