"""The parts of BILDGroup's chain: the per-station ideal loading, lambda, and the local section point's chain.

:class:`~bild_mdo.bild.bild_group.BILDGroup` assembles them; they live here so
that the group's module reads as the algorithm (paper Alg. 1) and this one as
the wiring of its options (``ideal_loading``, ``section_point``).
"""
import openmdao.api as om

from bild_mdo.bild.chord import ChordComp
from bild_mdo.bild.eta2 import Eta2Comp
from bild_mdo.bild.exact_eta2 import ExactEta2Comp
from bild_mdo.bild.exact_ideal_loading import ExactIdealLoadingComp
from bild_mdo.bild.ideal_loading import IdealLoadingComp
from bild_mdo.bild.induced_velocity import InducedVelocityComp
from bild_mdo.bild.inflow_angle import InflowAngleComp
from bild_mdo.bild.local_section_point_comp import (
    LoadReynoldsComp,
    LocalSectionPointComp,
    ReferenceReynoldsComp,
    ReferenceSectionPointComp,
)
from bild_mdo.bild.momentum_loads import MomentumLoadsComp
from bild_mdo.bild.reference_induced_velocity import ReferenceInducedVelocityComp
from bild_mdo.bild.reference_station import REFERENCE_INPUTS, ReferenceStationComp
from bild_mdo.bild.reynolds_ideal_loading_comp import ReynoldsIdealLoadingComp, ReynoldsStationComp


def add_ideal_stations(group, size, loss, checked, along, exact=False):
    """Add eta2 -> induced velocity -> inflow angle -> momentum loads, the per-station chain both section points use.

    ``exact=None``: no eta2 component (the Reynolds-aware exact loading's station component gives eta2).
    """
    eta2_in = ["v_axial", "v_theta", "ideal_loading_constant", "cl_star", "cd_star"]
    if exact is None:
        pass
    elif exact:
        group.add_subsystem("eta2", ExactEta2Comp(**size, **loss, **checked, **along),
                             promotes_inputs=eta2_in + ["radii", "radius", "hub_radius"], promotes_outputs=["eta2"])
    else:
        group.add_subsystem("eta2", Eta2Comp(**size, **checked, **along), promotes_inputs=eta2_in,
                             promotes_outputs=["eta2"])
    group.add_subsystem("induced_velocity", InducedVelocityComp(**size, **checked, **along),
                         promotes_inputs=["eta2", "v_axial", "v_theta", "cl_star", "cd_star"],
                         promotes_outputs=["u_axial", "u_theta"])
    group.add_subsystem("inflow_angle", InflowAngleComp(**size, **checked, **along),
                         promotes_inputs=["u_axial", "u_theta", "v_theta", "alpha_star"],
                         promotes_outputs=["phi", "inflow_speed", "twist"])
    group.add_subsystem("momentum_loads", MomentumLoadsComp(**size, **loss, **checked),
                         promotes_inputs=["u_axial", "u_theta", "phi", "radii", "v_axial", "rho", "rpm", "radius",
                                          "hub_radius"],
                         promotes_outputs=["loss_factor", "dthrust_dr", "dtorque_dr", "denergy_loss_dr"])


def add_ideal_loading(group, ideal_loading, node, loss, checked, reference_in):
    """Add lambda (Eq. (22), or the exact ``(F e)'/(F t)'`` at ``phi_ref``); return whether it is the exact one."""
    if ideal_loading == "exact":
        group.add_subsystem("ideal_loading", ExactIdealLoadingComp(**node, **loss, **checked),
                             promotes_inputs=["phi_ref"] + [name for name in reference_in if name != "ref_chord"],
                             promotes_outputs=["ideal_loading_constant"])
    else:
        group.add_subsystem("ideal_loading", IdealLoadingComp(**node, **checked),
                             promotes_inputs=["u_axial_ref", "u_theta_ref", "v_axial", "v_theta_ref"],
                             promotes_outputs=["ideal_loading_constant"])
    return ideal_loading == "exact"


