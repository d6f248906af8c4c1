"""Rotor blade geometry files: CSV, JSON and the QPROP/XROTOR-style propeller file.

All three hold one :class:`RotorGeometry`: station radii ``r``, chord ``c`` and
twist (pitch) ``beta`` of one blade, the tip and hub radius, the number of
blades, the airfoil name and the design point the geometry was made for.
Units are always written into the file.  Writing then reading gives the same
geometry to the 12 significant digits written.

CSV (``.csv``)
--------------
Comment lines ``# key [unit]: value`` hold the metadata, then one header row and
one row per station::

    # bild-mdo rotor geometry, format 1
    # name: bild-mdo design (naca4412, B=3)
    # airfoil: naca4412
    # num_blades: 3
    # loss_model: tip_hub
    # radius [m]: 1.5
    # hub_radius [m]: 0.3
    # design_point.v_axial [m/s]: 0
    # design_point.rpm [rpm]: 800
    ...
    r [m],chord [m],twist [deg]
    0.32,0.1359434876,25.930843669
    ...

On reading, the header may give lengths in m, cm, mm or in and the twist in
deg or rad; a file without ``radius``/``hub_radius`` lines gets them by
extending the first and last station half a spacing outwards (exact for
stations at the midpoints of equal annuli).

JSON (``.json``)
----------------
One object with ``"format": "bild-mdo rotor geometry"``, ``"version": 1`` and a
list ``"designs"`` of objects with the keys ``"name"``, ``"airfoil"``,
``"num_blades"``, ``"loss_model"``, ``"radius [m]"``, ``"hub_radius [m]"``,
``"r [m]"``, ``"chord [m]"``, ``"twist [deg]"`` (lists) and
``"design_point"`` (``{"v_axial [m/s]": ..., "rpm [rpm]": ...}``).  Other keys
(:meth:`~bild_mdo.design.DesignResult.to_json` adds ``"performance"`` and
``"distributions"``) are ignored by the reader.

QPROP propeller file (``.qprop``, ``.prop`` or any other name)
--------------------------------------------------------------
The propeller file of M. Drela's QPROP (QPROP User Guide v1.21), which
QPROP reads as is.  Lines, in this order (blank lines and lines starting with
``#`` are skipped; text after ``!`` is a comment)::

    <name>                                   line 1: free text
    B  R                 ! Nblades  [ R ]    number of blades; tip radius R (optional)
    CL0  CL_a            ! CL0     CL_a      lift line: cl = CL0 + CL_a*alpha (alpha in rad)
    CLmin  CLmax         ! CLmin   CLmax     stall limits of cl
    CD0 CD2u CD2l CLCD0  ! CD0 CD2u CD2l CLCD0
    REref  REexp         ! REref  REexp
    Rfac  Cfac  Bfac     ! Rfac   Cfac   Bfac     scale factors
    Radd  Cadd  Badd     ! Radd   Cadd   Badd     offsets
    r  c  beta           one row per station (more columns are ignored here)

with the drag model ``cd = (CD0 + CD2*(cl - CLCD0)^2) * (Re/REref)^REexp``,
``CD2 = CD2u`` above ``CLCD0`` and ``CD2l`` below, and the stations
``r = r_file*Rfac + Radd``, ``c = c_file*Cfac + Cadd``,
``beta = beta_file*Bfac + Badd`` (beta in degrees).  As in QPROP's source,
``R`` is used as given (not scaled) and defaults to the last station's ``r``.

QPROP's blade spans the first to the last station (it integrates between
them), while BILD's stations are the midpoints of equal annuli from hub to
tip.  So that QPROP sees the whole blade, this module writes two extra rows:
one at the hub radius and one at the tip radius ``R``, with chord and twist
extrapolated linearly from the two nearest stations (the chord limited to at
least half the nearest station's, as QPROP needs positive chords).  ``r`` and
``c`` are written in metres and ``beta`` in degrees with factors 1 and offsets
0, and those units are declared in the ``#  r [m]  chord [m]  beta [deg]``
comment above the rows.  bild-mdo's metadata (airfoil, hub radius, design
point, and ``end_stations = extrapolated``) sit in
``# bild-mdo: key [unit] = value`` comment lines, which QPROP skips; reading
such a file drops the two extrapolated rows again, so the round trip returns
the BILD stations.  A QPROP file from elsewhere is read with QPROP's meaning:
the blade runs from the first station (the hub radius) to ``R``.

The airfoil lines are fitted to the polar at the design's reference Reynolds
number ``REref`` (:func:`qprop_airfoil_coefficients`): ``CL0`` and ``CL_a``
from a least-squares line through ``cl`` over the 6 degrees of angle of attack
below the maximum-L/D angle ``alpha*``; ``CLmax`` and ``CLmin`` are the extreme
``cl`` over -20 ... 25 deg; ``CD0`` and ``CLCD0`` are the minimum drag and its
``cl`` in attached flow (the angles below ``alpha*`` where ``cl`` stays within
0.05 of that line); ``CD2u`` puts the quadratic through the maximum-L/D point
(so QPROP's model has the design's ``cl*``, ``cd*``); ``CD2l`` is a
least-squares fit of the attached points from ``CLCD0`` down by
``cl* - CLCD0``; ``REexp`` is the log-slope of ``cd*`` between ``REref/2``
and ``2 REref``.  Reading a QPROP file keeps these numbers in
``RotorGeometry.polar_coefficients``; :func:`polar_from_qprop` turns them into an
:class:`~bild_mdo.airfoil.AnalyticPolar` (symmetric drag with ``k = CD2u``,
smooth stall near ``CLmax``/``CLmin``) for files of unknown airfoil.
"""
from __future__ import annotations

