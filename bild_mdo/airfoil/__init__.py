"""Airfoil polars: the Polar interface, an analytic polar, the smooth XFOIL surrogate and max L/D.

Public API
----------
Polar, PolarValues, PolarSecondDerivatives, MaxLiftToDrag
    The interface (:mod:`bild_mdo.airfoil.polar`).
AnalyticPolar
    Closed-form C^2 polar (linear lift, quadratic drag, Viterna post-stall).
TabulatedPolar
    Smooth bicubic surrogate of tabulated polars (XFOIL), Viterna-extended.
max_lift_to_drag
    Exact maximum-L/D point with Reynolds derivatives.
get_polar, naca4412, available_polars
    Registry of built-in airfoils.
PolarData, read_xfoil_polar, read_polar_table, load_builtin_polars
    Polar file readers (:mod:`bild_mdo.airfoil.readers`).
"""
from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.airfoil.builtin import available_polars, get_polar, naca4412
from bild_mdo.airfoil.max_lift_to_drag import max_lift_to_drag
from bild_mdo.airfoil.polar import MaxLiftToDrag, Polar, PolarSecondDerivatives, PolarValues
from bild_mdo.airfoil.surrogate import TabulatedPolar

__all__ = [
    "AnalyticPolar", "MaxLiftToDrag", "Polar", "PolarSecondDerivatives", "PolarValues",
    "TabulatedPolar", "available_polars", "get_polar", "max_lift_to_drag", "naca4412",
]

try:
    from bild_mdo.airfoil.readers import (PolarData, load_builtin_polars, read_polar_table,
                                          read_xfoil_polar)
except ModuleNotFoundError as exc:  # readers may not exist yet in a partial checkout
    if exc.name != "bild_mdo.airfoil.readers":
        raise
else:
    __all__ += ["PolarData", "load_builtin_polars", "read_polar_table", "read_xfoil_polar"]
