import numpy as np

from bild_mdo.bild.induced_velocity import InducedVelocityComp
from tests.bild.conftest import NN, NR, check_component, state


def test_partials(kind):
    check_component(InducedVelocityComp(num_nodes=NN, num_radial=NR), state(kind))


def test_satisfies_eq25(kind):
    # Eq. (26) is the positive root of Eq. (25): check Eq. (25) on the outputs.
    values = state(kind)
    prob = check_component(InducedVelocityComp(num_nodes=NN, num_radial=NR), values)
    u_x, u_t = prob.get_val("u_x"), prob.get_val("u_theta")
    v_x, v_t = values["v_axial"][:, None], values["v_theta"]
    cl, cd = values["cl_star"][:, None], values["cd_star"][:, None]
    lhs = 2.0 * (u_x - v_x) / u_t
    rhs = (cl * (v_t - u_t / 2) - cd * u_x) / (cl * u_x + cd * (v_t - u_t / 2))
    np.testing.assert_allclose(lhs, rhs, rtol=1e-12)
    # Eq. (24) inverts Eq. (23).
    np.testing.assert_allclose((v_t - u_t / 2) / v_t, values["eta2"], rtol=1e-14)
    # Assumption 3: V_x < u_x and 0 < u_theta < V_theta.
    assert np.all(u_x > v_x) and np.all((u_t > 0) & (u_t < v_t))


def test_unloaded_station_in_hover():
    # eta2 = 1 and V_x = 0: no induction (q = b**2 > 0 keeps the derivatives finite).
    values = state("hover")
    values["eta2"] = np.ones((NN, NR))
    prob = check_component(InducedVelocityComp(num_nodes=NN, num_radial=NR), values)
    assert np.max(np.abs(prob.get_val("u_x"))) < 1e-12
    np.testing.assert_array_equal(prob.get_val("u_theta"), 0.0)