import csv
import dataclasses
import json
import re
from pathlib import Path

import numpy as np

FORMAT_NAME = "bild-mdo rotor geometry"
FORMAT_VERSION = 1
SIGNIFICANT_DIGITS = 12

#: Design-point metadata: key -> units label (SI, '-' dimensionless).
DESIGN_POINT_UNITS = {
    "v_axial": "m/s",
    "advance_ratio": "-",
    "rpm": "rpm",
    "altitude": "m",
    "ref_chord": "m",
    "ref_radius_ratio": "-",
    "hub_radius_ratio": "-",
    "reynolds_ref": "-",
    "thrust": "N",
    "torque": "N*m",
    "power": "W",
    "efficiency": "-",
    "figure_of_merit": "-",
}

#: Half width (in cl) of the band about the fitted lift line that counts as attached flow.
LINEAR_LIFT_BAND = 0.05

QPROP_COEFFICIENTS = ("CL0", "CL_a", "CLmin", "CLmax", "CD0", "CD2u", "CD2l", "CLCD0", "REref",
                      "REexp")

_LENGTH_UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254}
_ANGLE_UNITS = {"deg": np.pi / 180.0, "rad": 1.0}
_KEY_RE = re.compile(r"^\s*(?P<key>[A-Za-z_][\w.]*)\s*(?:\[(?P<units>[^\]]*)\])?\s*$")


def unit_key(name, units):
    """``'name [units]'``, the key form used in the CSV header and the JSON files (``None`` -> ``'-'``)."""
    return f"{name} [{units or '-'}]"


def _split_key(text):
    match = _KEY_RE.match(text)
    if not match:
        raise ValueError(f"cannot read key {text!r}; expected 'name [unit]'")
    return match["key"], (match["units"] or "-").strip()


def _num(value):
    return f"{float(value):.{SIGNIFICANT_DIGITS}g}"


