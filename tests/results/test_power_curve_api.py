"""power_curve and TurbineDesign.power_curve: a blade's power curve and AEP in one call.

Sources: the design's own power coefficient (a turbine BILD design analyses as designed: tests/results/
test_design_turbine.py), the cubic law of a Reynolds-independent polar at a fixed tip-speed ratio (hand), and
the same curve built through PowerCurveGroup with the ISA component (tests/energy/test_tip_speed_limit.py).
"""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo import PowerCurve, design_turbine, power_curve
from bild_mdo.airfoil import AnalyticPolar
from tests.energy.test_power_curve_group import POLAR, RADIUS, TSR, _values
from tests.energy.test_tip_speed_limit import LIMIT, _curve

RATED = 1.5e6
#: The test rotors' tip station is in the turbulent-wake state at the lowest wind speeds (the API warns; the group
#: in tests/energy ignores it, on_invalid='ignore').
TEST_ROTORS_WARN = pytest.mark.filterwarnings("ignore::bild_mdo.BEMStateWarning")


@pytest.fixture(scope="module")
def rotor():
    # The most power at lambda = 7 on a 40-m rotor, with a Reynolds-independent polar.
    return design_turbine(wind_speed=8.0, tip_speed_ratio=7.0, radius=40.0, hub_radius_ratio=0.05, num_radial=12,
                          airfoil=AnalyticPolar())


def test_design_curve_keeps_the_designs_power_coefficient(rotor):
    curve = rotor.power_curve(rated_power=RATED, num_wind_speeds=9)
    assert isinstance(curve, PowerCurve) and not curve.is_batch
    below = curve.wind_speed < curve.rated_wind_speed
    # Region 2 at the design tip-speed ratio: the design's C_P at every wind speed (the polar does not depend
    # on the Reynolds number), and rated where 1/2 rho A C_P V**3 = P_r (hand).
    np.testing.assert_allclose(curve.power_coefficient[below], rotor.power_coefficient, rtol=1e-6)
    rho = 1.225  # ISA sea level, the design's altitude
    v_r = (RATED / (0.5 * rho * np.pi * 40.0 ** 2 * rotor.power_coefficient)) ** (1.0 / 3.0)
    assert curve.rated_wind_speed == pytest.approx(v_r, rel=1e-6)
    np.testing.assert_allclose(curve.power[curve.wind_speed >= curve.rated_wind_speed], RATED, rtol=1e-9)
    assert curve.tip_speed_limit_wind_speed == curve.rated_wind_speed and curve.max_tip_speed == np.inf
    text = curve.summary()
    assert "annual energy" in text and f"{curve.annual_energy / 3.6e12:12.5g} GWh" in text
    assert len(text.splitlines()) == 10 + 9


def test_design_curve_with_a_tip_speed_limit(rotor):
    curve = rotor.power_curve(rated_power=RATED, max_tip_speed=60.0, num_wind_speeds=13)
    # Omega R = 60 m/s from V = 60 / 7 m/s on (hand), a lower AEP than without the limit for the rotor of most
    # power at lambda = 7 (its C_P is largest at the design tip-speed ratio, which region 2.5 leaves).
    assert curve.tip_speed_limit_wind_speed == pytest.approx(60.0 / 7.0, rel=1e-14)
    tip = curve.rpm * np.pi / 30.0 * 40.0
    np.testing.assert_allclose(tip[curve.wind_speed >= 60.0 / 7.0], 60.0, rtol=1e-14)
    free = rotor.power_curve(rated_power=RATED, num_wind_speeds=13)
    assert curve.rated_wind_speed > free.rated_wind_speed
    assert curve.annual_energy < free.annual_energy
    # A limit not reached below rated changes nothing (region 2 on the same nodes).
    high = rotor.power_curve(rated_power=RATED, max_tip_speed=200.0, num_wind_speeds=13)
    assert high.annual_energy == pytest.approx(free.annual_energy, rel=1e-9)


def test_power_above_rated_below_the_rated_wind_speed_is_refused(rotor):
    # At a 50-m/s limit this rotor's power at zero pitch peaks near 12 m/s (1.43 MW: analyze_rotor) and falls
    # before it rises again: 1.43 MW is reached at several wind speeds and the rated-speed solve finds 19.5 m/s.
    # At 21 points a node exceeds rated power, at 13 the power falls between nodes: refused either way.
    for nw in (13, 21):
        with pytest.raises(om.AnalysisError, match="exceeds rated power or falls as the wind rises"):
            rotor.power_curve(rated_power=1.43e6, max_tip_speed=50.0, num_wind_speeds=nw)


