"""The BEM analysis of a BILD design's own blade: how the design analyses, beside what it was designed for.

A BILD design's thrust and power are those of its ideal loading.  A BEM
analysis of the same blade (chord, twist, stations, blades, loss model and
polar; :class:`~bild_mdo.bem.BEMAnalysisGroup`) at the same operating point
returns them exactly only where the design evaluates each station as the
analysis does:

* with the paper's reference section point every station runs at the airfoil
  point of the reference station's Reynolds number (Assumption 2), while the
  analysis runs it at its own: the two differ by the polar's Reynolds
  dependence (a 2-blade UAV propeller designed for 25 N with the NACA 4412
  analyses some per cent lower);
* the root-chord correction (Eq. (32)) changes the chord near the hub after the
  ideal loading is found.

Stations left unloaded (zero chord) carry nothing in the design.  The analysis
needs a blade at every station, so they get a token chord (the reference
chord, so that their Reynolds number stays of the design's order and the polar
does not warn about it) and are left out of its sums: the annuli of the BEM
model are independent, so this is the analysis of
the blade without them.  With ``section_point='local'`` each station runs at
its own Reynolds number in the design too, and the two agree to round-off.
:func:`analyze_designs` analyses a whole batch in one vectorised run of a
cached, set-up problem.
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.bem.bem_group import BEMAnalysisGroup
from bild_mdo.bem.performance import rotor_performance
from bild_mdo.fluid import fluid_arrays
from bild_mdo.utils.problem_cache import ProblemCache

#: Per-design values of the analysis in a :class:`~bild_mdo.results.design_result.DesignResult`: name -> units
#: (the BEM analysis's ``thrust``, ``torque``, ``power``, ``efficiency``, ``figure_of_merit``).
ANALYSIS_UNITS = {"bem_thrust": "N", "bem_torque": "N*m", "bem_power": "W", "bem_efficiency": None,
                  "bem_figure_of_merit": None}

# Set-up analysis problems by configuration, least recently used first (as bild.problem keeps BILD's).
_CACHE = ProblemCache(size=4)


def _problem(num_nodes, num_radial, num_blades, polar, loss_model, use_atmosphere):
    def make():
        # BILD's stations are the midpoints of equal annuli from hub to tip, the analysis group's default.
        prob = om.Problem(BEMAnalysisGroup(num_nodes=num_nodes, num_radial=num_radial, num_blades=num_blades,
                                           polar=polar, loss_model=loss_model, on_invalid="ignore",
                                           use_atmosphere=use_atmosphere), reports=False)
        prob.setup(check=False)
        prob.final_setup()
        return prob

    return _CACHE.get((num_nodes, num_radial, num_blades, loss_model, use_atmosphere), polar, make)


def analyze_designs(values, outputs, feasible, num_blades, polar, loss_model, fluid=None):
    """:data:`ANALYSIS_UNITS` of every design (NaN where infeasible) and the number of loaded stations of each
    design that the analysis finds outside the propeller flow state.

    ``values`` holds the designs' inputs (``v_axial``, ``rpm``, ``radius``, ``hub_radius_ratio``, ``altitude``,
    ``ref_chord``, shape ``(nn,)``), ``outputs`` the BILD model's (``chord``, ``twist``, shape ``(nn, nr)``);
    ``fluid`` a :class:`~bild_mdo.fluid.Fluid` instead of the ISA at ``altitude``.
    """
    nn, nr = outputs["chord"].shape
    result = {name: np.full(nn, np.nan) for name in ANALYSIS_UNITS}
    invalid = np.zeros(nn, dtype=int)
    at = np.flatnonzero(feasible)
    if at.size == 0:
        return result, invalid
    prob = _problem(at.size, nr, num_blades, polar, loss_model, fluid is None)
    radius = values["radius"][at]
    chord = outputs["chord"][at]
    loaded = chord > 0.0
    prob.set_val("chord", np.where(loaded, chord, values["ref_chord"][at][:, None]), units="m")
    prob.set_val("twist", outputs["twist"][at], units="rad")
    prob.set_val("radius", radius, units="m")
    prob.set_val("hub_radius", values["hub_radius_ratio"][at] * radius, units="m")
    prob.set_val("rpm", values["rpm"][at], units="rpm")
    prob.set_val("v_axial", values["v_axial"][at], units="m/s")
    if fluid is None:
        prob.set_val("altitude", values["altitude"][at], units="m")
    else:
        for name, value in fluid_arrays(fluid, at.size).items():
            prob.set_val(name, value)
    prob.run_model()
    dr = prob.get_val("dr", units="m")
    thrust = np.sum(np.where(loaded, prob.get_val("dthrust_dr", units="N/m") * dr, 0.0), axis=1)
    torque = np.sum(np.where(loaded, prob.get_val("dtorque_dr", units="N*m/m") * dr, 0.0), axis=1)
    metrics, _ = rotor_performance(thrust, torque, np.sum(chord * dr, axis=1), values["v_axial"][at],
                                   values["rpm"][at], radius, prob.get_val("rho", units="kg/m**3"), num_blades,
                                   speed_of_sound=prob.get_val("speed_of_sound", units="m/s"), partials=False)
    for name in ANALYSIS_UNITS:
        result[name][at] = metrics[name[len("bem_"):]]
    # Flow-state codes: 1 is the propeller state; the others are not what a BILD design is analysed in.
    invalid[at] = np.sum(loaded & (np.rint(prob.get_val("flow_state")).astype(int) != 1), axis=1)
    return result, invalid


def analysis_reason(design):
    """Why the BEM analysis of one design may differ from the design's own numbers (one sentence)."""
    causes = []
    if getattr(design, "section_point", "reference") != "local":
        causes.append("the design runs every station at the section point of Re_ref (the paper's Assumption 2), "
                      "the analysis each at its own Reynolds number (section_point='local' designs at those too)")
    if design.root_chord_correction is not None:
        causes.append("the root-chord correction (Eq. 32) changes the chord near the hub after the ideal loading")
    if not causes:
        return "the design evaluates every station as the analysis does: they agree to round-off"
    return "they can differ because " + "; ".join(causes)
