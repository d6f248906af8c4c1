import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.bild.inflow_angle import InflowAngleComp
from bild_mdo.utils.testing import check_component_partials
from tests.bild.conftest import NN, NR, state


def test_partials_and_geometry(kind):
    values = state(kind)
    prob = check_component_partials(InflowAngleComp(num_nodes=NN, num_radial=NR), values)
    phi = prob.get_val("phi", units="rad")
    w = prob.get_val("inflow_speed", units="m/s")
    v_t = values["v_theta"] - 0.5 * values["u_theta"]
    # Fig. 1b: W sin(phi) = u_axial, W cos(phi) = V_theta - u_theta/2 (Eqs. (7), (30)).
    np.testing.assert_allclose(w * np.sin(phi), values["u_axial"], rtol=1e-13)
    np.testing.assert_allclose(w * np.cos(phi), v_t, rtol=1e-13)
    # Sec. 4.3: theta = phi + alpha*.
    np.testing.assert_allclose(prob.get_val("twist"), phi + values["alpha_star"][:, None], rtol=1e-14)


def test_tangential_induction_beyond_twice_blade_speed_names_node_and_station():
    # V_theta - u_theta/2 = eta2 V_theta (Eq. (23)) must be positive; u_theta = 2.5 V_theta makes it negative.
    values = state("cruise")
    values["u_theta"] = values["u_theta"].copy()
    values["u_theta"][1, 3] = 2.5 * values["v_theta"][1, 3]
    with pytest.raises(om.AnalysisError, match=r"u_theta >= 2 V_theta \(eta2 <= 0\).* at 1 node\(s\): "
                                               r"node 1, station 3 \(u_theta "):
        check_component_partials(InflowAngleComp(num_nodes=NN, num_radial=NR), values)
