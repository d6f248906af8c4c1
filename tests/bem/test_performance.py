"""RotorPerformanceComp: paper Table 2 metrics by hand, and partials."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.bem.performance import RotorPerformanceComp
from bild_mdo.utils.testing import check_component_partials

NN, NR, B = 3, 7, 3


def _values(v_axial):
    rng = np.random.default_rng(7)
    return dict(dthrust_dr=rng.uniform(10.0, 400.0, (NN, NR)), dtorque_dr=rng.uniform(5.0, 80.0, (NN, NR)),
                dr=rng.uniform(0.02, 0.1, (NN, NR)), chord=rng.uniform(0.05, 0.15, (NN, NR)), v_axial=v_axial,
                rpm=[1200.0, 2400.0, 3100.0], radius=[0.7, 1.1, 1.6], rho=[1.225, 1.0, 0.9])


def _problem(v_axial):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("perf", RotorPerformanceComp(num_nodes=NN, num_radial=NR, num_blades=B),
                             promotes=["*"])
    prob.setup(force_alloc_complex=True)
    for name, value in _values(v_axial).items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


@pytest.mark.filterwarnings("ignore:(?s).*zero derivatives")  # eta = 0 in hover: some partials vanish
@pytest.mark.parametrize("v_axial", [[0.0, 0.0, 0.0], [0.0, 12.0, 45.0]], ids=["hover", "cruise"])
def test_partials(v_axial):
    check_component_partials(RotorPerformanceComp(num_nodes=NN, num_radial=NR, num_blades=B), _values(v_axial),
                             atol=1e-10, rtol=1e-10)


def test_metrics_by_hand():
    prob = _problem([0.0, 12.0, 45.0])
    g = prob.get_val
    T = (g("dthrust_dr") * g("dr")).sum(axis=1)
    Q = (g("dtorque_dr") * g("dr")).sum(axis=1)
    omega = g("rpm") * np.pi / 30.0
    n, D, rho, R, vx = g("rpm") / 60.0, 2.0 * g("radius"), g("rho"), g("radius"), g("v_axial")
    # Paper Table 2.
    np.testing.assert_allclose(g("thrust"), T, rtol=1e-14)
    np.testing.assert_allclose(g("torque"), Q, rtol=1e-14)
    np.testing.assert_allclose(g("power"), omega * Q, rtol=1e-14)
    np.testing.assert_allclose(g("efficiency"), vx * T / (omega * Q), rtol=1e-14)
    np.testing.assert_allclose(g("figure_of_merit"), T / (omega * Q) * np.sqrt(T / (2 * np.pi * R**2 * rho)),
                               rtol=1e-14)
    np.testing.assert_allclose(g("thrust_coefficient"), T / (rho * n**2 * D**4), rtol=1e-14)
    np.testing.assert_allclose(g("torque_coefficient"), Q / (rho * n**2 * D**5), rtol=1e-14)
    # C_P = 2 pi C_Q follows from P = 2 pi n Q (hand).
    np.testing.assert_allclose(g("power_coefficient"), 2 * np.pi * g("torque_coefficient"), rtol=1e-14)
    np.testing.assert_allclose(g("energy_loss"), omega * Q - vx * T, rtol=1e-14)
    sol = B * (g("chord") * g("dr")).sum(axis=1) / (np.pi * R**2)
    np.testing.assert_allclose(g("solidity"), sol, rtol=1e-14)
    np.testing.assert_allclose(g("blade_loading"), g("thrust_coefficient") / sol, rtol=1e-14)


def test_figure_of_merit_is_odd_in_thrust():
    prob = _problem([0.0, 0.0, 0.0])
    fm = prob.get_val("figure_of_merit").copy()
    prob.set_val("dthrust_dr", -prob.get_val("dthrust_dr"))
    prob.run_model()
    np.testing.assert_allclose(prob.get_val("figure_of_merit"), -fm, rtol=1e-14)
    assert np.all(np.isfinite(prob.get_val("figure_of_merit")))


def test_hover_efficiency_is_exactly_zero():
    # eta = V_x T / (Omega Q) with V_x = 0 and P > 0 (Table 2): exactly 0, not NaN.
    prob = _problem([0.0, 0.0, 0.0])
    np.testing.assert_array_equal(prob.get_val("efficiency"), 0.0)


@pytest.mark.parametrize("name, value, match", [
    ("dtorque_dr", 0.0, r"torque = 0\.0 at node 1: the shaft power P = Omega Q must be nonzero"),
    ("rpm", 0.0, r"rpm = 0\.0 at node 1: the rotor speed must be positive"),
    ("rpm", -100.0, r"rpm = -100\.0 at node 1: the rotor speed must be positive"),
])
def test_zero_power_or_rotor_speed_raises(name, value, match):
    # P = Omega Q = 0 would make eta, FM, C_T ... inf/NaN: report it instead (the component names itself).
    prob = _problem([0.0, 12.0, 45.0])
    values = prob.get_val(name).copy()
    values[1] = value
    prob.set_val(name, values)
    with pytest.raises(om.AnalysisError, match=r"'perf' <class RotorPerformanceComp>: rotor performance: " + match):
        prob.run_model()


def test_windmilling_rotor_keeps_finite_signed_metrics():
    # A windmilling rotor (T < 0, Q < 0 at rpm > 0) extracts power: P < 0, and eta = V_x T / P stays finite
    # (the BEM analysis reports such states, tests/bem/test_validation.py).
    prob = _problem([0.0, 12.0, 45.0])
    prob.set_val("dthrust_dr", -prob.get_val("dthrust_dr"))
    prob.set_val("dtorque_dr", -prob.get_val("dtorque_dr"))
    prob.run_model()
    assert np.all(prob.get_val("power") < 0.0)
    for name in ("efficiency", "figure_of_merit", "power_coefficient", "blade_loading"):
        assert np.all(np.isfinite(prob.get_val(name)))


def test_tip_mach_by_hand():
    # Tip Mach number sqrt(V_x^2 + (Omega R)^2) / a (issue definition), a = 340.294 m/s by default
    # (sea-level ISA) and as given.
    prob = _problem([0.0, 12.0, 45.0])
    omega = np.array([1200.0, 2400.0, 3100.0]) * np.pi / 30.0
    tip_speed = np.hypot([0.0, 12.0, 45.0], omega * np.array([0.7, 1.1, 1.6]))
    np.testing.assert_allclose(prob.get_val("tip_mach"), tip_speed / 340.294, rtol=1e-15)
    prob.set_val("speed_of_sound", [300.0, 320.0, 340.0])
    prob.run_model()
    np.testing.assert_allclose(prob.get_val("tip_mach"), tip_speed / [300.0, 320.0, 340.0], rtol=1e-15)


def test_blade_without_area_has_zero_blade_loading():
    # S = sum(c dr) = 0 (no blade): C_T / sigma_r is taken as 0 (no load), not 0/0.
    prob = _problem([0.0, 12.0, 45.0])
    prob.set_val("chord", np.zeros((NN, NR)))
    prob.set_val("dthrust_dr", np.zeros((NN, NR)))
    prob.run_model()
    assert np.all(prob.get_val("blade_loading") == 0.0) and np.all(prob.get_val("solidity") == 0.0)


def test_values_without_partials_are_the_same():
    # A run without derivatives (RotorPerformanceComp.compute) evaluates the same formulas.
    from bild_mdo.bem.performance import rotor_performance

    args = (np.array([900.0, -50.0]), np.array([120.0, 30.0]), np.array([0.2, 0.0]), np.array([0.0, 20.0]),
            np.array([800.0, 1200.0]), np.array([1.5, 1.0]), np.array([1.225, 1.0]), B)
    full, _ = rotor_performance(*args)
    values, partials = rotor_performance(*args, partials=False)
    assert partials is None
    for name, value in full.items():
        np.testing.assert_array_equal(values[name], value)
