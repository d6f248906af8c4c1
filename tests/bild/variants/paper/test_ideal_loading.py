"""IdealLoadingComp: the ideal-loading constant lambda of Eq. (22)."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.bild.variants.paper.ideal_loading import IdealLoadingComp
from bild_mdo.utils.testing import check_component_partials

from tests.bild.conftest import NN, state


def reference_values(kind):
    values = state(kind)
    return dict(u_axial_ref=values["u_axial"][:, 3], u_theta_ref=2 * values["v_theta_ref"] * (1 - values["eta2"][:, 3]),
                v_axial=values["v_axial"], v_theta_ref=values["v_theta_ref"])


def run(values, num_nodes):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("comp", IdealLoadingComp(num_nodes=num_nodes), promotes=["*"])
    prob.setup()
    for name, value in values.items():
        prob.set_val(name, value)
    prob.run_model()
    return prob.get_val("ideal_loading_constant")


def test_hand_computed_values():
    # Hover: 50*2/(2*20) + 50*10/48 - 0 = 2.5 + 10.41666...; cruise: 60*3/(2*30) + 60*25/57 - 20 = 3 + 26.3157... - 20.
    lam = run(dict(u_axial_ref=[10.0, 25.0], u_theta_ref=[2.0, 3.0], v_axial=[0.0, 20.0], v_theta_ref=[50.0, 60.0]), 2)
    np.testing.assert_allclose(lam, [2.5 + 500.0 / 48.0, 3.0 + 1500.0 / 57.0 - 20.0], rtol=1e-15)


def test_lambda_exceeds_induced_velocity():
    # Appendix 7.1: under Assumption 3, lambda > u_axial - V_x > 0.
    rng = np.random.default_rng(2)
    n = 1000
    v_x = np.where(rng.random(n) < 0.3, 0.0, rng.uniform(0.0, 100.0, n))
    v_t = rng.uniform(5.0, 300.0, n)
    u_axial = v_x + rng.uniform(1e-3, 50.0, n)
    u_t = v_t * rng.uniform(1e-4, 1.0 - 1e-4, n)
    lam = run(dict(u_axial_ref=u_axial, u_theta_ref=u_t, v_axial=v_x, v_theta_ref=v_t), n)
    assert np.all(lam > u_axial - v_x)


def test_partials(kind):
    check_component_partials(IdealLoadingComp(num_nodes=NN), reference_values(kind))


@pytest.mark.parametrize("name, value, rule", [
    ("u_axial_ref", 20.0, r"u_axial_ref > V_x"),
    ("u_theta_ref", 0.0, r"u_theta_ref > 0"),
    ("u_theta_ref", 500.0, r"u_theta_ref < V_theta_ref"),
    ("v_axial", -1.0, r"V_x >= 0"),
])
def test_assumption_3_violations_raise(name, value, rule):
    values = reference_values("cruise")
    values[name] = values[name].copy()
    values[name][1] = value  # node 1 has V_x = 30 m/s
    with pytest.raises(om.AnalysisError,
                       match=rf"Assumption 3 violated at the reference station: {rule} fails.* node 1 \("):
        run(values, NN)


def test_overloaded_reference_station_says_what_to_change():
    values = reference_values("cruise")
    values["u_theta_ref"] = values["u_theta_ref"].copy()
    values["u_theta_ref"][1] = 1.5 * values["v_theta_ref"][1]
    with pytest.raises(om.AnalysisError, match=r"reduce ref_chord \(reference solidity\) or the advance ratio"):
        run(values, NN)
