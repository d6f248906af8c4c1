"""Registry of the airfoil polars that ship with bild-mdo, and the one way to turn a name into a polar."""
from __future__ import annotations

import functools

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.airfoil.polar import Polar
from bild_mdo.airfoil.sources.readers import load_builtin_polars
from bild_mdo.airfoil.surrogate import TabulatedPolar


@functools.lru_cache(maxsize=None)
def naca4412():
    """Smooth surrogate of the built-in XFOIL polars of the NACA 4412 (cached).

    Ten Reynolds numbers from 5e4 to 2e6, as in the paper (Appendix 7.2).

    Returns
    -------
    TabulatedPolar
        The same object on every call.
    """
    return TabulatedPolar(load_builtin_polars("naca4412"), name="naca4412")


_REGISTRY = {
    "naca4412": naca4412,
    "analytic": AnalyticPolar,
}


def available_polars():
    """Names accepted by :func:`get_polar`.

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


def resolve_polar(airfoil):
    """The polar an ``airfoil`` argument stands for: a :class:`Polar` or a built-in name.

    Every public entry point that takes an airfoil (design, analysis,
    optimisation, verification) resolves it here, so they all accept the same
    values and raise the same message.

    Parameters
    ----------
    airfoil : Polar or str
        A polar object (returned as is) or the name of a built-in airfoil
        (case-insensitive, see :func:`available_polars`).

    Returns
    -------
    Polar
        ``airfoil`` itself, or :func:`get_polar` of the name (the cached
        surrogate for ``'naca4412'``).  Its ``name`` attribute labels results.

    Raises
    ------
    ValueError
        For an unknown name or a value that is neither a name nor a polar;
        the one-line message lists the available names.
    """
    if isinstance(airfoil, Polar):
        return airfoil
    choices = ", ".join(available_polars())
    if isinstance(airfoil, str):
        key = airfoil.strip().lower()
        if key not in _REGISTRY:
            raise ValueError(f"unknown airfoil {airfoil!r}; available: {choices} "
                             "(or pass a bild_mdo.airfoil.Polar object)")
        return _REGISTRY[key]()
    raise ValueError(f"airfoil must be a built-in name ({choices}) or a bild_mdo.airfoil.Polar object, "
                     f"got {type(airfoil).__name__}")
