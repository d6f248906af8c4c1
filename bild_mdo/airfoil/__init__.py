"""Airfoil polars: the Polar interface, an analytic polar, the smooth XFOIL surrogate and max L/D.

Public API
----------
Polar, PolarValues, PolarSecondDerivatives
    The interface (:mod:`bild_mdo.airfoil.polar`).
AnalyticPolar
    Closed-form C^2 polar (linear lift, quadratic drag, Viterna post-stall).
TabulatedPolar
    Smooth bicubic surrogate of tabulated polars (XFOIL), Viterna-extended.
max_lift_to_drag, MaxLiftToDrag
    Exact maximum-L/D point with Reynolds derivatives.
get_polar, naca4412, available_polars, resolve_polar
    Registry of built-in airfoils; ``resolve_polar`` turns a name or a Polar into a Polar.
PolarData, read_xfoil_polar, read_polar_table, load_builtin_polars
    Polar file readers (:mod:`bild_mdo.airfoil.sources`).
"""
from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.airfoil.builtin import available_polars, get_polar, naca4412, resolve_polar
from bild_mdo.airfoil.max_lift_to_drag import MaxLiftToDrag, max_lift_to_drag
from bild_mdo.airfoil.polar import Polar, PolarSecondDerivatives, PolarValues
from bild_mdo.airfoil.sources import PolarData, load_builtin_polars, read_polar_table, read_xfoil_polar
from bild_mdo.airfoil.surrogate import TabulatedPolar

__all__ = [
    "AnalyticPolar", "MaxLiftToDrag", "Polar", "PolarData", "PolarSecondDerivatives", "PolarValues",
    "TabulatedPolar", "available_polars", "get_polar", "load_builtin_polars", "max_lift_to_drag",
    "naca4412", "read_polar_table", "read_xfoil_polar", "resolve_polar",
]
