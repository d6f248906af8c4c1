"""AnnualEnergyComp: closed forms of the Weibull integrals, the regions' limits and complex-step partials."""
import numpy as np
import openmdao.api as om
import pytest
from scipy.special import gamma, gammainc

from bild_mdo.energy import HOURS_PER_YEAR, AnnualEnergyComp
from bild_mdo.utils.testing import check_component_partials

YEAR = HOURS_PER_YEAR * 3600.0


def _run(nn=1, **values):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("aep", AnnualEnergyComp(num_nodes=nn), promotes=["*"])
    prob.setup(force_alloc_complex=True)
    for name, value in values.items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


def _gain(cp, radius, rho):
    return 0.5 * rho * np.pi * radius ** 2 * cp


def test_region_two_alone_is_the_incomplete_gamma_closed_form():
    # Rated power out of reach (V_r > V_out): AEP = H K c**3 [gamma(1 + 3/k, z_out) - gamma(1 + 3/k, z_in)], the
    # lower incomplete gamma function (E[V**3] of the Weibull law between the limits; hand derivation).
    c, k, v_in, v_out = 7.5, 1.8, 3.0, 25.0
    prob = _run(power_coefficient=0.45, radius=40.0, rho=1.2, rated_power=1e9, weibull_scale=c, weibull_shape=k,
                cut_in_speed=v_in, cut_out_speed=v_out)
    s = 1.0 + 3.0 / k
    lower = gamma(s) * (gammainc(s, (v_out / c) ** k) - gammainc(s, (v_in / c) ** k))
    expected = YEAR * _gain(0.45, 40.0, 1.2) * c ** 3 * lower
    assert prob.get_val("annual_energy")[0] == pytest.approx(expected, rel=1e-12)


def test_rayleigh_energy_pattern_factor():
    # Rayleigh winds (k = 2) over all speeds: E[V**3] = (6/pi) Vmean**3 (the energy pattern factor 6/pi;
    # Manwell, McGowan & Rogers, Wind Energy Explained), Vmean = c sqrt(pi)/2.
    c = 8.0
    prob = _run(power_coefficient=0.5, radius=30.0, rho=1.225, rated_power=1e12, weibull_scale=c, weibull_shape=2.0,
                cut_in_speed=1e-3, cut_out_speed=80.0)
    mean = c * np.sqrt(np.pi) / 2.0
    expected = YEAR * _gain(0.5, 30.0, 1.225) * 6.0 / np.pi * mean ** 3
    assert prob.get_val("annual_energy")[0] == pytest.approx(expected, rel=1e-9)


def test_rated_below_cut_in_gives_rated_power_between_the_limits():
    # V_r < V_in: the rotor makes P_r whenever it runs: AEP = H P_r [F(V_out) - F(V_in)] (Weibull CDF).
    c, k = 9.0, 2.2
    prob = _run(power_coefficient=0.5, radius=80.0, rho=1.225, rated_power=1e5, weibull_scale=c, weibull_shape=k,
                cut_in_speed=4.0, cut_out_speed=25.0)
    expected = YEAR * 1e5 * (np.exp(-(4.0 / c) ** k) - np.exp(-(25.0 / c) ** k))
    assert prob.get_val("annual_energy")[0] == pytest.approx(expected, rel=1e-14)
    assert prob.get_val("capacity_factor")[0] == pytest.approx(expected / (YEAR * 1e5), rel=1e-14)


def test_rated_wind_speed_and_regions_meet_with_equal_power():
    # K V_r**3 = P_r; and the AEP is the sum of its two regions computed apart.
    values = dict(power_coefficient=0.48, radius=63.0, rho=1.225, rated_power=5e6, weibull_scale=8.5,
                  weibull_shape=2.0, cut_in_speed=3.0, cut_out_speed=25.0)
    prob = _run(**values)
    v_r = prob.get_val("rated_wind_speed")[0]
    assert _gain(0.48, 63.0, 1.225) * v_r ** 3 == pytest.approx(5e6, rel=1e-14)
    assert 10.0 < v_r < 12.0
    c, k = 8.5, 2.0
    s = 1.0 + 3.0 / k
    region2 = _gain(0.48, 63.0, 1.225) * c ** 3 * gamma(s) * (gammainc(s, (v_r / c) ** k) - gammainc(s, (3.0 / c) ** k))
    region3 = 5e6 * (np.exp(-(v_r / c) ** k) - np.exp(-(25.0 / c) ** k))
    assert prob.get_val("annual_energy")[0] == pytest.approx(YEAR * (region2 + region3), rel=1e-12)
    assert 0.3 < prob.get_val("capacity_factor")[0] < 0.6


@pytest.mark.parametrize("rated_power", [[5e6, 3e6, 1e9], [1e5, 5e6, 2e6]])
def test_partials_complex_step(rated_power):
    # Three rotors: rated inside the range, and (per case) out of reach or below cut-in: every branch of b.
    check_component_partials(AnnualEnergyComp(num_nodes=3, num_quadrature=24), {
        "power_coefficient": np.array([0.48, 0.42, 0.5]), "radius": np.array([63.0, 45.0, 20.0]),
        "rho": np.array([1.225, 1.1, 1.2]), "rated_power": np.array(rated_power),
        "weibull_scale": np.array([8.5, 7.0, 9.5]), "weibull_shape": np.array([2.0, 1.7, 2.4]),
        "cut_in_speed": np.array([3.0, 3.5, 4.0]), "cut_out_speed": np.array([25.0, 22.0, 20.0])})


@pytest.mark.parametrize("name, value, words", [("weibull_shape", 0.0, "weibull_shape must be positive"),
                                                ("cut_out_speed", 2.0, "must exceed cut_in_speed")])
def test_bad_inputs_raise_one_clear_line(name, value, words):
    with pytest.raises(om.AnalysisError, match=words):
        _run(**{name: value})
