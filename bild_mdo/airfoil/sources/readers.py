"""Read and write airfoil polar files (each read gives a :class:`PolarData`).

Two formats are read:

* XFOIL's saved polar (the file ``PACC`` writes): a header with
  ``Mach = ... Re = ... e 6 Ncrit = ...``, a line of column names
  (``alpha CL CD CDp CM Top_Xtr Bot_Xtr ...``), a line of dashes, then rows.
  Read with :func:`read_xfoil_polar`.
* A plain table, whitespace- or comma-separated, with a line naming the
  columns (angle ``alpha``, ``alpha_deg``, ``AoA`` or ``Alpha``; ``CL``/``cl``;
  ``CD``/``cd``; any case, any order, other columns ignored) before the rows.
  ``#`` starts a comment.  Comment lines of the form ``# reynolds = 1e6``
  (also ``mach``, ``ncrit``, ``source``) carry the operating condition, so a
  table written by :func:`write_polar_table` reads back without extra
  arguments.  Text lines before the column line are a preamble and skipped,
  except ``key,value`` (or ``key = value``, ``key: value``) lines that give
  ``Reynolds number``, ``Re``, ``Mach`` or ``Ncrit``: an airfoiltools.com CSV
  reads as it is downloaded.  Read with :func:`read_polar_table`.

:func:`read_polar_file` tells the two formats apart, and :func:`read_polar_files`
reads a list of files or a folder (several Reynolds and Mach numbers).

Every problem found in a file raises
:class:`~bild_mdo.airfoil.sources.polar_data.PolarFileError` with a message
that starts ``<file>:<line>:`` so the user can go straight to the bad line
(the checks shared by both formats live in :mod:`bild_mdo.airfoil.sources.polar_data`).

The NACA 4412 polars that ship with the package (XFOIL, ten Reynolds numbers,
see ``data/README.md``) are loaded with :func:`load_builtin_polars`.
"""
from __future__ import annotations

import importlib.resources
import math
import os
import re
from pathlib import Path

from bild_mdo.airfoil.sources.polar_data import (PolarData, PolarFileError, parse_float, polar_from_rows,
                                                 read_lines)

__all__ = [
    "available_builtin_polars",
    "load_builtin_polars",
    "parse_xfoil_file",
    "read_polar_file",
    "read_polar_files",
    "read_polar_table",
    "read_xfoil_polar",
    "write_polar_table",
]

_DATA_PACKAGE = "bild_mdo.airfoil"
_DATA_FOLDER = "data"
_BUILTIN_PATTERN = re.compile(r"^(?P<name>.+)_re(?P<re>\d+)\.txt$")
_TABLE_COLUMNS = ("alpha_deg", "cl", "cd")
# Column spellings (compared lower-case, without spaces or quotes) -> the column they name.
_COLUMN_ALIASES = {
    **{a: "alpha_deg" for a in ("alpha", "alpha_deg", "aoa", "aoa_deg", "alpha(deg)", "alpha[deg]",
                                "aoa(deg)", "aoa[deg]", "alpha_(deg)")},
    "cl": "cl", "c_l": "cl", "cd": "cd", "c_d": "cd",
}
# Preamble keys (lower case, spaces removed) -> operating condition.
_PREAMBLE_KEYS = {"reynolds": "reynolds", "reynoldsnumber": "reynolds", "re": "reynolds", "mach": "mach",
                  "machnumber": "mach", "ncrit": "ncrit", "n_crit": "ncrit"}
_PREAMBLE_SPLIT = re.compile(r"\s*[,=:]\s*")
_RE_IN_NAME = re.compile(r"(?:^|[_\-. ])re[_\-=]?(\d+(?:\.\d+)?(?:e[+]?\d+)?)(?![\d.])")
_POLAR_SUFFIXES = {".txt", ".dat", ".csv", ".pol", ".polar"}


# XFOIL writes "Re =     1.000 e 6": mantissa and exponent separated by " e ".
_XFOIL_RE = re.compile(r"\bRe\s*=\s*([-+]?\d*\.?\d+(?:[eE][-+]?\d+)?)(?:\s*[eE]\s*([-+]?\d+))?")
_XFOIL_MACH = re.compile(r"\bMach\s*=\s*([-+]?\d*\.?\d+(?:[eE][-+]?\d+)?)")
_XFOIL_NCRIT = re.compile(r"\bNcrit\s*=\s*([-+]?\d*\.?\d+)")


