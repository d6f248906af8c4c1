"""A 3D blade for CAD or 3D printing: a closed triangle mesh (STL) or a lofted solid (STEP).

Built from the chord and twist of a :class:`~bild_mdo.io.geometry.RotorGeometry` and one airfoil
section: a NACA 4- or 5-digit designation or a Selig coordinates file
(:mod:`bild_mdo.airfoil.sources.coordinates`).

Frame (right-handed; metres in Python, the ``units`` of a file): **x** is the rotation axis, positive
in the thrust direction (the slipstream leaves towards -x); **z** is the blade's pitch-change axis,
radial (the section at radius r lies in the plane z = r); **y** = z × x.  The blade turns positively
about +x (clockwise seen from behind, looking along +x: a right-hand propeller), so at z > 0 it moves
towards -y: the leading edge points to -y, the upper (suction) side faces +x.  ``hand='left'``
mirrors y for the opposite rotation.

Stacking: each section's chord line crosses the z axis at the chord fraction ``stacking`` = s
(default 0.25, the quarter chord), and the twist beta (pitch from the rotor plane y-z) turns the
section about that axis, leading edge forward (+x) for beta > 0.  The point at chord fraction xi and
thickness eta (per chord, from the leading edge) of the section of chord c at radius r is::

    x = c [-(xi - s) sin(beta) + eta cos(beta)],   y = c [(xi - s) cos(beta) + eta sin(beta)],   z = r

Sections stand at the geometry's stations and, by default (``extend=True``), at the hub and tip
radius with the end stations' chord and twist (each end annulus has that chord in BEM), so the blade
spans R_hub ... R.  Between sections the surface is ruled (STL) or a smooth loft (STEP); flat root
and tip caps close it.  There is no hub: add one in CAD.
"""
from __future__ import annotations

import importlib.util
import os
import re
from pathlib import Path
from typing import NamedTuple

import numpy as np

from bild_mdo import validation
from bild_mdo.airfoil.sources.coordinates import parse_airfoil, read_coordinates
from bild_mdo.io.geometry import LENGTH_UNITS, as_geometry

__all__ = ["BladeSurface", "DEFAULT_STACKING", "LIBRARIES", "blade_sections", "blade_surface", "require",
           "section_coordinates", "step_solid", "write_step", "write_stl"]

#: Chord fraction of the stacking point on the pitch-change axis (the quarter chord).
DEFAULT_STACKING = 0.25
#: Points per surface (upper and lower) of a section.
DEFAULT_POINTS = 60
#: File format -> (the library that writes it, how to install it).
LIBRARIES = {"stl": ("trimesh", "pip install trimesh"),
             "step": ("OCP", "pip install 'bild-mdo[cad]' (OpenCascade's binding cadquery-ocp-novtk)")}
# NACA 5-digit mean lines by the P digit: normal (m, k1) from Abbott & von Doenhoff, Theory of Wing Sections
# (1959) ch. 6, reflexed (m, k1, k2/k1) as commonly tabulated; k1 is for c_l,design = 0.3 (L = 2), scaled by L/2.
_NACA5 = {1: (0.0580, 361.4), 2: (0.1260, 51.640), 3: (0.2025, 15.957), 4: (0.2900, 6.643), 5: (0.3910, 3.230)}
_NACA5_REFLEX = {2: (0.1300, 51.990, 0.000764), 3: (0.2170, 15.793, 0.00677), 4: (0.3180, 6.520, 0.0303),
                 5: (0.4410, 3.191, 0.1355)}
# Airfoil text a polar name adds around a section name: 'neuralfoil:naca2412', 'naca4412@re=1e6'.
_POLAR_DECORATION = re.compile(r"^\s*(?:neuralfoil:)?(?P<name>.+?)(?:\s*@\s*re\s*=.*)?\s*$", re.IGNORECASE)
_DIGITS = re.compile(r"^\s*(?:naca)?[\s_-]*\d+\s*$", re.IGNORECASE)


