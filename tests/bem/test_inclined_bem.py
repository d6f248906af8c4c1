"""Inclined-flow BEM: kinematics, sector components, per-station inflow, turbine performance and the group."""
import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials

from bild_mdo.bem.analyze import station_radii
from bild_mdo.bem.bem_group import BEMAnalysisGroup
from bild_mdo.bem.inclined_bem_group import InclinedBEMGroup
from bild_mdo.bem.inflow import InflowComp
from bild_mdo.bem.loads import SECTION_OUTPUTS, BladeElementLoadsComp
from bild_mdo.bem.metrics import PERFORMANCE_OUTPUTS, TURBINE_OUTPUTS
from bild_mdo.bem.sector_average import SectorAverageComp
from bild_mdo.bem.sector_stations import SectorStationsComp
from bild_mdo.bem.turbine_performance import TurbinePerformanceComp
from bild_mdo.bem.turbine_polar import TurbinePolar
from bild_mdo.bem.wind_components import WindComponentsComp
from bild_mdo.utils.testing import assert_totals_match, check_component_partials

NN, NR, NS, B = 2, 4, 3, 3
GEOMETRY = dict(precone=np.radians([2.5, -3.0]), tilt=np.radians([5.0, 8.0]), yaw=np.radians([10.0, -15.0]),
                hub_height=[90.0, 30.0], shear_exponent=[0.2, 0.14])


def _turbine_blade(nn=NN, nr=NR, seed=0):
    """A seeded 3-bladed turbine-like blade (R about 10 m) at tip-speed ratios near 6 (the windmill state)."""
    rng = np.random.default_rng(seed)
    radius = rng.uniform(9.0, 11.0, nn)
    hub = 0.1 * radius
    v = rng.uniform(7.0, 10.0, nn)
    rpm = 6.0 * v / radius * 30.0 / np.pi
    x = np.linspace(0.0, 1.0, nr)
    chord = radius[:, None] * (0.09 - 0.05 * x) * rng.uniform(0.9, 1.1, (nn, 1))
    twist = np.radians(12.0 - 10.0 * x)[None, :] * np.ones((nn, 1))
    return dict(v_axial=v, rpm=rpm, radius=radius, hub_radius=hub, chord=chord, twist=twist,
                radii=station_radii(radius, hub, nr), rho=[1.225, 1.1], mu=[1.8e-5, 1.75e-5])


def test_wind_components_partials():
    values = dict(_turbine_blade(), **GEOMETRY)
    check_component_partials(WindComponentsComp(num_nodes=NN, num_radial=NR, num_sectors=NS), values,
                             atol=1e-10, rtol=1e-10)


def test_wind_components_hand_cases():
    # Derived in bild_mdo.bem.wind_components: yaw alone, blade up (Lambda = 0) and horizontal (Lambda = 90 deg).
    prob = check_component_partials(WindComponentsComp(num_nodes=1, num_radial=2, num_sectors=4),
                                    dict(v_axial=[10.0], rpm=[30.0 / np.pi], radii=[[2.0, 4.0]], yaw=[0.3]))
    vx, vt = (prob.get_val(n).reshape(4, 2) for n in ("v_axial_local", "v_theta_local"))
    np.testing.assert_allclose(vx, 10.0 * np.cos(0.3), rtol=1e-14)
    azimuth = np.arange(4)[:, None] * np.pi / 2
    np.testing.assert_allclose(vt, np.array([2.0, 4.0]) - 10.0 * np.sin(0.3) * np.cos(azimuth), atol=1e-13)
    # Tilt and shear: the station at Lambda = 0 is r cos(tilt) above the hub.
    prob = check_component_partials(WindComponentsComp(num_nodes=1, num_radial=1, num_sectors=2),
                                    dict(v_axial=[10.0], rpm=[30.0 / np.pi], radii=[[20.0]], tilt=[0.1],
                                         hub_height=[80.0], shear_exponent=[0.2]))
    vx, vt = prob.get_val("v_axial_local")[0], prob.get_val("v_theta_local")[0]
    speed = 10.0 * (1.0 + np.array([1.0, -1.0]) * 20.0 * np.cos(0.1) / 80.0) ** 0.2
    np.testing.assert_allclose(vx, speed * np.cos(0.1), rtol=1e-14)
    np.testing.assert_allclose(vt, 20.0, rtol=1e-14)  # sin(Lambda) = 0 and no yaw: no in-plane wind


