"""What the geometry readers share: text decoding, the metadata of a file, its format version, twist units, and
stations that tile hub to tip.

Every check ends in ONE line a user can act on (a ValueError naming the file).  The rules for the station
widths and for files without them are in :mod:`bild_mdo.io.geometry`'s docstring.
"""
from __future__ import annotations

import codecs
import contextlib
import csv
from pathlib import Path

import numpy as np

from bild_mdo import validation
from bild_mdo.io.geometry import ANGLE_UNITS, FORMAT_VERSION, LENGTH_UNITS, RotorGeometry, split_key, station_widths

#: Exceptions a damaged file can raise inside a reader; :func:`file_errors` turns them into one ValueError.
_READ_ERRORS = (ValueError, TypeError, KeyError, IndexError, AttributeError, OverflowError, RecursionError,
                csv.Error)

#: Relative slack (of the tip radius) in the checks of station widths: files carry 12 digits.
WIDTH_TOLERANCE = 1e-9


def _one_line(text):
    return " ".join(str(text).split())


def not_text(path, what, detail, data=b""):
    """The one-line message for a file that is not text (``detail``: where the first binary byte is).

    ``data``, the file's first bytes, tells UTF-16 text (a Windows "Unicode text" save) from binary data.
    """
    if data.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        return f"{path}: the {what} file is UTF-16 text; save it as UTF-8 (with or without a byte-order mark)"
    return f"{path}: not a text {what} file ({detail}); is it the right file?"


def read_text(path, what="geometry"):
    """The text of ``path``, decoded as UTF-8 with or without a byte-order mark (spreadsheets write one).

    Raises
    ------
    FileNotFoundError
        ``'<what> file not found: PATH'``.
    ValueError
        One line: the file is not text (bytes that are not UTF-8, or a NUL
        byte), or cannot be read.
    """
    path = Path(path)
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise FileNotFoundError(f"{what} file not found: {path}") from None
    except IsADirectoryError:
        raise ValueError(f"{path}: is a folder, not a {what} file") from None
    except OSError as err:
        raise ValueError(f"{path}: cannot read the {what} file ({err.strerror or type(err).__name__})") from None
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as err:
        raise ValueError(not_text(path, what, f"byte {err.start} is not UTF-8", data)) from None
    if "\x00" in text:
        line = text.count("\n", 0, text.index("\x00")) + 1
        raise ValueError(not_text(path, what, f"a NUL byte on line {line}", data))
    return text


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
        raise ValueError(not_text(path, "geometry", f"byte {err.start} is not UTF-8")) from None
    except _READ_ERRORS as err:
        text = _one_line(err) if not isinstance(err, KeyError) else f"missing key {err}"
        if isinstance(err, RecursionError):
            text = "nested too deeply"
        if text.startswith(str(path)):
            raise ValueError(text) from None
        raise ValueError(f"{where}: {text or type(err).__name__}") from None


def check_version(path, version):
    """Check a file's format version: a whole number from 1 to :data:`FORMAT_VERSION`.

    Returns
    -------
    int

    Raises
    ------
    ValueError
        One line: a version newer than this reader (update bild-mdo), or not a version.
    """
    try:
        version = validation.integer("format version", version)
    except ValueError:
        raise ValueError(f"{path}: the format version must be a whole number >= 1, got {version!r}") from None
    if version > FORMAT_VERSION:
        raise ValueError(f"{path}: format version {version} is newer than this bild-mdo reads (1 ... "
                         f"{FORMAT_VERSION}); update bild-mdo (pip install --upgrade bild-mdo) to read it")
    return version


def twist_to_radians(path, key, values, units):
    """Twist values of a file in ``units`` (deg or rad) converted to rad.

    Raises
    ------
    ValueError
        For values declared in rad that go past one turn (2 pi) but would be
        plausible in degrees (at most 360): the message says they look like
        degrees, which the key does not say.
    """
    values = np.asarray(values, dtype=float)
    worst = float(np.max(np.abs(values))) if values.size else 0.0
    if units == "rad" and 2.0 * np.pi < worst <= 360.0:
        raise ValueError(f"{path}: {key!r} holds {worst:g}, more than one turn (2 pi = 6.28319 rad): the values "
                         f"look like degrees, but the file gives them in rad; write the key as "
                         f"'{split_key(key)[0]} [deg]' or give the twist in radians")
    return values * ANGLE_UNITS[units]


