"""Run the turbine BILD (:class:`~bild_mdo.bild.turbine_group.TurbineBILDGroup`) for a set of designs.

:func:`run_turbine_bild` sets up the group for the member of the family asked for (the most power, a thrust,
a reference chord), runs it, with the section point at the Reynolds number of the designed reference chord
where the reference chord is an output (a fixed point), and returns the designs' outputs.  The Python design
API (:func:`~bild_mdo.results.turbine_design.design_turbine`) and the turbine optimisation's and
verification's BILD blades (:mod:`bild_mdo.optimization.turbine`, :mod:`bild_mdo.verification.turbine_sweep`)
run it.
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.bild.turbine_group import TurbineBILDGroup

#: Distributions of a design (name -> units).
TURBINE_DISTRIBUTIONS = {"radii": "m", "chord": "m", "twist": "rad", "phi": "rad", "axial_induction": None,
                         "tangential_induction": None, "loss_factor": None, "dthrust_dr": "N/m",
                         "dtorque_dr": "N*m/m", "inflow_speed": "m/s", "dr": "m"}
#: Per-design outputs (name -> units).
TURBINE_VALUES = {"power": "W", "thrust": "N", "torque": "N*m", "power_coefficient": None,
                  "thrust_coefficient": None, "tip_speed_ratio": None, "power_thrust_multiplier": "m/s",
                  "ref_chord": "m", "alpha_star": "rad", "cl_star": None, "cd_star": None, "reynolds_ref": None,
                  "rho": "kg/m**3", "mu": "Pa*s", "speed_of_sound": "m/s"}
_REYNOLDS_RTOL = 1e-10
_REYNOLDS_ITERATIONS = 30


def run_turbine_bild(values, num_radial, num_blades, polar, loss_model, design_for, fluid=None):
    """Outputs ``{name: array}`` (:data:`TURBINE_DISTRIBUTIONS`, :data:`TURBINE_VALUES`) of the designs.

    ``values``: arrays ``[nn]`` of ``wind_speed``, ``rpm``, ``radius``, ``hub_radius_ratio``,
    ``ref_radius_ratio``, ``altitude`` (without ``fluid``) and ``thrust`` or ``ref_chord`` for those members;
    ``design_for`` ``'multiplier'`` (the most power), ``'thrust'`` or ``'ref_chord'``; ``fluid`` None (the ISA
    at ``altitude``) or the arrays ``rho, mu, speed_of_sound``.  Raises ``om.AnalysisError`` where a member does
    not exist or no reference chord runs at its own section point.
    """
    nn = values["radius"].size
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("turbine", TurbineBILDGroup(num_nodes=nn, num_radial=num_radial, num_blades=num_blades,
                                                         polar=polar, loss_model=loss_model, design_for=design_for,
                                                         use_atmosphere=fluid is None), promotes=["*"])
    prob.setup()
    for name in ("rpm", "radius", "hub_radius_ratio", "ref_radius_ratio"):
        prob.set_val(name, values[name])
    prob.set_val("v_axial", values["wind_speed"])
    if fluid is None:
        prob.set_val("altitude", values["altitude"])
    else:
        for name, arr in fluid.items():
            prob.set_val(name, arr)
    if design_for == "ref_chord":
        prob.set_val("ref_chord", values["ref_chord"])
        prob.run_model()
    else:
        if design_for == "thrust":
            prob.set_val("thrust_target", values["thrust"])
        _section_fixed_point(prob, 0.05 * values["radius"])
    return {name: np.array(prob.get_val(name, units=units)) for name, units in
            {**TURBINE_DISTRIBUTIONS, **TURBINE_VALUES}.items()}


def _section_fixed_point(prob, guess):
    """Run with the section point at the Reynolds number of the designed reference chord (a fixed point:
    ``C_l*, C_d*`` vary slowly with the Reynolds number, so a few passes converge to 1e-10)."""
    chord, before = guess, None
    for _ in range(_REYNOLDS_ITERATIONS):
        prob.set_val("section_chord", chord)
        prob.run_model()
        new = np.array(prob.get_val("ref_chord", units="m"))
        new = np.where(new > 0.0, new, chord)  # an unloaded reference station keeps the guess
        change = np.abs(new - chord) / new
        if np.all(change <= _REYNOLDS_RTOL):
            return
        cycle = before is not None and np.all(np.abs(before - new) <= 1e-6 * new)
        before, chord = chord, new
    worst = int(np.argmax(change))
    if cycle:
        # A two-cycle: the airfoil's best lift-to-drag point jumps between two branches across the Reynolds
        # numbers of the two chords, so no reference chord runs at its own section point.
        raise om.AnalysisError(
            "design_turbine: no reference chord runs at its own section point: the airfoil's best lift-to-drag "
            f"point jumps between two branches between the chords {min(before[worst], new[worst]):.4g} m and "
            f"{max(before[worst], new[worst]):.4g} m (their Reynolds numbers; design {worst}); give a polar frozen "
            "at one Reynolds number (airfoil='NAME@re=...'), a larger rotor or ref_chord=")
    raise om.AnalysisError("design_turbine: the section point's Reynolds number did not settle (the reference "
                           f"chord changed by {change[worst]:.3g} in the last pass, design {worst})")