def parse_xfoil_file(path, lenient=False):
    """Header values and data rows of an XFOIL polar file, unchecked.

    Parameters
    ----------
    path : str or os.PathLike
        A file written by XFOIL's ``PACC`` command.
    lenient : bool
        Skip rows with a wrong column count or a malformed number instead of
        raising (for the files of an XFOIL run that crashed mid-row).

    Returns
    -------
    tuple
        ``(path, reynolds, mach, ncrit, rows)`` with ``rows`` a list of
        ``(lineno, alpha_deg, cl, cd)``; :func:`read_xfoil_polar` checks them.

    Raises
    ------
    PolarFileError
        Missing or unsupported header (and, unless ``lenient``, bad rows).
    """
    path, lines = read_lines(path)
    reynolds = mach = ncrit = None
    header_line = dash_line = None
    columns = None
    for i, line in enumerate(lines, start=1):
        if reynolds is None and (m := _XFOIL_RE.search(line)):
            exponent = int(m.group(2)) if m.group(2) else 0
            reynolds = float(m.group(1)) * 10.0 ** exponent
            if (mm := _XFOIL_MACH.search(line)):
                mach = float(mm.group(1))
            if (mn := _XFOIL_NCRIT.search(line)):
                ncrit = float(mn.group(1))
            continue
        lowered = [t.lower() for t in line.split()]
        if columns is None and "alpha" in lowered and "cl" in lowered and "cd" in lowered:
            columns, header_line = lowered, i
            continue
        if columns is not None and line.strip() and set(line.replace(" ", "")) == {"-"}:
            dash_line = i
            break
    if reynolds is None:
        raise PolarFileError(f"{path}:1: missing header: no 'Re = ...' line found; is this an XFOIL "
                             f"polar file (XFOIL OPER command PACC)?")
    if reynolds <= 0.0:
        raise PolarFileError(f"{path}: Re = {reynolds:g} in the header; a fixed Re > 0 polar is needed "
                             f"(XFOIL polar type 1)")
    if columns is None or dash_line is None:
        raise PolarFileError(f"{path}:{len(lines)}: missing header: expected a column line "
                             f"'alpha CL CD ...' followed by a line of dashes")
    if any("reynolds number ~" in line.lower() for line in lines[:dash_line]):
        raise PolarFileError(f"{path}: the Reynolds number varies with CL in this polar; only fixed-Re "
                             f"polars (XFOIL polar type 1) are supported")
    idx = [columns.index(c) for c in ("alpha", "cl", "cd")]
    rows = []
    for lineno in range(dash_line + 1, len(lines) + 1):
        tokens = lines[lineno - 1].split()
        if not tokens:
            continue
        try:
            if len(tokens) != len(columns):
                raise PolarFileError(f"{path}:{lineno}: {len(tokens)} columns, expected "
                                     f"{len(columns)} ({' '.join(columns)} from line {header_line})")
            rows.append((lineno, *(parse_float(tokens[j], path, lineno, columns[j]) for j in idx)))
        except PolarFileError:
            if not lenient:
                raise
    return path, reynolds, (mach if mach is not None else 0.0), ncrit, rows


def read_xfoil_polar(path):
    """Read a polar file saved by XFOIL's ``PACC`` command.

    Parameters
    ----------
    path : str or os.PathLike
        The polar file.

    Returns
    -------
    PolarData
        ``reynolds``, ``mach`` and ``ncrit`` from the header, ``alpha_deg``,
        ``cl``, ``cd`` from the columns ``alpha``, ``CL``, ``CD``.

    Raises
    ------
    PolarFileError
        Missing ``Re =`` header or column header, malformed numbers, wrong
        column count, fewer than
        :data:`~bild_mdo.airfoil.sources.polar_data.MIN_POINTS` rows,
        non-increasing alpha, ``cd <= 0`` or NaN; the message names the file
        and line.
    """
    path, reynolds, mach, ncrit, rows = parse_xfoil_file(path)
    return polar_from_rows(path, rows, reynolds, mach, ncrit, path.name)


def _split(line, delimiter):
    if delimiter == ",":
        return [t.strip() for t in line.split(",")]
    return line.split()


