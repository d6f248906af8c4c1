"""The full-BEM optimisation of a wind turbine: the most power for a given thrust (``rotor_type='turbine'``).

A turbine is the BEM kernel's rotor with the airfoil turned over
(:class:`~bild_mdo.bem.turbine_polar.TurbinePolar`): twist is CCBlade's
``theta`` (``alpha = phi - theta``), and the kernel's thrust and torque are
minus the turbine's.  So the propeller problem of
:mod:`bild_mdo.optimization.problem` solves the turbine's as it stands: its
objective, the rate of energy loss ``E = Omega Q_k - V T_k``, is
``V T - P`` in the turbine's signs (the power the rotor takes out of the wind
by its thrust, less the power it extracts), so at a fixed thrust ``T = T*``
minimising ``E`` maximises the power ``P``.  The thrust target is given
downwind-positive and enters the model as ``-T*``.

What differs from a propeller is here:

* twist bounds ``phi_0 + TURBINE_TWIST_MARGINS`` clipped to
  ``TURBINE_TWIST_LIMITS``, ``phi_0 = atan(V / (Omega r))``: a turbine's
  twist is the inflow angle *less* the angle of attack, and the induction
  lowers the inflow angle (``(1 - a) V``), so an optimal twist lies below
  ``phi_0`` (about ``2/3 phi_0 - 6 deg`` for Glauert's rotor) and is negative
  near the tip of a fast rotor;
* the cold start: chord from ``1.5 c_ref`` at the root to ``0.5 c_ref`` at the
  tip, ``c_ref`` Betz-Schmitz's chord at 0.7 R
  (``c = 16 pi r / (9 B c_l lambda_r^2)``, with ``c_l = 1``) unless given, and
  twist ``atan((1 - a) V / (Omega r)) - 5 deg`` linear from root to tip, ``a``
  the actuator-disc induction of ``T*``;
* the objective reference: the actuator disc's loss ``E = T a V``
  (``T = 2 rho A V^2 a (1 - a)``, ``P = T (1 - a) V``) on the annulus outside
  the hub;
* the BILD start: the turbine BILD designed for ``T*``
  (:func:`~bild_mdo.bild.turbine_problem.run_turbine_bild`, as ``design_turbine(thrust=...)``);
* the result's ``performance``: the turbine's metrics (:func:`turbine_metrics`).
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.atmosphere import isa
from bild_mdo.bild.turbine_problem import run_turbine_bild
from bild_mdo.constants import angular_velocity
from bild_mdo.optimization.initial_design import twist_bounds
from bild_mdo.optimization.parameterization import station_fractions

#: Rotor types of the optimisation, and the sign of the thrust target in the model (the kernel's convention).
ROTOR_TYPES = ("propeller", "turbine")
THRUST_SIGN = {"propeller": 1.0, "turbine": -1.0}
#: Twist bounds of a turbine relative to the inflow angle without induction (rad), and absolute (rad).
TURBINE_TWIST_MARGINS = (np.radians(-50.0), np.radians(10.0))
TURBINE_TWIST_LIMITS = (np.radians(-45.0), 0.5 * np.pi)
#: Angle of attack of the cold start (rad).
_ALPHA_START = np.radians(5.0)


def turbine_twist_bounds(v_axial, rpm, radius, hub_radius, fractions):
    """Per-design-value twist bounds of a turbine (rad): ``phi_0 + TURBINE_TWIST_MARGINS`` within the limits."""
    return twist_bounds(v_axial, rpm, radius, hub_radius, fractions, TURBINE_TWIST_MARGINS, TURBINE_TWIST_LIMITS)


def _induction(thrust, v_axial, radius, hub_radius, rho):
    """Actuator-disc axial induction of thrust ``T`` on the annulus (the windmill branch, ``a <= 1/2``)."""
    loading = thrust / (0.5 * rho * np.pi * (radius**2 - hub_radius**2) * v_axial**2)
    if not loading <= 1.0:
        raise ValueError(f"thrust_target {thrust:g} N is above the actuator disc's largest windmill thrust "
                         f"({thrust / loading:g} N, C_T = 1 on the annulus outside the hub): give a smaller thrust")
    return 0.5 * (1.0 - np.sqrt(1.0 - loading))


def ideal_turbine_energy_loss(thrust, v_axial, radius, hub_radius, rho):
    """The actuator disc's rate of energy loss ``E = T a V`` (W) at thrust ``T`` (N): the objective reference."""
    return float(thrust * _induction(thrust, v_axial, radius, hub_radius, rho) * v_axial)


