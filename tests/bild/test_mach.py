import numpy as np

from bild_mdo.bild.mach import LocalMachComp
from bild_mdo.utils.testing import check_component_partials
from tests.bild.conftest import NN, NR, state


def test_partials_and_definition(kind):
    values = state(kind)
    values["inflow_speed"] = np.hypot(values["u_axial"], values["v_theta"] - 0.5 * values["u_theta"])
    values["speed_of_sound"] = np.array([340.294, 336.4, 328.6])  # ISA at 0, 1000, 3000 m
    prob = check_component_partials(LocalMachComp(num_nodes=NN, num_radial=NR), values)
    # M = W / a (definition of the local Mach number).
    np.testing.assert_allclose(prob.get_val("mach"), values["inflow_speed"] / values["speed_of_sound"][:, None],
                               rtol=1e-15)
