"""Design-variable bounds, the cold-start design and the objective reference of the BEM optimisation.

Bounds.  They keep the optimiser's trial points where blade elements make
sense; BILD's designs of the whole Sec. 5.1 sweep lie well inside them.

* ``c/R`` in [1e-4, 1]: the paper notes that without a lower bound the root
  chord of forward-flight designs goes to zero (Sec. 5.2.1, Fig. 11).  The
  lower bound only excludes zero and negative chords, where the solidity and
  the Reynolds number vanish; it is 40 times below BILD's smallest chord
  (4e-3 R, root, J = 3).  It is active at the optimum only at the first one
  or two stations of forward-flight rotors with small c_ref, where the
  optimal chord tends to zero and the station carries almost no load.  The
  upper bound is 1.6 times BILD's largest chord (0.63 R, hover root,
  R = 0.5 m, c_ref = 0.22 m).
* twist within [phi_0 - 15 deg, phi_0 + 60 deg] and [0, 90] deg, with
  ``phi_0 = atan(V_x / (Omega r))`` the inflow angle without induction:
  BILD's twist exceeds ``phi_0`` by 6 to 40 deg over the sweep.  Fixed
  bounds [0, 90] deg let SLSQP try a hovering root section at 90 deg, where
  the BEM residual has no root.
"""
from __future__ import annotations

import numpy as np

from bild_mdo.bild.problem import bild_problem
from bild_mdo.constants import angular_velocity
from bild_mdo.optimization.parameterization import station_fractions

INITIAL_DESIGNS = ("bild", "linear")

#: Bounds on the chord design values, c/R (see the module docstring).
CHORD_RATIO_BOUNDS = (1.0e-4, 1.0)
#: Twist bounds relative to the inflow angle without induction (rad), and absolute (rad).
TWIST_MARGINS = (np.radians(-15.0), np.radians(60.0))
TWIST_LIMITS = (0.0, 0.5 * np.pi)


def _actuator_disk_induced_velocity(thrust, v_axial, radius, hub_radius, rho):
    """Induced velocity ``w`` of an actuator disk: ``T = 2 rho A (V_x + w) w`` on ``A = pi (R^2 - r_hub^2)``."""
    area = np.pi * (radius**2 - hub_radius**2)
    return -0.5 * v_axial + np.sqrt(0.25 * v_axial**2 + thrust / (2.0 * rho * area))


def ideal_energy_loss(thrust, v_axial, radius, hub_radius, rho):
    """Ideal induced energy loss of an actuator disk (momentum theory): the objective reference.

    ``T = 2 rho A (V_x + w) w`` on the annulus ``A = pi (R^2 - r_hub^2)``
    gives the induced velocity ``w``; the loss is ``E = T w``.

    Parameters
    ----------
    thrust, v_axial, radius, hub_radius, rho : float
        N, m/s, m, m, kg/m^3.

    Returns
    -------
    float
        Rate of energy loss (W).
    """
    return float(thrust * _actuator_disk_induced_velocity(thrust, v_axial, radius, hub_radius, rho))


def twist_bounds(v_axial, rpm, radius, hub_radius, fractions, margins=TWIST_MARGINS, limits=TWIST_LIMITS):
    """Per-design-value twist bounds around the inflow angle without induction.

    Parameters
    ----------
    v_axial, rpm, radius, hub_radius : float
        m/s, rpm, m, m.
    fractions : array_like
        Normalised span positions of the design values
        (:func:`~bild_mdo.optimization.parameterization.design_value_fractions`).
    margins, limits : tuple of float
        ``(lower, upper)`` relative to ``phi_0`` and absolute (rad); a propeller's by default (a turbine's:
        :mod:`bild_mdo.optimization.turbine`).

    Returns
    -------
    lower, upper : ndarray
        Bounds (rad): ``phi_0 + margins`` clipped to ``limits``.
    """
    radii = hub_radius + np.asarray(fractions) * (radius - hub_radius)
    phi0 = np.arctan2(v_axial, angular_velocity(rpm) * radii)
    return np.clip(phi0 + margins[0], *limits), np.clip(phi0 + margins[1], *limits)


