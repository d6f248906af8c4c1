"""Region 2.5 of the power curve: the rotor speed held where the tip speed reaches ``max_tip_speed``.

Components: complex-step partials on both sides of each kink and the hand formulas of the nodes and the
rotor speed.  The group: the test rotors of tests/energy/test_power_curve_group.py (analytic polar, scale-
invariant in the wind speed) against an independent dense integration of plain BEM analyses.
"""
import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials
from scipy.integrate import simpson

from bild_mdo.bem import analyze_rotor
from bild_mdo.energy import AnnualEnergyComp, PowerCurveGroup
from bild_mdo.energy.annual_energy import HOURS_PER_YEAR, weibull_density, weibull_survival
from bild_mdo.energy.curve_energy import CurveEnergyComp
from bild_mdo.energy.rotor_speed import RotorSpeedComp
from bild_mdo.energy.wind_speeds import WindSpeedsComp, lobatto, region2_split, region_sizes
from bild_mdo.utils.testing import assert_totals_match, check_component_partials
from tests.energy.test_power_curve_group import NR, POLAR, RADIUS, TSR, _values

NN, NW = 3, 9
LIMITS = dict(cut_in_speed=[3.0, 3.5, 4.0], rated_wind_speed=[10.0, 11.0, 12.5], cut_out_speed=[25.0, 24.0, 22.0])
# Rotors 0 and 2 reach the limit below rated (60/7 = 8.57 m/s, 70/9 = 7.78 m/s), rotor 1 does not (200/8 = 25).
TIP = dict(max_tip_speed=[60.0, 200.0, 70.0], tip_speed_ratio=[7.0, 8.0, 9.0])


def test_wind_speeds_split_region_two_where_the_limit_is_reached():
    prob = check_component_partials(WindSpeedsComp(num_nodes=NN, num_wind_speeds=NW, tip_speed_limit=True),
                                    dict(LIMITS, **TIP))
    v, knee = prob.get_val("wind_speed"), prob.get_val("tip_speed_limit_wind_speed")
    # V_k = min(V_tip / lambda, V_r) (hand), a node shared by the two intervals of region 2.
    np.testing.assert_allclose(knee, [60.0 / 7.0, 11.0, 70.0 / 9.0], rtol=1e-15)
    n2, n3 = region_sizes(NW, tip_speed_limit=True)
    n2a, n2b, n3_split = region2_split(NW)
    # Region 2 before the limit keeps the points it has without the limit; regions 2.5 and 3 share the rest.
    assert (n2a, n2 + n3 - 1, n3_split) == (region_sizes(NW)[0], NW, n3) and n2a + n2b - 1 == n2
    np.testing.assert_allclose(v[:, [0, n2a - 1, n2 - 1, -1]],
                               np.column_stack([LIMITS["cut_in_speed"], knee, LIMITS["rated_wind_speed"],
                                                LIMITS["cut_out_speed"]]), rtol=1e-15)
    # Lobatto nodes of each interval: the interior of [V_in, V_k] at the rule's own points.
    t = 0.5 * (lobatto(n2a)[0] + 1.0)
    np.testing.assert_allclose(v[0, :n2a], 3.0 + (knee[0] - 3.0) * t, rtol=1e-15)
    assert np.all(np.diff(v[[0, 2]], axis=1) > 0.0)
    # Where the limit is not reached the second interval has length zero: its points repeat the rated point.
    np.testing.assert_allclose(v[1, n2a - 1:n2], 11.0, rtol=1e-15)


def test_wind_speeds_reject_a_limit_reached_below_cut_in():
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("wind", WindSpeedsComp(num_wind_speeds=7, tip_speed_limit=True), promotes=["*"])
    prob.setup()
    prob.set_val("max_tip_speed", 20.0)
    with pytest.raises(om.AnalysisError, match="not above the cut-in speed"):
        prob.run_model()


@pytest.mark.parametrize("capped", [True, False])
def test_rotor_speed_holds_the_tip_speed_limit(capped):
    v = np.linspace(3.0, 25.0, NN * NW).reshape(NN, NW) + np.array([[0.1], [0.2], [0.3]])
    values = dict(wind_speed=v, radius=[40.0, 50.0, 60.0], rated_wind_speed=LIMITS["rated_wind_speed"], **TIP)
    prob = check_component_partials(RotorSpeedComp(num_nodes=NN, num_points=NW, capped=capped,
                                                   tip_speed_limit=True), values)
    # Omega R = min(lambda min(V, V_r), V_tip,max) (hand derivation; 30/pi rpm per rad/s).
    governing = np.minimum(v, np.array(LIMITS["rated_wind_speed"])[:, None]) if capped else v
    tip = np.minimum(np.array(TIP["tip_speed_ratio"])[:, None] * governing, np.array(TIP["max_tip_speed"])[:, None])
    np.testing.assert_allclose(prob.get_val("rpm"), tip / np.array([40.0, 50.0, 60.0])[:, None] * 30 / np.pi,
                               rtol=1e-14)