@dataclasses.dataclass(eq=False)
class RotorGeometry:
    """One rotor's blade geometry and the design point it was made for.

    Attributes
    ----------
    radii : ndarray, shape (nr,)
        Station radii (m), strictly increasing within ``[hub_radius, radius]``.
    chord : ndarray, shape (nr,)
        Chord (m), >= 0.
    twist : ndarray, shape (nr,)
        Twist (pitch) angle, from the rotor plane (rad).
    radius, hub_radius : float
        Tip and hub radius (m).
    num_blades : int
        Number of blades.
    airfoil : str or None
        Built-in airfoil name (:func:`~bild_mdo.airfoil.get_polar`), None if unknown.
    loss_model : str
        Prandtl loss model of the design (``'tip_hub'``, ``'tip'``, ``'none'``).
    design_point : dict
        Design-point metadata, keys and units in :data:`DESIGN_POINT_UNITS`.
    name : str
        Free text.
    polar_coefficients : dict or None
        QPROP airfoil-model numbers read from a QPROP file.
    """

    radii: np.ndarray
    chord: np.ndarray
    twist: np.ndarray
    radius: float
    hub_radius: float
    num_blades: int
    airfoil: str | None = None
    loss_model: str = "tip_hub"
    design_point: dict = dataclasses.field(default_factory=dict)
    name: str = "rotor"
    polar_coefficients: dict | None = None

    def __post_init__(self):
        self.radii = np.array(self.radii, dtype=float)
        self.chord = np.array(self.chord, dtype=float)
        self.twist = np.array(self.twist, dtype=float)
        self.radius = float(self.radius)
        self.hub_radius = float(self.hub_radius)
        if isinstance(self.num_blades, bool) or int(self.num_blades) != self.num_blades or self.num_blades < 1:
            raise ValueError(f"num_blades must be a positive integer, got {self.num_blades!r}")
        self.num_blades = int(self.num_blades)
        if self.radii.ndim != 1 or self.radii.size < 2:
            raise ValueError(f"a geometry needs at least 2 stations in a 1-D array, got shape {self.radii.shape}")
        if self.chord.shape != self.radii.shape or self.twist.shape != self.radii.shape:
            raise ValueError(f"r, chord and twist must have the same length, got {self.radii.size}, "
                             f"{self.chord.size}, {self.twist.size}")
        if not all(np.all(np.isfinite(a)) for a in (self.radii, self.chord, self.twist)):
            raise ValueError("r, chord and twist must be finite numbers")
        if np.any(np.diff(self.radii) <= 0.0):
            raise ValueError("station radii must be strictly increasing")
        if np.any(self.chord < 0.0):
            raise ValueError("chord must be non-negative")
        if not 0.0 <= self.hub_radius < self.radius:
            raise ValueError(f"need 0 <= hub_radius < radius, got hub {self.hub_radius:g} m, tip {self.radius:g} m")
        # A little slack: radii written to 12 digits may land a hair outside.
        tol = 1e-9 * self.radius
        if self.radii[0] < self.hub_radius - tol or self.radii[-1] > self.radius + tol:
            raise ValueError(f"stations must lie within hub and tip radius ({self.hub_radius:g} ... "
                             f"{self.radius:g} m), got {self.radii[0]:g} ... {self.radii[-1]:g} m")
        self.design_point = {k: float(v) for k, v in (self.design_point or {}).items()}

    @property
    def twist_deg(self):
        """Twist (deg)."""
        return np.degrees(self.twist)

    @property
    def radial_fractions(self):
        """Station radii over the tip radius r/R (-)."""
        return self.radii / self.radius

    @property
    def num_radial(self):
        """Number of stations."""
        return self.radii.size


def as_geometry(source, index=None):
    """A :class:`RotorGeometry` from a geometry, a single design of a DesignResult, a dict of arrays or a file.

    Parameters
    ----------
    source : RotorGeometry, DesignResult, dict, str or path
        A dict takes the :class:`RotorGeometry` field names.
    index : int, optional
        Design of a batch DesignResult or of a multi-design JSON file.
    """
    from bild_mdo.design import DesignResult

    if isinstance(source, RotorGeometry):
        return source
    if isinstance(source, DesignResult):
        return source.geometry(index)
    if isinstance(source, dict):
        return RotorGeometry(**source)
    if isinstance(source, (str, Path)):
        return read_geometry(source, design=0 if index is None else index)
    raise ValueError(f"cannot make a rotor geometry from {type(source).__name__}; give a DesignResult, "
                     "RotorGeometry, dict of arrays or a geometry file path")


def _extend_ends(radii):
    """Hub and tip radius by extending the end stations half a spacing outwards."""
    hub = max(radii[0] - 0.5 * (radii[1] - radii[0]), 0.0)
    tip = radii[-1] + 0.5 * (radii[-1] - radii[-2])
    return hub, tip