def add_local_section_chain(group, polar, node, size, loss, checked):
    """Steps 1-7 with each station's own section point (``section_point='local'``).

    Two coupled loops, each a subgroup solved by Newton's method with a
    direct linear solve (exact totals through the loops):

    * ``reference_point``: the reference station's BEM inflow angle with
      ``c_ref`` and its section point at ``Re_ref = rho W0 c_ref / mu``: the
      point that is a minimum of ``cd/cl`` along its own path of fixed load
      (:mod:`~bild_mdo.bild.local_section_point_reference`), so a station
      placed at ``r_ref`` gets the same load, the same point and the chord
      ``c_ref`` (except where the path has a second, lower minimum: see there).
    * ``section_point_loop`` (paper loading): eta2 (with each station's own
      ``cd/cl``) -> induced velocities -> phi, W -> loads -> load Reynolds
      number -> the stations' section points -> eta2.

    With ``ideal_loading='exact'`` the second loop is replaced by
    :class:`~bild_mdo.bild.reynolds_ideal_loading_comp.ReynoldsIdealLoadingComp`
    (lambda at the reference state) and
    :class:`~bild_mdo.bild.reynolds_ideal_loading_comp.ReynoldsStationComp`
    (each station's ``(phi, alpha, Re)`` solved on its own, giving eta2 and
    the section point), followed by the same induced-velocity, inflow-angle
    and loads components.
    """
    opts = group.options
    if polar.varies_along_span or polar.varies_with_mach:
        raise ValueError("section_point='local' needs a polar that varies with the Reynolds number only; "
                         f"{polar.name!r} varies with Mach number or along the span: use section_point='reference'")
    form = dict(num_blades=opts["num_blades"], chord_form=opts["chord_form"])
    reference_in = [(name, f"{name}_ref") if name in ("cl_star", "cd_star") else name
                    for name in REFERENCE_INPUTS]
    group.add_subsystem("reference_reynolds", ReferenceReynoldsComp(**node),
                        promotes_inputs=["v_axial", "v_theta_ref", "ref_chord", "rho", "mu"],
                        promotes_outputs=["reynolds_ref"])
    loop = coupled_loop(group.add_subsystem("reference_point", om.Group(), promotes=["*"]))
    loop.add_subsystem("reference_station", ReferenceStationComp(**node, **loss),
                       promotes_inputs=reference_in, promotes_outputs=["phi_ref"])
    loop.add_subsystem("reference_section_point",
                       ReferenceSectionPointComp(**node, chord_form=opts["chord_form"], polar=polar),
                       promotes_inputs=["phi_ref", "reynolds_ref"],
                       promotes_outputs=["alpha_star_ref", "cl_star_ref", "cd_star_ref"])
    group.add_subsystem("reference_induced_velocity", ReferenceInducedVelocityComp(**node, **loss),
                        promotes_inputs=["phi_ref"] + reference_in,
                        promotes_outputs=["u_axial_ref", "u_theta_ref"])
    along = dict(varies_along_span=True)
    chord_load = ["dthrust_dr"] if opts["chord_form"] == "thrust" else ["dtorque_dr", "radii"]
    if opts["ideal_loading"] == "exact":
        # Reynolds-aware exact loading: every station solves its own (phi, alpha, Re) given lambda.
        flow_in = ["v_axial", "radius", "hub_radius", "rho", "mu"]
        aware = dict(**loss, chord_form=opts["chord_form"], polar=polar, **checked)
        group.add_subsystem("ideal_loading", ReynoldsIdealLoadingComp(**node, **aware),
                            promotes_inputs=["phi_ref", "alpha_star_ref", "reynolds_ref", "v_theta_ref",
                                             "ref_radius"] + flow_in,
                            promotes_outputs=["ideal_loading_constant"])
        group.add_subsystem("station_loading", ReynoldsStationComp(**size, **aware),
                            promotes_inputs=["ideal_loading_constant", "v_theta", "radii"] + flow_in,
                            promotes_outputs=["eta2", "alpha_star", "cl_star", "cd_star", "reynolds",
                                              "load_reynolds"])
        add_ideal_stations(group, size, loss, checked, along, exact=None)
    else:
        add_ideal_loading(group, "paper", node, loss, checked, reference_in)
        loop = coupled_loop(group.add_subsystem("section_point_loop", om.Group(), promotes=["*"]))
        add_ideal_stations(loop, size, loss, checked, along, exact=False)
        loop.add_subsystem("load_reynolds", LoadReynoldsComp(**size, **form),
                           promotes_inputs=chord_load + ["inflow_speed", "v_theta", "v_axial", "mu"],
                           promotes_outputs=["load_reynolds"])
        loop.add_subsystem("section_point", LocalSectionPointComp(**size, **form, polar=polar),
                           promotes_inputs=["phi", "load_reynolds"],
                           promotes_outputs=["alpha_star", "cl_star", "cd_star", "reynolds"])
    group.add_subsystem("chord", ChordComp(**size, **form, **checked, **along),
                        promotes_inputs=chord_load + ["phi", "inflow_speed", "rho", "cl_star", "cd_star"],
                        promotes_outputs=["chord_raw", "lift_coefficient", "drag_coefficient"])


def coupled_loop(group):
    """Newton's method with a direct linear solve on a subgroup that closes a loop of explicit components."""
    # The implicit members (the reference BEM solve, eta2) solve themselves at every iteration, so Newton's
    # method only closes the loop of the section point, which is mildly nonlinear: 2-4 iterations.
    newton = om.NewtonSolver(solve_subsystems=True, max_sub_solves=_LOOP_MAX_ITERATIONS,
                             maxiter=_LOOP_MAX_ITERATIONS, atol=1e-10, rtol=1e-12, iprint=-1,
                             err_on_non_converge=True)
    group.nonlinear_solver = newton
    group.linear_solver = om.DirectSolver(assemble_jac=True)
    return group


_LOOP_MAX_ITERATIONS = 30
