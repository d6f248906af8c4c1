"""The rotor blade geometry that the file formats read and write: :class:`RotorGeometry`.

A geometry is the station radii ``r``, chord ``c`` and twist (pitch) ``beta``
of one blade, the tip and hub radius, the number of blades, the airfoil name
and the design point the geometry was made for.  The three file formats
(:mod:`bild_mdo.io.csv`, :mod:`bild_mdo.io.json`, :mod:`bild_mdo.io.qprop`)
always write the units into the file, as ``name [unit]`` keys
(:func:`unit_key`).  CSV and QPROP write numbers to :data:`SIGNIFICANT_DIGITS`
significant digits, so writing then reading gives the same geometry to 12
digits; JSON writes every digit.  Each format carries the blade's airfoil
(:mod:`bild_mdo.io.airfoil`).

This module knows no result class: :func:`as_geometry` takes a
:class:`RotorGeometry`, a dict of its fields, or any object with a
``geometry(index)`` method (a :class:`~bild_mdo.results.design.DesignResult`
has one).
"""
from __future__ import annotations

import contextlib
import csv
import dataclasses
import re

import numpy as np

from bild_mdo import validation
from bild_mdo.airfoil.polar import Polar
from bild_mdo.bem.prandtl import LOSS_MODELS

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

#: Length and angle units a file may use: label -> factor to m / rad.
LENGTH_UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254}
ANGLE_UNITS = {"deg": np.pi / 180.0, "rad": 1.0}
_KEY_RE = re.compile(r"^\s*(?P<key>[A-Za-z_][\w.]*)\s*(?:\[(?P<units>[^\]]*)\])?\s*$")


def unit_key(name, units):
    """``'name [units]'``, the key form used in the CSV header and the JSON files (``None`` -> ``'-'``)."""
    return f"{name} [{units or '-'}]"


def split_key(text):
    """``('name', 'units')`` of a ``'name [units]'`` key (units ``'-'`` when absent)."""
    match = _KEY_RE.match(text)
    if not match:
        raise ValueError(f"cannot read key {text!r}; expected 'name [unit]'")
    return match["key"], (match["units"] or "-").strip()


def format_number(value):
    """A number as written into the files: :data:`SIGNIFICANT_DIGITS` significant digits."""
    return f"{float(value):.{SIGNIFICANT_DIGITS}g}"


def design_point_key(key):
    """``'key [units]'`` of a design-point entry (units from :data:`DESIGN_POINT_UNITS`)."""
    return unit_key(key, DESIGN_POINT_UNITS.get(key, "-"))


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
        Airfoil name: a label, or text that :func:`~bild_mdo.io.airfoil.resolve_airfoil`
        resolves (a built-in name, a NACA designation, ...); None if unknown.
    loss_model : str
        Prandtl loss model of the design (``'tip_hub'``, ``'tip'``, ``'none'``).
    design_point : dict
        Design-point metadata, keys and units in :data:`DESIGN_POINT_UNITS`.
    name : str
        Free text.
    polar_coefficients : dict or None
        QPROP airfoil-model numbers read from a QPROP file.
    polar : Polar or None
        The polar the blade was designed with, when known.  The files carry it
        (JSON embeds it, CSV and QPROP name a polar file next to them:
        :mod:`bild_mdo.io.airfoil`) and the readers rebuild it.
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
    polar: Polar | None = dataclasses.field(default=None, repr=False)

    def __post_init__(self):
        self.radii = np.array(self.radii, dtype=float)
        self.chord = np.array(self.chord, dtype=float)
        self.twist = np.array(self.twist, dtype=float)
        self.radius = float(validation.positive("radius", self.radius, units="m", ndim=(0,)))
        self.hub_radius = float(validation.non_negative("hub_radius", self.hub_radius, units="m", ndim=(0,)))
        self.num_blades = validation.integer("num_blades", self.num_blades)
        validation.choice("loss_model", self.loss_model, LOSS_MODELS)
        if self.airfoil is not None and not isinstance(self.airfoil, str):
            raise ValueError(f"airfoil must be a name (text) or None, got {self.airfoil!r}")
        self.name = str(self.name)
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
        if not isinstance(self.design_point or {}, dict):
            raise ValueError(f"design_point must be a mapping of names to numbers, got {self.design_point!r}")
        self.design_point = {str(k): float(validation.real_array(f"design_point {k}", v, ndim=(0,)))
                             for k, v in (self.design_point or {}).items()}
        if self.polar_coefficients is not None:
            self.polar_coefficients = {str(k): float(validation.real_array(k, v, ndim=(0,)))
                                       for k, v in self.polar_coefficients.items()}

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
    """A :class:`RotorGeometry` from a geometry, a dict of its fields, or an object with a ``geometry`` method.

    Parameters
    ----------
    source : RotorGeometry, dict or object
        A dict takes the :class:`RotorGeometry` field names; an object with a
        ``geometry(index)`` method (such as a
        :class:`~bild_mdo.results.design.DesignResult`) is asked for one.
    index : int, optional
        Design of a batch, passed on to ``source.geometry``.

    Returns
    -------
    RotorGeometry
    """
    if isinstance(source, RotorGeometry):
        return source
    if isinstance(source, dict):
        return RotorGeometry(**source)
    make = getattr(source, "geometry", None)
    if callable(make):
        return make(index)
    raise ValueError(f"cannot make a rotor geometry from {type(source).__name__}; give a DesignResult, "
                     "RotorGeometry, dict of arrays or a geometry file path")


