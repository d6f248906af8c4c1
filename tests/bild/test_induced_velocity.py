import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.bild.induced_velocity import InducedVelocityComp
from bild_mdo.utils.testing import check_component_partials
from tests.bild.conftest import NN, NR, state


def test_partials(kind):
    check_component_partials(InducedVelocityComp(num_nodes=NN, num_radial=NR), state(kind))


def test_satisfies_eq25(kind):
    # Eq. (26) is the positive root of Eq. (25): check Eq. (25) on the outputs.
    values = state(kind)
    prob = check_component_partials(InducedVelocityComp(num_nodes=NN, num_radial=NR), values)
    u_axial, u_t = prob.get_val("u_axial"), prob.get_val("u_theta")
    v_x, v_t = values["v_axial"][:, None], values["v_theta"]
    cl, cd = values["cl_star"][:, None], values["cd_star"][:, None]
    lhs = 2.0 * (u_axial - v_x) / u_t
    rhs = (cl * (v_t - u_t / 2) - cd * u_axial) / (cl * u_axial + cd * (v_t - u_t / 2))
    np.testing.assert_allclose(lhs, rhs, rtol=1e-12)
    # Eq. (24) inverts Eq. (23).
    np.testing.assert_allclose((v_t - u_t / 2) / v_t, values["eta2"], rtol=1e-14)
    # Assumption 3: V_x < u_axial and 0 < u_theta < V_theta.
    assert np.all(u_axial > v_x) and np.all((u_t > 0) & (u_t < v_t))


def test_unloaded_station_in_hover():
    # eta2 = 1 and V_x = 0: no induction (q = b**2 > 0 keeps the derivatives finite).
    values = state("hover")
    values["eta2"] = np.ones((NN, NR))
    prob = check_component_partials(InducedVelocityComp(num_nodes=NN, num_radial=NR), values)
    assert np.max(np.abs(prob.get_val("u_axial"))) < 1e-12
    np.testing.assert_array_equal(prob.get_val("u_theta"), 0.0)


def _eq25_sides(prob, values):
    """Both sides of Eq. (25), 2 (u_axial - V_x) / u_theta = C_x / C_theta (in velocity form)."""
    u_axial, u_t = prob.get_val("u_axial"), prob.get_val("u_theta")
    v_x, v_t = values["v_axial"][:, None], values["v_theta"]
    cl, cd = values["cl_star"][:, None], values["cd_star"][:, None]
    lhs = 2.0 * (u_axial - v_x) / u_t
    rhs = (cl * (v_t - u_t / 2) - cd * u_axial) / (cl * u_axial + cd * (v_t - u_t / 2))
    return lhs, rhs


@pytest.mark.parametrize("gap", [1e-10, 1e-13])
def test_no_cancellation_near_unloaded_hover(gap):
    # Hover, eta2 -> 1: b = -V_theta C_d/(2 C_l) < 0 and c -> 0, where b + sqrt(b**2 + c) loses ~|b|/u_axial
    # digits (measured: Eq. (25) off by 5e-8 relative at 1 - eta2 = 1e-13); the stable form keeps it exact.
    values = state("hover")
    values["eta2"] = np.full((NN, NR), 1.0 - gap)
    prob = check_component_partials(InducedVelocityComp(num_nodes=NN, num_radial=NR), values)
    lhs, rhs = _eq25_sides(prob, values)
    np.testing.assert_allclose(lhs, rhs, rtol=1e-12)
    assert np.all(prob.get_val("u_axial") > 0.0)


def _cruise_at_ratio(ratio, node=1, station=2):
    """Cruise inputs where V_x = ratio * eta2 V_theta C_l/C_d at one station (all others far inside the rule)."""
    values = state("cruise")
    v_t = values["v_theta"].copy()
    # Put the station's V_theta exactly where the rule V_x < eta2 V_theta C_l/C_d is met with the given ratio.
    lift_to_drag = values["cl_star"][node] / values["cd_star"][node]
    v_t[node, station] = values["v_axial"][node] / (ratio * values["eta2"][node, station] * lift_to_drag)
    values["v_theta"] = v_t
    return values


def test_positive_local_thrust_boundary_is_exact():
    # Hand derivation from Eq. (25): u_axial - V_x has the sign of (1 - eta2)(eta2 V_theta - V_x C_d/C_l).
    # Just inside the boundary the station is loaded (u_axial > V_x) ...
    values = _cruise_at_ratio(1.0 - 1e-9)
    prob = check_component_partials(InducedVelocityComp(num_nodes=NN, num_radial=NR), values)
    assert prob.get_val("u_axial")[1, 2] > values["v_axial"][1]
    # ... just outside it the station would windmill, and the component says where and what to change.
    values = _cruise_at_ratio(1.0 + 1e-9)
    with pytest.raises(om.AnalysisError, match=r"(?s)u_axial > V_x.*"
                                               r"needs V_x < eta2 V_theta C_l\*/C_d\*.*hub_radius_ratio.*"
                                               r"advance ratio.*higher maximum L/D.*node 1, station 2 "):
        check_component_partials(InducedVelocityComp(num_nodes=NN, num_radial=NR), values)


def test_low_lift_to_drag_inboard_station_raises():
    # C_l/C_d = 0.5 at node 0 (V_x = 20 m/s): the rule V_x < eta2 V_theta C_l/C_d fails at the innermost
    # station (V_theta = 32.3 m/s, eta2 < 0.98: limit < 15.8 m/s) and holds at the tip (118 m/s: limit > 53 m/s).
    values = state("cruise")
    values["cd_star"] = values["cd_star"].copy()
    values["cd_star"][0] = 2.0 * values["cl_star"][0]
    with pytest.raises(om.AnalysisError, match=r"at 1 node\(s\): node 0, station 0 \(V_theta "):
        check_component_partials(InducedVelocityComp(num_nodes=NN, num_radial=NR), values)
