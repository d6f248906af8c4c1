"""MultipointRotorGroup: the BEM reproduces the BILD design at its design point, trim, exact totals.

BILD and the BEM solve the same blade-element momentum equations (paper Sec. 3 and 4): BILD
back-computes the chord and twist that make every element carry the ideal loading at the airfoil's
maximum-L/D point, and the BEM, given that blade at the same condition, finds the same inflow
angle at every station.  What differs is the polar evaluation: BILD takes C_l*, C_d* at the
reference station's Reynolds number for every station (Assumption 2), the BEM evaluates each
station at its own Reynolds number.  With a Reynolds-independent polar the two are therefore
identical to solver tolerance; with the Reynolds-dependent NACA 4412 they differ by at most the
spread of the section coefficients along the blade (bound derived in the test).
"""
import warnings

import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.multipoint import MultipointRotorGroup
from bild_mdo.utils.testing import check_group_totals

NN, NR = 3, 7
POLAR = AnalyticPolar()  # Reynolds-independent (reynolds_exponent = 0)
#: Design conditions: a lift rotor in hover and a propeller in cruise (J = V / (n D) ~ 0.6).
DESIGNS = {
    "hover": dict(design_v_axial=[0.0], design_rpm=[2000.0], radius=[0.75], ref_chord=[0.1]),
    "cruise": dict(design_v_axial=[40.0], design_rpm=[2200.0], radius=[0.9], ref_chord=[0.08],
                   design_altitude=[1000.0]),
}

pytestmark = pytest.mark.filterwarnings("ignore:.*Reynolds numbers outside the tabulated range:UserWarning")


def _run(values, **options):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("rotor", MultipointRotorGroup(num_nodes=NN, num_radial=NR, **options), promotes=["*"])
    prob.setup()
    for name, value in values.items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


def _at_design_point(kind):
    """The design values plus three analysis points that all repeat the design condition."""
    d = DESIGNS[kind]
    return dict(d, v_axial=np.full(NN, d["design_v_axial"][0]), rpm=np.full(NN, d["design_rpm"][0]),
                altitude=np.full(NN, d.get("design_altitude", [0.0])[0]))


@pytest.mark.parametrize("kind", list(DESIGNS))
def test_design_point_reproduced_exactly_with_a_reynolds_independent_polar(kind):
    prob = _run(_at_design_point(kind), polar=POLAR)
    for name in ("thrust", "torque", "power", "figure_of_merit", "efficiency", "tip_mach"):
        design = prob.get_val(f"design_{name}")[0]
        np.testing.assert_allclose(prob.get_val(name), design, rtol=1e-10, atol=1e-12, err_msg=name)
    # The BEM operates every element at BILD's angle of attack alpha* (twist = phi + alpha*, Eq. (30)).
    np.testing.assert_allclose(prob.get_val("rotor.analysis.bem.lift_coefficient"),
                               np.repeat(prob.get_val("rotor.design.lift_coefficient"), NN, axis=0), rtol=1e-10)


@pytest.mark.parametrize("kind", list(DESIGNS))
def test_design_point_reproduced_to_the_polar_spread_with_naca4412(kind):
    prob = _run(_at_design_point(kind))
    cl_star, cd_star = prob.get_val("rotor.design.cl_star")[0], prob.get_val("rotor.design.cd_star")[0]
    cl = prob.get_val("rotor.analysis.bem.lift_coefficient")[0]
    cd = prob.get_val("rotor.analysis.bem.drag_coefficient")[0]
    spread_cl = np.max(np.abs(cl / cl_star - 1.0))
    spread_cd = np.max(np.abs(cd / cd_star - 1.0))
    # Each element's thrust is linear in C_l at a given inflow and the induced inflow adjusts against it
    # (momentum theory in hover: T ~ C_l^(2/3)), so |dT/T| <= max |dC_l/C_l|; the torque adds the profile
    # term, linear in C_d: |dQ/Q| <= max |dC_l/C_l| + max |dC_d/C_d|.
    rel_thrust = abs(prob.get_val("thrust")[0] / prob.get_val("design_thrust")[0] - 1.0)
    rel_torque = abs(prob.get_val("torque")[0] / prob.get_val("design_torque")[0] - 1.0)
    assert spread_cl > 1e-4 and spread_cd > 1e-3  # the polar does vary with Reynolds number
    assert rel_thrust <= spread_cl
    assert rel_torque <= spread_cl + spread_cd


def test_rpm_trim_in_hover_follows_the_square_law():
    # Hover with a Reynolds- and Mach-independent polar: the inflow angles do not depend on Omega, so
    # T and Q scale with Omega^2 (dimensional analysis) and FM is unchanged.  Trimming the design blade
    # to k times its design thrust therefore needs exactly sqrt(k) times the design rpm.
    ratios = np.array([0.7, 1.0, 1.3])
    design = _run(_at_design_point("hover"), polar=POLAR)
    values = dict(DESIGNS["hover"], v_axial=np.zeros(NN), collective_pitch=np.zeros(NN),
                  thrust_target=ratios * design.get_val("design_thrust")[0])
    prob = _run(values, polar=POLAR, trim="rpm")
    np.testing.assert_allclose(prob.get_val("thrust"), values["thrust_target"], rtol=1e-10)
    np.testing.assert_allclose(prob.get_val("rpm"), 2000.0 * np.sqrt(ratios), rtol=1e-9)
    np.testing.assert_allclose(prob.get_val("figure_of_merit"), prob.get_val("design_figure_of_merit")[0], rtol=1e-9)


