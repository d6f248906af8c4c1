"""BEMAnalysisGroup: total derivatives through the implicit inflow solve, and options."""
import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials

from bild_mdo.airfoil import get_polar
from bild_mdo.bem.flow_states import PROPELLER, TURBULENT_WAKE, BEMStateWarning
from bild_mdo.bem.bem_group import BEMAnalysisGroup
from bild_mdo.utils.testing import assert_totals_match, check_group_totals

NN, NR, B = 3, 7, 3
OF = ["thrust", "torque", "energy_loss", "efficiency"]


def _problem(polar, blade, use_atmosphere=True, loss_model="tip_hub"):
    prob = om.Problem(BEMAnalysisGroup(num_nodes=NN, num_radial=NR, num_blades=B, polar=polar,
                                       loss_model=loss_model, use_atmosphere=use_atmosphere),
                      reports=False)
    prob.setup(force_alloc_complex=True)
    for name in ("v_axial", "rpm", "radius", "hub_radius", "chord", "twist"):
        prob.set_val(name, blade[name])
    if use_atmosphere:
        prob.set_val("altitude", blade["altitude"])
    else:
        prob.set_val("rho", [1.225, 1.1, 0.95])
        prob.set_val("mu", [1.79e-5, 1.75e-5, 1.7e-5])
    prob.run_model()
    return prob


@pytest.mark.parametrize("loss_model", ["tip_hub", "none"])
def test_totals_hover_and_cruise(smooth_polar, make_blade, loss_model):
    # Node 0 hovers, nodes 1-2 cruise (make_blade).
    prob = _problem(smooth_polar, make_blade(NN, NR), loss_model=loss_model)
    assert_no_approx_partials(prob.model, include_self=True, recurse=True)
    check_group_totals(lambda: BEMAnalysisGroup(num_nodes=NN, num_radial=NR, num_blades=B, polar=smooth_polar,
                                                loss_model=loss_model),
                       of=OF, wrt=["chord", "twist", "v_axial", "rpm", "radius", "hub_radius", "altitude"],
                       values=make_blade(NN, NR))


def test_totals_with_rho_mu_inputs(smooth_polar, make_blade):
    blade = make_blade(NN, NR, seed=2)
    values = {name: blade[name] for name in ("v_axial", "rpm", "radius", "hub_radius", "chord", "twist")}
    values.update(rho=[1.225, 1.1, 0.95], mu=[1.79e-5, 1.75e-5, 1.7e-5])
    check_group_totals(lambda: BEMAnalysisGroup(num_nodes=NN, num_radial=NR, num_blades=B, polar=smooth_polar,
                                                use_atmosphere=False),
                       of=OF, wrt=["chord", "rho", "mu", "rpm"], values=values)


def test_totals_in_reverse_mode(analytic_polar, make_blade):
    prob = om.Problem(BEMAnalysisGroup(num_nodes=NN, num_radial=NR, num_blades=B, polar=analytic_polar),
                      reports=False)
    prob.model.add_design_var("chord")
    prob.model.add_design_var("twist")
    prob.model.add_design_var("rpm")
    prob.model.add_objective("energy_loss", index=0)
    prob.model.add_constraint("thrust", lower=0.0)
    prob.setup(mode="rev", force_alloc_complex=True)
    blade = make_blade(NN, NR, seed=3)
    for name in ("v_axial", "rpm", "radius", "hub_radius", "chord", "twist", "altitude"):
        prob.set_val(name, blade[name])
    prob.run_model()
    assert_totals_match(prob.check_totals(method="cs", out_stream=None), atol=1e-8, rtol=1e-8)


def test_group_is_feed_forward_runonce(analytic_polar, make_blade):
    prob = _problem(analytic_polar, make_blade(NN, NR))
    assert isinstance(prob.model.nonlinear_solver, om.NonlinearRunOnce)
    assert isinstance(prob.model.linear_solver, om.LinearRunOnce)
    # Hover node: thrust and figure of merit positive and FM < 1 (momentum theory bound).
    assert prob.get_val("thrust")[0] > 0 and 0 < prob.get_val("figure_of_merit")[0] < 1


def test_on_invalid_option_and_flow_state_output():
    # The blade: outboard annuli with negative pitch push air against the freestream at
    # V_x = 5 m/s and against the rotor's own wake in hover (turbulent wake / vortex ring, invalid).

    def run(v_axial, on_invalid):
        prob = om.Problem(BEMAnalysisGroup(num_nodes=1, num_radial=20, num_blades=3, polar=get_polar("naca4412"),
                                           on_invalid=on_invalid), reports=False)
        prob.setup()
        prob.set_val("radius", 1.0)
        prob.set_val("hub_radius", 0.2)
        prob.set_val("rpm", 3000.0)
        prob.set_val("v_axial", v_axial)
        prob.set_val("chord", np.full((1, 20), 0.1))
        prob.set_val("twist", np.radians(np.linspace(20, -10, 20))[None, :])
        prob.run_model()
        return prob

    with pytest.raises(om.AnalysisError, match="turbulent wake / vortex ring"):
        run(5.0, "raise")
    with pytest.warns(BEMStateWarning, match="node 0, station"):
        prob = run(5.0, "warn")
    assert np.any(prob.get_val("flow_state") == TURBULENT_WAKE)
    with pytest.raises(om.AnalysisError, match="station 19 .*turbulent wake / vortex ring"):
        run(0.0, "raise")
    assert np.all(run(0.0, "ignore").get_val("flow_state")[0, :10] == PROPELLER)