class BladeSurface(NamedTuple):
    """A closed triangle mesh of the blade(s): ``vertices[nv, 3]`` (m, the module's frame) and ``faces[nf, 3]``.

    ``faces`` holds the vertex indices of each triangle, counter-clockwise seen from outside.
    """

    vertices: np.ndarray
    faces: np.ndarray


def _cosine(n):
    return 0.5 * (1.0 - np.cos(np.linspace(0.0, np.pi, n + 1)))


def _naca_surfaces(digits, n):
    """Upper and lower surface (LE -> TE, paired along the mean line) of a NACA 4- or 5-digit section."""
    x = _cosine(n)
    t = int(digits[-2:]) / 100.0
    # The NACA thickness distribution (Abbott & von Doenhoff ch. 6), open (finite) trailing edge as tabulated.
    y_t = 5.0 * t * (0.2969 * np.sqrt(x) - 0.1260 * x - 0.3516 * x**2 + 0.2843 * x**3 - 0.1015 * x**4)
    if len(digits) == 4:
        m, p = int(digits[0]) / 100.0, int(digits[1]) / 10.0
        if m > 0.0 and p == 0.0:
            raise ValueError(f"NACA {digits}: camber {digits[0]} % needs a camber position (second digit) of 1 ... 9")
        front = x < p
        scale = np.where(front, m / max(p, 1e-12) ** 2, m / (1.0 - p) ** 2)
        y_c = scale * np.where(front, 2 * p * x - x**2, 1.0 - 2 * p + 2 * p * x - x**2)
        slope = 2.0 * scale * (p - x)
    else:
        design, position, reflexed = int(digits[0]) / 2.0, int(digits[1]), digits[2] == "1"
        if reflexed and position not in _NACA5_REFLEX:
            raise ValueError(f"NACA {digits}: a reflexed 5-digit mean line needs P = 2 ... 5")
        m, k1, ratio = _NACA5_REFLEX[position] if reflexed else (*_NACA5[position], 0.0)
        k1 *= design
        front = x < m
        # Normal mean line: ratio = 0 and the aft part is the straight line k1 m^3 (1 - x) / 6.
        cube = np.where(front, (x - m) ** 3, ratio * (x - m) ** 3)
        y_c = k1 / 6.0 * (cube - ratio * (1 - m) ** 3 * x - m**3 * x + m**3)
        slope = k1 / 6.0 * (np.where(front, 3 * (x - m) ** 2, 3 * ratio * (x - m) ** 2) - ratio * (1 - m) ** 3 - m**3)
    theta = np.arctan(slope)
    upper = np.column_stack([x - y_t * np.sin(theta), y_c + y_t * np.cos(theta)])
    lower = np.column_stack([x + y_t * np.sin(theta), y_c - y_t * np.cos(theta)])
    return upper, lower


def _file_surfaces(xy, n, where):
    """Upper and lower surface (LE -> TE) of Selig coordinates, at n + 1 cosine-spaced points each."""
    xy = np.asarray(xy, dtype=float)
    if xy.ndim != 2 or xy.shape[1] != 2 or xy.shape[0] < 5 or not np.isfinite(xy).all():
        raise ValueError(f"{where}: section coordinates must be finite (x, y) rows, at least 5")
    xy = xy[np.r_[True, np.any(np.diff(xy, axis=0) != 0.0, axis=1)]]
    le = int(np.argmin(xy[:, 0]))
    chord = xy[:, 0].max() - xy[le, 0]
    if le in (0, xy.shape[0] - 1) or chord <= 0.0:
        raise ValueError(f"{where}: expected Selig order (trailing edge, upper surface, leading edge, lower surface, "
                         "trailing edge); the smallest x is at an end of the list")
    unit = (xy - xy[le]) / chord
    first, second = unit[le::-1], unit[le:]
    if first[:, 1].mean() < second[:, 1].mean():
        first, second = second, first
    s = _cosine(n)
    surfaces = []
    for chain in (first, second):
        if np.any(np.diff(chain[:, 0]) <= 0.0):
            raise ValueError(f"{where}: x must fall along the upper surface to the leading edge and rise along "
                             "the lower surface (Selig order, no loops)")
        x = s * chain[-1, 0]
        surfaces.append(np.column_stack([x, np.interp(x, chain[:, 0], chain[:, 1])]))
    return tuple(surfaces)


