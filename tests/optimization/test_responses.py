"""NormalizedResponsesComp and ResponseSumsComp: partials against complex step and the defining formulas (paper Eq. 10)."""
import numpy as np

from bild_mdo.optimization.responses import NormalizedResponsesComp, ResponseSumsComp
from bild_mdo.utils.testing import check_component_partials


def test_partials_and_values():
    values = dict(thrust=[400.0, 1500.0, 90.0], energy_loss=[3700.0, 16000.0, 400.0],
                  thrust_target=[420.0, 1500.0, 100.0], energy_loss_ref=[3000.0, 12000.0, 300.0])
    prob = check_component_partials(NormalizedResponsesComp(num_nodes=3), values, atol=1e-12, rtol=1e-12)
    # Definitions: E / E_ref and T / T* - 1.
    np.testing.assert_allclose(prob.get_val("energy_loss_ratio"), [3700 / 3000, 16000 / 12000, 400 / 300])
    np.testing.assert_allclose(prob.get_val("thrust_residual"), [400 / 420 - 1, 0.0, -0.1], atol=1e-15)


def test_declares_no_radial_size():
    # A per-design component: only num_nodes, no num_radial.
    comp = NormalizedResponsesComp()
    assert "num_nodes" in comp.options and "num_radial" not in comp.options


def test_sums_partials_and_values():
    values = dict(energy_loss_ratio=[1.2, 1.05, 1.4, 1.1], thrust_residual=[1e-3, -2e-3, 0.0, 5e-4])
    prob = check_component_partials(ResponseSumsComp(num_nodes=4), values, atol=1e-12, rtol=1e-12)
    # Definition: plain sums over the designs (the cases of a lockstep batch do not interact).
    assert prob.get_val("energy_loss_ratio_sum")[0] == np.sum(values["energy_loss_ratio"])
    assert prob.get_val("thrust_residual_sum")[0] == np.sum(values["thrust_residual"])
