"""Any fluid instead of the ISA: the named fluids, the entry points, and what a fluid changes.

Sources: the named fluids' formulas (UNESCO 1981 pure-water density; Kestin, Sokolov & Wakeham 1978 viscosity;
Mackenzie 1981 sound speed in seawater), recomputed here; and two invariants of the BEM/BILD equations: a
fluid with the ISA's properties at an altitude is that altitude, and with a polar that depends on neither
Reynolds nor Mach number every load is proportional to the density at fixed velocity triangles, so the
ideal blade is the same and its thrust and power scale with rho.
"""
import numpy as np
import pytest

from bild_mdo import analyze_rotor, design_mil, design_rotor, off_design_sweep, write_geometry
from bild_mdo.atmosphere import isa
from bild_mdo.fluid import FLUIDS, Fluid, resolve_fluid


def test_named_fluids_follow_their_sources():
    t = 15.0
    rho_water = (999.842594 + 6.793952e-2 * t - 9.09529e-3 * t**2 + 1.001685e-4 * t**3 - 1.120083e-6 * t**4
                 + 6.536332e-9 * t**5)
    mu_water = 1.002e-3 * 10.0 ** ((1.1709 * (20.0 - t) - 1.827e-3 * (t - 20.0) ** 2) / (t + 89.93))
    assert FLUIDS["water"].rho == pytest.approx(rho_water, abs=0.01)
    assert FLUIDS["water"].mu == pytest.approx(mu_water, rel=1e-4)
    assert FLUIDS["seawater"].speed_of_sound == pytest.approx(
        1448.96 + 4.591 * t - 5.304e-2 * t**2 + 2.374e-4 * t**3, abs=0.05)
    sea_level = isa(0.0, derivatives=False)
    assert FLUIDS["air"].rho == pytest.approx(float(sea_level.rho), rel=1e-15)
    assert resolve_fluid("Water") == FLUIDS["water"]
    assert resolve_fluid((1000.0, 1e-3, 1480.0)).rho == 1000.0


@pytest.mark.parametrize("fluid, message", [
    ("mercury", "fluid must be one of"),
    ((1000.0, 1e-3), "fluid must be one of"),
    (Fluid(-1.0, 1e-3, 1480.0), "fluid density rho must be a positive"),
])
def test_bad_fluids_say_what_is_wrong(fluid, message):
    with pytest.raises(ValueError, match=message):
        resolve_fluid(fluid)


def test_a_fluid_with_the_isa_properties_is_that_altitude():
    state = isa(2000.0, derivatives=False)
    air_2000 = (float(state.rho), float(state.mu), float(state.speed_of_sound))
    at_altitude = design_rotor(advance_ratio=[0.0, 0.5], ref_chord=0.1, altitude=2000.0)
    in_fluid = design_rotor(advance_ratio=[0.0, 0.5], ref_chord=0.1, fluid=air_2000)
    np.testing.assert_allclose(in_fluid.thrust, at_altitude.thrust, rtol=1e-13)
    np.testing.assert_allclose(in_fluid.chord, at_altitude.chord, rtol=1e-13)
    np.testing.assert_allclose(in_fluid.bem_thrust, at_altitude.bem_thrust, rtol=1e-13)
    mil = dict(v_axial=20.0, rpm=2400.0, radius=0.5, hub_radius=0.1, cl_star=0.7, cd_star=0.01,
               alpha_star=np.radians(4.0))
    np.testing.assert_allclose(design_mil(500.0, fluid=air_2000, **mil).chord,
                               design_mil(500.0, altitude=2000.0, **mil).chord, rtol=1e-13)
    with pytest.raises(ValueError, match="either altitude"):
        design_rotor(fluid="water", altitude=100.0)


def test_with_a_fixed_polar_water_scales_every_load_by_its_density():
    options = dict(v_axial=2.0, rpm=300.0, radius=0.3, num_blades=4, ref_chord=0.04, airfoil="analytic")
    air, water = design_rotor(**options, fluid="air"), design_rotor(**options, fluid="water")
    ratio = FLUIDS["water"].rho / FLUIDS["air"].rho
    np.testing.assert_allclose(water.chord, air.chord, rtol=1e-12)
    np.testing.assert_allclose(water.twist, air.twist, rtol=1e-12)
    assert water.thrust / air.thrust == pytest.approx(ratio, rel=1e-12)
    assert water.power / air.power == pytest.approx(ratio, rel=1e-12)


@pytest.mark.parametrize("suffix", [".json", ".csv", ".prop"])
def test_a_water_design_analyses_in_water_from_its_file(tmp_path, suffix):
    design = design_rotor(fluid="water", v_axial=2.0, rpm=300.0, radius=0.3, num_blades=4, thrust=500.0,
                          airfoil="analytic")
    path = tmp_path / f"blade{suffix}"
    write_geometry(path, design)  # the format from the suffix
    sweep = off_design_sweep(path, v_axial=[2.0], polar="analytic")
    assert sweep.thrust[0] == pytest.approx(500.0, rel=1e-8)
    # The same file asked for the ISA at sea level: the air's density, about 1/816 of the thrust.
    in_air = off_design_sweep(path, v_axial=[2.0], polar="analytic", altitude=0.0)
    assert in_air.thrust[0] < 1e-2 * 500.0


def test_analyze_rotor_takes_a_fluid():
    chord, twist = np.full(10, 0.03), np.linspace(0.6, 0.2, 10)
    args = (chord, twist, 0.3, 0.06, 300.0, 2.0, 4, "analytic")
    water = FLUIDS["water"]
    named = analyze_rotor(*args, fluid="water")
    explicit = analyze_rotor(*args, rho=water.rho, mu=water.mu, speed_of_sound=water.speed_of_sound)
    assert float(named.thrust) == float(explicit.thrust)
    with pytest.raises(ValueError, match="either fluid or rho"):
        analyze_rotor(*args, fluid="water", rho=1000.0, mu=1e-3)
