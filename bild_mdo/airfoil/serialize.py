"""Polars as plain, JSON-ready dictionaries, and back: how a geometry file carries its airfoil.

:func:`polar_to_dict` describes a polar with numbers, strings and lists only
(no pickle), and :func:`polar_from_dict` rebuilds it:

* a built-in polar by its name (``{"type": "builtin", "name": "naca4412"}``);
* an :class:`~bild_mdo.airfoil.analytic.AnalyticPolar` by its parameters;
* a tabulated polar (:class:`~bild_mdo.airfoil.surrogate.TabulatedPolar`,
  :class:`~bild_mdo.airfoil.mach_surrogate.MachTabulatedPolar`: XFOIL, polar
  files, NeuralFoil) by its tables and surrogate settings, so a file read on
  another machine gives the same surrogate (and the polar cache makes the
  rebuild free on this one);
* a :class:`~bild_mdo.airfoil.compressibility.CompressiblePolar` by its base
  and correction, a :class:`~bild_mdo.airfoil.spanwise.SpanwisePolar` by its
  stations.

A polar whose section thickness ratio was set (``polar.thickness_ratio``, used by the noise models;
:mod:`bild_mdo.airfoil.thickness`) carries it as ``"thickness_ratio"`` in its description (not a
built-in, whose name gives it).

Floats are kept as Python floats, which ``json`` writes with their shortest
round-trip representation, so a polar written to JSON and read back gives
the same numbers bit for bit.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.airfoil.builtin import _REGISTRY, get_polar
from bild_mdo.airfoil.compressibility import CompressiblePolar
from bild_mdo.airfoil.mach_surrogate import MachTabulatedPolar, tabulated_polar
from bild_mdo.airfoil.sources.polar_data import PolarData
from bild_mdo.airfoil.spanwise import SpanwisePolar
from bild_mdo.airfoil.surrogate import TabulatedPolar
from bild_mdo.airfoil.thickness import checked_thickness_ratio

__all__ = ["polar_from_dict", "polar_to_dict"]


def _floats(array):
    return [float(x) for x in np.asarray(array, dtype=float)]


def polar_to_dict(polar):
    """A JSON-ready description of ``polar`` (see the module docstring).

    Parameters
    ----------
    polar : Polar

    Returns
    -------
    dict

    Raises
    ------
    ValueError
        A polar that cannot be described by data (a user's own Polar
        subclass, or a surrogate made without its tables).
    """
    description = _describe(polar)
    explicit = vars(polar).get("_thickness_ratio")
    if explicit is not None and description["type"] != "builtin":
        description["thickness_ratio"] = float(explicit)
    return description


def _describe(polar):
    for name, factory in _REGISTRY.items():
        if name != "analytic" and polar is factory():
            return {"type": "builtin", "name": name}
    if isinstance(polar, AnalyticPolar):
        return {"type": "analytic", "parameters": {f.name: float(getattr(polar, f.name))
                                                   for f in dataclasses.fields(polar)}}
    if isinstance(polar, (TabulatedPolar, MachTabulatedPolar)):
        if polar.data is None:
            raise ValueError(f"{polar.name}: this surrogate was made without its tables and cannot be written")
        settings = {k: (None if v is None else (v if isinstance(v, str) else float(v)))
                    for k, v in polar.settings.items()}
        tables = [{"reynolds": p.reynolds, "mach": p.mach, "ncrit": p.ncrit, "source": p.source,
                   "alpha_deg": _floats(p.alpha_deg), "cl": _floats(p.cl), "cd": _floats(p.cd)} for p in polar.data]
        return {"type": "tables", "name": polar.name, "settings": settings, "tables": tables}
    if isinstance(polar, CompressiblePolar):
        return {"type": "compressible", "correction": polar.correction, "reference_mach": polar.reference_mach,
                "name": polar.name, "base": polar_to_dict(polar.base)}
    if isinstance(polar, SpanwisePolar):
        return {"type": "spanwise", "name": polar.name, "radial_fractions": _floats(polar.radial_fractions),
                "polars": [polar_to_dict(p) for p in polar.polars]}
    raise ValueError(f"airfoil {getattr(polar, 'name', polar)!r} ({type(polar).__name__}) cannot be written to a "
                     "file; use a built-in, tabulated, analytic, compressible or spanwise polar")


def polar_from_dict(data):
    """The polar described by the dictionary ``data`` (the inverse of :func:`polar_to_dict`).

    Raises ``ValueError`` (one line) for an unknown ``type`` or missing or
    malformed fields.
    """
    polar = _rebuild(data)
    if isinstance(data, dict) and data.get("thickness_ratio") is not None and data.get("type") != "builtin":
        polar.thickness_ratio = checked_thickness_ratio(data["thickness_ratio"], "airfoil thickness_ratio")
    return polar


def _rebuild(data):
    try:
        kind = data["type"]
        if kind == "builtin":
            return get_polar(data["name"])
        if kind == "analytic":
            return AnalyticPolar(**data["parameters"])
        if kind == "tables":
            tables = [PolarData(t["reynolds"], t["mach"], t["alpha_deg"], t["cl"], t["cd"], source=t["source"],
                                ncrit=t.get("ncrit")) for t in data["tables"]]
            return tabulated_polar(tables, name=data.get("name"), **data.get("settings", {}))
        if kind == "compressible":
            return CompressiblePolar(polar_from_dict(data["base"]), data["correction"], data["reference_mach"],
                                     name=data.get("name"))
        if kind == "spanwise":
            return SpanwisePolar([polar_from_dict(p) for p in data["polars"]], data["radial_fractions"],
                                 name=data.get("name"))
    except (KeyError, TypeError) as exc:
        raise ValueError(f"airfoil description is incomplete or malformed ({type(exc).__name__}: {exc})") from None
    raise ValueError(f"unknown airfoil description type {data.get('type')!r}; expected builtin, analytic, tables, "
                     "compressible or spanwise")
