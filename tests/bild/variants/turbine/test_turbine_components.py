"""Partials of every component of the turbine BILD loading against complex step (num_nodes != num_radial)."""
import numpy as np
import pytest

from bild_mdo.bild.variants.turbine.thrust_limit import ThrustLimitComp
from bild_mdo.bild.variants.turbine.turbine_chord import TurbineChordComp
from bild_mdo.bild.variants.turbine.turbine_inflow import TurbineInflowComp
from bild_mdo.bild.variants.turbine.turbine_loads import TurbineLoadsComp
from bild_mdo.bild.variants.turbine.turbine_performance import TurbinePerformanceComp
from bild_mdo.bild.variants.turbine.turbine_reference import TurbineReferenceStationComp
from bild_mdo.utils.testing import check_component_partials

NN, NR = 2, 5
RPM = np.array([20.0, 16.0])
RADIUS = np.array([40.0, 35.0])
HUB = np.array([2.0, 3.5])


def _stations():
    radii = HUB[:, None] + (RADIUS - HUB)[:, None] * (np.arange(NR) + 0.5) / NR
    return radii, RPM[:, None] * np.pi / 30.0 * radii, np.broadcast_to(((RADIUS - HUB) / NR)[:, None], (NN, NR))


def _node_inputs():
    return {"v_axial": np.array([10.0, 8.0]), "radius": RADIUS, "hub_radius": HUB, "rho": np.array([1.225, 1.1]),
            "cl_star": np.array([0.95, 1.1]), "cd_star": np.array([0.011, 0.02]),
            "alpha_star": np.array([0.1, 0.12]), "rpm": RPM}


def _phi(mu):
    """Loaded inflow angles from the inflow component itself."""
    radii, v_theta, _ = _stations()
    prob = check_component_partials(TurbineInflowComp(num_nodes=NN, num_radial=NR),
                                    {**_node_inputs(), "radii": radii, "v_theta": v_theta,
                                     "power_thrust_multiplier": mu}, atol=1e-7, rtol=1e-7)
    return prob.get_val("phi")


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip", "none"])
@pytest.mark.parametrize("mu", [np.array([0.0, 0.0]), np.array([3.0, -2.0])])
def test_inflow_loads_chord(loss_model, mu):
    radii, v_theta, _ = _stations()
    values = {**_node_inputs(), "radii": radii, "v_theta": v_theta, "power_thrust_multiplier": mu}
    prob = check_component_partials(TurbineInflowComp(num_nodes=NN, num_radial=NR, loss_model=loss_model), values,
                                    atol=1e-7, rtol=1e-7)
    values["phi"] = prob.get_val("phi")
    loads = check_component_partials(TurbineLoadsComp(num_nodes=NN, num_radial=NR, loss_model=loss_model), values,
                                     atol=1e-6, rtol=1e-7)
    assert np.all(loads.get_val("axial_induction") > 0.0) and np.all(loads.get_val("axial_induction") < 0.5)
    values.update({name: loads.get_val(name) for name in ("dthrust_dr", "inflow_speed")})
    check_component_partials(TurbineChordComp(num_nodes=NN, num_radial=NR), values, atol=1e-8, rtol=1e-8)


def test_inflow_unloaded_station():
    """A multiplier above G(phi0) = V (no drag) leaves stations unloaded: phi = atan(V / (Omega r))."""
    radii, v_theta, _ = _stations()
    values = {**_node_inputs(), "radii": radii, "v_theta": v_theta, "power_thrust_multiplier": np.array([9.99, 12.0])}
    prob = check_component_partials(TurbineInflowComp(num_nodes=NN, num_radial=NR), values)
    np.testing.assert_allclose(prob.get_val("phi")[1], np.arctan(8.0 / v_theta[1]), rtol=1e-15)


def test_performance():
    radii, _, dr = _stations()
    values = {**_node_inputs(), "dthrust_dr": 100.0 + radii ** 2, "dtorque_dr": 50.0 * radii, "dr": dr}
    prob = check_component_partials(TurbinePerformanceComp(num_nodes=NN, num_radial=NR), values)
    omega = RPM * np.pi / 30.0
    power = omega * np.sum(50.0 * radii * dr, axis=1)
    np.testing.assert_allclose(prob.get_val("power"), power, rtol=1e-14)
    np.testing.assert_allclose(prob.get_val("power_coefficient"),
                               power / (0.5 * values["rho"] * np.pi * RADIUS ** 2 * values["v_axial"] ** 3), rtol=1e-14)
    np.testing.assert_allclose(prob.get_val("tip_speed_ratio"), omega * RADIUS / values["v_axial"], rtol=1e-14)


@pytest.mark.parametrize("loss_model", ["tip_hub", "none"])
def test_reference_station_both_ways(loss_model):
    """mu -> c_ref and c_ref -> mu are inverse to each other (the family has one parameter)."""
    ref_radius = 0.7 * RADIUS
    values = {**_node_inputs(), "ref_radius": ref_radius, "v_theta_ref": RPM * np.pi / 30.0 * ref_radius,
              "power_thrust_multiplier": np.array([0.0, 2.5])}
    forward = check_component_partials(TurbineReferenceStationComp(num_nodes=NN, loss_model=loss_model), values,
                                       atol=1e-7, rtol=1e-7)
    values["ref_chord"] = forward.get_val("ref_chord")
    back = check_component_partials(TurbineReferenceStationComp(num_nodes=NN, loss_model=loss_model,
                                                                given="ref_chord"), values, atol=1e-7, rtol=1e-7)
    np.testing.assert_allclose(back.get_val("power_thrust_multiplier"), [0.0, 2.5], atol=1e-9)
    np.testing.assert_allclose(back.get_val("phi_ref"), forward.get_val("phi_ref"), rtol=1e-12)


@pytest.mark.parametrize("loss_model", ["tip_hub", "none"])
def test_thrust_limit(loss_model):
    radii, v_theta, dr = _stations()
    values = {**_node_inputs(), "radii": radii, "v_theta": v_theta, "dr": dr,
              "thrust_target": np.array([1.5e5, 1.2e5])}
    prob = check_component_partials(ThrustLimitComp(num_nodes=NN, num_radial=NR, loss_model=loss_model), values,
                                    atol=1e-7, rtol=1e-7)
    assert np.all(np.isfinite(prob.get_val("power_thrust_multiplier")))
