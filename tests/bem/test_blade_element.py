"""Blade element with a Mach-dependent polar, a spanwise polar and collective pitch: partials and invariants."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.airfoil.spanwise import SpanwisePolar
from bild_mdo.atmosphere import isa
from bild_mdo.bem.analyze import analyze_rotor, station_radii
from bild_mdo.bem.bem_group import BEMAnalysisGroup
from bild_mdo.bem.inflow import InflowComp
from bild_mdo.bem.loads import BladeElementLoadsComp
from bild_mdo.utils.testing import check_component_partials, check_group_totals

NN, NR, B = 3, 7, 3
# In hover V_x = 0 makes d(W0)/d(V_x) = V_x/W0 vanish, so OpenMDAO reports declared-but-zero partials.
pytestmark = pytest.mark.filterwarnings("ignore:(?s).*zero derivatives")


def _blade(make_blade, seed=0):
    """The seeded blades at half their rpm: tip Mach numbers 0.2-0.65, inside the Karman-Tsien rule's range."""
    blade = make_blade(NN, NR, seed=seed)
    blade["rpm"] = 0.5 * blade["rpm"]
    return blade


def _section_values(blade):
    values = {name: blade[name] for name in ("v_axial", "rpm", "radius", "hub_radius", "chord", "twist")}
    values.update(radii=station_radii(blade["radius"], blade["hub_radius"], NR), rho=[1.225, 1.1, 0.95],
                  mu=[1.79e-5, 1.75e-5, 1.7e-5], speed_of_sound=[340.3, 330.0, 320.0],
                  collective_pitch=[0.05, -0.03, 0.02])
    return values


@pytest.mark.parametrize("polar_name", ["mach_polar", "spanwise_polar"])
def test_inflow_and_loads_partials(request, make_blade, polar_name):
    polar = request.getfixturevalue(polar_name)
    kw = dict(num_nodes=NN, num_radial=NR, num_blades=B, polar=polar)
    prob = check_component_partials(InflowComp(**kw), _section_values(_blade(make_blade)), atol=1e-9, rtol=1e-9)
    values = _section_values(_blade(make_blade))
    values["phi"] = prob.get_val("phi")
    check_component_partials(BladeElementLoadsComp(**kw), values, atol=1e-9, rtol=1e-9)


def test_mach_by_hand(mach_polar, make_blade):
    # Local Mach number M = W / a with the inflow speed W of Eq. (7) (blade_element module docstring);
    # tip Mach number sqrt(V_x^2 + (Omega R)^2) / a (issue definition), a from the ISA (340.294 m/s at 0 m).
    blade = _blade(make_blade)
    result = analyze_rotor(blade["chord"], blade["twist"], blade["radius"], blade["hub_radius"], blade["rpm"],
                           blade["v_axial"], B, mach_polar, altitude=blade["altitude"], on_invalid="ignore")
    a = isa(blade["altitude"]).speed_of_sound
    omega = blade["rpm"] * np.pi / 30.0
    np.testing.assert_allclose(result.speed_of_sound, a, rtol=1e-15)
    w = np.hypot(result.u_axial, omega[:, None] * result.radii - 0.5 * result.u_theta)
    np.testing.assert_allclose(result.mach, w / a[:, None], rtol=1e-13)
    np.testing.assert_allclose(result.tip_mach, np.hypot(blade["v_axial"], omega * blade["radius"]) / a, rtol=1e-14)
    # With rho and mu given, a comes from the altitude unless speed_of_sound is given.
    kw = dict(rho=1.2, mu=1.8e-5, on_invalid="ignore")
    args = (blade["chord"][0], blade["twist"][0], 1.0, 0.15, 2000.0, 10.0, B, mach_polar)
    np.testing.assert_allclose(analyze_rotor(*args, altitude=3000.0, **kw).speed_of_sound,
                               isa(3000.0).speed_of_sound, rtol=1e-15)
    at_300 = analyze_rotor(*args, speed_of_sound=300.0, **kw)
    assert at_300.tip_mach == np.hypot(10.0, 2000.0 * np.pi / 30.0) / 300.0
    # Prandtl-Glauert/Karman-Tsien raise the lift at fixed alpha, so the same blade loads more at a lower a.
    assert at_300.thrust > analyze_rotor(*args, speed_of_sound=400.0, **kw).thrust


