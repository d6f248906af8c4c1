"""PowerCurveGroup: the trimmed BEM power curve of two test rotors, its physical invariants and exact AEP totals.

The rotors have a Betz-like blade (twist from the ideal inflow angle 2/3 atan(R / (lambda r)) less a design angle
of attack of 6 deg, chord ~ 1/r) and the analytic polar, which depends on neither the Reynolds nor the Mach
number: at a fixed tip-speed ratio and pitch the BEM is then scale-invariant in the wind speed, so C_P is
constant in region 2 and the AEP must equal AnnualEnergyComp's for that C_P.
"""
import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials

from bild_mdo.airfoil import AnalyticPolar
from bild_mdo.bem import analyze_rotor
from bild_mdo.energy import AnnualEnergyComp, PowerCurveGroup
from bild_mdo.energy.wind_speeds import region_sizes
from bild_mdo.utils.testing import assert_totals_match

NR, NW = 6, 9
RADIUS, HUB, TSR = np.array([40.0, 38.0]), np.array([2.0, 2.0]), np.array([7.0, 7.5])
RATED = np.array([1.5e6, 1.2e6])
POLAR = AnalyticPolar()


def _blade(radius, hub, tsr):
    x = (np.arange(NR) + 0.5) / NR
    r = hub + x * (radius - hub)
    phi = 2.0 / 3.0 * np.arctan(radius / (tsr * r))
    chord = 16.0 * np.pi * radius / (9.0 * 3 * 1.0 * tsr ** 2) * radius / r
    return np.minimum(chord, 0.12 * radius), phi - np.radians(6.0)


def _values():
    blades = [_blade(*args) for args in zip(RADIUS, HUB, TSR)]
    return dict(chord=np.array([b[0] for b in blades]), twist=np.array([b[1] for b in blades]), radius=RADIUS,
                hub_radius=HUB, tip_speed_ratio=TSR, rated_power=RATED, weibull_scale=[8.0, 7.0],
                weibull_shape=[2.0, 1.8], cut_in_speed=[3.0, 3.5], cut_out_speed=[25.0, 24.0], altitude=[0.0, 500.0])


def _problem(nn=2, nw=NW, mode="auto", **options):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("curve", PowerCurveGroup(num_nodes=nn, num_radial=NR, num_wind_speeds=nw, polar=POLAR,
                                                      on_invalid="ignore", **options), promotes=["*"])
    prob.setup(force_alloc_complex=True, mode=mode)
    for name, value in _values().items():
        prob.set_val(name, np.asarray(value)[:nn])
    return prob


@pytest.fixture(scope="module")
def solved():
    prob = _problem()
    prob.run_model()
    return prob


def test_region_three_holds_rated_power_and_the_rated_point_is_continuous(solved):
    n2, _ = region_sizes(NW)
    power = solved.get_val("power")
    # Invariant: from the rated point (rated-speed solve, index n2 - 1) to cut-out (pitch solves) P = P_r.
    np.testing.assert_allclose(power[:, n2 - 1:], np.repeat(RATED[:, None], NW - n2 + 1, axis=1), rtol=1e-9)
    np.testing.assert_allclose(solved.get_val("wind_speed")[:, n2 - 1], solved.get_val("rated_wind_speed"),
                               rtol=1e-15)
    assert np.all(np.diff(power[:, :n2], axis=1) > 0.0)


def test_pitch_is_zero_to_rated_and_pitches_to_feather_above(solved):
    n2, _ = region_sizes(NW)
    pitch = solved.get_val("collective_pitch")
    assert np.all(pitch[:, :n2] == 0.0)
    # Pitch-regulated turbines feather as the wind rises (e.g. NREL 5-MW, NREL/TP-500-38060, Table 7-1).
    assert np.all(np.diff(pitch[:, n2 - 1:], axis=1) > 0.0)
    # The rotor speed tracks the tip-speed ratio below rated and holds its rated value above (Omega = lambda V/R).
    rpm, v = solved.get_val("rpm"), solved.get_val("wind_speed")
    np.testing.assert_allclose(rpm[:, :n2], TSR[:, None] * v[:, :n2] / RADIUS[:, None] * 30 / np.pi, rtol=1e-14)
    np.testing.assert_allclose(rpm[:, n2:], np.repeat(rpm[:, n2 - 1:n2], NW - n2, axis=1), rtol=1e-14)