def turbine_linear_initial_design(v_axial, rpm, radius, hub_radius, thrust_target, rho, num_radial, num_blades,
                                  reference_chord=None):
    """Cold-start geometry of a turbine (module docstring): ``(chord, twist)`` at the stations (m, rad)."""
    omega = angular_velocity(rpm)
    if reference_chord is None:
        r_ref = 0.7 * radius
        reference_chord = 16.0 * np.pi * r_ref / (9.0 * num_blades * (omega * r_ref / v_axial) ** 2)
    x = station_fractions(num_radial)
    radii = hub_radius + x * (radius - hub_radius)
    a = _induction(thrust_target, v_axial, radius, hub_radius, rho)
    ends = np.arctan((1.0 - a) * v_axial / (omega * radii[[0, -1]])) - _ALPHA_START
    chord = float(reference_chord) * (1.5 - x)
    twist = ends[0] + (ends[1] - ends[0]) * (radii - radii[0]) / (radii[-1] - radii[0])
    return chord, twist


def turbine_bild_initial_design(v_axial, rpm, radius, hub_radius, thrust_target, altitude, num_radial, num_blades,
                                polar, loss_model):
    """The turbine BILD blade designed for ``T*`` (reference station at 0.7 R): ``(chord, twist)`` at the stations
    (m, rad); ``polar`` the airfoil's own (not mirrored).  ValueError in one line where no member of the family
    gives the thrust."""
    values = {name: np.array([float(value)]) for name, value in (
        ("wind_speed", v_axial), ("rpm", rpm), ("radius", radius), ("hub_radius_ratio", hub_radius / radius),
        ("ref_radius_ratio", 0.7), ("altitude", altitude), ("thrust", thrust_target))}
    try:
        out = run_turbine_bild(values, num_radial, num_blades, polar, loss_model, "thrust")
    except om.AnalysisError as exc:
        raise ValueError(f"initial='bild': no turbine BILD design gives T* = {thrust_target:g} N here ({exc}); "
                         "give initial='linear' or bild_chord and bild_twist") from None
    return out["chord"][0].copy(), out["twist"][0].copy()


def turbine_metrics(performance, v_axial, rpm, radius, altitude):
    """The turbine's metrics from the kernel's (propeller-signed) performance of one design.

    Returns ``thrust`` (downwind, N), ``torque`` (driving, N m), ``power`` (extracted, W),
    ``power_coefficient`` ``P / (1/2 rho A V^3)``, ``thrust_coefficient`` ``T / (1/2 rho A V^2)``,
    ``torque_coefficient`` ``Q / (1/2 rho A V^2 R)`` (``A = pi R^2``), ``efficiency`` ``P / (V T)`` (the share
    of the power taken from the wind by the thrust that is extracted), ``figure_of_merit`` NaN (hover only),
    ``energy_loss`` ``V T - P`` (W), ``tip_speed_ratio``.
    """
    rho = float(isa(altitude).rho)
    thrust, torque, power = (-float(performance[name]) for name in ("thrust", "torque", "power"))
    dynamic = 0.5 * rho * np.pi * radius**2 * v_axial**2
    return {"thrust": thrust, "torque": torque, "power": power, "power_coefficient": power / (dynamic * v_axial),
            "thrust_coefficient": thrust / dynamic, "torque_coefficient": torque / (dynamic * radius),
            "efficiency": power / (v_axial * thrust) if thrust != 0.0 else np.nan, "figure_of_merit": np.nan,
            "energy_loss": float(performance["energy_loss"]),
            "tip_speed_ratio": angular_velocity(rpm) * radius / v_axial}
