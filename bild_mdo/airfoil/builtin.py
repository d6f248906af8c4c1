"""Registry of the airfoil polars that ship with bild-mdo."""
from __future__ import annotations

import functools

from bild_mdo.airfoil.analytic import AnalyticPolar


@functools.lru_cache(maxsize=None)
def naca4412():
    """Smooth surrogate of the built-in XFOIL polars of the NACA 4412 (cached).

    Ten Reynolds numbers from 5e4 to 2e6, as in the paper (Appendix 7.2).

    Returns
    -------
    TabulatedPolar
        The same object on every call.
    """
    from bild_mdo.airfoil.readers import load_builtin_polars
    from bild_mdo.airfoil.surrogate import TabulatedPolar

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
