"""Feasibility checks of the BILD chain: every failing node named, placeholders with consistent partials."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.bild.feasibility import FeasibilityLedger, node_ranges
from bild_mdo.bild.variants.paper.ideal_loading import IdealLoadingComp
from bild_mdo.bild.momentum_loads import MomentumLoadsComp
from bild_mdo.utils.testing import check_component_partials

from .conftest import NN, NR, state


def _reference_values():
    values = state("cruise")
    return dict(u_axial_ref=values["u_axial"][:, 3].copy(),
                u_theta_ref=2 * values["v_theta_ref"] * (1 - values["eta2"][:, 3]),
                v_axial=values["v_axial"], v_theta_ref=values["v_theta_ref"])


def test_node_ranges_name_every_node():
    assert node_ranges([0, 1, 2, 3, 7, 9, 10]) == "0-3, 7, 9-10"
    assert node_ranges([]) == ""


def test_component_alone_names_every_failing_node():
    # Assumption 3 at the reference station: u_axial_ref > V_x (paper Sec. 4); two nodes break it.
    values = _reference_values()
    values["u_axial_ref"][[0, 2]] = values["v_axial"][[0, 2]] - 1.0
    with pytest.raises(om.AnalysisError, match=r"u_axial_ref > V_x fails.* at 2 node\(s\): node 0 \(.*; node 2 \("):
        check_component_partials(IdealLoadingComp(num_nodes=NN), values)


def test_ledger_records_placeholders_with_consistent_partials():
    # Inside a BILDGroup an infeasible node gets lambda = V_theta_ref; its partials must match (complex step).
    values = _reference_values()
    values["u_theta_ref"][1] = 1.5 * values["v_theta_ref"][1]  # overloaded: u_theta_ref > V_theta_ref
    ledger = FeasibilityLedger(NN)
    prob = check_component_partials(IdealLoadingComp(num_nodes=NN, feasibility=ledger), values)
    np.testing.assert_array_equal(ledger.infeasible, np.arange(NN) == 1)
    assert prob.get_val("ideal_loading_constant")[1] == values["v_theta_ref"][1]
    assert ledger.status()[0] == "ok" and "u_theta_ref < V_theta_ref" in ledger.status()[1]
    assert ledger.message().startswith(f"1 of {NN} node(s) infeasible:") and "node(s) 1 [node 1 (" in ledger.message()


def test_unloaded_hover_node_gets_finite_placeholder_loads():
    # u_theta = 0 at every station of node 0 (eta2 = 1 everywhere, Eq. (24)): dQ/dr = 0, the rotor has no torque.
    values = state("hover")
    values["u_theta"] = values["u_theta"].copy()
    values["u_theta"][0] = 0.0
    ledger = FeasibilityLedger(NN)
    prob = check_component_partials(MomentumLoadsComp(num_nodes=NN, num_radial=NR, feasibility=ledger), values)
    np.testing.assert_array_equal(ledger.infeasible, np.arange(NN) == 0)
    np.testing.assert_array_equal(prob.get_val("dtorque_dr")[0], np.ones(NR))
    assert np.all(prob.get_val("dtorque_dr")[1:] > 0.0)


def test_light_nodes_fail_only_checks_that_ask_for_a_larger_chord():
    # FeasibilityLedger.light: a thrust-target solve searches above such a node, so a node that also fails a
    # check asking for a smaller chord (or another change) is not light.
    ledger = FeasibilityLedger(4)
    ledger.record("unloaded", [True, True, False, False], "no station loaded: raise ref_chord", {}, light=True)
    ledger.record("overloaded", [False, True, True, False], "overloaded: reduce ref_chord", {})
    np.testing.assert_array_equal(ledger.light, [True, False, False, False])
    np.testing.assert_array_equal(ledger.infeasible, [True, True, True, False])
    # A check recorded again without the flag is no longer light.
    ledger.record("unloaded", [True, False, False, False], "no station loaded", {})
    np.testing.assert_array_equal(ledger.light, [False, False, False, False])