# -- CSV ----------------------------------------------------------------------------------------------
def write_csv(path, geometry):
    """Write a geometry as CSV (see the module docstring).

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
             f"# radius [m]: {_num(geometry.radius)}",
             f"# hub_radius [m]: {_num(geometry.hub_radius)}"]
    for key, value in geometry.design_point.items():
        lines.append(f"# design_point.{key} [{DESIGN_POINT_UNITS.get(key, '-')}]: {_num(value)}")
    lines.append("r [m],chord [m],twist [deg]")
    lines += [f"{_num(r)},{_num(c)},{_num(t)}" for r, c, t in zip(geometry.radii, geometry.chord, geometry.twist_deg)]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def _column_scale(header):
    names = {}
    for column, text in enumerate(header):
        key, units = _split_key(text)
        table = _ANGLE_UNITS if key in ("twist", "beta") else _LENGTH_UNITS
        if units not in table:
            raise ValueError(f"column {text!r}: unknown units {units!r}; use one of {', '.join(table)}")
        names["twist" if key == "beta" else key] = (column, table[units])
    missing = {"r", "chord", "twist"} - set(names)
    if missing:
        raise ValueError(f"CSV header lacks column(s) {sorted(missing)}; expected 'r [m],chord [m],twist [deg]'")
    return names


def read_csv(path):
    """Read a geometry CSV (see the module docstring).

    Returns
    -------
    RotorGeometry

    Raises
    ------
    ValueError
        If the file is not a readable geometry table (the message says why).
    """
    path = Path(path)
    meta, design_point, rows, header = {}, {}, [], None
    with path.open(encoding="utf-8", newline="") as handle:
        for line_no, line in enumerate(handle, start=1):
            text = line.strip()
            if not text:
                continue
            if text.startswith("#"):
                body = text.lstrip("#").strip()
                if ":" not in body:
                    continue
                key_text, value = body.split(":", 1)
                try:
                    key, units = _split_key(key_text)
                except ValueError:
                    continue
                value = value.strip()
                if key.startswith("design_point."):
                    design_point[key.split(".", 1)[1]] = float(value)
                else:
                    meta[key] = (value, units)
                continue
            cells = next(csv.reader([text]))
            if header is None:
                header = _column_scale(cells)
                continue
            try:
                rows.append([float(cells[header[k][0]]) * header[k][1] for k in ("r", "chord", "twist")])
            except (ValueError, IndexError):
                raise ValueError(f"{path}:{line_no}: expected numbers in every column, got {text!r}") from None
    if header is None or not rows:
        raise ValueError(f"{path}: no geometry table found (need a header 'r [m],chord [m],twist [deg]' and rows)")
    data = np.array(rows)
    radii = data[:, 0]

    def length(key, fallback):
        if key not in meta:
            return fallback
        value, units = meta[key]
        if units not in _LENGTH_UNITS:
            raise ValueError(f"{path}: {key} has unknown units {units!r}")
        return float(value) * _LENGTH_UNITS[units]

    hub, tip = _extend_ends(radii) if radii.size > 1 else (0.0, radii[-1])
    if "num_blades" not in meta:
        raise ValueError(f"{path}: the number of blades is missing (a line '# num_blades: 3')")
    return RotorGeometry(radii=radii, chord=data[:, 1], twist=data[:, 2],
                         radius=length("radius", tip), hub_radius=length("hub_radius", hub),
                         num_blades=int(meta["num_blades"][0]),
                         airfoil=meta.get("airfoil", ("",))[0] or None,
                         loss_model=meta.get("loss_model", ("tip_hub",))[0],
                         name=meta.get("name", (path.stem,))[0], design_point=design_point)


# -- JSON ---------------------------------------------------------------------------------------------
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
        "design_point": {unit_key(k, DESIGN_POINT_UNITS.get(k, "-")): v for k, v in geometry.design_point.items()},
    }


def _round_floats(obj):
    if isinstance(obj, float):
        return float(_num(obj))
    if isinstance(obj, dict):
        return {k: _round_floats(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_round_floats(v) for v in obj]
    if isinstance(obj, np.floating):
        return float(_num(obj))
    if isinstance(obj, np.integer):
        return int(obj)
    return obj


def write_json(path, geometries, extras=None):
    """Write one or more geometries to a JSON file (see the module docstring).

    Parameters
    ----------
    path : str or path
    geometries : RotorGeometry, DesignResult or list of them
    extras : list of dict, optional
        Additional keys merged into each design's entry.

    Returns
    -------
    pathlib.Path
    """
    from bild_mdo.design import DesignResult

    if isinstance(geometries, DesignResult):
        geometries = [d.geometry() for d in geometries]
    elif not isinstance(geometries, (list, tuple)):
        geometries = [geometries]
    entries = [_geometry_entry(as_geometry(g)) for g in geometries]
    for entry, extra in zip(entries, extras or []):
        entry.update(extra)
    doc = {"format": FORMAT_NAME, "version": FORMAT_VERSION,
           "units": {"r": "m", "chord": "m", "twist": "deg", "radius": "m", "hub_radius": "m"},
           "designs": entries}
    path = Path(path)
    path.write_text(json.dumps(_round_floats(doc), indent=1) + "\n", encoding="utf-8")
    return path


def _lookup(entry, name, default_units, path):
    """Value of ``name [units]`` in a JSON entry, converted to SI (lengths) or rad (angles)."""
    for key, value in entry.items():
        try:
            base, units = _split_key(key)
        except ValueError:
            continue
        if base != name:
            continue
        table = _ANGLE_UNITS if name == "twist" else _LENGTH_UNITS
        if units not in table:
            raise ValueError(f"{path}: {key!r} has unknown units; use one of {', '.join(table)}")
        return np.asarray(value, dtype=float) * table[units]
    raise ValueError(f"{path}: design entry lacks '{name} [{default_units}]'")


def read_json(path, design=0):
    """Read design ``design`` of a geometry JSON file.

    Returns
    -------
    RotorGeometry
    """
    path = Path(path)
    try:
        doc = json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as err:
        raise ValueError(f"{path}: not valid JSON ({err})") from None
    if not isinstance(doc, dict) or doc.get("format") != FORMAT_NAME or "designs" not in doc:
        raise ValueError(f"{path}: not a {FORMAT_NAME!r} JSON file")
    designs = doc["designs"]
    if not -len(designs) <= design < len(designs):
        raise ValueError(f"{path}: holds {len(designs)} design(s); design {design} does not exist")
    entry = designs[design]
    point = {}
    for key, value in (entry.get("design_point") or {}).items():
        name, _ = _split_key(key)
        point[name] = value
    return RotorGeometry(radii=_lookup(entry, "r", "m", path), chord=_lookup(entry, "chord", "m", path),
                         twist=_lookup(entry, "twist", "deg", path),
                         radius=float(_lookup(entry, "radius", "m", path)),
                         hub_radius=float(_lookup(entry, "hub_radius", "m", path)),
                         num_blades=entry["num_blades"], airfoil=entry.get("airfoil"),
                         loss_model=entry.get("loss_model", "tip_hub"), design_point=point,
                         name=entry.get("name", path.stem))


def count_json_designs(path):
    """Number of designs in a geometry JSON file."""
    doc = json.loads(Path(path).read_text(encoding="utf-8"))
    return len(doc.get("designs", []))


# -- QPROP --------------------------------------------------------------------------------------------
def qprop_airfoil_coefficients(polar, reynolds):
    """QPROP's airfoil-model numbers fitted to a polar at one Reynolds number.

    See the module docstring for how each number is obtained.

    Parameters
    ----------
    polar : Polar
    reynolds : float
        ``REref``.

    Returns
    -------
    dict
        Keys :data:`QPROP_COEFFICIENTS` (``CL_a`` per rad).
    """
    reynolds = float(reynolds)
    star = polar.max_lift_to_drag(np.array([reynolds / 2.0, reynolds, 2.0 * reynolds]))
    a_star, cl_star, cd_star = float(star.alpha[1]), float(star.cl[1]), float(star.cd[1])
    alpha_lin = a_star + np.radians(np.linspace(-6.0, 0.0, 25))
    cl_lin = polar.evaluate(alpha_lin, reynolds).cl
    cl_a, cl0 = np.polyfit(alpha_lin, cl_lin, 1)

    scan = np.radians(np.linspace(-20.0, 25.0, 901))
    values = polar.evaluate(scan, reynolds)
    cl, cd = np.asarray(values.cl), np.asarray(values.cd)
    i_max = int(np.argmax(cl))
    i_min = int(np.argmin(np.where(scan <= a_star, cl, np.inf)))
    # Attached flow: the contiguous run around alpha* where cl stays within 0.05 of the fitted line.
    linear = np.abs(cl - (cl0 + cl_a * scan)) <= LINEAR_LIFT_BAND
    i_star = int(np.argmin(np.abs(scan - a_star)))
    lo = i_star
    while lo > 0 and linear[lo - 1]:
        lo -= 1
    i_cd = lo + int(np.argmin(cd[lo:i_star + 1]))
    cd0, clcd0 = float(cd[i_cd]), float(cl[i_cd])
    cd2u = (cd_star - cd0) / (cl_star - clcd0) ** 2 if cl_star > clcd0 else 0.0
    # Below CLCD0, fit over as wide a cl range as the upper branch spans (CLCD0 ... cl*), in attached flow.
    lower = np.arange(lo, i_cd)
    lower = lower[cl[lower] >= 2.0 * clcd0 - cl_star]
    dcl = cl[lower] - clcd0
    fit = np.sum(dcl**4)
    cd2l = float(np.sum(dcl**2 * (cd[lower] - cd0)) / fit) if fit > 0.0 else cd2u
    re_exp = float(np.log(star.cd[2] / star.cd[0]) / np.log(4.0))
    return {"CL0": float(cl0), "CL_a": float(cl_a), "CLmin": float(cl[i_min]), "CLmax": float(cl[i_max]),
            "CD0": cd0, "CD2u": float(cd2u), "CD2l": cd2l, "CLCD0": clcd0, "REref": reynolds, "REexp": re_exp}


def polar_from_qprop(coefficients):
    """An :class:`~bild_mdo.airfoil.AnalyticPolar` approximating QPROP's airfoil model.

    Linear lift ``CL0 + CL_a alpha``, drag ``CD0 (Re/REref)^REexp + CD2u (cl - CLCD0)^2``
    (symmetric: ``CD2l`` is not represented), stall near ``CLmax`` and ``CLmin``.
    """
    from bild_mdo.airfoil.analytic import AnalyticPolar

    c = coefficients
    half = np.radians(3.0)
    alpha_max = float(np.clip((c["CLmax"] - c["CL0"]) / c["CL_a"], 1.1 * half, np.radians(60.0)))
    alpha_min = float(np.clip((c["CLmin"] - c["CL0"]) / c["CL_a"], -np.radians(60.0), -1.1 * half))
    return AnalyticPolar(cl0=c["CL0"], cl_alpha=c["CL_a"], cd0=c["CD0"], k=max(c["CD2u"], 1e-6),
                         cl_cd_min=c["CLCD0"], alpha_stall=alpha_max, alpha_stall_negative=alpha_min,
                         stall_half_width=half, reynolds_exponent=-c["REexp"], reynolds_ref=c["REref"])


def _design_reynolds(geometry):
    """REref for the QPROP lines: the design's reference Reynolds number, else Re at 0.75 R at sea level."""
    if "reynolds_ref" in geometry.design_point:
        return geometry.design_point["reynolds_ref"]
    from bild_mdo.atmosphere import isa

    state = isa(geometry.design_point.get("altitude", 0.0))
    r75 = 0.75 * geometry.radius
    chord = float(np.interp(r75, geometry.radii, geometry.chord))
    omega = geometry.design_point.get("rpm", 800.0) * np.pi / 30.0
    speed = np.hypot(geometry.design_point.get("v_axial", 0.0), omega * r75)
    return float(state.rho * speed * chord / state.mu)