def _surfaces(airfoil, num_points):
    n = validation.integer("num_points", num_points, minimum=4)
    if isinstance(airfoil, (str, os.PathLike)):
        text = _POLAR_DECORATION.match(airfoil)["name"] if isinstance(airfoil, str) else airfoil
        try:
            kind, spec = parse_airfoil(text)
        except ValueError:
            if _DIGITS.match(str(text)):  # a designation with a fault: parse_airfoil's message names it
                raise
            raise ValueError(f"airfoil {str(airfoil)!r} names no section shape; give a NACA 4- or 5-digit "
                             "designation (naca4412) or a Selig coordinates file") from None
        if kind == "naca":
            return _naca_surfaces(spec, n)
        try:
            return _file_surfaces(read_coordinates(spec)[1], n, spec)
        except ValueError as err:
            raise ValueError(f"airfoil {spec} is not a coordinates file: {err}") from None
    return _file_surfaces(airfoil, n, "airfoil")


def _sharp(upper, lower):
    return bool(np.hypot(*(upper[-1] - lower[-1])) < 1e-6)


def _loop(upper, lower):
    """Selig loop (TE, upper, LE, lower, TE) of paired surfaces; a sharp trailing edge is one point."""
    if _sharp(upper, lower):
        tail = 0.5 * (upper[-1] + lower[-1])
        return np.vstack([tail, upper[-2::-1], lower[1:-1]])
    return np.vstack([upper[::-1], lower[1:]])


def section_coordinates(airfoil, num_points=DEFAULT_POINTS):
    """The unit-chord section of ``airfoil``, as one closed loop in Selig order.

    Parameters
    ----------
    airfoil : str, os.PathLike or array_like, shape (k, 2)
        A NACA 4- or 5-digit designation (``'naca4412'``, ``'NACA 23012'``;
        ``'@re=...'`` and ``'neuralfoil:'`` of a polar name are ignored), the
        path of a Selig coordinates file, or Selig coordinates.  NACA sections
        follow Abbott & von Doenhoff (finite trailing edge, cosine spacing);
        coordinates are scaled to x = 0 ... 1 from their leading edge (smallest
        x), chord along x, and resampled at cosine-spaced x on each surface.
    num_points : int
        Points per surface (>= 4).

    Returns
    -------
    ndarray, shape (m, 2)
        ``(xi, eta)`` from the trailing edge over the upper surface to the leading edge (0, 0) and back
        along the lower one, the first point not repeated: ``m = 2 num_points + 1``, ``2 num_points``
        for a sharp trailing edge (one point).
    """
    return _loop(*_surfaces(airfoil, num_points))


def _cap(n, sharp):
    """Triangles (loop indices) filling a section: strips between paired upper and lower points."""
    m = 2 * n if sharp else 2 * n + 1
    i = np.arange(n)
    up, low = n - i, (n + i) % m
    up_next, low_next = n - i - 1, (n + i + 1) % m
    tris = np.vstack([np.column_stack([up, up_next, low_next]), np.column_stack([up, low_next, low])])
    keep = (tris[:, 0] != tris[:, 1]) & (tris[:, 1] != tris[:, 2]) & (tris[:, 0] != tris[:, 2])
    return tris[keep]


