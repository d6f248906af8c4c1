"""The airfoil a geometry file carries: as text, as a polar description, or in a polar file next to it.

A blade file is only useful with the polar it was designed with, so every
format keeps it:

* JSON embeds :func:`~bild_mdo.airfoil.serialize.polar_to_dict` of the polar
  in each design entry (``"polar"``): tables, analytic parameters or the
  spanwise set, with every float as written by Python (read back bit for bit);
* CSV and QPROP files name the airfoil (``airfoil``), and, for a polar that a
  name does not rebuild (tables of an XFOIL run or of polar files, a spanwise
  set), a polar file next to them: ``<stem>.polar.json`` (:func:`write_polar_file`),
  named by the metadata line ``polar_file``.  Copy the two files together.

Text that names an airfoil (``--airfoil``, the ``airfoil`` line of a file) is
resolved by :func:`resolve_airfoil`: anything
:func:`~bild_mdo.airfoil.builtin.resolve_polar` accepts, a polar file written
here, a polar frozen at one Reynolds number (``naca4412@re=1e6``) and a
spanwise set of airfoils at radial fractions r/R, written
``0.2:naca4415;1:naca4412`` (or with commas, ``0.2:naca4415,1:naca4412``).
Before any of that, the files the text names are checked: a path that does
not exist is one line ``airfoil file or folder not found: PATH``, and a file
that is not text (a NUL or other control byte, or mostly bytes that are not
UTF-8) is one line saying so, instead of a parse error quoting its bytes.
"""
from __future__ import annotations

import json
import re
import warnings
from pathlib import Path

from bild_mdo.airfoil.builtin import resolve_polar
from bild_mdo.airfoil.polar import Polar
from bild_mdo.airfoil.serialize import polar_from_dict, polar_to_dict
from bild_mdo.airfoil.text import sweep_polar
from bild_mdo.io.file_checks import not_text, read_text

__all__ = ["POLAR_FILE_FORMAT", "airfoil_text", "check_airfoil_file", "polar_description", "polar_file_for",
           "read_polar_file", "resolve_airfoil", "write_polar_file"]

#: ``"format"`` of a polar file.
POLAR_FILE_FORMAT = "bild-mdo airfoil polar"
POLAR_FILE_VERSION = 1
#: Suffix of the polar file written next to a CSV or QPROP geometry file.
POLAR_FILE_SUFFIX = ".polar.json"

# r/R:AIRFOIL, as one station of a spanwise set.
_STATION = re.compile(r"^\s*[0-9.eE+-]+\s*:\s*\S")
_STATION_PREFIX = re.compile(r"^\s*[0-9.eE+-]+\s*:")
_NEURALFOIL_PREFIX = re.compile(r"^\s*neuralfoil\s*:", re.IGNORECASE)
_FIXED_RE_SUFFIX = re.compile(r"@\s*re\s*=.*$", re.IGNORECASE)
# Text that can only be a path: a folder separator, or the suffix of a polar, coordinates or polar-JSON file.
_PATH_LIKE = re.compile(r"[/\\]|\.(txt|dat|csv|pol|polar|json)$", re.IGNORECASE)
# Bytes of a file that is checked for text (a polar or coordinates file is far smaller).
_TEXT_CHECK_BYTES = 1 << 16
# Control characters that no text file holds (tab, line feed, carriage return, form feed and vertical tab may).
_CONTROL = re.compile(rb"[\x00-\x08\x0e-\x1f\x7f]")


def resolve_airfoil(airfoil):
    """The polar that ``airfoil`` (text, a path or a Polar) names (see the module docstring).

    Raises
    ------
    ValueError
        One line, for text that names no airfoil.
    """
    if isinstance(airfoil, Polar):
        return airfoil
    text = str(airfoil).strip() if isinstance(airfoil, (str, Path)) else airfoil
    if not isinstance(text, str):
        return resolve_polar(airfoil)
    for name in _named_paths(airfoil_text(text)):
        check_airfoil_file(name)
    if text.lower().endswith(".json") and Path(text).expanduser().is_file():
        return read_polar_file(Path(text).expanduser())
    return sweep_polar(airfoil_text(text))


def _named_paths(text):
    """The names in airfoil text that may be files: each member of a spanwise set, each of a list of files."""
    for member in text.split(";"):
        member = _FIXED_RE_SUFFIX.sub("", _NEURALFOIL_PREFIX.sub("", _STATION_PREFIX.sub("", member)))
        for name in member.split(","):
            if name.strip():
                yield name.strip()


