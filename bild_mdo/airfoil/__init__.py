"""Airfoil polars: the Polar interface, analytic and tabulated polars, Mach and spanwise models, max L/D.

Public API
----------
Polar, PolarValues, PolarSecondDerivatives, MachPolarValues, StationPolarValues
    The interface (:mod:`bild_mdo.airfoil.polar`): ``evaluate(alpha, Re, mach=None, radial_fraction=None)``.
AnalyticPolar
    Closed-form C^2 polar (linear lift, quadratic drag, Viterna post-stall).
TabulatedPolar
    Smooth bicubic surrogate of tabulated polars (XFOIL), Viterna-extended, cached on disk.
MachTabulatedPolar, tabulated_polar
    Surrogate of tables at several Mach numbers, smooth in ``(alpha, Re, M)``.
CompressiblePolar
    Prandtl-Glauert or Karman-Tsien lift correction of single-Mach data.
SpanwisePolar
    Airfoils placed along the span, blended C^2-smoothly in ``r/R``.
max_lift_to_drag, MaxLiftToDrag, StationMaxLiftToDrag
    Exact maximum-L/D point with derivatives with respect to Re (and Mach, ``r/R``).
get_polar, naca4412, available_polars, resolve_polar, spanwise_polar
    Built-in airfoils; ``resolve_polar`` turns any airfoil argument (name, NACA designation,
    files, folder, coordinates, ``neuralfoil:NAME``) into a Polar.
PolarData, read_xfoil_polar, read_polar_table, read_polar_files, load_builtin_polars
    Polar file readers (:mod:`bild_mdo.airfoil.sources`).
cache_dir, clear_cache
    The on-disk polar cache (:mod:`bild_mdo.airfoil.cache`).
polar_to_dict, polar_from_dict
    JSON-ready description of a polar (tables, settings, stations) and back.
"""
from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.airfoil.builtin import available_polars, get_polar, naca4412, resolve_polar, spanwise_polar
from bild_mdo.airfoil.cache import cache_dir, clear_cache
from bild_mdo.airfoil.compressibility import CompressiblePolar
from bild_mdo.airfoil.mach_surrogate import MachTabulatedPolar, tabulated_polar
from bild_mdo.airfoil.max_lift_to_drag import MaxLiftToDrag, StationMaxLiftToDrag, max_lift_to_drag
from bild_mdo.airfoil.polar import (MachPolarSecondDerivatives, MachPolarValues, Polar, PolarSecondDerivatives,
                                    PolarValues, StationPolarSecondDerivatives, StationPolarValues)
from bild_mdo.airfoil.serialize import polar_from_dict, polar_to_dict
from bild_mdo.airfoil.sources import (PolarData, load_builtin_polars, read_polar_files, read_polar_table,
                                      read_xfoil_polar)
from bild_mdo.airfoil.spanwise import SpanwisePolar
from bild_mdo.airfoil.surrogate import TabulatedPolar
from bild_mdo.airfoil.text import (DEFAULT_AIRFOIL, REYNOLDS_INDEPENDENT_AIRFOIL, FixedReynoldsPolar,
                                   sweep_polar)

from bild_mdo.airfoil.single_table import SingleTablePolar  # noqa: E402

__all__ = [
    "AnalyticPolar", "CompressiblePolar", "DEFAULT_AIRFOIL", "FixedReynoldsPolar", "MachPolarSecondDerivatives", "MachPolarValues", "MachTabulatedPolar",
    "MaxLiftToDrag", "Polar", "PolarData", "PolarSecondDerivatives", "PolarValues", "SpanwisePolar",
    "REYNOLDS_INDEPENDENT_AIRFOIL", "SingleTablePolar", "StationMaxLiftToDrag", "StationPolarSecondDerivatives", "StationPolarValues", "TabulatedPolar",
    "available_polars", "cache_dir", "clear_cache", "get_polar", "load_builtin_polars", "max_lift_to_drag",
    "naca4412", "polar_from_dict", "polar_to_dict", "read_polar_files", "read_polar_table", "read_xfoil_polar",
    "resolve_polar", "spanwise_polar", "sweep_polar", "tabulated_polar",
]
