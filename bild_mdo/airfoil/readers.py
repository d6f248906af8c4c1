"""Read and write airfoil polar files.

Two formats are read:

* XFOIL's saved polar (the file ``PACC`` writes): a header with
  ``Mach = ... Re = ... e 6 Ncrit = ...``, a line of column names
  (``alpha CL CD CDp CM Top_Xtr Bot_Xtr ...``), a line of dashes, then rows.
  Read with :func:`read_xfoil_polar`.
* A plain table, whitespace- or comma-separated, whose first non-comment line
  names the columns (``alpha_deg``, ``cl``, ``cd`` in any order, other columns
  ignored).  ``#`` starts a comment.  Comment lines of the form
  ``# reynolds = 1e6`` (also ``mach``, ``ncrit``, ``source``) carry the
  operating condition, so a table written by :func:`write_polar_table` reads
  back without extra arguments.  Read with :func:`read_polar_table`.

Every problem found in a file raises :class:`PolarFileError` with a message
that starts ``<file>:<line>:`` so the user can go straight to the bad line.

The NACA 4412 polars that ship with the package (XFOIL, ten Reynolds numbers,
see ``data/README.md``) are loaded with :func:`load_builtin_polars`.
"""
from __future__ import annotations

import dataclasses
import importlib.resources
import math
import os
import re
from pathlib import Path

import numpy as np

__all__ = [
    "MIN_POINTS",
    "PolarData",
    "PolarFileError",
    "available_builtin_polars",
    "load_builtin_polars",
    "read_polar_table",
    "read_xfoil_polar",
    "write_polar_table",
]

#: A polar file must hold at least this many points: fewer cannot resolve the
#: lift slope, the drag bucket and stall that the surrogate is fitted to.
MIN_POINTS = 10

_DATA_PACKAGE = "bild_mdo.airfoil"
_DATA_FOLDER = "data"
_BUILTIN_PATTERN = re.compile(r"^(?P<name>.+)_re(?P<re>\d+)\.txt$")
_TABLE_COLUMNS = ("alpha_deg", "cl", "cd")


class PolarFileError(ValueError):
    """A polar file cannot be read; the message names the file and the line."""