def _stations(geometry, extend, zero_chord):
    """Radii, chord and twist of the sections (zero-chord ends trimmed or refused, ends extended)."""
    r, c, beta = geometry.radii, geometry.chord, geometry.twist
    loaded = np.flatnonzero(c > 0.0)
    if loaded.size < r.size:
        zero = np.flatnonzero(c <= 0.0)
        problem = (f"chord is 0 at {zero.size} of {r.size} stations (r = {r[zero[0]]:.4g} ... {r[zero[-1]]:.4g} m): "
                   "the ideal load vanishes there and a 3D blade has no section")
        if loaded.size < 2 or loaded[-1] - loaded[0] + 1 != loaded.size:
            raise ValueError(f"{problem}, and fewer than 2 loaded stations or a gap between them remain")
        if zero_chord == "refuse":
            raise ValueError(f"{problem}; pass zero_chord='trim' to end the blade at the last loaded station, "
                             "or redesign with a larger reference chord")
    root_trimmed, tip_trimmed = loaded[0] > 0, loaded[-1] < r.size - 1
    r, c, beta = (a[loaded[0]:loaded[-1] + 1] for a in (r, c, beta))
    tol = 1e-9 * geometry.radius
    if extend and not root_trimmed and r[0] > geometry.hub_radius + tol:
        r, c, beta = np.r_[geometry.hub_radius, r], np.r_[c[0], c], np.r_[beta[0], beta]
    if extend and not tip_trimmed and r[-1] < geometry.radius - tol:
        r, c, beta = np.r_[r, geometry.radius], np.r_[c, c[-1]], np.r_[beta, beta[-1]]
    return r, c, beta


def blade_sections(geometry, airfoil=None, stacking=DEFAULT_STACKING, hand="right", extend=True,
                   zero_chord="refuse", num_points=DEFAULT_POINTS):
    """The blade's sections placed in space: one closed loop of points per section.

    Parameters
    ----------
    geometry : RotorGeometry, dict or single-design DesignResult
    airfoil : str, os.PathLike or array_like, optional
        Section shape (see :func:`section_coordinates`); default the
        geometry's ``airfoil`` when it is a NACA designation or coordinates file.
    stacking : float
        Chord fraction on the pitch-change (z) axis, 0 ... 1 (default the quarter chord).
    hand : {'right', 'left'}
        Rotation sense: 'right' turns positively about the thrust axis +x
        (leading edge towards -y); 'left' is its mirror image (y -> -y).
    extend : bool
        Add root and tip sections at the hub and tip radius (end stations' chord and twist).
    zero_chord : {'refuse', 'trim'}
        A station of zero chord has no section: refuse (ValueError), or end the
        blade at the last loaded station ('trim'; zero chord only at the ends).
    num_points : int
        Points per surface of a section.

    Returns
    -------
    loops : ndarray, shape (ns, m, 3)
        Section points (m), loop order of :func:`section_coordinates`.
    sharp : bool
        Whether the trailing edge is sharp (one point per section).
    """
    geometry = as_geometry(geometry)
    validation.choice("hand", hand, ("right", "left"))
    validation.choice("zero_chord", zero_chord, ("refuse", "trim"))
    stacking = float(validation.in_range("stacking", stacking, 0.0, 1.0, ndim=(0,)))
    airfoil = geometry.airfoil if airfoil is None else airfoil
    if airfoil is None:
        raise ValueError("the geometry names no airfoil; give the section (a NACA designation or coordinates file)")
    upper, lower = _surfaces(airfoil, num_points)
    unit = _loop(upper, lower)
    r, c, beta = _stations(geometry, bool(extend), zero_chord)
    xi, eta = unit[:, 0] - stacking, unit[:, 1]
    sin, cos, chord = np.sin(beta)[:, None], np.cos(beta)[:, None], c[:, None]
    x = chord * (-xi * sin + eta * cos)
    y = chord * (xi * cos + eta * sin) * (1.0 if hand == "right" else -1.0)
    z = np.broadcast_to(r[:, None], x.shape)
    return np.stack([x, y, z], axis=-1), _sharp(upper, lower)