def linear_initial_design(v_axial, rpm, radius, hub_radius, thrust_target, rho, num_radial,
                          reference_chord=None, alpha_design=np.radians(5.0)):
    """Cold-start geometry: chord and twist linear from root to tip.

    As in the authors' optimisation scripts, the initial chord and twist are
    straight lines from root to tip.  Their end values come from the case:
    the chord falls from ``1.5 c_ref`` at the root to ``0.5 c_ref`` at the
    tip, and the twist is ``alpha_design`` plus the inflow angle
    ``atan((V_x + w) / (Omega r))`` of an actuator disk producing ``T*``
    (momentum theory) at the first and the last station.

    Parameters
    ----------
    v_axial, rpm, radius, hub_radius, thrust_target, rho : float
        Case inputs (m/s, rpm, m, m, N, kg/m^3).
    num_radial : int
        Number of stations.
    reference_chord : float, optional
        Chord scale c_ref (m); default 0.1 R.
    alpha_design : float
        Angle of attack added to the inflow angle (rad).

    Returns
    -------
    chord, twist : ndarray, shape (num_radial,)
        m and rad.
    """
    c_ref = 0.1 * radius if reference_chord is None else float(reference_chord)
    x = station_fractions(num_radial)
    radii = hub_radius + x * (radius - hub_radius)
    w = _actuator_disk_induced_velocity(thrust_target, v_axial, radius, hub_radius, rho)
    ends = np.arctan((v_axial + w) / (angular_velocity(rpm) * radii[[0, -1]])) + alpha_design
    chord = c_ref * (1.5 - x)
    twist = ends[0] + (ends[1] - ends[0]) * (radii - radii[0]) / (radii[-1] - radii[0])
    return chord, twist


def bild_initial_design(v_axial, rpm, radius, hub_radius, thrust_target, altitude, num_radial, num_blades, polar,
                        loss_model):
    """The paper's BILD blade for the case, designed for its thrust: ``(chord, twist)`` at the stations (m, rad).

    BILD (reference section point, paper loading, r_ref = R / 2) with its reference chord solved for
    ``thrust_target`` (:class:`~bild_mdo.bild.BILDGroup` with ``thrust_target=True``); its stations are the
    midpoints of equal annuli from hub to tip, those of the optimisation.  ValueError in one line where the
    ideal loading cannot give the thrust.
    """
    if not 0.0 < hub_radius < 0.5 * radius:
        raise ValueError(f"initial='bild' puts BILD's reference station at r = R/2, outside the hub; the hub "
                         f"radius {hub_radius:g} m of R = {radius:g} m leaves none: give initial='linear' or "
                         "bild_chord and bild_twist")
    prob = bild_problem(num_radial=num_radial, num_blades=num_blades, airfoil=polar, loss_model=loss_model,
                        thrust_target=True, on_infeasible="flag")
    for name, value, units in (("v_axial", v_axial, "m/s"), ("rpm", rpm, "rpm"), ("radius", radius, "m"),
                               ("hub_radius_ratio", hub_radius / radius, None), ("ref_radius_ratio", 0.5, None),
                               ("altitude", altitude, "m"), ("thrust_target", thrust_target, "N")):
        prob.set_val(name, value, units=units)
    # The same start for the same case, whatever was designed before (the cached model keeps its last chord).
    prob.model.thrust_target_balance.forget_history()
    prob.run_model()
    if prob.model.feasibility.infeasible[0]:
        raise ValueError(f"initial='bild': no BILD design gives T* = {thrust_target:g} N here "
                         f"({prob.model.feasibility.status()[0]}); give initial='linear' or bild_chord and bild_twist")
    return prob.get_val("chord", units="m")[0].copy(), prob.get_val("twist", units="rad")[0].copy()
