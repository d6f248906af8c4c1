"""Airfoil shape arguments shared by the polar generators: a NACA 4- or 5-digit designation or a coordinates file.

:mod:`bild_mdo.airfoil.sources.xfoil` and :mod:`bild_mdo.airfoil.sources.neuralfoil`
accept the same ``airfoil`` argument; :func:`parse_airfoil` classifies it and
:func:`read_coordinates` reads a Selig-format coordinates file.
"""
from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np

__all__ = ["parse_airfoil", "read_coordinates"]

_NACA4 = re.compile(r"^\s*(?:naca)?[\s_-]*(\d+)\s*$", re.IGNORECASE)


#: Thickest NACA section (% of chord) accepted: XFOIL's viscous polars of thicker ones rarely converge.
MAX_NACA_THICKNESS = 40


def parse_airfoil(airfoil):
    """Classify an airfoil argument as a NACA 4- or 5-digit designation or a coordinates file.

    Parameters
    ----------
    airfoil : str or os.PathLike
        ``"NACA 4412"``, ``"naca4412"``, ``"4412"``, ``"NACA 23012"`` or the path of a
        coordinates file (Selig format: an optional name line, then ``x y``
        rows from the trailing edge over the upper surface to the leading
        edge and back along the lower surface).

    Returns
    -------
    tuple
        ``("naca", "4412")`` or ``("file", Path)``.

    Raises
    ------
    ValueError
        A NACA designation that is not 4 or 5 digits or has zero thickness, or a
        string that is neither a designation nor an existing file.
    """
    if isinstance(airfoil, os.PathLike):
        path = Path(airfoil)
        if not path.is_file():
            raise ValueError(f"airfoil coordinates file {path} does not exist")
        return "file", path
    text = str(airfoil)
    m = _NACA4.match(text)
    if m:
        digits = m.group(1)
        if len(digits) not in (4, 5):
            raise ValueError(f"airfoil {text!r}: only NACA 4- and 5-digit designations are supported "
                             f"(got {len(digits)} digits); for other sections pass a coordinates file")
        if len(digits) == 5 and not (digits[0] != "0" and digits[1] in "12345" and digits[2] in "01"):
            raise ValueError(f"airfoil {text!r}: a NACA 5-digit designation is L P Q TT with P in 1-5 and "
                             "Q 0 (normal) or 1 (reflexed), e.g. 23012")
        if int(digits[-2:]) == 0:
            raise ValueError(f"airfoil {text!r}: the last two digits give the thickness in percent "
                             f"of chord and must not be 00")
        if int(digits[-2:]) > MAX_NACA_THICKNESS:
            raise ValueError(f"airfoil {text!r}: a thickness of {int(digits[-2:])} % of chord is beyond what "
                             f"XFOIL's polars hold (NACA sections up to {MAX_NACA_THICKNESS} %); rotor blades use "
                             "about 6-25 %")
        if len(digits) == 4 and digits[0] != "0" and digits[1] == "0":
            raise ValueError(f"airfoil {text!r}: a NACA 4-digit designation is M P TT, the camber M % at P tenths "
                             "of the chord; a camber needs a position P of 1-9 (e.g. 4412)")
        return "naca", digits
    path = Path(text)
    if path.is_file():
        return "file", path
    raise ValueError(f"airfoil {text!r} is neither a NACA 4- or 5-digit designation ('NACA 4412', "
                     f"'naca23012', '4412') nor an existing coordinates file")


def read_coordinates(path):
    """Read a Selig-format coordinates file.

    Parameters
    ----------
    path : str or os.PathLike
        An optional name line, then ``x y`` rows from the trailing edge over
        the upper surface to the leading edge and back along the lower surface.

    Returns
    -------
    name : str or None
        The name line, if the file has one.
    xy : ndarray, shape (n, 2)
        The coordinates, ``n >= 10``.

    Raises
    ------
    ValueError
        A row that is not two finite numbers, a Lednicer-format file or fewer
        than 10 points; the message names the file (and line).
    """
    name = None
    points = []
    for lineno, line in enumerate(Path(path).read_text(encoding="utf-8", errors="replace").splitlines(), 1):
        tokens = line.split()
        if not tokens:
            continue
        try:
            values = [float(t) for t in tokens]
        except ValueError:
            if not points and name is None:
                name = line.strip()
                continue
            raise ValueError(f"{path}:{lineno}: expected two numbers 'x y', got {line.strip()!r}") from None
        if len(values) != 2:
            raise ValueError(f"{path}:{lineno}: expected two numbers 'x y', got {len(values)}")
        points.append(values)
    xy = np.array(points, dtype=float).reshape(-1, 2)
    if xy.shape[0] and (xy[0] > 1.5).all():
        raise ValueError(f"{path}: looks like Lednicer format (first row gives point counts "
                         f"{xy[0, 0]:g} {xy[0, 1]:g}); convert it to Selig format (one closed loop "
                         f"from the trailing edge over the upper surface and back)")
    if xy.shape[0] < 10:
        raise ValueError(f"{path}: {xy.shape[0]} coordinate points; at least 10 are needed")
    if not np.isfinite(xy).all():
        raise ValueError(f"{path}: coordinates must be finite numbers")
    return name, xy
