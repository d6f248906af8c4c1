"""Registry of the airfoil polars that ship with bild-mdo, and the one way to turn an ``airfoil`` argument into a polar."""
from __future__ import annotations

import functools
import importlib.util
import os
import re
from pathlib import Path

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.airfoil.compressibility import CompressiblePolar
from bild_mdo.airfoil.generated import neuralfoil_polars, xfoil_polars
from bild_mdo.airfoil.mach_surrogate import tabulated_polar
from bild_mdo.airfoil.polar import Polar
from bild_mdo.airfoil.sources.coordinates import parse_airfoil, read_coordinates
from bild_mdo.airfoil.sources.readers import load_builtin_polars, read_polar_files
from bild_mdo.airfoil.spanwise import SpanwisePolar
from bild_mdo.airfoil.surrogate import TabulatedPolar
from bild_mdo.airfoil.thickness import coordinates_thickness_ratio, thickness_from_header


#: The lowest Reynolds number of the paper's NACA 4412 tables (Appendix 7.2): the built-in surrogate is split
#: there (``TabulatedPolar(split_reynolds=...)``), so that above it it is the paper's surrogate, bit for bit.
NACA4412_PAPER_LOWEST_REYNOLDS = 5e4


@functools.lru_cache(maxsize=None)
def naca4412():
    """Smooth surrogate of the built-in XFOIL polars of the NACA 4412 (cached).

    Sixteen Reynolds numbers from 1e4 to 2e6 (``bild_mdo/airfoil/data/README.md``):
    the paper's ten from 5e4 (Appendix 7.2) and six low-Reynolds tables from
    1e4 to 4.5e4 made with the same XFOIL settings.  The spline in Re is split
    at 5e4 (:data:`NACA4412_PAPER_LOWEST_REYNOLDS`), so from 5e4 up the
    surrogate is the one of the paper's tables alone; below 1e4 it continues
    bounded (:class:`~bild_mdo.airfoil.surrogate.TabulatedPolar`).  Loaded
    from the polar cache (:mod:`bild_mdo.airfoil.cache`) after the first
    build on a machine.

    Returns
    -------
    TabulatedPolar
        The same object on every call.
    """
    return TabulatedPolar.cached(load_builtin_polars("naca4412"), name="naca4412",
                                 split_reynolds=NACA4412_PAPER_LOWEST_REYNOLDS, low_end="physical")


_REGISTRY = {
    "naca4412": naca4412,
    "analytic": AnalyticPolar,
}

#: What ``resolve_polar`` accepts besides the built-in names, for messages.
ACCEPTED = ("a NACA 4- or 5-digit designation (naca2412, 'NACA 23012': XFOIL polars made on first use), "
            "a polar file, folder or list of polar files, a coordinates file, neuralfoil:NAME, or a Polar object")
NEURALFOIL_PREFIX = "neuralfoil:"

# Polars resolved in this process, so that one airfoil argument gives one object (models are cached per polar).
_RESOLVED = {}


def available_polars():
    """Built-in names accepted by :func:`get_polar`.

    Returns
    -------
    list of str
    """
    return sorted(_REGISTRY)


def get_polar(name):
    """A built-in polar by name (case-insensitive).

    Parameters
    ----------
    name : str
        ``'naca4412'`` (XFOIL surrogate, cached) or ``'analytic'`` (a new
        :class:`AnalyticPolar` with default parameters).

    Returns
    -------
    Polar

    Raises
    ------
    ValueError
        For an unknown name; the message lists the available airfoils.
    """
    key = str(name).strip().lower()
    try:
        factory = _REGISTRY[key]
    except KeyError:
        raise ValueError(f"unknown airfoil {name!r}; available: "
                         f"{', '.join(available_polars())}") from None
    return factory()


def _file_identity(path):
    stat = path.stat()
    return str(path.resolve()), stat.st_mtime_ns, stat.st_size


