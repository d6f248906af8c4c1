"""The data every airfoil-polar source returns, and the checks every polar file reader shares.

:class:`PolarData` holds one polar (one airfoil at one Reynolds and Mach
number).  The readers in :mod:`bild_mdo.airfoil.sources.readers`, the XFOIL
runner and the NeuralFoil runner all return it, and
:class:`~bild_mdo.airfoil.surrogate.TabulatedPolar` is fitted to a list of it.

A file reader collects rows ``(lineno, alpha_deg, cl, cd)`` and hands them to
:func:`polar_from_rows`, which checks them and raises :class:`PolarFileError`
with a message that starts ``<file>:<line>:``, so the user can go straight to
the bad line.
"""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np

__all__ = ["MIN_POINTS", "PolarData", "PolarFileError", "parse_float", "polar_from_rows", "read_lines"]

#: A polar file must hold at least this many points: fewer cannot resolve the
#: lift slope, the drag bucket and stall that the surrogate is fitted to.
MIN_POINTS = 10


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


def read_lines(path):
    """The lines of a polar file, with the file's path.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    path : Path
    lines : list of str
        Without line ends; undecodable bytes are replaced.

    Raises
    ------
    PolarFileError
        The file does not exist or is a directory.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig", errors="replace")
    except FileNotFoundError:
        raise PolarFileError(f"{path}: no such polar file") from None
    except IsADirectoryError:
        raise PolarFileError(f"{path}: is a directory, not a polar file") from None
    return path, text.splitlines()


def parse_float(token, path, lineno, what):
    """``float(token)``, or a :class:`PolarFileError` naming the file, line and column ``what``."""
    try:
        return float(token)
    except ValueError:
        raise PolarFileError(
            f"{_where(path, lineno)}: malformed number {token!r} in column {what!r}") from None


def polar_from_rows(path, rows, reynolds, mach, ncrit, source):
    """Check the rows read from a polar file and build a :class:`PolarData`.

    Parameters
    ----------
    path : Path
        The file, for messages.
    rows : list of tuple
        ``(lineno, alpha_deg, cl, cd)`` in file order.
    reynolds, mach : float
        Operating condition of the file.
    ncrit : float or None
        e^N amplification factor, when known.
    source : str
        :attr:`PolarData.source`.

    Returns
    -------
    PolarData
        The rows as arrays, after the checks below.

    Raises
    ------
    PolarFileError
        Fewer than :data:`MIN_POINTS` rows, a value that is not finite,
        ``cd <= 0`` or alpha not strictly increasing; the message names the line.
    """
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