@TEST_ROTORS_WARN
def test_power_curve_of_a_blade_is_the_groups():
    # The test rotors of tests/energy (two blades in one batch), through the API (ISA by isa()) and through
    # PowerCurveGroup with its AtmosphereComp.
    values = _values()
    curve = power_curve(values["chord"], values["twist"], RADIUS, values["hub_radius"], TSR, values["rated_power"],
                        airfoil=POLAR, max_tip_speed=LIMIT, weibull_scale=values["weibull_scale"],
                        weibull_shape=values["weibull_shape"], cut_in_speed=values["cut_in_speed"],
                        cut_out_speed=values["cut_out_speed"], altitude=values["altitude"], num_wind_speeds=21)
    group = _curve(True, LIMIT)
    assert curve.is_batch and len(curve) == 2
    for name in ("annual_energy", "rated_wind_speed", "tip_speed_limit_wind_speed"):
        np.testing.assert_allclose(getattr(curve, name), group.get_val(name), rtol=1e-12)
    np.testing.assert_allclose(curve.power, group.get_val("power"), rtol=1e-12)
    # A rotor of a batch is the rotor alone.
    alone = power_curve(values["chord"][1], values["twist"][1], RADIUS[1], values["hub_radius"][1], TSR[1],
                        values["rated_power"][1], airfoil=POLAR, max_tip_speed=LIMIT[1],
                        weibull_scale=values["weibull_scale"][1], weibull_shape=values["weibull_shape"][1],
                        cut_in_speed=values["cut_in_speed"][1], cut_out_speed=values["cut_out_speed"][1],
                        altitude=values["altitude"][1], num_wind_speeds=21)
    assert alone.annual_energy == pytest.approx(curve[1].annual_energy, rel=1e-12)
    assert curve[-1].annual_energy == curve[1].annual_energy
    with pytest.raises(IndexError):
        curve[2]


@pytest.mark.parametrize("change, message", [
    (dict(rated_power=-1.0), "rated_power must be"),
    (dict(cut_in_speed=30.0), "cut_in_speed must be smaller than cut_out_speed"),
    (dict(max_tip_speed=0.0), "max_tip_speed must be"),
    (dict(twist=np.zeros(5)), "same number of stations"),
    (dict(num_wind_speeds=4), "num_wind_speeds"),
    (dict(max_tip_speed=20.0), "reached above cut_in_speed"),
])
def test_power_curve_rejects_bad_inputs_in_one_line(change, message):
    args = dict(chord=np.full(6, 2.0), twist=np.full(6, 0.1), radius=40.0, hub_radius=2.0, tip_speed_ratio=7.0,
                rated_power=RATED, airfoil=AnalyticPolar())
    args.update(change)
    with pytest.raises(ValueError, match=message) as info:
        power_curve(**args)
    assert "\n" not in str(info.value)


@TEST_ROTORS_WARN
def test_to_csv_round_trips_the_curves(tmp_path):
    values = _values()
    curve = power_curve(values["chord"], values["twist"], RADIUS, values["hub_radius"], TSR, values["rated_power"],
                        airfoil=POLAR, num_wind_speeds=7)
    path = curve.to_csv(tmp_path / "curve.csv")
    with open(path, encoding="utf-8") as handle:
        header = [line for line in handle if not line.startswith("#")][0].strip().split(",")
    assert header[:3] == ["rotor [-]", "wind_speed [m/s]", "rpm [rpm]"]
    table = np.genfromtxt(path, delimiter=",", comments="#", skip_header=2)
    table = np.rec.fromarrays(table.T, names=[name.split(" [")[0] for name in header])
    assert table.size == 2 * 7
    for i in range(2):
        rows = table[table["rotor"] == i]
        np.testing.assert_allclose(rows["wind_speed"], curve.wind_speed[i], rtol=1e-9)
        np.testing.assert_allclose(rows["power"], curve.power[i], rtol=1e-9)
        np.testing.assert_allclose(rows["collective_pitch"], np.degrees(curve.collective_pitch[i]), rtol=1e-9,
                                   atol=1e-12)
        np.testing.assert_allclose(rows["annual_energy"], curve.annual_energy[i] / 3.6e12, rtol=1e-9)


@TEST_ROTORS_WARN
def test_plot_power_curve_draws_the_curve(tmp_path):
    pytest.importorskip("matplotlib")
    from bild_mdo.plots import plot_power_curve

    values = _values()
    curve = power_curve(values["chord"][0], values["twist"][0], RADIUS[0], values["hub_radius"][0], TSR[0],
                        values["rated_power"][0], airfoil=POLAR, max_tip_speed=LIMIT[0], num_wind_speeds=7)
    path = tmp_path / "curve.png"
    fig = plot_power_curve(curve, path)
    assert path.stat().st_size > 10_000
    power_axes = fig.axes[0]
    np.testing.assert_allclose(power_axes.lines[0].get_ydata(), curve.power / 1e3, rtol=1e-15)
    # Rated (dashed) and the start of region 2.5 (dotted) are marked.
    marks = sorted(line.get_xdata()[0] for line in power_axes.lines[1:])
    np.testing.assert_allclose(marks, sorted([curve.rated_wind_speed, curve.tip_speed_limit_wind_speed]), rtol=1e-15)
