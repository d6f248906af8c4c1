import numpy as np

from bild_mdo.bild.rotational_speed import RotationalSpeedComp
from bild_mdo.utils.testing import check_component_partials
from tests.bild.conftest import NN, NR, state


def test_partials_and_values(kind):
    values = state(kind)
    prob = check_component_partials(RotationalSpeedComp(num_nodes=NN, num_radial=NR), values)
    # Hand derivation: V_theta = Omega r with Omega = 2 pi rpm / 60.
    omega = values["rpm"] * 2.0 * np.pi / 60.0
    np.testing.assert_allclose(prob.get_val("v_theta"), omega[:, None] * values["radii"], rtol=1e-14)
    np.testing.assert_allclose(prob.get_val("v_theta_ref"), omega * values["ref_radius"], rtol=1e-14)
