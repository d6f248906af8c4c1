"""The one registry of per-design performance outputs (paper Table 2).

Every per-design metric that the BEM analysis and BILD report is one
:class:`Metric` entry here.  The OpenMDAO outputs of
:class:`~bild_mdo.bem.performance.RotorPerformanceComp`, the fields of the
result objects, the text tables, the results store of the verification sweep
and its statistics all read this tuple, so adding a metric is one entry here
plus its formula and partials in :func:`~bild_mdo.bem.performance.rotor_performance`.
"""
from __future__ import annotations

import warnings
from typing import NamedTuple

import numpy as np


class Metric(NamedTuple):
    """One per-design output.

    Attributes
    ----------
    name : str
        Output and field name (snake_case).
    units : str or None
        OpenMDAO units (SI); None for nondimensional values.
    description : str
        One line with its definition.
    label : str
        Short column title for text tables, with its display units.
    display_scale : float
        Factor from SI to the display units of ``label`` (W -> kW is 1e-3).
    verified : bool
        Whether the verification sweep stores it per method and compares BILD
        against the optimum (the quantities of the paper's Table 3).
    """

    name: str
    units: str | None
    description: str
    label: str
    display_scale: float = 1.0
    verified: bool = False


METRICS = (
    Metric("thrust", "N", "rotor thrust T = sum(dT/dr dr)", "T [N]"),
    Metric("torque", "N*m", "rotor torque Q = sum(dQ/dr dr)", "Q [N m]"),
    Metric("power", "W", "shaft power P = Omega Q", "P [kW]", 1e-3),
    Metric("thrust_coefficient", None, "C_T = T / (rho n^2 D^4), n in rev/s, D = 2R", "C_T [-]", verified=True),
    Metric("torque_coefficient", None, "C_Q = Q / (rho n^2 D^5)", "C_Q [-]", verified=True),
    Metric("power_coefficient", None, "C_P = P / (rho n^3 D^5)", "C_P [-]", verified=True),
    Metric("efficiency", None, "propulsive efficiency eta = V_x T / (Omega Q)", "eta [-]", verified=True),
    Metric("figure_of_merit", None, "figure of merit FM = T/P sqrt(T / (2 pi R^2 rho)) (odd in T)", "FM [-]",
           verified=True),
    Metric("energy_loss", "W", "rate of energy loss E = Omega Q - V_x T", "E [kW]", 1e-3, verified=True),
    Metric("solidity", None, "blade solidity sigma_r = B sum(c dr) / (pi R^2)", "sigma [-]"),
    Metric("blade_loading", None, "blade loading C_T / sigma_r", "C_T/sigma [-]"),
    Metric("tip_mach", None, "tip Mach number sqrt(V_x^2 + (Omega R)^2) / a", "M_tip [-]"),
)

#: Per-design outputs of a wind turbine (:class:`~bild_mdo.bem.turbine_performance.TurbinePerformanceComp`),
#: signed for energy extraction; ``A = pi (R cos(precone))^2`` is the swept area (CCBlade's), V the wind at hub height.
TURBINE_METRICS = (
    Metric("thrust", "N", "rotor thrust along the shaft, downwind positive: T = -sum(dT/dr dr)", "T [kN]", 1e-3),
    Metric("torque", "N*m", "aerodynamic torque driving the rotor Q = -sum(dQ/dr dr)", "Q [kN m]", 1e-3),
    Metric("power", "W", "power extracted P = Omega Q (= -Omega times the propeller-signed torque)", "P [kW]", 1e-3),
    Metric("power_coefficient", None, "C_P = P / (1/2 rho A V^3), A = pi (R cos(precone))^2", "C_P [-]"),
    Metric("thrust_coefficient", None, "C_T = T / (1/2 rho A V^2)", "C_T [-]"),
    Metric("torque_coefficient", None, "C_Q = Q / (1/2 rho A V^2 R cos(precone))", "C_Q [-]"),
    Metric("tip_speed_ratio", None, "tip-speed ratio lambda = Omega R / V", "TSR [-]"),
    Metric("tip_mach", None, "tip Mach number sqrt(V^2 + (Omega R)^2) / a", "M_tip [-]"),
)
#: Turbine outputs: name -> (units, description).
TURBINE_OUTPUTS = {metric.name: (metric.units, metric.description) for metric in TURBINE_METRICS}

#: name -> Metric.
METRICS_BY_NAME = {metric.name: metric for metric in METRICS}
#: Per-design outputs: name -> (units, description), the form OpenMDAO declarations use.
PERFORMANCE_OUTPUTS = {metric.name: (metric.units, metric.description) for metric in METRICS}
#: The metrics the verification sweep stores per method (the paper's Table 3 quantities), in registry order.
VERIFIED_METRICS = tuple(metric.name for metric in METRICS if metric.verified)


class TipMachWarning(UserWarning):
    """A blade whose tip moves at or above the speed of sound, where its aerodynamic model no longer holds."""


def warn_supersonic_tip(tip_mach, what="design"):
    """One :class:`TipMachWarning` if any ``tip_mach >= 1`` (NaN ignored), naming the first such items.

    Blade-element polars (even Mach-corrected ones) and momentum theory do not
    represent shocks on the blade, so results past a sonic tip are numbers
    without physical meaning; they are returned, flagged by this warning.
    """
    tip_mach = np.atleast_1d(np.asarray(tip_mach, dtype=float))
    sonic = np.flatnonzero(tip_mach >= 1.0)
    if sonic.size == 0:
        return
    where = "" if tip_mach.size == 1 else f" of {what}(s) {sonic[:10].tolist()}"
    warnings.warn(f"tip Mach number {tip_mach[sonic[0]]:.3g}{where} is >= 1: the blade-element polar and "
                  f"momentum theory do not hold at a supersonic tip; lower the rpm or the radius",
                  TipMachWarning, stacklevel=3)