def check_end_gaps(path, geometry, fix):
    """Refuse stations without widths whose end annulus stretches over a missing part of the blade.

    The rule for files without station widths (format 1, QPROP files from
    elsewhere, hand-made tables): the gap from the first station to the hub
    and from the last station to the tip may be at most the spacing to the
    neighbouring station (plus the files' round-off).  Stations at the
    midpoints of equal annuli (every file bild-mdo wrote) have half a spacing
    there; tables with stations at the hub and the tip (CCBlade, QPROP)
    none.  A larger gap makes that station's annulus (:func:`station_widths`)
    more than 1.5 times its neighbour's and carries its load over blade that
    the file does not describe: stations are missing.

    Parameters
    ----------
    path : path
        The file, for the message.
    geometry : RotorGeometry
    fix : str
        What the user can do, ending the message.

    Raises
    ------
    ValueError
        One line naming the end, the gap, the spacing and ``fix``.
    """
    r, cells = geometry.radii, geometry.dr
    slack = WIDTH_TOLERANCE * geometry.radius
    ends = ((-1, -2, "last", geometry.radius - r[-1], "tip", f"R = {geometry.radius:.6g} m"),
            (0, 1, "first", r[0] - geometry.hub_radius, "hub", f"hub radius {geometry.hub_radius:.6g} m"))
    for i, j, which, gap, end, at in ends:
        spacing = abs(r[j] - r[i])
        if gap > spacing + slack:
            raise ValueError(f"{path}: the {which} station (r = {r[i]:.6g} m) is {gap:.6g} m from the {end} "
                             f"({at}), more than the {spacing:.6g} m to its neighbour: its annulus would stretch "
                             f"to the {end}, {cells[i] / cells[j]:.3g} times as wide as its neighbour's, so "
                             f"stations are missing (a cut file?); {fix}")


def check_stations(path, geometry, dr=None, fix="write the file again from the design"):
    """Check that a file's stations tile hub to tip as the analysis will integrate them.

    With the widths ``dr`` the file carries: as many as stations, adding up
    to ``radius - hub_radius``, and each the cell between the midpoints to its
    neighbours (:attr:`RotorGeometry.dr`, what the BEM analysis integrates
    over), all to :data:`WIDTH_TOLERANCE` of the tip radius.  Without them:
    :func:`check_end_gaps`.

    Parameters
    ----------
    path : path
        The file, for the messages.
    geometry : RotorGeometry
        The geometry read.
    dr : array_like or None
        The widths the file carries (m).
    fix : str
        What the user can do about a file without widths.

    Returns
    -------
    RotorGeometry
        ``geometry``.

    Raises
    ------
    ValueError
        One line naming what is wrong and what to do.
    """
    if dr is None:
        check_end_gaps(path, geometry, fix)
        return geometry
    dr = np.asarray(dr, dtype=float)
    slack = WIDTH_TOLERANCE * geometry.radius
    span = geometry.radius - geometry.hub_radius
    if dr.shape != geometry.radii.shape:
        raise ValueError(f"{path}: {geometry.num_radial} stations but {dr.size} widths 'dr [m]': the file was cut "
                         "or edited; write it again from the design")
    if not np.all(np.isfinite(dr)):
        raise ValueError(f"{path}: the station widths 'dr [m]' must be finite numbers")
    total = float(np.sum(dr))
    if not abs(total - span) <= slack:
        raise ValueError(f"{path}: the station widths 'dr [m]' add up to {total:.6g} m, but hub to tip is "
                         f"{span:.6g} m ({geometry.hub_radius:.6g} ... {geometry.radius:.6g} m): stations are "
                         "missing (a cut file?); write the file again from the design")
    cells = geometry.dr
    bad = np.flatnonzero(~(np.abs(dr - cells) <= slack))
    if bad.size:
        i = int(bad[0])
        raise ValueError(f"{path}: station {i} (r = {geometry.radii[i]:.6g} m) has the width dr = {dr[i]:.6g} m, "
                         f"but its annulus between the midpoints to its neighbours, which the analysis integrates "
                         f"over, is {cells[i]:.6g} m; correct 'dr [m]' or the radii (or drop dr to check the "
                         "stations only)")
    return geometry


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

    def lengths(self, key):
        """The values of ``key`` (numbers separated by blanks) in m, converted from its units; None when absent."""
        if key not in self.entries:
            return None
        value, units = self.entries[key]
        if units not in LENGTH_UNITS:
            raise ValueError(f"{self.path}: {key} has unknown units {units!r}; use one of {', '.join(LENGTH_UNITS)}")
        return np.array([self._float(key, part) for part in value.split()]) * LENGTH_UNITS[units]

    def version(self):
        """The format version of the ``format`` line, checked (:func:`check_version`); 1 without one."""
        text = self.text("format")
        if text is None:
            return 1
        try:
            value = float(text)
        except ValueError:
            value = text
        return check_version(self.path, value)

    def geometry(self, radii, chord, twist, radius, hub_radius, num_blades, name, **extra):
        """A :class:`RotorGeometry` with the stations given and airfoil, loss model and design point from here."""
        return RotorGeometry(radii=radii, chord=chord, twist=twist, radius=radius, hub_radius=hub_radius,
                             num_blades=num_blades, airfoil=self.text("airfoil"),
                             loss_model=self.text("loss_model", "tip_hub"), design_point=self.design_point,
                             name=name, **extra)