def write_qprop(path, geometry, polar=None, reynolds=None):
    """Write a geometry as a QPROP propeller file (see the module docstring).

    Parameters
    ----------
    path : str or path
    geometry : RotorGeometry or single-design DesignResult
    polar : Polar, optional
        Polar for the airfoil lines; default the geometry's built-in airfoil.
    reynolds : float, optional
        ``REref``; default the design's reference Reynolds number.

    Returns
    -------
    pathlib.Path
    """
    from bild_mdo.airfoil.builtin import get_polar
    from bild_mdo.design import DesignResult

    if polar is None and isinstance(geometry, DesignResult) and not geometry.is_batch:
        polar = geometry.polar
    geometry = as_geometry(geometry)
    if polar is None:
        if geometry.airfoil is None:
            if geometry.polar_coefficients is None:
                raise ValueError("give a polar: the geometry names no built-in airfoil")
            coeffs = geometry.polar_coefficients
        else:
            polar = get_polar(geometry.airfoil)
    if polar is not None:
        coeffs = qprop_airfoil_coefficients(polar, _design_reynolds(geometry) if reynolds is None else reynolds)
    c = {k: float(v) for k, v in coeffs.items()}
    lines = [
        geometry.name or "rotor",
        "",
        f" {geometry.num_blades:d}  {_num(geometry.radius)}   ! Nblades  [ R ]   (R in m)",
        "",
        f" {c['CL0']:.6f}  {c['CL_a']:.6f}   ! CL0     CL_a    (CL_a per rad)",
        f" {c['CLmin']:.6f}  {c['CLmax']:.6f}   ! CLmin   CLmax",
        "",
        f" {c['CD0']:.6f}  {c['CD2u']:.6f}  {c['CD2l']:.6f}  {c['CLCD0']:.6f}   !  CD0    CD2u   CD2l   CLCD0",
        f" {c['REref']:.1f}  {c['REexp']:.6f}   !  REref  REexp",
        "",
        " 1.0  1.0  1.0   !  Rfac   Cfac   Bfac   (r, c in m; beta in deg)",
        " 0.0  0.0  0.0   !  Radd   Cadd   Badd",
        "",
        f"# bild-mdo: format = {FORMAT_VERSION}",
        f"# bild-mdo: airfoil = {geometry.airfoil or ''}",
        f"# bild-mdo: loss_model = {geometry.loss_model}",
        f"# bild-mdo: hub_radius [m] = {_num(geometry.hub_radius)}",
    ]
    for key, value in geometry.design_point.items():
        lines.append(f"# bild-mdo: design_point.{key} [{DESIGN_POINT_UNITS.get(key, '-')}] = {_num(value)}")
    lines.append("# bild-mdo: end_stations = extrapolated")
    lines.append("#  r [m]  chord [m]  beta [deg]")
    radii, chord, twist = _with_end_stations(geometry)
    lines += [f" {_num(r)}  {_num(ch)}  {_num(b)}" for r, ch, b in zip(radii, chord, np.degrees(twist))]
    path = Path(path)
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def _with_end_stations(geometry):
    """Stations with rows added at the hub and tip radius (linear extrapolation of chord and twist)."""
    r, c, t = geometry.radii, geometry.chord, geometry.twist

    def extrapolate(target, i, j):
        slope_c = (c[j] - c[i]) / (r[j] - r[i])
        slope_t = (t[j] - t[i]) / (r[j] - r[i])
        chord = max(c[i] + slope_c * (target - r[i]), 0.5 * c[i])
        return chord, t[i] + slope_t * (target - r[i])

    hub_c, hub_t = extrapolate(geometry.hub_radius, 0, 1)
    tip_c, tip_t = extrapolate(geometry.radius, -1, -2)
    return (np.concatenate([[geometry.hub_radius], r, [geometry.radius]]),
            np.concatenate([[hub_c], c, [tip_c]]), np.concatenate([[hub_t], t, [tip_t]]))