def test_wind_below_ground_raises():
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("wind", WindComponentsComp(num_nodes=1, num_radial=2, num_sectors=2), promotes=["*"])
    prob.setup()
    prob.set_val("radii", [[30.0, 60.0]])
    prob.set_val("hub_height", [50.0])
    with pytest.raises(om.AnalysisError, match="reaches the ground"):
        prob.run_model()


def test_sector_stations_and_average_partials():
    rng = np.random.default_rng(3)
    prob = check_component_partials(SectorStationsComp(num_nodes=NN, num_radial=NR, num_sectors=NS),
                                    dict(chord=rng.uniform(0.1, 1.0, (NN, NR)), twist=rng.uniform(0, 1, (NN, NR))))
    np.testing.assert_array_equal(prob.get_val("sector_chord").reshape(NN, NS, NR)[:, 2], prob.get_val("chord"))
    loads = {"sector_dthrust_dr": rng.normal(size=(NN, NS * NR)), "sector_dtorque_dr": rng.normal(size=(NN, NS * NR)),
             "precone": [0.05, -0.1]}
    prob = check_component_partials(SectorAverageComp(num_nodes=NN, num_radial=NR, num_sectors=NS), loads)
    expected = np.cos(loads["precone"])[:, None] * loads["sector_dthrust_dr"].reshape(NN, NS, NR).mean(axis=1)
    np.testing.assert_allclose(prob.get_val("dthrust_dr"), expected, rtol=1e-14)


def _station_values(blade, nr=NR, ns=NS):
    rng = np.random.default_rng(5)
    tile = {name: np.tile(blade[name], (1, ns)) for name in ("radii", "chord", "twist")}
    omega_r = (blade["rpm"] * np.pi / 30.0)[:, None] * tile["radii"]
    tile.update(v_axial_local=blade["v_axial"][:, None] * rng.uniform(0.9, 1.1, omega_r.shape),
                v_theta_local=omega_r * rng.uniform(0.9, 1.1, omega_r.shape),
                **{name: blade[name] for name in ("radius", "hub_radius", "rho", "mu")})
    return tile


@pytest.mark.parametrize("component", [InflowComp, BladeElementLoadsComp])
def test_station_velocity_partials(smooth_polar, component):
    values = _station_values(_turbine_blade())
    if component is BladeElementLoadsComp:
        inflow = check_component_partials(InflowComp(num_nodes=NN, num_radial=NS * NR, num_blades=B,
                                                     polar=TurbinePolar(smooth_polar), station_velocities=True),
                                          values, atol=1e-9, rtol=1e-9)
        values["phi"] = inflow.get_val("phi")
    check_component_partials(component(num_nodes=NN, num_radial=NS * NR, num_blades=B, polar=TurbinePolar(smooth_polar),
                                       station_velocities=True), values, atol=1e-9, rtol=1e-9)


def test_turbine_polar_mirrors_the_airfoil(analytic_polar):
    alpha = np.linspace(-0.4, 0.4, 9) + 1e-30j
    mirror = TurbinePolar(analytic_polar).evaluate(-alpha, 1e6)
    own = analytic_polar.evaluate(alpha, 1e6)
    np.testing.assert_array_equal(mirror.cl, -own.cl)
    np.testing.assert_array_equal(mirror.cd, own.cd)
    np.testing.assert_allclose(mirror.dcl_dalpha, np.imag(mirror.cl) / -1e-30, rtol=1e-12)
    with pytest.raises(ValueError, match="already a TurbinePolar"):
        TurbinePolar(TurbinePolar(analytic_polar))


def test_turbine_performance_partials_and_values():
    rng = np.random.default_rng(7)
    values = dict(dthrust_dr=-rng.uniform(1e3, 2e3, (NN, NR)), dtorque_dr=-rng.uniform(1e3, 5e3, (NN, NR)),
                  dr=rng.uniform(0.5, 1.0, (NN, NR)), v_axial=[8.0, 11.0], rpm=[12.0, 14.0], radius=[60.0, 50.0],
                  rho=[1.225, 1.2], precone=[0.04, 0.0], speed_of_sound=[340.0, 330.0])
    prob = check_component_partials(TurbinePerformanceComp(num_nodes=NN, num_radial=NR), values)
    power = -np.sum(values["dtorque_dr"] * values["dr"], axis=1) * np.array(values["rpm"]) * np.pi / 30.0
    area = np.pi * (np.array(values["radius"]) * np.cos(values["precone"])) ** 2
    np.testing.assert_allclose(prob.get_val("power_coefficient"),
                               power / (0.5 * np.array(values["rho"]) * area * np.array(values["v_axial"]) ** 3))
    np.testing.assert_allclose(prob.get_val("tip_speed_ratio"), [12 * np.pi / 30 * 60 / 8, 14 * np.pi / 30 * 50 / 11])


