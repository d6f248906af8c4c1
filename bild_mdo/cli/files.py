"""Checks of the command line's output files and airfoil option, made before any work is done.

Every subcommand checks the files it will write (``--csv``, ``--json``,
``--qprop``, ``--plot``, ``--output-dir``) and resolves ``--airfoil`` first, so a
bad path or name stops the run at once with one line and no file created.
"""
from __future__ import annotations

import importlib.util
import os
from pathlib import Path

from bild_mdo.airfoil.builtin import available_polars
from bild_mdo.io.airfoil import resolve_airfoil
from bild_mdo.io.files import check_output_file

#: Figure formats matplotlib writes (by file suffix); a name without a suffix gets ``.png``.
FIGURE_SUFFIXES = (".png", ".pdf", ".svg", ".svgz", ".eps", ".ps", ".jpg", ".jpeg", ".tif", ".tiff", ".webp",
                   ".pgf")


def output_file(option, path):
    """The path of an output file after checking it can be written (see :func:`check_output_file`)."""
    return None if path is None else check_output_file(path, option)


def batch_files(option, path, count):
    """The QPROP file names a batch of ``count`` designs writes for ``path`` (``NAME_<i>.ext``), each checked."""
    if path is None:
        return []
    base = check_output_file(path, option)
    if count == 1:
        return [base]
    return [check_output_file(base.with_name(f"{base.stem}_{i}{base.suffix}"), option) for i in range(count)]


def figure_file(option, path):
    """The path a figure is written to: ``path``, or ``path.png`` without a suffix; checked, matplotlib present.

    Raises
    ------
    ValueError
        If matplotlib is missing, the suffix is not a figure format, or the
        file cannot be written.
    """
    if path is None:
        return None
    if importlib.util.find_spec("matplotlib") is None:
        raise ValueError(f"{option} needs matplotlib: pip install matplotlib (or leave out {option})")
    target = Path(path)
    if target.is_dir():
        raise ValueError(f"{option} {path}: is a folder; give a file name such as {target / 'figure.png'}")
    if not target.suffix:
        target = target.with_name(target.name + ".png")
    elif target.suffix.lower() not in FIGURE_SUFFIXES:
        raise ValueError(f"{option} {path}: unknown figure format {target.suffix!r}; use one of "
                         f"{', '.join(FIGURE_SUFFIXES)}")
    return check_output_file(target, option)


def output_folder(option, path):
    """Check that ``path`` is a writable folder or can be made as one (nothing is created)."""
    folder = Path(path)
    if folder.exists() and not folder.is_dir():
        raise ValueError(f"{option} {path}: is a file, not a folder")
    existing = folder
    while not existing.exists():
        existing = existing.parent
    if not existing.is_dir():
        raise ValueError(f"{option} {path}: {existing} is a file, not a folder")
    if not os.access(existing, os.W_OK | os.X_OK):
        raise ValueError(f"{option} {path}: folder {existing} is not writable")
    return folder


#: What ``--airfoil`` accepts, for the help of every subcommand that has it.
AIRFOIL_HELP = (f"airfoil: a built-in name ({', '.join(available_polars())}), a NACA 4- or 5-digit designation "
                "(naca2412: XFOIL polars made on first use, then cached), a polar file, a folder of polar files, "
                "a coordinates file, neuralfoil:NAME, a polar file written next to a geometry file "
                "(NAME.polar.json), AIRFOIL@re=RE (frozen at one Reynolds number), or airfoils along the span "
                "at radial fractions r/R: '0.2:naca4415;1:naca4412' (or with commas)")


def airfoil_polar(option, text):
    """The polar ``--airfoil`` names (:func:`~bild_mdo.io.airfoil.resolve_airfoil`); its ValueError is the one line."""
    if text is None:
        return None
    try:
        return resolve_airfoil(text)
    except ValueError as err:
        raise ValueError(f"{option}: {err}") from None