def read_polar_table(path, reynolds=None, mach=None):
    """Read a plain polar table with named columns ``alpha_deg``, ``cl``, ``cd``.

    The first line that is neither blank nor a comment names the columns,
    separated by commas or whitespace (the same separator is then used in
    every row).  Column order is free and other columns are ignored.  ``#``
    starts a comment; comment lines ``# key = value`` with key ``reynolds``,
    ``mach``, ``ncrit`` or ``source`` give the operating condition.

    Parameters
    ----------
    path : str or os.PathLike
        The table file.
    reynolds : float, optional
        Chord Reynolds number of the data.  Required unless the file has a
        ``# reynolds = ...`` line; if both are given they must agree.
    mach : float, optional
        Mach number; defaults to the file's ``# mach = ...`` line, else 0.

    Returns
    -------
    PolarData

    Raises
    ------
    PolarFileError
        Missing header or Reynolds number, malformed numbers, wrong column
        count, fewer than :data:`~bild_mdo.airfoil.sources.polar_data.MIN_POINTS`
        rows, non-increasing alpha, ``cd <= 0`` or NaN; the message names the
        file and line.
    """
    path, lines = read_lines(path)
    meta = {}
    columns = delimiter = header_line = candidate = None
    rows = []
    idx = None
    for lineno, raw in enumerate(lines, start=1):
        body, _, comment = raw.partition("#")
        if not body.strip():
            key, eq, value = comment.partition("=")
            key = key.strip().lower()
            if eq and key in ("reynolds", "mach", "ncrit", "source"):
                meta[key] = (value.strip(), lineno)
            continue
        if columns is None:
            line_delimiter = "," if "," in body else None
            tokens = [t.strip().strip("\"'") for t in _split(body, line_delimiter)]
            named = [_COLUMN_ALIASES.get(t.lower().replace(" ", "")) for t in tokens]
            if all(c in named for c in _TABLE_COLUMNS):
                delimiter, columns, header_line = line_delimiter, [t.lower() for t in tokens], lineno
                idx = [named.index(c) for c in _TABLE_COLUMNS]
                continue
            filled = [t for t in tokens if t]
            if not filled:
                continue
            if all(_is_number(t) for t in filled):
                if candidate is not None:
                    c_line, c_tokens = candidate
                    missing = [c for c in _TABLE_COLUMNS if c not in
                               [_COLUMN_ALIASES.get(t.lower().replace(" ", "")) for t in c_tokens]]
                    raise PolarFileError(f"{path}:{c_line}: missing header: found columns {c_tokens}, "
                                         f"missing {missing} (angle: alpha, alpha_deg, AoA; lift: cl; drag: cd)")
                raise PolarFileError(f"{path}:{lineno}: missing header: the first row holds numbers: add a "
                                     "header line naming the columns, e.g. 'alpha_deg cl cd'")
            # A preamble line: keep the operating condition it may give.
            parts = _PREAMBLE_SPLIT.split(body.strip(), maxsplit=1)
            key = parts[0].lower().replace(" ", "")
            if len(parts) == 2 and key in _PREAMBLE_KEYS and _is_number(parts[1].split()[0] if parts[1] else ""):
                meta.setdefault(_PREAMBLE_KEYS[key], (parts[1].split()[0], lineno))
            elif len(filled) >= 3:
                candidate = (lineno, [t.lower() for t in filled])
            continue
        tokens = _split(body, delimiter)
        if len(tokens) != len(columns):
            raise PolarFileError(f"{path}:{lineno}: {len(tokens)} columns, expected {len(columns)} "
                                 f"({', '.join(columns)} from line {header_line})")
        rows.append((lineno, *(parse_float(tokens[j], path, lineno, columns[j]) for j in idx)))
    if columns is None:
        raise PolarFileError(f"{path}:{max(len(lines), 1)}: missing header: no line naming the columns "
                             f"alpha_deg, cl, cd")

    def meta_float(key):
        value, lineno = meta[key]
        try:
            return float(value)
        except ValueError:
            raise PolarFileError(f"{path}:{lineno}: malformed number {value!r} for {key}") from None

    file_re = meta_float("reynolds") if "reynolds" in meta else None
    if file_re is None and (m := _RE_IN_NAME.search(path.stem.lower())):
        file_re = float(m.group(1))
    if reynolds is None:
        if file_re is None:
            raise PolarFileError(f"{path}: no Reynolds number: pass reynolds=... or add a line "
                                 f"'# reynolds = <value>' to the file (or name it like 'foil_re500000.txt')")
        reynolds = file_re
    elif file_re is not None and not math.isclose(float(reynolds), file_re, rel_tol=1e-9):
        raise PolarFileError(f"{path}:{meta['reynolds'][1]}: file says reynolds = {file_re:g} "
                             f"but reynolds={float(reynolds):g} was passed")
    if mach is None:
        mach = meta_float("mach") if "mach" in meta else 0.0
    ncrit = meta_float("ncrit") if "ncrit" in meta else None
    source = meta["source"][0] if "source" in meta else path.name
    try:
        return polar_from_rows(path, rows, float(reynolds), float(mach), ncrit, source)
    except PolarFileError:
        raise
    except ValueError as exc:
        raise PolarFileError(f"{path}: {exc}") from None