def check_airfoil_file(name):
    """Check a name in airfoil text that is a file: it exists if it looks like a path, and it is text.

    Raises
    ------
    ValueError
        ``airfoil file or folder not found: NAME`` for a path (a name with a
        folder separator or a polar-file suffix) that does not exist;
        ``NAME: not a text polar file (...)`` for a file that holds binary
        data (a NUL or other control byte, or more than 16 and more than 10 %
        of its bytes not UTF-8, in its first 64 KiB).  Text in another 8-bit
        encoding with a few accented letters is still text (as the polar
        readers take it).
    """
    path = Path(name).expanduser()
    if not path.exists():
        if _PATH_LIKE.search(name):
            raise ValueError(f"airfoil file or folder not found: {name}")
        return
    if not path.is_file():
        return
    try:
        with path.open("rb") as handle:
            data = handle.read(_TEXT_CHECK_BYTES)
    except OSError as err:
        raise ValueError(f"{path}: cannot read the polar file ({err.strerror or type(err).__name__})") from None
    # ASCII control bytes never occur inside a UTF-8 multi-byte character: search the bytes themselves.
    control = _CONTROL.search(data)
    if control:
        raise ValueError(not_text(path, "polar", f"a control byte 0x{control.group()[0]:02x} at byte "
                                                 f"{control.start()}", data))
    # A multi-byte character cut at the end of the block is not binary.
    bad = data.decode("utf-8", errors="replace")[:-1].count("\ufffd")
    if bad > max(16, 0.1 * len(data)):
        raise ValueError(not_text(path, "polar", f"{bad} of its first {len(data)} bytes are not UTF-8 text", data))


def airfoil_text(text):
    """``text`` with a spanwise set written with commas (``0.2:naca4415,1:naca4412``) in the ``;`` form.

    The form :func:`~bild_mdo.airfoil.text.sweep_polar` reads (and a
    verification store keeps); any other text is returned stripped.
    """
    text = str(text).strip()
    parts = text.split(",")
    if ";" not in text and len(parts) > 1 and all(_STATION.match(p) for p in parts):
        return ";".join(part.strip() for part in parts)
    return text


def polar_description(polar, name=None):
    """``polar_to_dict(polar)``, or None (with a warning) for a polar that cannot be described by data.

    A polar that the text ``name`` rebuilds in this process (a built-in name, a
    form of :func:`resolve_airfoil`) needs no description and gives None quietly.
    """
    if polar is None:
        return None
    try:
        return polar_to_dict(polar)
    except ValueError as err:
        try:
            same = name is not None and resolve_airfoil(name) is polar
        except ValueError:
            same = False
        if not same:
            warnings.warn(f"the geometry file names its airfoil {name!r} but cannot carry its polar ({err}); "
                          "give the polar again when reading it (bild-mdo analyze --airfoil)", stacklevel=4)
        return None


def polar_file_for(path):
    """The polar file that goes with the geometry file ``path``: ``<stem>.polar.json`` in its folder."""
    path = Path(path)
    return path.with_name(path.stem + POLAR_FILE_SUFFIX)


def needs_polar_file(description):
    """Whether a polar described by ``description`` needs a polar file (a built-in name rebuilds itself)."""
    return description is not None and description.get("type") != "builtin"


def write_polar_file(path, polar):
    """Write ``polar`` as a polar file (JSON: ``format``, ``version``, ``airfoil`` = its description).

    Returns
    -------
    pathlib.Path
    """
    description = polar if isinstance(polar, dict) else polar_to_dict(polar)
    doc = {"format": POLAR_FILE_FORMAT, "version": POLAR_FILE_VERSION, "airfoil": description}
    path = Path(path)
    path.write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")
    return path


def read_polar_file(path):
    """The polar of a polar file written by :func:`write_polar_file`.

    Raises
    ------
    ValueError
        One line naming the file: missing, not JSON, not a polar file, or a damaged description.
    """
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"polar file {path} not found (it goes with the geometry file: copy both)")
    try:
        doc = json.loads(read_text(path, "polar"))
    except json.JSONDecodeError as err:
        raise ValueError(f"{path}:{err.lineno}: not valid JSON ({err.msg}, column {err.colno})") from None
    if not isinstance(doc, dict) or doc.get("format") != POLAR_FILE_FORMAT or not isinstance(doc.get("airfoil"),
                                                                                           dict):
        raise ValueError(f"{path}: not a {POLAR_FILE_FORMAT!r} file")
    return polar_from_description(doc["airfoil"], path)


def polar_from_description(description, where):
    """:func:`~bild_mdo.airfoil.serialize.polar_from_dict` with every error as one line naming ``where``."""
    try:
        return polar_from_dict(description)
    except (ValueError, TypeError, KeyError, IndexError, AttributeError) as err:
        text = " ".join(str(err).split()) or type(err).__name__
        raise ValueError(f"{where}: airfoil polar: {text}") from None