def _memo(key, build):
    if key not in _RESOLVED:
        _RESOLVED[key] = build()
    return _RESOLVED[key]


def _from_files(paths, name=None):
    files = sorted(Path(p) for p in paths)
    identity = tuple(_file_identity(f) if f.is_file() else (str(f.resolve()), tuple(
        _file_identity(g) for g in sorted(f.iterdir()) if g.is_file())) for f in files)
    if name is None:
        # 'naca2412_re500000.txt' -> 'naca2412'
        name = re.sub(r"[_\-. ]re[_\-=]?\d.*$", "", files[0].stem.lower(), flags=re.IGNORECASE) or files[0].stem
    polar = _memo(("files", identity), lambda: tabulated_polar(read_polar_files(files), name=name))
    # A '# thickness_ratio = t/c' comment line of the first table file gives the section thickness.
    first = files[0] if files[0].is_file() else next((f for f in sorted(files[0].iterdir()) if f.is_file()), None)
    header = None if first is None else thickness_from_header(first)
    if header is not None:
        polar.thickness_ratio = header
    return polar


def _generated(spec, tool):
    kind, value = parse_airfoil(spec)
    label = f"naca{value}" if kind == "naca" else value.stem.lower()
    identity = value if kind == "naca" else _file_identity(value)
    if tool == "neuralfoil":
        if importlib.util.find_spec("neuralfoil") is None:
            raise ValueError(f"airfoil '{NEURALFOIL_PREFIX}{spec}' needs the optional package neuralfoil: "
                             "pip install 'bild-mdo[neuralfoil]'")
        make = neuralfoil_polars
        label = f"{label}-neuralfoil"
    else:
        make = xfoil_polars
    try:
        polar = _memo((tool, identity), lambda: tabulated_polar(make(spec), name=label))
        if kind != "naca" and vars(polar).get("_thickness_ratio") is None:
            try:  # the shape's thickness; a shape it cannot be read from stays without one (the noise layer warns)
                polar.thickness_ratio = coordinates_thickness_ratio(read_coordinates(value)[1], str(value))
            except ValueError:
                pass
        return polar
    except (RuntimeError, ImportError) as exc:
        raise ValueError(f"airfoil {spec!r}: {' '.join(str(exc).split())}") from None


def _resolve_text(airfoil):
    text = airfoil.strip()
    key = text.lower()
    compact = "".join(key.split())   # "NACA 4412" is the built-in naca4412, not a new XFOIL run
    if compact in _REGISTRY:
        return _REGISTRY[compact]()
    if key.startswith(NEURALFOIL_PREFIX):
        return _generated(text[len(NEURALFOIL_PREFIX):].strip(), "neuralfoil")
    path = Path(text).expanduser()
    if path.is_dir():
        return _from_files([path], path.resolve().name.lower())
    if path.is_file():
        try:
            read_coordinates(path)
        except ValueError:
            return _from_files([path])
        return _generated(str(path), "xfoil")
    if "," in text:
        parts = [Path(p.strip()).expanduser() for p in text.split(",") if p.strip()]
        if all(p.exists() for p in parts):
            return _from_files(parts)
    try:
        kind, _ = parse_airfoil(text)
    except ValueError as exc:
        if any(c.isdigit() for c in text) and key.replace(" ", "").startswith("naca"):
            raise ValueError(str(exc)) from None
        kind = None
    if kind == "naca":
        return _generated(text, "xfoil")
    raise ValueError(f"unknown airfoil {airfoil!r}; available: {', '.join(available_polars())}, or {ACCEPTED}")