def _floats(text, count, what, path, line_no, optional=0):
    parts = text.split()
    try:
        values = [float(p) for p in parts[:count]]
    except ValueError:
        values = []
    if len(values) < count - optional:
        raise ValueError(f"{path}:{line_no}: expected {what}, got {text!r}")
    return values


def read_qprop(path):
    """Read a QPROP propeller file (see the module docstring).

    Returns
    -------
    RotorGeometry
        With ``polar_coefficients`` from the file's airfoil lines and, for files
        written by bild-mdo, the airfoil name, hub radius and design point.
    """
    path = Path(path)
    meta, design_point, content = {}, {}, []
    for line_no, raw in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        stripped = raw.strip()
        if stripped.startswith("#"):
            body = stripped.lstrip("#").strip()
            if body.startswith("bild-mdo:") and "=" in body:
                key_text, value = body[len("bild-mdo:"):].split("=", 1)
                key, units = _split_key(key_text)
                if key.startswith("design_point."):
                    design_point[key.split(".", 1)[1]] = float(value)
                else:
                    meta[key] = (value.strip(), units)
            continue
        if not content:
            if stripped:
                content.append((line_no, stripped))
            continue
        text = stripped.split("!", 1)[0].strip()
        if text:
            content.append((line_no, text))
    if len(content) < 9:
        raise ValueError(f"{path}: too short for a QPROP propeller file (name, 7 parameter lines, stations)")
    (_, name), blades_line = content[0], content[1]
    nb = _floats(blades_line[1], 2, "'Nblades [R]'", path, blades_line[0], optional=1)
    cl0, cla = _floats(content[2][1], 2, "'CL0 CL_a'", path, content[2][0])
    clmin, clmax = _floats(content[3][1], 2, "'CLmin CLmax'", path, content[3][0])
    cd0, cd2u, cd2l, clcd0 = _floats(content[4][1], 4, "'CD0 CD2u CD2l CLCD0'", path, content[4][0])
    reref, reexp = _floats(content[5][1], 2, "'REref REexp'", path, content[5][0])
    rfac, cfac, bfac = _floats(content[6][1], 3, "'Rfac Cfac Bfac'", path, content[6][0])
    radd, cadd, badd = _floats(content[7][1], 3, "'Radd Cadd Badd'", path, content[7][0])
    rows = np.array([_floats(text, 3, "a station row 'r c beta'", path, line_no)
                     for line_no, text in content[8:]])
    radii = rows[:, 0] * rfac + radd
    chord = rows[:, 1] * cfac + cadd
    beta = np.radians(rows[:, 2] * bfac + badd)
    # QPROP's blade runs from the first station to R (R unscaled, default the last station).
    hub, tip = radii[0], (nb[1] if len(nb) > 1 else radii[-1])
    if meta.get("end_stations", ("",))[0] == "extrapolated":
        if radii.size < 4:
            raise ValueError(f"{path}: a bild-mdo QPROP file needs at least 2 stations besides hub and tip rows")
        radii, chord, beta = radii[1:-1], chord[1:-1], beta[1:-1]
    if "hub_radius" in meta:
        value, units = meta["hub_radius"]
        hub = float(value) * _LENGTH_UNITS[units]
    if int(nb[0]) != nb[0]:
        raise ValueError(f"{path}:{blades_line[0]}: Nblades must be an integer, got {nb[0]:g}")
    coefficients = dict(zip(QPROP_COEFFICIENTS, (cl0, cla, clmin, clmax, cd0, cd2u, cd2l, clcd0, reref, reexp)))
    return RotorGeometry(radii=radii, chord=chord, twist=beta, radius=tip, hub_radius=hub,
                         num_blades=int(nb[0]), airfoil=meta.get("airfoil", ("",))[0] or None,
                         loss_model=meta.get("loss_model", ("tip_hub",))[0], design_point=design_point,
                         name=name, polar_coefficients=coefficients)