def _copies(points, num_blades):
    """``points`` (..., 3) and its copies turned about x by 2 pi k / B, k = 0 ... B-1, stacked on a new axis 0."""
    angle = 2.0 * np.pi * np.arange(num_blades) / num_blades
    cos, sin, one, zero = np.cos(angle), np.sin(angle), np.ones(num_blades), np.zeros(num_blades)
    turn = np.array([[one, zero, zero], [zero, cos, -sin], [zero, sin, cos]])  # (3, 3, B)
    return np.einsum("ijb,...j->b...i", turn, points)


def blade_surface(geometry, airfoil=None, stacking=DEFAULT_STACKING, all_blades=False, **options):
    """The blade surface as a closed triangle mesh (ruled between sections, flat root and tip caps).

    Parameters
    ----------
    geometry : RotorGeometry, dict or single-design DesignResult
    all_blades : bool
        All ``num_blades`` blades, turned about x by 2 pi / B each (closed shells, no hub); default
        one blade, along +z.
    airfoil, stacking, **options
        ``hand``, ``extend``, ``zero_chord``, ``num_points`` of :func:`blade_sections`.

    Returns
    -------
    BladeSurface
        ``vertices`` (m) and ``faces``, oriented outwards (positive volume).
    """
    loops, sharp = blade_sections(geometry, airfoil=airfoil, stacking=stacking, **options)
    ns, m = loops.shape[:2]
    k, j = np.meshgrid(np.arange(ns - 1), np.arange(m), indexing="ij")
    a, b = k * m + j, k * m + (j + 1) % m
    c, d = b + m, a + m
    side = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    cap = _cap((m if sharp else m - 1) // 2, sharp)
    faces = np.concatenate([side, cap, cap[:, ::-1] + (ns - 1) * m])
    vertices = loops.reshape(-1, 3)
    v0, v1, v2 = (vertices[faces[:, i]] for i in range(3))
    if np.einsum("ij,ij->i", v0, np.cross(v1, v2)).sum() < 0.0:
        faces = faces[:, ::-1]
    if all_blades:
        count = as_geometry(geometry).num_blades
        vertices = _copies(vertices, count).reshape(-1, 3)
        faces = (faces[None] + (np.arange(count) * ns * m)[:, None, None]).reshape(-1, 3)
    return BladeSurface(np.ascontiguousarray(vertices), np.ascontiguousarray(faces))


def require(fmt):
    """Raise an ImportError naming what to install if the library that writes ``fmt`` ('stl', 'step') is missing."""
    module, install = LIBRARIES[fmt]
    if importlib.util.find_spec(module) is None:
        raise ImportError(f"writing {fmt.upper()} needs {module}: {install}")


def _scale(units):
    validation.choice("units", units, tuple(LENGTH_UNITS))
    return 1.0 / LENGTH_UNITS[units]


def write_stl(path, geometry, units="mm", **options):
    """Write the blade surface as a binary STL file (through trimesh).

    Parameters
    ----------
    path : str or path
    geometry : RotorGeometry, dict or single-design DesignResult
    units : {'mm', 'm', 'cm', 'in'}
        Length unit of the numbers in the file.  STL carries no unit; slicers and most CAD programs
        read millimetres, hence the default.
    **options
        ``airfoil``, ``stacking``, ``all_blades``, ``hand``, ``extend``, ``zero_chord``, ``num_points``
        of :func:`blade_surface`.

    Returns
    -------
    pathlib.Path
    """
    require("stl")
    import trimesh

    surface = blade_surface(geometry, **options)
    trimesh.Trimesh(surface.vertices * _scale(units), surface.faces, process=False).export(path, file_type="stl")
    return Path(path)


# -- STEP (OpenCascade, an optional extra) ------------------------------------------------------------------------

def _wire(points, sharp):
    """A section wire: one interpolating B-spline over the surfaces and, for a finite trailing edge, a line."""
    try:
        from OCP.collections import HArray1_gp_Pnt as PointArray
    except ImportError:  # OCP 7.x
        from OCP.TColgp import TColgp_HArray1OfPnt as PointArray
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeWire
    from OCP.GeomAPI import GeomAPI_Interpolate
    from OCP.gp import gp_Pnt

    chain = np.vstack([points, points[:1]]) if sharp else points
    array = PointArray(1, chain.shape[0])
    for i, p in enumerate(chain, 1):
        array.SetValue(i, gp_Pnt(*map(float, p)))
    spline = GeomAPI_Interpolate(array, False, 1e-9 * float(np.ptp(points, axis=0).max()))
    spline.Perform()
    wire = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(spline.Curve()).Edge())
    if not sharp:
        wire.Add(BRepBuilderAPI_MakeEdge(gp_Pnt(*map(float, points[-1])), gp_Pnt(*map(float, points[0]))).Edge())
    return wire.Wire()