def test_mach_independent_polar_ignores_speed_of_sound(analytic_polar, make_blade):
    # A polar without Mach dependence never sees the Mach number: thrust and torque are bitwise equal.
    blade = _blade(make_blade)
    args = (blade["chord"][0], blade["twist"][0], 1.0, 0.15, 2000.0, 10.0, B, analytic_polar)
    low = analyze_rotor(*args, rho=1.2, mu=1.8e-5, speed_of_sound=250.0)
    high = analyze_rotor(*args, rho=1.2, mu=1.8e-5, speed_of_sound=400.0)
    assert low.thrust == high.thrust and low.torque == high.torque


def test_collective_pitch_equals_twist_offset(analytic_polar, make_blade):
    # The blade pitch is twist + collective pitch at every station, so a pitch offset D on blade A is
    # blade A with twist + D (to round-off).
    blade = make_blade(NN, NR, seed=3)
    common = (blade["radius"], blade["hub_radius"], blade["rpm"], blade["v_axial"], B, analytic_polar)
    delta = np.array([0.04, -0.02, 0.07])
    pitched = analyze_rotor(blade["chord"], blade["twist"], *common, collective_pitch=delta)
    twisted = analyze_rotor(blade["chord"], blade["twist"] + delta[:, None], *common)
    for name in ("thrust", "torque", "power", "phi", "dthrust_dr", "alpha"):
        np.testing.assert_allclose(getattr(pitched, name), getattr(twisted, name), rtol=1e-12, atol=1e-14)
    assert np.all(pitched.thrust != analyze_rotor(blade["chord"], blade["twist"], *common).thrust)


def test_spanwise_set_of_identical_polars_is_the_polar(make_blade):
    # SpanwisePolar blends weights that sum to one, so two copies of one airfoil are that airfoil
    # (the single polar is evaluated without r/R, the set with it).
    polar = AnalyticPolar(reynolds_exponent=0.2)
    blade = make_blade(NN, NR, seed=4)
    args = (blade["radius"], blade["hub_radius"], blade["rpm"], blade["v_axial"], B)
    single = analyze_rotor(blade["chord"], blade["twist"], *args, polar)
    pair = analyze_rotor(blade["chord"], blade["twist"], *args, SpanwisePolar([polar, polar], [0.2, 0.8]))
    for name in ("thrust", "torque", "phi", "lift_coefficient"):
        np.testing.assert_allclose(getattr(pair, name), getattr(single, name), rtol=1e-13, atol=1e-15)


def test_spanwise_blend_between_its_airfoils(spanwise_polar, make_blade):
    # Each station's lift lies between the lift of the root and tip airfoils at the same alpha and Re.
    blade = make_blade(NN, NR, seed=5)
    result = analyze_rotor(blade["chord"], blade["twist"], blade["radius"], blade["hub_radius"], blade["rpm"],
                           blade["v_axial"], B, spanwise_polar)
    root, tip = (p.evaluate(result.alpha, result.reynolds).cl for p in spanwise_polar.polars)
    lo, hi = np.minimum(root, tip), np.maximum(root, tip)
    assert np.all((result.lift_coefficient >= lo - 1e-12) & (result.lift_coefficient <= hi + 1e-12))


@pytest.mark.parametrize("polar_name", ["mach_polar", "spanwise_polar"])
def test_group_totals(request, make_blade, polar_name):
    polar = request.getfixturevalue(polar_name)
    blade = _blade(make_blade, seed=1)
    values = {name: blade[name] for name in ("v_axial", "rpm", "radius", "hub_radius", "chord", "twist", "altitude")}
    values["collective_pitch"] = [0.03, -0.02, 0.01]
    # Mach numbers depend on rpm and the altitude (speed of sound); r/R on the radius.
    wrt = ["twist", "collective_pitch"] + (["rpm", "altitude"] if polar.varies_with_mach else ["radius"])
    check_group_totals(lambda: BEMAnalysisGroup(num_nodes=NN, num_radial=NR, num_blades=B, polar=polar),
                       of=["thrust", "torque", "tip_mach", "mach"], wrt=wrt, values=values)


def test_analyze_accepts_airfoil_names(make_blade):
    blade = make_blade(1, NR, seed=6)
    result = analyze_rotor(blade["chord"][0], blade["twist"][0], 1.0, 0.15, 2000.0, 10.0, B, "analytic")
    assert result.thrust > 0.0
    with pytest.raises(ValueError, match="speed_of_sound"):
        analyze_rotor(blade["chord"][0], blade["twist"][0], 1.0, 0.15, 2000.0, 10.0, B, "analytic",
                      speed_of_sound=300.0)