@dataclasses.dataclass(frozen=True, eq=False)
class PolarData:
    """Lift and drag coefficients of one airfoil at one Reynolds and Mach number.

    Attributes
    ----------
    reynolds : float
        Chord Reynolds number (> 0).
    mach : float
        Mach number (>= 0).
    alpha_deg : ndarray, shape (n,)
        Angle of attack (deg), strictly increasing.
    cl : ndarray, shape (n,)
        Lift coefficient.
    cd : ndarray, shape (n,)
        Drag coefficient (> 0).
    source : str
        Where the data came from: a file name or a generator description.
    ncrit : float or None
        e^N transition amplification factor used by XFOIL, when known.

    The arrays are read-only copies; the constructor checks shapes, finiteness,
    monotonic alpha and positive drag and raises ``ValueError`` otherwise.
    """

    reynolds: float
    mach: float
    alpha_deg: np.ndarray
    cl: np.ndarray
    cd: np.ndarray
    source: str
    ncrit: float | None = None

    def __post_init__(self):
        reynolds = float(self.reynolds)
        mach = float(self.mach)
        if not (math.isfinite(reynolds) and reynolds > 0.0):
            raise ValueError(f"{self.source}: Reynolds number must be finite and > 0, got {self.reynolds!r}")
        if not (math.isfinite(mach) and mach >= 0.0):
            raise ValueError(f"{self.source}: Mach number must be finite and >= 0, got {self.mach!r}")
        arrays = {}
        for field in ("alpha_deg", "cl", "cd"):
            arr = np.array(getattr(self, field), dtype=float)
            if arr.ndim != 1:
                raise ValueError(f"{self.source}: {field} must be 1-D, got shape {arr.shape}")
            arrays[field] = arr
        n = arrays["alpha_deg"].size
        if arrays["cl"].size != n or arrays["cd"].size != n:
            raise ValueError(f"{self.source}: alpha_deg, cl, cd lengths differ "
                             f"({n}, {arrays['cl'].size}, {arrays['cd'].size})")
        for field, arr in arrays.items():
            bad = np.flatnonzero(~np.isfinite(arr))
            if bad.size:
                raise ValueError(f"{self.source}: {field}[{bad[0]}] is not finite ({arr[bad[0]]})")
        steps = np.flatnonzero(np.diff(arrays["alpha_deg"]) <= 0.0)
        if steps.size:
            i = steps[0] + 1
            raise ValueError(f"{self.source}: alpha_deg must be strictly increasing; "
                             f"alpha_deg[{i}] = {arrays['alpha_deg'][i]} follows "
                             f"{arrays['alpha_deg'][i - 1]}")
        bad = np.flatnonzero(arrays["cd"] <= 0.0)
        if bad.size:
            raise ValueError(f"{self.source}: cd must be > 0; cd[{bad[0]}] = {arrays['cd'][bad[0]]}")
        ncrit = None if self.ncrit is None else float(self.ncrit)
        for arr in arrays.values():
            arr.flags.writeable = False
        object.__setattr__(self, "reynolds", reynolds)
        object.__setattr__(self, "mach", mach)
        object.__setattr__(self, "ncrit", ncrit)
        object.__setattr__(self, "source", str(self.source))
        for field, arr in arrays.items():
            object.__setattr__(self, field, arr)

    @property
    def lift_to_drag(self):
        """``cl / cd`` at every point, shape (n,)."""
        return self.cl / self.cd

    def __repr__(self):
        ncrit = "" if self.ncrit is None else f", ncrit={self.ncrit:g}"
        return (f"PolarData(reynolds={self.reynolds:g}, mach={self.mach:g}{ncrit}, "
                f"{self.alpha_deg.size} points, alpha {self.alpha_deg[0]:g}..{self.alpha_deg[-1]:g} deg, "
                f"source={self.source!r})") if self.alpha_deg.size else (
                f"PolarData(reynolds={self.reynolds:g}, mach={self.mach:g}{ncrit}, 0 points, "
                f"source={self.source!r})")


def _where(path, lineno):
    return f"{path}:{lineno}"


def _read_lines(path):
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
    except FileNotFoundError:
        raise PolarFileError(f"{path}: no such polar file") from None
    except IsADirectoryError:
        raise PolarFileError(f"{path}: is a directory, not a polar file") from None
    return path, text.splitlines()


def _parse_float(token, path, lineno, what):
    try:
        return float(token)
    except ValueError:
        raise PolarFileError(
            f"{_where(path, lineno)}: malformed number {token!r} in column {what!r}") from None


def _validated(path, rows, reynolds, mach, ncrit, source):
    """Check rows ``[(lineno, alpha, cl, cd), ...]`` and build a PolarData; errors name the line."""
    if len(rows) < MIN_POINTS:
        span = f" (lines {rows[0][0]}-{rows[-1][0]})" if rows else ""
        raise PolarFileError(f"{path}: only {len(rows)} data rows{span}; at least {MIN_POINTS} are needed")
    for lineno, alpha, cl, cd in rows:
        for name, value in (("alpha", alpha), ("cl", cl), ("cd", cd)):
            if not math.isfinite(value):
                raise PolarFileError(f"{_where(path, lineno)}: {name} is {value} (not a finite number)")
        if cd <= 0.0:
            raise PolarFileError(f"{_where(path, lineno)}: cd = {cd} must be > 0")
    for (prev_line, prev_alpha, _, _), (lineno, alpha, _, _) in zip(rows, rows[1:]):
        if alpha <= prev_alpha:
            raise PolarFileError(
                f"{_where(path, lineno)}: alpha must be strictly increasing; alpha = {alpha:g} follows "
                f"alpha = {prev_alpha:g} on line {prev_line} (sort the rows and remove duplicates)")
    arr = np.array([r[1:] for r in rows], dtype=float)
    return PolarData(reynolds=reynolds, mach=mach, alpha_deg=arr[:, 0], cl=arr[:, 1], cd=arr[:, 2],
                     source=source, ncrit=ncrit)