def test_thrust_peaks_at_rated_and_falls_as_the_blade_pitches(solved):
    n2, _ = region_sizes(NW)
    thrust = solved.get_val("thrust")
    # The shape of a pitch-to-feather rotor's thrust curve: it grows to rated and falls above as the pitch lowers
    # the angle of attack at constant power (the NREL 5-MW rotor's, Jonkman et al. 2009, NREL/TP-500-38060, Fig. 7-1).
    assert np.all(np.argmax(thrust, axis=1) == n2 - 1)
    assert np.all(np.diff(thrust[:, n2 - 1:], axis=1) < 0.0)


def test_trimmed_pitch_gives_rated_power_in_an_independent_analysis(solved):
    # The plain-Python turbine BEM (analyze_rotor) at the trimmed pitch reproduces rated power.
    n2, _ = region_sizes(NW)
    values = _values()
    for i in range(2):
        res = analyze_rotor(values["chord"][i], values["twist"][i], RADIUS[i], HUB[i], solved.get_val("rpm")[i, n2:],
                            solved.get_val("wind_speed")[i, n2:], 3, POLAR, altitude=values["altitude"][i],
                            rotor_type="turbine", collective_pitch=solved.get_val("collective_pitch")[i, n2:],
                            on_invalid="ignore")
        np.testing.assert_allclose(res.power, RATED[i], rtol=1e-9)


def test_aep_equals_annual_energy_comp_when_the_power_coefficient_is_constant():
    # Hand check: with this Reynolds- and Mach-independent polar, C_P at the design tip-speed ratio is the same
    # at every region-2 wind speed, so the BEM curve is AnnualEnergyComp's cubic; 21 points converge to it.
    prob = _problem(nn=1, nw=21)
    prob.run_model()
    n2, _ = region_sizes(21)
    cp = prob.get_val("power_coefficient")[0, :n2]
    np.testing.assert_allclose(cp, cp[0], rtol=1e-10)
    reference = om.Problem(reports=False)
    reference.model.add_subsystem("aep", AnnualEnergyComp(), promotes=["*"])
    reference.setup()
    for name in ("radius", "rated_power", "weibull_scale", "weibull_shape", "cut_in_speed", "cut_out_speed"):
        reference.set_val(name, np.asarray(_values()[name])[:1])
    reference.set_val("power_coefficient", cp[0])
    reference.set_val("rho", prob.get_val("rho"))
    reference.run_model()
    for name in ("annual_energy", "capacity_factor", "rated_wind_speed"):
        assert prob.get_val(name)[0] == pytest.approx(reference.get_val(name)[0], rel=1e-9)


@pytest.mark.parametrize("mode", ["fwd", "rev"])
def test_aep_totals_on_every_pair(mode):
    prob = _problem(mode=mode)
    prob.run_model()
    assert_no_approx_partials(prob.model, include_self=True, recurse=True)
    data = prob.check_totals(of=["annual_energy", "capacity_factor"], wrt=list(_values()), method="cs",
                             out_stream=None)
    assert len(data) == 2 * len(_values())
    assert_totals_match(data, atol=1e-8, rtol=1e-8)


def test_rated_power_out_of_reach_raises():
    prob = _problem(nn=1)
    prob.set_val("rated_power", 5.0e7)
    with pytest.raises(om.AnalysisError, match="not reached below the cut-out speed"):
        prob.run_model()


def test_pitch_trim_without_a_solution_raises():
    prob = _problem(nn=1, pitch_bounds=(0.0, 0.02))
    with pytest.raises(om.AnalysisError, match="holds rated power above the rated wind speed was not found"):
        prob.run_model()
