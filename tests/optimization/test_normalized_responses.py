"""NormalizedResponsesComp: partials against complex step and the defining formulas."""
import numpy as np
import openmdao.api as om
from openmdao.utils.assert_utils import assert_check_partials

from bild_mdo.optimization.normalized_responses import NormalizedResponsesComp


def test_partials_and_values():
    nn = 3
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("comp", NormalizedResponsesComp(num_nodes=nn, num_radial=7), promotes=["*"])
    prob.setup(force_alloc_complex=True)
    values = dict(thrust=[400.0, 1500.0, 90.0], energy_loss=[3700.0, 16000.0, 400.0],
                  thrust_target=[420.0, 1500.0, 100.0], energy_loss_ref=[3000.0, 12000.0, 300.0])
    for name, val in values.items():
        prob.set_val(name, val)
    prob.run_model()
    assert_check_partials(prob.check_partials(method="cs", out_stream=None), atol=1e-12, rtol=1e-12)
    # Definitions: E / E_ref and T / T* - 1.
    np.testing.assert_allclose(prob.get_val("energy_loss_ratio"), [3700 / 3000, 16000 / 12000, 400 / 300])
    np.testing.assert_allclose(prob.get_val("thrust_residual"), [400 / 420 - 1, 0.0, -0.1], atol=1e-15)