def test_curve_energy_with_the_split_rule():
    n2, n3 = region_sizes(NW)
    rng = np.random.default_rng(25)
    values = dict(LIMITS, wind_speed=rng.uniform(3.0, 25.0, (NN, NW)), power=rng.uniform(1e5, 5e6, (NN, NW)),
                  rated_power=[4e6, 5e6, 3e6], weibull_scale=[7.0, 8.0, 9.0], weibull_shape=[1.8, 2.0, 2.3],
                  tip_speed_limit_wind_speed=[8.0, 11.0, 9.0])
    check_component_partials(CurveEnergyComp(num_nodes=NN, num_wind_speeds=NW, check_trim=False,
                                             tip_speed_limit=True), values)


def test_split_rule_integrates_the_cubic_curve_as_annual_energy_comp():
    # The two Lobatto rules of region 2 integrate the same function as one: the cubic curve P = 1/2 rho A C_P V**3
    # of AnnualEnergyComp's model (checked there against the incomplete-gamma closed form), split at 6 m/s.
    cp, radius, p_rated, v_in, v_out, v_k, nw = 0.45, 40.0, 2.0e6, 3.0, 25.0, 6.0, 31
    gain = 0.5 * 1.225 * np.pi * radius ** 2 * cp
    v_r = (p_rated / gain) ** (1.0 / 3.0)
    n2a, n2b, n3 = region2_split(nw)
    n2 = n2a + n2b - 1
    v = np.concatenate((v_in + (v_k - v_in) * 0.5 * (lobatto(n2a)[0] + 1.0),
                        v_k + (v_r - v_k) * 0.5 * (lobatto(n2b)[0][1:] + 1.0),
                        v_r + (v_out - v_r) * 0.5 * (lobatto(n3)[0][1:] + 1.0)))
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("energy", CurveEnergyComp(num_wind_speeds=nw, tip_speed_limit=True), promotes=["*"])
    prob.setup()
    for name, value in dict(cut_in_speed=v_in, rated_wind_speed=v_r, cut_out_speed=v_out, rated_power=p_rated,
                            weibull_scale=8.0, weibull_shape=2.0, wind_speed=v[None, :],
                            tip_speed_limit_wind_speed=v_k,
                            power=np.where(np.arange(nw) < n2 - 1, gain * v ** 3, p_rated)[None, :]).items():
        prob.set_val(name, value)
    prob.run_model()
    reference = om.Problem(reports=False)
    reference.model.add_subsystem("aep", AnnualEnergyComp(), promotes=["*"])
    reference.setup()
    for name, value in dict(power_coefficient=cp, radius=radius, rated_power=p_rated, weibull_scale=8.0).items():
        reference.set_val(name, value)
    reference.run_model()
    assert prob.get_val("annual_energy")[0] == pytest.approx(reference.get_val("annual_energy")[0], rel=1e-12)


def _curve(limited, max_tip_speed=None, nw=21, mode="auto", high_induction="buhl"):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("curve", PowerCurveGroup(num_nodes=2, num_radial=NR, num_wind_speeds=nw, polar=POLAR,
                                                      on_invalid="ignore", tip_speed_limit=limited,
                                                      high_induction=high_induction), promotes=["*"])
    prob.setup(force_alloc_complex=True, mode=mode)
    for name, value in _values().items():
        prob.set_val(name, np.asarray(value))
    if limited:
        prob.set_val("max_tip_speed", max_tip_speed)
    prob.run_model()
    return prob


#: Tip-speed limits of the two test rotors (m/s), reached at 60/7 = 8.57 and 65/7.5 = 8.67 m/s, below their
#: rated wind speeds (9.94 and 9.70 m/s without the limit).
LIMIT = np.array([60.0, 65.0])


@pytest.fixture(scope="module", params=["none", "buhl"])
def limited(request):
    return _curve(True, LIMIT, high_induction=request.param)


