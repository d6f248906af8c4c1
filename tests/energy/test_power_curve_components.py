"""The components of PowerCurveGroup: complex-step partials, the Lobatto rule and the wind-speed nodes."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.energy import AnnualEnergyComp
from bild_mdo.energy.curve_assembly import CurveAssemblyComp
from bild_mdo.energy.curve_energy import CurveEnergyComp
from bild_mdo.energy.pitch_trim import _axial_induction
from bild_mdo.energy.rated_wind_speed import RatedWindSpeedComp
from bild_mdo.energy.rotor_broadcast import RotorBroadcastComp
from bild_mdo.energy.rotor_speed import RotorSpeedComp
from bild_mdo.energy.wind_speeds import WindSpeedsComp, lobatto, region_sizes
from bild_mdo.utils.testing import check_component_partials

NN, NR, NW = 3, 4, 7
RNG = np.random.default_rng(27)
LIMITS = dict(cut_in_speed=[3.0, 3.5, 4.0], rated_wind_speed=[10.0, 11.0, 12.5], cut_out_speed=[25.0, 24.0, 22.0])


def test_lobatto_rule_is_exact_to_degree_2n_minus_3():
    # Gauss-Lobatto-Legendre with n nodes integrates x**m exactly on [-1, 1] for m <= 2n - 3
    # (Abramowitz & Stegun 25.4.32); the 5-point weights are 1/10, 49/90, 32/45 (ibid., Table 25.6).
    for n in (3, 5, 8):
        x, w = lobatto(n)
        for m in range(2 * n - 2):
            assert w @ x ** m == pytest.approx((1.0 + (-1.0) ** m) / (m + 1.0), abs=1e-14)
    np.testing.assert_allclose(lobatto(5)[1], [0.1, 49 / 90, 32 / 45, 49 / 90, 0.1], rtol=1e-14)
    assert region_sizes(7) == (4, 4) and region_sizes(8) == (4, 5)


def test_wind_speeds_hold_cut_in_rated_and_cut_out():
    prob = check_component_partials(WindSpeedsComp(num_nodes=NN, num_wind_speeds=NW), LIMITS)
    v = prob.get_val("wind_speed")
    n2, _ = region_sizes(NW)
    np.testing.assert_allclose(v[:, [0, n2 - 1, -1]], np.array(list(LIMITS.values())).T, rtol=1e-15)
    assert np.all(np.diff(v, axis=1) > 0.0)


def test_wind_speeds_reject_rated_outside_the_operating_range():
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("wind", WindSpeedsComp(num_nodes=1, num_wind_speeds=5), promotes=["*"])
    prob.setup()
    prob.set_val("rated_wind_speed", 30.0)
    with pytest.raises(om.AnalysisError, match="not reached below the cut-out speed"):
        prob.run_model()
    prob.set_val("rated_wind_speed", 2.0)
    with pytest.raises(om.AnalysisError, match="below the cut-in speed"):
        prob.run_model()


@pytest.mark.parametrize("capped", [True, False])
def test_rotor_speed_partials_and_rated_cap(capped):
    v = RNG.uniform(3.0, 25.0, (NN, NW))
    values = dict(wind_speed=v, tip_speed_ratio=[7.0, 8.0, 9.0], radius=[40.0, 50.0, 60.0],
                  rated_wind_speed=LIMITS["rated_wind_speed"])
    prob = check_component_partials(RotorSpeedComp(num_nodes=NN, num_points=NW, capped=capped), values)
    governing = np.minimum(v, np.array(LIMITS["rated_wind_speed"])[:, None]) if capped else v
    # Omega = lambda V / R below rated, held above (hand derivation; 30/pi rpm per rad/s).
    expected = np.array([7.0, 8.0, 9.0])[:, None] * governing / np.array([40.0, 50.0, 60.0])[:, None] * 30 / np.pi
    np.testing.assert_allclose(prob.get_val("rpm"), expected, rtol=1e-14)


def test_rotor_speed_of_one_wind_speed_per_rotor():
    prob = check_component_partials(RotorSpeedComp(num_nodes=NN, capped=False), dict(wind_speed=[9.0, 10.0, 11.0]))
    assert prob.get_val("rpm").shape == (NN,)


def test_rated_wind_speed_partials_and_residual():
    prob = check_component_partials(RatedWindSpeedComp(num_nodes=NN), dict(power=[4e6, 5e6, 6e6],
                                                                          rated_power=[5e6, 5e6, 5e6]))
    # R = V (1 - (P_r/P)**(1/3)): zero where P = P_r (the rated point), of the sign of P - P_r elsewhere.
    prob.model.run_apply_nonlinear()
    residual = prob.model._residuals["rated_wind_speed"]
    v = prob.get_val("rated_wind_speed")
    np.testing.assert_allclose(residual, v * (1.0 - (5e6 / np.array([4e6, 5e6, 6e6])) ** (1 / 3)), rtol=1e-14)


def test_rated_wind_speed_rejects_a_rotor_without_power():
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("rated", RatedWindSpeedComp(num_nodes=2), promotes=["*"])
    prob.setup()
    prob.set_val("power", [1e6, -1.0])
    prob.final_setup()
    with pytest.raises(om.AnalysisError, match="extracts no power"):
        prob.model.run_apply_nonlinear()


def test_rotor_broadcast_partials_and_layout():
    chord = RNG.uniform(1.0, 3.0, (NN, NR))
    prob = check_component_partials(RotorBroadcastComp(num_nodes=NN, num_radial=NR, num_points=2),
                                    dict(chord=chord, rho=[1.2, 1.1, 1.0]))
    # Rotor i at its points i*np ... (i+1)*np - 1.
    np.testing.assert_array_equal(prob.get_val("point_chord"), np.repeat(chord, 2, axis=0))
    np.testing.assert_array_equal(prob.get_val("point_rho"), [1.2, 1.2, 1.1, 1.1, 1.0, 1.0])


def test_curve_assembly_partials_and_layout():
    n2, n3 = region_sizes(NW)
    values = {"region2_power": RNG.uniform(size=NN * n2), "region3_power": RNG.uniform(size=NN * (n3 - 1)),
              "region3_collective_pitch": RNG.uniform(size=NN * (n3 - 1))}
    prob = check_component_partials(CurveAssemblyComp(num_nodes=NN, num_wind_speeds=NW), values)
    power = prob.get_val("power")
    np.testing.assert_array_equal(power[:, :n2], values["region2_power"].reshape(NN, n2))
    np.testing.assert_array_equal(power[:, n2:], values["region3_power"].reshape(NN, n3 - 1))
    assert np.all(prob.get_val("collective_pitch")[:, :n2] == 0.0)


def test_curve_energy_partials():
    values = dict(LIMITS, wind_speed=RNG.uniform(3.0, 25.0, (NN, NW)), power=RNG.uniform(1e5, 5e6, (NN, NW)),
                  rated_power=[4e6, 5e6, 3e6], weibull_scale=[7.0, 8.0, 9.0], weibull_shape=[1.8, 2.0, 2.3])
    check_component_partials(CurveEnergyComp(num_nodes=NN, num_wind_speeds=NW, check_trim=False), values)


def _cubic_curve(nw, cp=0.45, radius=40.0, rho=1.225, p_rated=2.0e6, v_in=3.0, v_out=25.0):
    gain = 0.5 * rho * np.pi * radius ** 2 * cp
    v_r = (p_rated / gain) ** (1.0 / 3.0)
    n2, n3 = region_sizes(nw)
    v = np.concatenate((v_in + (v_r - v_in) * 0.5 * (lobatto(n2)[0] + 1.0),
                        v_r + (v_out - v_r) * 0.5 * (lobatto(n3)[0][1:] + 1.0)))
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("energy", CurveEnergyComp(num_wind_speeds=nw), promotes=["*"])
    prob.setup()
    for name, value in dict(cut_in_speed=v_in, rated_wind_speed=v_r, cut_out_speed=v_out, rated_power=p_rated,
                            weibull_scale=8.0, weibull_shape=2.0, wind_speed=v[None, :],
                            power=np.where(np.arange(nw) < n2 - 1, gain * v ** 3, p_rated)[None, :]).items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


def test_curve_energy_of_the_cubic_curve_is_annual_energy_comp():
    # P = 1/2 rho A C_P V**3 below rated and P_r above is AnnualEnergyComp's model (48-point Gauss-Legendre,
    # checked there against the incomplete-gamma closed form): the Lobatto sums converge to it.
    reference = om.Problem(reports=False)
    reference.model.add_subsystem("aep", AnnualEnergyComp(), promotes=["*"])
    reference.setup()
    for name, value in dict(power_coefficient=0.45, radius=40.0, rated_power=2.0e6, weibull_scale=8.0).items():
        reference.set_val(name, value)
    reference.run_model()
    expected = reference.get_val("annual_energy")[0]
    errors = [abs(_cubic_curve(nw).get_val("annual_energy")[0] / expected - 1.0) for nw in (9, 17, 31)]
    assert errors[-1] < 1e-12 and errors[0] < 1e-5
    assert errors[1] < errors[0]


def test_curve_energy_rejects_a_failed_trim():
    prob = _cubic_curve(9)
    power = prob.get_val("power")
    power[0, -1] *= 1.01
    prob.set_val("power", power)
    with pytest.raises(om.AnalysisError, match="pitch trim does not hold rated power at 25 m/s"):
        prob.run_model()


def test_axial_induction_is_the_small_actuator_disk_root():
    # C_P = 4 a (1 - a)**2 (Betz): a = 1/3 at C_P = 16/27, a = 0 at 0.
    cp = np.array([0.0, 0.2, 0.4, 16.0 / 27.0])
    a = _axial_induction(cp)
    np.testing.assert_allclose(4.0 * a * (1.0 - a) ** 2, cp, atol=1e-13)
    assert np.all(a <= 1.0 / 3.0 + 1e-12)