# XFOIL writes "Re =     1.000 e 6": mantissa and exponent separated by " e ".
_XFOIL_RE = re.compile(r"\bRe\s*=\s*([-+]?\d*\.?\d+(?:[eE][-+]?\d+)?)(?:\s*[eE]\s*([-+]?\d+))?")
_XFOIL_MACH = re.compile(r"\bMach\s*=\s*([-+]?\d*\.?\d+(?:[eE][-+]?\d+)?)")
_XFOIL_NCRIT = re.compile(r"\bNcrit\s*=\s*([-+]?\d*\.?\d+)")


def _parse_xfoil_file(path, lenient=False):
    """Header values and data rows ``[(lineno, alpha, cl, cd), ...]`` of an XFOIL polar file.

    With ``lenient`` (used on files of an XFOIL run that crashed) rows with a
    wrong column count or a malformed number are skipped instead of raising.
    """
    path, lines = _read_lines(path)
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
                raise PolarFileError(f"{_where(path, lineno)}: {len(tokens)} columns, expected "
                                     f"{len(columns)} ({' '.join(columns)} from line {header_line})")
            rows.append((lineno, *(_parse_float(tokens[j], path, lineno, columns[j]) for j in idx)))
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
        column count, fewer than :data:`MIN_POINTS` rows, non-increasing
        alpha, ``cd <= 0`` or NaN; the message names the file and line.
    """
    path, reynolds, mach, ncrit, rows = _parse_xfoil_file(path)
    return _validated(path, rows, reynolds, mach, ncrit, path.name)


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
        count, fewer than :data:`MIN_POINTS` rows, non-increasing alpha,
        ``cd <= 0`` or NaN; the message names the file and line.
    """
    path, lines = _read_lines(path)
    meta = {}
    columns = delimiter = header_line = None
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
            delimiter = "," if "," in body else None
            columns = [c.lower() for c in _split(body, delimiter)]
            header_line = lineno
            missing = [c for c in _TABLE_COLUMNS if c not in columns]
            if missing:
                looks_numeric = all(_is_number(c) for c in columns)
                hint = ("the first row holds numbers: add a header line naming the columns, "
                        "e.g. 'alpha_deg cl cd'") if looks_numeric else (
                        f"found columns {columns}, missing {missing}")
                raise PolarFileError(f"{_where(path, lineno)}: missing header: {hint}")
            idx = [columns.index(c) for c in _TABLE_COLUMNS]
            continue
        tokens = _split(body, delimiter)
        if len(tokens) != len(columns):
            raise PolarFileError(f"{_where(path, lineno)}: {len(tokens)} columns, expected {len(columns)} "
                                 f"({', '.join(columns)} from line {header_line})")
        rows.append((lineno, *(_parse_float(tokens[j], path, lineno, columns[j]) for j in idx)))
    if columns is None:
        raise PolarFileError(f"{path}:{max(len(lines), 1)}: missing header: no line naming the columns "
                             f"alpha_deg, cl, cd")

    def meta_float(key):
        value, lineno = meta[key]
        try:
            return float(value)
        except ValueError:
            raise PolarFileError(f"{_where(path, lineno)}: malformed number {value!r} for {key}") from None

    file_re = meta_float("reynolds") if "reynolds" in meta else None
    if reynolds is None:
        if file_re is None:
            raise PolarFileError(f"{path}: no Reynolds number: pass reynolds=... or add a line "
                                 f"'# reynolds = <value>' to the file")
        reynolds = file_re
    elif file_re is not None and not math.isclose(float(reynolds), file_re, rel_tol=1e-9):
        raise PolarFileError(f"{_where(path, meta['reynolds'][1])}: file says reynolds = {file_re:g} "
                             f"but reynolds={float(reynolds):g} was passed")
    if mach is None:
        mach = meta_float("mach") if "mach" in meta else 0.0
    ncrit = meta_float("ncrit") if "ncrit" in meta else None
    source = meta["source"][0] if "source" in meta else path.name
    try:
        return _validated(path, rows, float(reynolds), float(mach), ncrit, source)
    except PolarFileError:
        raise
    except ValueError as exc:
        raise PolarFileError(f"{path}: {exc}") from None


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