def read_polar_file(path):
    """Read one polar file (a path): an XFOIL saved polar or a plain table, told apart by XFOIL's ``Re =`` header.

    Returns a :class:`PolarData`; raises :class:`PolarFileError` as
    :func:`read_xfoil_polar` or :func:`read_polar_table` do.
    """
    path, lines = read_lines(path)
    head = lines[:20]
    if any(_XFOIL_RE.search(line) and "mach" in line.lower() for line in head) and any(
            set(line.replace(" ", "")) == {"-"} for line in lines[:40] if line.strip()):
        return read_xfoil_polar(path)
    return read_polar_table(path)


def read_polar_files(paths):
    """Read several polar files, or every polar file in a folder (``.txt .dat .csv .pol .polar``).

    Parameters
    ----------
    paths : str, os.PathLike or sequence of them
        Files, or one folder.

    Returns
    -------
    list of PolarData
        Sorted by Mach number, then Reynolds number.

    Raises
    ------
    PolarFileError
        An unreadable file (the message names it and the line), an empty
        folder, or two files at the same Reynolds and Mach numbers.
    """
    if isinstance(paths, (str, os.PathLike)):
        paths = [paths]
    files = []
    for p in map(Path, paths):
        if p.is_dir():
            found = sorted(f for f in p.iterdir() if f.is_file() and f.suffix.lower() in _POLAR_SUFFIXES)
            if not found:
                raise PolarFileError(f"{p}: no polar files ({', '.join(sorted(_POLAR_SUFFIXES))}) in this folder")
            files += found
        else:
            files.append(p)
    polars = [read_polar_file(f) for f in files]
    seen = {}
    for f, polar in zip(files, polars):
        key = (polar.reynolds, polar.mach)
        if key in seen:
            raise PolarFileError(f"{f}: Re = {polar.reynolds:g}, Mach = {polar.mach:g} again (also in "
                                 f"{seen[key]}); give one file per Reynolds and Mach number")
        seen[key] = f
    return sorted(polars, key=lambda q: (q.mach, q.reynolds))


def _is_number(token):
    try:
        float(token)
    except ValueError:
        return False
    return True


def write_polar_table(path, data):
    """Write ``data`` as a plain table that :func:`read_polar_table` reads back exactly.

    The operating condition goes into ``# key = value`` comment lines; the
    numbers are written with Python's shortest round-trip representation, so
    ``read_polar_table(path)`` returns the same values bit for bit.

    Parameters
    ----------
    path : str or os.PathLike
        Output file (overwritten).
    data : PolarData
        The polar to write.
    """
    if not isinstance(data, PolarData):
        raise TypeError(f"data must be a PolarData, got {type(data).__name__}")
    source = " ".join(str(data.source).split())
    out = [f"# source = {source}",
           f"# reynolds = {data.reynolds!r}",
           f"# mach = {data.mach!r}"]
    if data.ncrit is not None:
        out.append(f"# ncrit = {data.ncrit!r}")
    out.append(f"{'alpha_deg':>10} {'cl':>10} {'cd':>10}")
    for a, cl, cd in zip(data.alpha_deg, data.cl, data.cd):
        out.append(f"{float(a)!r:>10} {float(cl)!r:>10} {float(cd)!r:>10}")
    Path(path).write_text("\n".join(out) + "\n", encoding="utf-8")


def _builtin_files():
    folder = importlib.resources.files(_DATA_PACKAGE) / _DATA_FOLDER
    found = {}
    if folder.is_dir():
        for entry in folder.iterdir():
            m = _BUILTIN_PATTERN.match(entry.name)
            if m:
                found.setdefault(m.group("name"), []).append(entry)
    return found


def available_builtin_polars():
    """Names accepted by :func:`load_builtin_polars`, sorted (e.g. ``['naca4412']``)."""
    return sorted(_builtin_files())


def load_builtin_polars(name="naca4412"):
    """Load a polar set that ships with bild-mdo.

    Parameters
    ----------
    name : str
        Airfoil name; case, spaces and dashes are ignored (``"NACA 4412"`` is
        ``"naca4412"``).

    Returns
    -------
    list of PolarData
        One entry per Reynolds number, sorted by increasing Reynolds number.

    Raises
    ------
    ValueError
        Unknown name; the message lists the available names.
    """
    key = re.sub(r"[\s_-]+", "", str(name)).lower()
    files = _builtin_files()
    if key not in files:
        raise ValueError(f"no built-in polars named {name!r}; "
                         f"available: {', '.join(sorted(files)) or 'none'}")
    polars = []
    for entry in files[key]:
        with importlib.resources.as_file(entry) as real_path:
            polars.append(read_polar_table(os.fspath(real_path)))
    return sorted(polars, key=lambda p: p.reynolds)