def _set(prob, values):
    for name, value in values.items():
        prob.set_val(name, value)


def test_defaults_equal_the_axial_bem_bit_for_bit(analytic_polar, make_blade):
    blade = {k: v for k, v in make_blade(3, 7).items()}
    probs = []
    for group in (BEMAnalysisGroup, InclinedBEMGroup):
        prob = om.Problem(group(num_nodes=3, num_radial=7, num_blades=B, polar=analytic_polar), reports=False)
        prob.setup()
        _set(prob, blade)
        prob.run_model()
        probs.append(prob)
    for name in (*PERFORMANCE_OUTPUTS, *SECTION_OUTPUTS, "phi", "flow_state", "radii", "dr"):
        np.testing.assert_array_equal(probs[1].get_val(name), probs[0].get_val(name), err_msg=name)


def _group_values(blade):
    values = {k: blade[k] for k in ("v_axial", "rpm", "radius", "hub_radius", "chord", "twist", "rho", "mu")}
    return dict(values, **GEOMETRY)


@pytest.mark.parametrize("rotor_type", ["turbine", "propeller"])
def test_group_totals(smooth_polar, rotor_type):
    blade = _turbine_blade()
    if rotor_type == "propeller":
        blade["twist"] = blade["twist"] + 0.25  # thrust-producing pitch
    of = ["thrust", "torque", "power", "power_coefficient", "thrust_coefficient"]
    of += ["tip_speed_ratio"] if rotor_type == "turbine" else ["efficiency"]
    wrt = ["v_axial", "rpm", "radius", "hub_radius", "chord", "twist", "collective_pitch", "rho", *GEOMETRY]
    for mode in ("fwd", "rev"):
        prob = om.Problem(InclinedBEMGroup(num_nodes=NN, num_radial=NR, num_sectors=NS, num_blades=B,
                                           polar=smooth_polar, rotor_type=rotor_type, use_atmosphere=False),
                          reports=False)
        prob.setup(force_alloc_complex=True, mode=mode)
        _set(prob, _group_values(blade))
        prob.run_model()
        assert_no_approx_partials(prob.model, include_self=True, recurse=True)
        assert_totals_match(prob.check_totals(of=of, wrt=wrt, method="cs", out_stream=None), atol=1e-8, rtol=1e-7)
    if rotor_type == "turbine":
        assert np.all(prob.get_val("power") > 0.0) and np.all(prob.get_val("thrust") > 0.0)


def test_yaw_sign_symmetry_and_sector_mean(analytic_polar):
    # CCBlade's documented model: BEM per sector, loads averaged.  With an even number of sectors,
    # yaw +psi and -psi see the same set of tangential speeds (Lambda -> Lambda + pi): equal power.
    blade = _turbine_blade(nn=1, nr=6, seed=1)
    results = []
    for yaw in (0.0, 0.35, -0.35):
        prob = om.Problem(InclinedBEMGroup(num_nodes=1, num_radial=6, num_sectors=4, num_blades=B,
                                           polar=analytic_polar, rotor_type="turbine", use_atmosphere=False),
                          reports=False)
        prob.setup()
        _set(prob, {k: v[:1] for k, v in _group_values(blade).items() if k not in GEOMETRY})
        prob.set_val("yaw", [yaw])
        prob.run_model()
        results.append((prob.get_val("power")[0], prob.get_val("sector_dthrust_dr").reshape(4, 6)))
    np.testing.assert_allclose(results[1][0], results[2][0], rtol=1e-10)
    assert results[1][0] < results[0][0]  # yawed rotor extracts less power
    # Sectors 0 and 2 (blade up, blade down) swap under the sign change of the yaw; 1 and 3 do not change.
    np.testing.assert_allclose(results[1][1][[0, 1, 2, 3]], results[2][1][[2, 1, 0, 3]], rtol=1e-9)