def step_solid(geometry, all_blades=False, **options):
    """The blade as an OpenCascade solid: a smooth loft through the sections (a compound for ``all_blades``).

    Parameters are those of :func:`write_step` but ``units``; returns an
    ``OCP.TopoDS.TopoDS_Shape`` in millimetres (OpenCascade's unit).
    """
    require("step")
    from OCP.BRep import BRep_Builder
    from OCP.BRepOffsetAPI import BRepOffsetAPI_ThruSections
    from OCP.TopoDS import TopoDS_Compound

    loops, sharp = blade_sections(geometry, **options)
    blades = _copies(loops * _scale("mm"), as_geometry(geometry).num_blades if all_blades else 1)
    solids = []
    for blade in blades:
        loft = BRepOffsetAPI_ThruSections(True, False, 1e-6)
        loft.CheckCompatibility(False)
        for points in blade:
            loft.AddWire(_wire(points, sharp))
        loft.Build()
        if not loft.IsDone():
            raise ValueError("OpenCascade could not loft the blade sections into a solid")
        solids.append(loft.Shape())
    if len(solids) == 1:
        return solids[0]
    compound, builder = TopoDS_Compound(), BRep_Builder()
    builder.MakeCompound(compound)
    for solid in solids:
        builder.Add(compound, solid)
    return compound


def write_step(path, geometry, units="mm", **options):
    """Write the blade as a STEP (AP214) solid, lofted smoothly through the sections by OpenCascade.

    Needs the optional extra ``cad`` (:data:`LIBRARIES`); without it an ImportError names what to install.

    Parameters
    ----------
    path : str or path
    geometry : RotorGeometry, dict or single-design DesignResult
    units : {'mm', 'm', 'cm', 'in'}
        Length unit of the file (written into it).
    **options
        As for :func:`write_stl`.

    Returns
    -------
    pathlib.Path
    """
    _scale(units)
    shape = step_solid(geometry, **options)
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.Interface import Interface_Static
    from OCP.Message import Message, Message_Gravity
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer

    # The shape is in mm (OpenCascade's unit); the writer converts it to the file's unit.
    Interface_Static.SetCVal_s("write.step.unit", {"mm": "MM", "m": "M", "cm": "CM", "in": "INCH"}[units])
    found = Message.DefaultMessenger_s().Printers()
    printers = [(found.Value(i), found.Value(i).GetTraceLevel()) for i in range(1, found.Size() + 1)]
    try:  # OpenCascade prints transfer statistics on stdout: keep only failures
        for printer, _ in printers:
            printer.SetTraceLevel(Message_Gravity.Message_Fail)
        writer = STEPControl_Writer()
        writer.Transfer(shape, STEPControl_AsIs)
        path = Path(path)
        if writer.Write(str(path)) != IFSelect_RetDone:
            raise OSError(f"{path}: OpenCascade could not write the STEP file")
    finally:
        for printer, level in printers:
            printer.SetTraceLevel(level)
    return path
