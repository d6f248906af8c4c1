"""BEMOptimizationGroup: exact totals of objective and constraint through the BEM analysis."""
import warnings

import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials

from bild_mdo.airfoil import naca4412
from bild_mdo.bem.flow_states import PROPELLER, TURBULENT_WAKE, BEMStateWarning
from bild_mdo.optimization.bem_optimization_group import BEMOptimizationGroup
from bild_mdo.utils.testing import check_group_totals

NN, NR = 2, 7


def _group(parameterization):
    return BEMOptimizationGroup(num_nodes=NN, num_radial=NR, polar=naca4412(), parameterization=parameterization,
                                num_cp=5)


def _values(parameterization):
    ncp = NR if parameterization == "stations" else 5
    x = np.linspace(0.0, 1.0, ncp)
    # Node 0 hovers, node 1 cruises at J = 1 (V_x = J n D): both operating regimes in one vectorised run.
    return {"v_axial": [0.0, 800.0 / 60.0 * 2.0 * 1.2], "rpm": [800.0, 800.0], "radius": [1.0, 1.2],
            "hub_radius": [0.2, 0.24], "altitude": [0.0, 1500.0],
            "chord_ratio_cp": np.vstack([0.15 - 0.1 * x, 0.08 - 0.04 * x]),
            "twist_cp": np.radians(np.vstack([25.0 - 15.0 * x, 60.0 - 35.0 * x])),
            "thrust_target": [400.0, 300.0], "energy_loss_ref": [3000.0, 1000.0]}


def _problem(parameterization):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("rotor", _group(parameterization), promotes=["*"])
    prob.setup(force_alloc_complex=True, mode="rev")
    for name, value in _values(parameterization).items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


@pytest.mark.parametrize("parameterization", ["stations", "bspline"])
def test_totals(parameterization):
    prob = _problem(parameterization)
    assert np.all(prob.get_val("thrust") > 0.0)
    assert_no_approx_partials(prob.model)
    check_group_totals(lambda: _group(parameterization), of=["energy_loss_ratio", "thrust_residual"],
                       wrt=["chord_ratio_cp", "twist_cp", "thrust_target", "radius", "v_axial"],
                       values=_values(parameterization), atol=1e-9, rtol=1e-8)


def test_objective_and_constraint_definitions():
    prob = _problem("stations")
    # Sec. 4.1, Eq. (12): E = Omega Q - V_x T; the responses divide by the case references.
    omega = prob.get_val("rpm", units="rad/s")
    energy = omega * prob.get_val("torque") - prob.get_val("v_axial") * prob.get_val("thrust")
    np.testing.assert_allclose(prob.get_val("energy_loss"), energy, rtol=1e-12)
    np.testing.assert_allclose(prob.get_val("energy_loss_ratio"), energy / [3000.0, 1000.0], rtol=1e-12)
    np.testing.assert_allclose(prob.get_val("thrust_residual"), prob.get_val("thrust") / [400.0, 300.0] - 1.0,
                               rtol=1e-12)
    # The stations parameterisation sets chord = R (c/R) station by station.
    np.testing.assert_allclose(prob.get_val("chord"),
                               prob.get_val("radius")[:, None] * prob.get_val("chord_ratio_cp"), rtol=1e-15)


def test_annuli_are_independent():
    # BEM treats every annulus separately (paper Sec. 3): the energy-loss gradient at one station
    # does not change when another station's chord changes, and designs (nodes) do not interact.
    # hessian_scaling relies on this block-diagonal Hessian.
    prob = _problem("stations")
    of, wrt = ["energy_loss_ratio", "thrust_residual"], ["chord_ratio_cp", "twist_cp"]
    before = prob.compute_totals(of=of, wrt=wrt, return_format="array")
    chord = prob.get_val("chord_ratio_cp").copy()
    chord[0, 3] *= 1.01
    prob.set_val("chord_ratio_cp", chord)
    prob.run_model()
    change = prob.compute_totals(of=of, wrt=wrt, return_format="array") - before
    # Rows: (response, node); columns: chord (node, station), then twist (node, station).
    rows_node0 = [0, NN]
    cols_station3 = [3, NN * NR + 3]
    moved = np.zeros_like(change, dtype=bool)
    moved[np.ix_(rows_node0, cols_station3)] = True
    scale = np.abs(before).max()
    assert np.all(np.abs(change[~moved]) <= 1e-11 * scale)
    assert np.all(np.abs(change[moved]) > 1e-6 * scale)


def test_invalid_flow_states_are_silent_at_trial_points():
    # A hovering blade whose three inner stations have negative pitch pushes air upward there while
    # the rest drives the wake down: those annuli are in the vortex-ring state (Leishman, Principles
    # of Helicopter Aerodynamics, Sec. 2.14), flagged TURBULENT_WAKE.  An optimiser's trial point may
    # be such a design; inside the optimisation it must neither warn nor fail.
    values = _values("stations")
    values["twist_cp"][0, :3] = np.radians(-10.0)
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("rotor", _group("stations"), promotes=["*"])
    prob.setup()
    for name, value in values.items():
        prob.set_val(name, value)
    with warnings.catch_warnings():
        warnings.simplefilter("error", BEMStateWarning)
        prob.run_model()
    np.testing.assert_array_equal(prob.get_val("bem.flow_state")[0, :3], TURBULENT_WAKE)
    assert np.all(prob.get_val("bem.flow_state")[1] == PROPELLER)


def test_invalid_flow_states_can_still_be_raised():
    values = _values("stations")
    values["twist_cp"][0, :3] = np.radians(-10.0)
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("rotor", BEMOptimizationGroup(num_nodes=NN, num_radial=NR, polar=naca4412(),
                                                           on_invalid="raise"), promotes=["*"])
    prob.setup()
    for name, value in values.items():
        prob.set_val(name, value)
    with pytest.raises(om.AnalysisError, match="node 0, station 0"):
        prob.run_model()
