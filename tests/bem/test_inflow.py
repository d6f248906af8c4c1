"""InflowComp: bracketed solve, residual at convergence, partials, linear solve and errors."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.airfoil.polar import Polar, PolarValues
from bild_mdo.bem.analyze import station_radii
from bild_mdo.bem.blade_element import evaluate_section, residual_function
from bild_mdo.bem.inflow import InflowComp
from bild_mdo.utils.testing import check_component_partials

NN, NR, B = 3, 7, 3


def _values(blade, all_hover=False):
    values = {name: blade[name] for name in ("rpm", "radius", "hub_radius", "chord", "twist")}
    values.update(v_axial=0.0 * blade["v_axial"] if all_hover else blade["v_axial"],
                  radii=station_radii(blade["radius"], blade["hub_radius"], NR),
                  rho=[1.225, 1.1, 0.95], mu=[1.79e-5, 1.75e-5, 1.7e-5])
    return values


def _problem(polar, blade, loss_model="tip_hub", all_hover=False):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("inflow", InflowComp(num_nodes=NN, num_radial=NR, num_blades=B, polar=polar,
                                                  loss_model=loss_model), promotes=["*"])
    prob.setup(force_alloc_complex=True)
    for name, value in _values(blade, all_hover).items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip", "none"])
@pytest.mark.parametrize("all_hover", [False, True], ids=["hover+cruise", "hover"])
def test_solves_and_partials(smooth_polar, make_blade, loss_model, all_hover):
    comp = InflowComp(num_nodes=NN, num_radial=NR, num_blades=B, polar=smooth_polar, loss_model=loss_model)
    prob = check_component_partials(comp, _values(make_blade(NN, NR), all_hover), atol=1e-9, rtol=1e-9)
    prob.model.run_apply_nonlinear()
    assert np.max(np.abs(prob.model._residuals.asarray())) < 1e-12
    phi = prob.get_val("phi")
    assert np.all((phi > 0.0) & (phi < np.pi / 2))  # thrust-producing blades: region 1


def test_solve_linear_divides_by_state_jacobian(smooth_polar, make_blade):
    # With the diagonal state Jacobian stored in linearize, fwd and rev solves are the same division.
    prob = _problem(smooth_polar, make_blade(NN, NR))
    comp = prob.model.inflow
    comp.run_linearize()
    dR_dphi = comp._dR_dphi.copy()
    rhs = np.arange(1.0, NN * NR + 1).reshape(NN, NR)
    for mode in ("fwd", "rev"):
        d_outputs = {"phi": np.zeros((NN, NR)), "flow_state": np.zeros((NN, NR))}
        d_residuals = {"phi": np.zeros((NN, NR)), "flow_state": np.zeros((NN, NR))}
        (d_residuals if mode == "fwd" else d_outputs)["phi"] = rhs
        (d_residuals if mode == "fwd" else d_outputs)["flow_state"] = 2.0 * rhs
        comp.solve_linear(d_outputs, d_residuals, mode)
        result = d_outputs["phi"] if mode == "fwd" else d_residuals["phi"]
        np.testing.assert_allclose(result, rhs / dR_dphi, rtol=1e-15)
        # The flow-state label's residual is flow_state - label: an identity block.
        np.testing.assert_array_equal((d_outputs if mode == "fwd" else d_residuals)["flow_state"], 2.0 * rhs)


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip", "none"])
def test_solver_residual_matches_component_residual(smooth_polar, make_blade, loss_model):
    # The fast residual used inside the bracketed solve and the component's residual/partials are
    # the same function (one formula set, two code paths).
    blade = make_blade(NN, NR)
    radii = station_radii(blade["radius"], blade["hub_radius"], NR)
    phi = np.random.default_rng(9).uniform(-0.5, 2.5, (NN, NR))
    node = {k: np.asarray(blade[k], dtype=float)[:, None] for k in ("v_axial", "rpm", "radius", "hub_radius")}
    node.update(rho=np.full((NN, 1), 1.2), mu=np.full((NN, 1), 1.8e-5))
    values, partials = evaluate_section(phi, radii=radii, chord=blade["chord"], twist=blade["twist"],
                                        num_blades=B, polar=smooth_polar, loss_model=loss_model,
                                        loads=False, **node)
    flat = {k: np.broadcast_to(v, (NN, NR)).ravel() for k, v in node.items()}
    residual = residual_function(radii=radii.ravel(), chord=blade["chord"].ravel(),
                                 twist=blade["twist"].ravel(), num_blades=B, polar=smooth_polar,
                                 loss_model=loss_model, **flat)
    value, dphi = residual(phi.ravel(), np.arange(NN * NR))
    np.testing.assert_allclose(value, values["residual"].ravel(), rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(dphi, np.broadcast_to(partials["residual"]["phi"], (NN, NR)).ravel(),
                               rtol=1e-12, atol=1e-14)


@pytest.mark.parametrize("name, value", [("v_axial", -1.0), ("rpm", 0.0), ("chord", -0.1)])
def test_outside_domain_raises_analysis_error(smooth_polar, make_blade, name, value):
    prob = _problem(smooth_polar, make_blade(NN, NR))
    current = prob.get_val(name).copy()
    current.flat[1] = value
    prob.set_val(name, current)
    with pytest.raises(om.AnalysisError, match=name):
        prob.run_model()