#: Exceptions a damaged file can raise inside a reader; :func:`file_errors` turns them into one ValueError.
_READ_ERRORS = (ValueError, TypeError, KeyError, IndexError, AttributeError, OverflowError, RecursionError,
                csv.Error)


def _one_line(text):
    return " ".join(str(text).split())


@contextlib.contextmanager
def file_errors(path, line_no=None):
    """Turn any error from reading ``path`` into one ``ValueError`` line that names the file (and line).

    Messages that already name the file are kept; a message of a check on the
    values (``chord must be ...``) gets ``path:`` (or ``path:line:``) in front.
    Bytes that are not UTF-8 text are reported as such.
    """
    where = f"{path}:{line_no}" if line_no is not None else f"{path}"
    try:
        yield
    except UnicodeDecodeError as err:
        raise ValueError(f"{where}: not a UTF-8 text file (byte {err.start}: {err.reason})") from None
    except _READ_ERRORS as err:
        text = _one_line(err) if not isinstance(err, KeyError) else f"missing key {err}"
        if isinstance(err, RecursionError):
            text = "nested too deeply"
        if text.startswith(str(path)):
            raise ValueError(text) from None
        raise ValueError(f"{where}: {text or type(err).__name__}") from None


class FileMetadata:
    """The ``key [units]: value`` metadata lines of a geometry file, as the CSV and QPROP readers collect them.

    Keys ``design_point.<name>`` go to :attr:`design_point` (floats); the
    others are kept as text with their units.
    """

    def __init__(self, path):
        self.path = path
        self.entries = {}
        self.design_point = {}

    def add(self, key_text, value):
        """Store one line's key (``'name [units]'``) and value (text)."""
        key, units = split_key(key_text)
        value = value.strip()
        if key.startswith("design_point."):
            name = key.split(".", 1)[1]
            self.design_point[name] = self._float(key, value)
        else:
            self.entries[key] = (value, units)

    def __contains__(self, key):
        return key in self.entries

    @staticmethod
    def _float(key, text):
        try:
            value = float(text)
        except ValueError:
            raise ValueError(f"{key} must be a number, got {text!r}") from None
        if not np.isfinite(value):
            raise ValueError(f"{key} must be a finite number, got {text!r}")
        return value

    def integer(self, key):
        """The value of ``key`` as an integer >= 1 (``'3'`` or ``'3.0'``)."""
        return validation.integer(key, self._float(key, self.text(key, "")))

    def text(self, key, default=None):
        """The value of ``key`` as text; ``default`` when absent (an empty value counts as absent)."""
        value = self.entries.get(key, ("", None))[0]
        return value if value else default

    def length(self, key, default):
        """The value of ``key`` in m (converted from its units); ``default`` when absent."""
        if key not in self.entries:
            return default
        value, units = self.entries[key]
        if units not in LENGTH_UNITS:
            raise ValueError(f"{self.path}: {key} has unknown units {units!r}; use one of {', '.join(LENGTH_UNITS)}")
        return self._float(key, value) * LENGTH_UNITS[units]

    def geometry(self, radii, chord, twist, radius, hub_radius, num_blades, name, **extra):
        """A :class:`RotorGeometry` with the stations given and airfoil, loss model and design point from here."""
        return RotorGeometry(radii=radii, chord=chord, twist=twist, radius=radius, hub_radius=hub_radius,
                             num_blades=num_blades, airfoil=self.text("airfoil"),
                             loss_model=self.text("loss_model", "tip_hub"), design_point=self.design_point,
                             name=name, **extra)