def resolve_polar(airfoil, compressibility=None):
    """The polar an ``airfoil`` argument stands for.

    Every public entry point that takes an airfoil (design, analysis,
    optimisation, verification, the command line) resolves it here, so they
    all accept the same values and raise the same one-line message.

    Parameters
    ----------
    airfoil : Polar, str, os.PathLike or sequence of them
        * a :class:`Polar` (returned as is);
        * a built-in name (``'naca4412'``, ``'analytic'``; case-insensitive);
        * a NACA 4- or 5-digit designation (``'naca2412'``, ``'NACA 23012'``):
          XFOIL polars at :data:`~bild_mdo.airfoil.generated.DEFAULT_REYNOLDS`,
          generated on first use and then read from the polar cache;
        * a Selig coordinates file: the same, for that shape;
        * a polar file, a folder of polar files, or a list of files (or one
          string of comma-separated files): XFOIL saved polars or tables at
          several Reynolds and Mach numbers
          (:func:`~bild_mdo.airfoil.sources.readers.read_polar_files`); tables
          at several Mach numbers give a Mach-dependent surrogate;
        * ``'neuralfoil:NAME'``: NeuralFoil polars of a NACA designation or
          coordinates file (needs ``pip install bild-mdo[neuralfoil]``).
    compressibility : {None, 'none', 'prandtl-glauert', 'karman-tsien'}
        Wrap the polar in a :class:`~bild_mdo.airfoil.compressibility.CompressiblePolar`
        (a lift correction for data measured at one Mach number).

    Returns
    -------
    Polar
        The same object for the same argument within a process (surrogates
        are cached in memory and on disk).  Its ``name`` labels results.

    Raises
    ------
    ValueError
        An unknown name, a file that cannot be read (the message names the
        file and line), XFOIL missing or failing, NeuralFoil missing, or a
        value of another type; always one line.
    """
    polar = _resolve(airfoil)
    if compressibility is None or str(compressibility).strip().lower() == "none":
        return polar
    if polar.varies_with_mach:
        raise ValueError(f"airfoil {polar.name!r} already depends on Mach number (tables at several Mach "
                         "numbers); leave compressibility unset")
    if isinstance(airfoil, Polar):
        return CompressiblePolar(polar, compressibility)
    # Keyed by the argument (whose polar _RESOLVED or an lru_cache keeps alive), not by id() alone.
    key = airfoil if isinstance(airfoil, str) else repr(airfoil)
    return _memo(("compressible", key, id(polar), str(compressibility).strip().lower()),
                 lambda: CompressiblePolar(polar, compressibility))


def _resolve(airfoil):
    if isinstance(airfoil, Polar):
        return airfoil
    if isinstance(airfoil, str):
        return _resolve_text(airfoil)
    if isinstance(airfoil, os.PathLike):
        return _resolve_text(os.fspath(airfoil))
    if isinstance(airfoil, (list, tuple)) and airfoil and all(isinstance(a, (str, os.PathLike)) for a in airfoil):
        missing = [str(a) for a in airfoil if not Path(a).exists()]
        if missing:
            raise ValueError(f"polar files not found: {', '.join(missing)}")
        return _from_files(airfoil)
    raise ValueError(f"airfoil must be a built-in name ({', '.join(available_polars())}), {ACCEPTED}; "
                     f"got {type(airfoil).__name__}")


def spanwise_polar(stations, compressibility=None):
    """A :class:`~bild_mdo.airfoil.spanwise.SpanwisePolar` from ``{r/R: airfoil}``.

    Parameters
    ----------
    stations : mapping of float to airfoil, or sequence of (float, airfoil) pairs
        Radial fraction of each airfoil and anything :func:`resolve_polar` accepts.
    compressibility : str, optional
        As in :func:`resolve_polar`, applied to every airfoil.

    Returns
    -------
    SpanwisePolar
    """
    pairs = sorted(dict(stations).items()) if not isinstance(stations, (list, tuple)) else sorted(stations)
    if not pairs:
        raise ValueError("a spanwise polar needs at least one (r/R, airfoil) station")
    try:
        fractions = [float(x) for x, _ in pairs]
    except (TypeError, ValueError):
        raise ValueError(f"spanwise stations must be (r/R, airfoil) pairs, got {stations!r}") from None
    return SpanwisePolar([resolve_polar(a, compressibility) for _, a in pairs], fractions)