def test_pitch_trim_meets_every_thrust_target_inside_its_bounds():
    targets = np.array([500.0, 900.0, 300.0])
    values = dict(DESIGNS["hover"], v_axial=[0.0, 5.0, 30.0], rpm=[2000.0, 2000.0, 1800.0],
                  altitude=[0.0, 500.0, 1000.0], thrust_target=targets)
    prob = _run(values, trim="collective_pitch", trim_bounds=(-0.2, 0.6))
    np.testing.assert_allclose(prob.get_val("thrust"), targets, rtol=1e-10)
    pitch = prob.get_val("collective_pitch", units="rad")
    assert np.all((pitch > -0.2) & (pitch < 0.6))
    # Hover at 500 N needs less pitch than the design blade at its 700 N design thrust (zero pitch);
    # climbing at 5 m/s to 900 N needs more: thrust grows with the angle of attack.
    assert pitch[0] < 0.0 < pitch[1]


TOTALS_VALUES = dict(DESIGNS["hover"], v_axial=[0.0, 5.0, 30.0], rpm=[2000.0, 2100.0, 1800.0],
                     altitude=[0.0, 500.0, 1000.0], collective_pitch=[0.0, 0.03, 0.25],
                     thrust_target=[650.0, 800.0, 300.0], design_altitude=[100.0], ref_radius_ratio=[0.55])
TOTALS_OF = ["thrust", "torque", "power", "efficiency", "figure_of_merit", "tip_mach", "design_thrust",
             "design_power", "design_tip_mach", "chord", "twist"]
DESIGN_WRT = ["design_v_axial", "design_rpm", "design_altitude", "radius", "hub_radius_ratio", "ref_radius_ratio",
              "ref_chord"]
CONDITION_WRT = {None: ["v_axial", "altitude", "rpm", "collective_pitch"],
                 "collective_pitch": ["v_axial", "altitude", "rpm", "thrust_target"],
                 "rpm": ["v_axial", "altitude", "collective_pitch", "thrust_target"]}


@pytest.mark.parametrize("trim", list(CONDITION_WRT))
def test_totals_through_design_broadcast_analyses_and_trim(trim):
    of = TOTALS_OF + ([trim] if trim else [])
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*have a nonlinear solver that computes gradients")
        check_group_totals(lambda: MultipointRotorGroup(num_nodes=NN, num_radial=NR, polar=POLAR, trim=trim),
                           of=of, wrt=DESIGN_WRT + CONDITION_WRT[trim], values=TOTALS_VALUES, atol=1e-9, rtol=1e-6)


def test_pitch_trim_at_a_high_advance_ratio_finds_the_attached_flow_root():
    # Cruise at J = V / (n D) = 2 needs ~30 deg of pitch; from zero pitch the blade windmills, and past
    # stall the thrust falls again, so a second (stalled) root exists.  The momentum-theory first guess
    # (actuator disk, alpha* at 0.75 R) must lead Newton to the attached-flow root: every station below
    # the stall angle of the polar.
    values = dict(DESIGNS["hover"], v_axial=[5.0, 40.0, 60.0], rpm=[2000.0, 1500.0, 1200.0],
                  altitude=[0.0, 500.0, 500.0], thrust_target=[700.0, 300.0, 150.0])
    prob = _run(values, polar=POLAR, trim="collective_pitch")
    np.testing.assert_allclose(prob.get_val("thrust"), values["thrust_target"], rtol=1e-10)
    alpha = (prob.get_val("twist") + prob.get_val("collective_pitch")[:, None]
             - prob.get_val("rotor.analysis.bem.phi"))
    assert np.all(alpha < POLAR.alpha_stall - POLAR.stall_half_width)
    assert np.all(prob.get_val("efficiency")[1:] > 0.7)


def test_design_by_thrust_target_with_pitch_trim():
    # BILD solves its reference chord for the design thrust; the analyses trim pitch to theirs.
    values = dict(TOTALS_VALUES, design_thrust_target=[720.0])
    del values["ref_chord"]
    prob = _run(values, polar=POLAR, design_thrust_target=True, trim="collective_pitch")
    assert prob.get_val("design_thrust")[0] == pytest.approx(720.0, rel=1e-10)
    np.testing.assert_allclose(prob.get_val("thrust"), values["thrust_target"], rtol=1e-10)
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*have a nonlinear solver that computes gradients")
        check_group_totals(lambda: MultipointRotorGroup(num_nodes=NN, num_radial=NR, polar=POLAR,
                                                        design_thrust_target=True, trim="collective_pitch"),
                           of=["ref_chord", "chord", "power", "design_power", "collective_pitch"],
                           wrt=["design_thrust_target", "design_rpm", "radius", "v_axial", "thrust_target"],
                           values=values, atol=1e-9, rtol=1e-6)


def test_trim_bounds_must_be_an_interval():
    prob = om.Problem(reports=False)
    with pytest.raises(ValueError, match="trim_bounds"):
        prob.model.add_subsystem("rotor", MultipointRotorGroup(trim="rpm", trim_bounds=(3000.0, 100.0)))


def test_no_approximated_partials():
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("rotor", MultipointRotorGroup(num_nodes=NN, num_radial=NR, trim="collective_pitch"),
                             promotes=["*"])
    prob.setup()
    assert_no_approx_partials(prob.model, method="cs")
    assert_no_approx_partials(prob.model, method="fd")