# -- dispatch -----------------------------------------------------------------------------------------
FORMATS = ("csv", "json", "qprop")


def _format_of(path, fmt):
    if fmt is not None:
        if fmt not in FORMATS:
            raise ValueError(f"unknown geometry format {fmt!r}; use one of {', '.join(FORMATS)}")
        return fmt
    suffix = Path(path).suffix.lower()
    if suffix == ".csv":
        return "csv"
    if suffix == ".json":
        return "json"
    return "qprop"


def write_geometry(path, geometry, fmt=None, **kwargs):
    """Write a geometry; the format comes from ``fmt`` or the suffix (.csv, .json, anything else QPROP)."""
    writer = {"csv": write_csv, "json": write_json, "qprop": write_qprop}[_format_of(path, fmt)]
    return writer(path, geometry, **kwargs)


def read_geometry(path, fmt=None, design=0):
    """Read a geometry file written by this module (or any QPROP propeller file).

    The format comes from ``fmt`` or the suffix: ``.csv``, ``.json``, anything
    else is read as a QPROP file.

    Parameters
    ----------
    path : str or path
    fmt : {'csv', 'json', 'qprop'}, optional
    design : int
        Design of a multi-design JSON file.

    Returns
    -------
    RotorGeometry

    Raises
    ------
    FileNotFoundError
        If the file does not exist.
    ValueError
        If it cannot be read as a geometry.
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"geometry file not found: {path}")
    kind = _format_of(path, fmt)
    if kind == "json":
        return read_json(path, design=design)
    return read_csv(path) if kind == "csv" else read_qprop(path)