def test_region_two_and_a_half_turns_at_the_limit(limited):
    v, rpm = limited.get_val("wind_speed"), limited.get_val("rpm")
    knee, v_r = limited.get_val("tip_speed_limit_wind_speed"), limited.get_val("rated_wind_speed")
    np.testing.assert_allclose(knee, LIMIT / TSR, rtol=1e-15)
    tip = rpm * np.pi / 30.0 * RADIUS[:, None]
    assert np.all(tip <= LIMIT[:, None] * (1.0 + 1e-14))
    beyond = v >= knee[:, None]
    np.testing.assert_allclose(tip[beyond], np.broadcast_to(LIMIT[:, None], v.shape)[beyond], rtol=1e-14)
    np.testing.assert_allclose(tip[~beyond], (TSR[:, None] * v)[~beyond], rtol=1e-14)
    # The plain-Python turbine BEM at the curve's region-2.5 points and rotor speeds gives back their power.
    n2, _ = region_sizes(21, tip_speed_limit=True)
    values = _values()
    for i in range(2):
        points = (v[i] >= knee[i]) & (np.arange(v.shape[1]) < n2)
        res = analyze_rotor(values["chord"][i], values["twist"][i], RADIUS[i], values["hub_radius"][i], rpm[i, points],
                            v[i, points], 3, POLAR, altitude=values["altitude"][i], rotor_type="turbine",
                            on_invalid="ignore", high_induction=limited.model.curve.options["high_induction"])
        np.testing.assert_allclose(res.power, limited.get_val("power")[i, points], rtol=1e-9)
    assert np.all(v_r > knee)


def test_aep_with_the_limit_against_a_dense_integration(limited):
    # Independent reference: plain BEM analyses (analyze_rotor) at 401 wind speeds on each of [V_in, V_k] and
    # [V_k, V_r] with the rotor speed of the limit law, integrated against the Weibull density by Simpson's rule,
    # plus rated power's exact integral over [V_r, V_out].
    values = _values()
    high_induction = limited.model.curve.options["high_induction"]
    for i in range(2):
        c, k = values["weibull_scale"][i], values["weibull_shape"][i]
        v_in, v_out = values["cut_in_speed"][i], values["cut_out_speed"][i]
        v_k, v_r = limited.get_val("tip_speed_limit_wind_speed")[i], limited.get_val("rated_wind_speed")[i]
        energy = 0.0
        for lo, hi in ((v_in, v_k), (v_k, v_r)):
            v = np.linspace(lo, hi, 401)
            rpm = np.minimum(TSR[i] * v, LIMIT[i]) / RADIUS[i] * 30.0 / np.pi
            res = analyze_rotor(values["chord"][i], values["twist"][i], RADIUS[i], values["hub_radius"][i], rpm, v, 3,
                                POLAR, altitude=values["altitude"][i], rotor_type="turbine", on_invalid="ignore",
                                high_induction=high_induction)
            energy += simpson(np.asarray(res.power) * weibull_density(v, c, k)[0], x=v)
        survival = weibull_survival(np.array([v_r, v_out]), c, k)[0]
        energy += values["rated_power"][i] * (survival[0] - survival[1])
        expected = energy * HOURS_PER_YEAR * 3600.0
        # Measured: 2.2e-9 and 4e-13 with momentum theory's thrust (Simpson's error on 401 points); with Buhl's,
        # continuously differentiable but not twice where an annulus crosses a = 0.4 in region 2.5, the
        # 21-point Lobatto rule's own error shows: 3.5e-7 and -6.2e-8 (PowerCurveGroup's docstring).
        tolerance = 2e-8 if high_induction == "none" else 1e-6
        assert limited.get_val("annual_energy")[i] == pytest.approx(expected, rel=tolerance)


@pytest.mark.parametrize("nw", [5, 9])
def test_a_limit_not_reached_leaves_the_curve_unlimited(nw):
    # Limits above the tip speed at rated (69.6 and 72.7 m/s): the same rated point, and region 2 on the same
    # nodes as without the limit, so the same AEP (region 3 holds rated power either way) at any number of points.
    free, high = _curve(False, nw=nw), _curve(True, [200.0, 200.0], nw=nw)
    np.testing.assert_allclose(high.get_val("rated_wind_speed"), free.get_val("rated_wind_speed"), rtol=1e-12)
    np.testing.assert_allclose(high.get_val("tip_speed_limit_wind_speed"), free.get_val("rated_wind_speed"),
                               rtol=1e-12)
    np.testing.assert_allclose(high.get_val("annual_energy"), free.get_val("annual_energy"), rtol=1e-9)


@pytest.mark.parametrize("mode", ["fwd", "rev"])
def test_aep_totals_with_the_limit(mode):
    # One rotor reaches its limit below rated (60 m/s), the other does not (200 m/s).
    prob = _curve(True, [60.0, 200.0], nw=9, mode=mode)
    assert_no_approx_partials(prob.model, include_self=True, recurse=True)
    wrt = list(_values()) + ["max_tip_speed"]
    data = prob.check_totals(of=["annual_energy", "tip_speed_limit_wind_speed"], wrt=wrt, method="cs",
                             out_stream=None)
    assert len(data) == 2 * len(wrt)
    assert_totals_match(data, atol=1e-8, rtol=1e-8)
