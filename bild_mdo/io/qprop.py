"""The QPROP propeller file (``.qprop``, ``.prop`` or any other name) and QPROP's airfoil model.

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
comment above the rows.  bild-mdo's metadata (format version, airfoil, hub
radius, the station widths ``dr [m]`` of the BILD stations, design point,
``end_stations = extrapolated`` and, for a polar that its name
does not rebuild, ``polar_file = <stem>.polar.json``, the polar file written
next to it, :mod:`bild_mdo.io.airfoil`) sit in
``# bild-mdo: key [unit] = value`` comment lines, which QPROP skips; reading
such a file drops the two extrapolated rows again, so the round trip returns
the BILD stations, and checks them against the widths (a file that lost
rows is refused, :func:`~bild_mdo.io.file_checks.check_stations`).  A QPROP
file from elsewhere is read with QPROP's meaning: the blade runs from the
first station (the hub radius) to ``R``; its last station may be at most one
station spacing from ``R`` (:func:`~bild_mdo.io.file_checks.check_end_gaps`),
else its annulus would stretch over blade the file does not describe.

The airfoil lines are fitted to the polar (a spanwise set: its blend at
r/R = :data:`QPROP_RADIAL_FRACTION`) at the design's reference Reynolds
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

from pathlib import Path

import numpy as np

from bild_mdo import validation
from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.atmosphere import isa
from bild_mdo.constants import angular_velocity
from bild_mdo.io.airfoil import (needs_polar_file, polar_description, polar_file_for, read_polar_file,
                                 resolve_airfoil, write_polar_file)
from bild_mdo.io.file_checks import FileMetadata, check_stations, file_errors, read_text
from bild_mdo.io.geometry import FORMAT_VERSION, as_geometry, design_point_key, format_number

#: Half width (in cl) of the band about the fitted lift line that counts as attached flow.
LINEAR_LIFT_BAND = 0.05

#: r/R at which the airfoil lines of a blade with several airfoils along the span are fitted.
QPROP_RADIAL_FRACTION = 0.75

#: QPROP's airfoil-model numbers, in the order of the file's lines.
QPROP_COEFFICIENTS = ("CL0", "CL_a", "CLmin", "CLmax", "CD0", "CD2u", "CD2l", "CLCD0", "REref", "REexp")


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
    # QPROP has one airfoil: a spanwise set is represented by its blend at 3/4 of the radius.
    station = {"radial_fraction": QPROP_RADIAL_FRACTION} if polar.varies_along_span else {}
    star = polar.max_lift_to_drag(np.array([reynolds / 2.0, reynolds, 2.0 * reynolds]), **station)
    a_star, cl_star, cd_star = float(star.alpha[1]), float(star.cl[1]), float(star.cd[1])
    alpha_lin = a_star + np.radians(np.linspace(-6.0, 0.0, 25))
    cl_lin = polar.evaluate(alpha_lin, reynolds, **station).cl
    cl_a, cl0 = np.polyfit(alpha_lin, cl_lin, 1)

    scan = np.radians(np.linspace(-20.0, 25.0, 901))
    values = polar.evaluate(scan, reynolds, **station)
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


def check_qprop_coefficients(coefficients):
    """Check QPROP's airfoil-model numbers: finite, ``CL_a > 0``, ``CLmin < CLmax``, drag terms >= 0, ``REref > 0``.

    Raises
    ------
    ValueError
        One line naming the first number out of its range.
    """
    missing = [name for name in QPROP_COEFFICIENTS if name not in coefficients]
    if missing:
        raise ValueError(f"QPROP airfoil model lacks {', '.join(missing)}")
    c = {name: float(validation.real_array(name, coefficients[name], ndim=(0,))) for name in QPROP_COEFFICIENTS}
    validation.positive("CL_a", c["CL_a"], units="1/rad", hint="lift-curve slope")
    validation.smaller("CLmin", c["CLmin"], "CLmax", c["CLmax"])
    for name in ("CD0", "CD2u", "CD2l"):
        validation.non_negative(name, c[name])
    validation.positive("REref", c["REref"])
    return c


def polar_from_qprop(coefficients):
    """An :class:`~bild_mdo.airfoil.AnalyticPolar` approximating QPROP's airfoil model.

    Linear lift ``CL0 + CL_a alpha``, drag ``CD0 (Re/REref)^REexp + CD2u (cl - CLCD0)^2``
    (symmetric: ``CD2l`` is not represented), stall near ``CLmax`` and ``CLmin``.

    Raises
    ------
    ValueError
        If a number is out of its range (:func:`check_qprop_coefficients`).
    """
    c = check_qprop_coefficients(coefficients)
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
    state = isa(geometry.design_point.get("altitude", 0.0))
    r75 = 0.75 * geometry.radius
    chord = float(np.interp(r75, geometry.radii, geometry.chord))
    omega = angular_velocity(geometry.design_point.get("rpm", 800.0))
    speed = np.hypot(geometry.design_point.get("v_axial", 0.0), omega * r75)
    return float(state.rho * speed * chord / state.mu)


def write_qprop(path, geometry, polar=None, reynolds=None):
    """Write a geometry as a QPROP propeller file (see the module docstring).

    Parameters
    ----------
    path : str or path
    geometry : RotorGeometry, dict or single-design DesignResult
    polar : Polar, optional
        Polar for the airfoil lines; default the geometry's polar, else its built-in airfoil.
    reynolds : float, optional
        ``REref``; default the design's reference Reynolds number.

    Returns
    -------
    pathlib.Path
    """
    geometry = as_geometry(geometry)
    polar = geometry.polar if polar is None else polar
    if polar is None:
        if geometry.airfoil is None:
            if geometry.polar_coefficients is None:
                raise ValueError("give a polar: the geometry names no built-in airfoil")
            coeffs = geometry.polar_coefficients
        else:
            polar = resolve_airfoil(geometry.airfoil)
    if polar is not None:
        coeffs = qprop_airfoil_coefficients(polar, _design_reynolds(geometry) if reynolds is None else reynolds)
    c = {k: float(v) for k, v in coeffs.items()}
    lines = [
        geometry.name or "rotor",
        "",
        f" {geometry.num_blades:d}  {format_number(geometry.radius)}   ! Nblades  [ R ]   (R in m)",
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
        f"# bild-mdo: hub_radius [m] = {format_number(geometry.hub_radius)}",
        # The widths of the BILD stations (not of the hub and tip rows): QPROP reads no comment line.
        "# bild-mdo: dr [m] = " + " ".join(map(format_number, geometry.dr)),
    ]
    for key, value in geometry.design_point.items():
        lines.append(f"# bild-mdo: design_point.{design_point_key(key)} = {format_number(value)}")
    path = Path(path)
    description = polar_description(geometry.polar, geometry.airfoil)
    if needs_polar_file(description):
        lines.append(f"# bild-mdo: polar_file = {write_polar_file(polar_file_for(path), description).name}")
    lines.append("# bild-mdo: end_stations = extrapolated")
    lines.append("#  r [m]  chord [m]  beta [deg]")
    radii, chord, twist = _with_end_stations(geometry)
    lines += [" " + "  ".join(map(format_number, row)) for row in zip(radii, chord, np.degrees(twist))]
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
    if not np.all(np.isfinite(values)):
        raise ValueError(f"{path}:{line_no}: expected finite numbers {what}, got {text!r}")
    return values


def read_qprop(path, load_polar=True):
    """Read a QPROP propeller file (see the module docstring).

    ``load_polar`` reads the polar file that a ``polar_file`` line names
    (``RotorGeometry.polar``); False skips it.

    Returns
    -------
    RotorGeometry
        With ``polar_coefficients`` from the file's airfoil lines and, for files
        written by bild-mdo, the airfoil name, hub radius and design point.

    Raises
    ------
    ValueError
        If the file is not a readable QPROP propeller file: one line naming the
        file (and its line) and what is wrong.
    """
    path = Path(path)
    with file_errors(path):
        geometry, polar_file = _read_qprop(path)
    if load_polar and polar_file:
        geometry.polar = read_polar_file(path.parent / polar_file)
    return geometry


def _read_qprop(path):
    meta, content = FileMetadata(path), []
    for line_no, raw in enumerate(read_text(path).splitlines(), start=1):
        stripped = raw.strip()
        if stripped.startswith("#"):
            body = stripped.lstrip("#").strip()
            if body.startswith("bild-mdo:") and "=" in body:
                with file_errors(path, line_no):
                    meta.add(*body[len("bild-mdo:"):].split("=", 1))
            continue
        if not content:
            if stripped:
                content.append((line_no, stripped))
            continue
        text = stripped.split("!", 1)[0].strip()
        if text:
            content.append((line_no, text))
    # First: a newer file may hold lines this reader does not know.
    meta.version()
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
    with file_errors(path, blades_line[0]):
        num_blades = validation.integer("Nblades", nb[0])
    coefficients = dict(zip(QPROP_COEFFICIENTS, (cl0, cla, clmin, clmax, cd0, cd2u, cd2l, clcd0, reref, reexp)))
    try:
        check_qprop_coefficients(coefficients)
    except ValueError as err:
        # The line of the first number named in the message (each number sits on one of lines 3-6 of content).
        lines = {name: content[2 + k // 2 if k < 4 else (4 if k < 8 else 5)][0]
                 for k, name in enumerate(QPROP_COEFFICIENTS)}
        raise ValueError(f"{path}:{lines[str(err).split()[0]]}: {err}") from None
    rows = np.array([_floats(text, 3, "a station row 'r c beta'", path, line_no)[:3]
                     for line_no, text in content[8:]])
    radii = rows[:, 0] * rfac + radd
    chord = rows[:, 1] * cfac + cadd
    beta = np.radians(rows[:, 2] * bfac + badd)
    # QPROP's blade runs from the first station to R (R unscaled, default the last station).
    hub, tip = radii[0], (nb[1] if len(nb) > 1 else radii[-1])
    if meta.text("end_stations") == "extrapolated":
        if radii.size < 4:
            raise ValueError(f"{path}: a bild-mdo QPROP file needs at least 2 stations besides hub and tip rows")
        radii, chord, beta = radii[1:-1], chord[1:-1], beta[1:-1]
    hub = meta.length("hub_radius", hub)
    geometry = meta.geometry(radii, chord, beta, radius=tip, hub_radius=hub, num_blades=num_blades, name=name,
                             polar_coefficients=coefficients)
    if "format" in meta:
        fix = "write the file again from the design (bild-mdo design --qprop)"
    else:
        fix = ("add a station row at r = R, or leave R out of the Nblades line (the blade then ends at the last "
               "station, as QPROP integrates it)")
        if rfac != 1.0:
            fix += f"; R is not scaled by Rfac = {rfac:g}, as in QPROP"
    return check_stations(path, geometry, meta.lengths("dr"), fix=fix), meta.text("polar_file")
