"""Off-design BEM sweeps of BILD blades: design-point consistency, invariants, vectorisation, errors."""
import numpy as np
import pytest

import bild_mdo.results.off_design as off_design_module
import bild_mdo.results.point_analysis as point_analysis
from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.bem.metrics import METRICS
from bild_mdo.results.design import design_rotor
from bild_mdo.results.off_design import OffDesignResult, off_design_sweep

FAST = dict(airfoil="analytic", num_radial=16)


@pytest.mark.parametrize("advance_ratio", [0.4, 1.0, 2.0])
def test_design_point_reproduces_bild_with_reynolds_independent_polar(advance_ratio):
    # With a polar that does not depend on Re every element of the BILD blade works at alpha*, and
    # Eq. (25) zeroes the BEM residual at BILD's inflow angle: BEM must return BILD's T and Q
    # (measured ~1e-14 relative).
    rotor = design_rotor(advance_ratio=advance_ratio, **FAST)
    sweep = off_design_sweep(rotor, advance_ratios=[0.5 * advance_ratio, advance_ratio, 1.5 * advance_ratio])
    assert sweep.thrust[1] == pytest.approx(rotor.thrust, rel=1e-6)
    assert sweep.torque[1] == pytest.approx(rotor.torque, rel=1e-6)
    assert sweep.efficiency[1] == pytest.approx(rotor.efficiency, rel=1e-6)


def test_hover_design_point_reproduces_bild():
    rotor = design_rotor(**FAST)
    sweep = off_design_sweep(rotor, rpms=[600.0, 800.0, 1000.0])
    assert sweep.thrust[1] == pytest.approx(rotor.thrust, rel=1e-6)
    assert sweep.torque[1] == pytest.approx(rotor.torque, rel=1e-6)
    assert sweep.figure_of_merit[1] == pytest.approx(rotor.figure_of_merit, rel=1e-6)


@pytest.mark.parametrize("advance_ratio", [0.0, 0.5, 1.0, 2.0])
def test_design_point_with_naca4412(advance_ratio):
    # BILD takes alpha*, cl*, cd* at the reference Reynolds number for every station; BEM uses each
    # station's own Reynolds number, so T and Q differ by the polar's Re-dependence over the span.
    # Measured with 30 stations: |dT/T| = 7.3e-4, 1.24e-3, 1.28e-3, 9.4e-5 and |dQ/Q| = 9.0e-4, 1.0e-5,
    # 5.1e-4, 3.0e-4 for J = 0, 0.5, 1, 2.
    rotor = design_rotor(advance_ratio=advance_ratio, airfoil="naca4412", num_radial=30)
    if advance_ratio == 0.0:
        sweep = off_design_sweep(rotor, rpms=[rotor.rpm])
    else:
        sweep = off_design_sweep(rotor, advance_ratios=[advance_ratio])
    assert abs(sweep.thrust[0] / rotor.thrust - 1.0) < 2e-3
    assert abs(sweep.torque[0] / rotor.torque - 1.0) < 1.5e-3


def test_hover_coefficients_do_not_depend_on_rpm():
    # Dimensional analysis: in hover with a Re-independent polar and fixed density the flow scales with
    # Omega, so C_T, C_Q, C_P and FM are the same at every rotor speed.
    sweep = off_design_sweep(design_rotor(**FAST), rpms=np.linspace(300.0, 1500.0, 5))
    for name in ("thrust_coefficient", "torque_coefficient", "power_coefficient", "figure_of_merit"):
        values = getattr(sweep, name)
        np.testing.assert_allclose(values, values[0], rtol=1e-9)
    # T ~ Omega^2 at fixed C_T.
    np.testing.assert_allclose(sweep.thrust / sweep.rpm**2, sweep.thrust[0] / sweep.rpm[0] ** 2, rtol=1e-9)


def test_one_vectorised_analysis(monkeypatch):
    calls = []
    original = off_design_module.analyze_rotor

    def counting(*args, **kwargs):
        calls.append(np.size(args[4]))
        return original(*args, **kwargs)

    monkeypatch.setattr(off_design_module, "analyze_rotor", counting)
    sweep = off_design_sweep(design_rotor(advance_ratio=1.0, **FAST), advance_ratios=np.linspace(0.2, 1.8, 17))
    assert calls == [17]
    assert len(sweep) == 17 and sweep.bem.phi.shape == (17, 16)


def test_maximum_efficiency_point():
    # Paper Sec. 5.2.4 / Fig. 9: the best efficiency of a BILD blade is at least that at its design point.
    rotor = design_rotor(advance_ratio=1.0, **FAST)
    j = np.linspace(0.1, 2.5, 25)
    sweep = off_design_sweep(rotor, advance_ratios=j)
    best = sweep.max_efficiency_point
    useful = (sweep.thrust > 0) & (sweep.power > 0)
    assert best["efficiency"] == pytest.approx(np.max(sweep.efficiency[useful]))
    assert best["efficiency"] >= rotor.efficiency
    # J = V/(nD) of every point (Table 2).
    np.testing.assert_allclose(sweep.v_axial, j * 800.0 / 60.0 * 3.0, rtol=1e-14)
    assert "maximum efficiency" in sweep.summary()
    hover = off_design_sweep(design_rotor(**FAST), rpms=[700.0, 800.0])
    assert hover.max_efficiency_point is None


def test_geometry_sources_agree(tmp_path):
    rotor = design_rotor(advance_ratio=0.8, **FAST)
    path = rotor.to_csv(tmp_path / "blade.csv")[0]
    from_result = off_design_sweep(rotor, advance_ratios=[0.6, 0.8])
    from_file = off_design_sweep(path, advance_ratios=[0.6, 0.8])
    from_arrays = off_design_sweep(dict(radii=rotor.radii, chord=rotor.chord, twist=rotor.twist, radius=1.5,
                                        hub_radius=0.3, num_blades=3), advance_ratios=[0.6, 0.8], rpm=800.0,
                                   polar=AnalyticPolar())
    # The file carries 12 significant digits.
    np.testing.assert_allclose(from_file.thrust, from_result.thrust, rtol=1e-9)
    np.testing.assert_allclose(from_arrays.thrust, from_result.thrust, rtol=1e-12)
    out = from_file.to_csv(tmp_path / "perf.csv").read_text().splitlines()
    assert out[1].startswith("advance_ratio [-],v_axial [m/s],rpm [rpm],thrust [N]")
    assert len(out) == 4


@pytest.mark.parametrize("kwargs, message", [
    (dict(), "give advance_ratios .J sweep., rpms .rotor-speed sweep., a list of v_axial .airspeed sweep. or a "
             "list of collective_pitch"),
    (dict(advance_ratios=[1.0], rpms=[800.0]), "at most one"),
    (dict(advance_ratios=[0.5], collective_pitch=[]), "collective_pitch must be a number or a non-empty"),
    (dict(advance_ratios=[0.5], collective_pitch="0.1"), "collective_pitch must be a finite number in rad"),
    (dict(advance_ratios=[-0.5]), r"advance_ratios must be a finite number >= 0, got -0.5 \(point 0\)"),
    (dict(rpms=[900.0, 0.0]), r"rpms must be a positive finite number in rpm, got 0 \(point 1\)"),
    (dict(advance_ratios=[]), "non-empty"),
    (dict(advance_ratios=[0.5], rpm=-1.0), "rpm must be a positive finite number in rpm, got -1"),
    (dict(advance_ratios=["0.5"]), r"advance_ratios must be a finite number >= 0, got \['0.5'\]"),
    (dict(rpms=[800.0], v_axial=True), "v_axial must be a finite number >= 0 in m/s, got True"),
    (dict(advance_ratios=[0.5], polar="no_such_airfoil"), "unknown airfoil 'no_such_airfoil'"),
])
def test_invalid_sweeps(kwargs, message):
    with pytest.raises(ValueError, match=message):
        off_design_sweep(design_rotor(advance_ratio=0.5, **FAST), **kwargs)


def test_batch_needs_a_design_index():
    batch = design_rotor(advance_ratio=[0.5, 1.0], **FAST)
    with pytest.raises(ValueError, match="choose one with design=i"):
        off_design_sweep(batch, advance_ratios=[0.5])
    sweep = off_design_sweep(batch, advance_ratios=[1.0], design=1)
    assert sweep.thrust[0] == pytest.approx(batch.thrust[1], rel=1e-6)


def test_every_registry_metric_is_a_sweep_quantity(tmp_path):
    # The sweep follows the registry of per-design outputs (bild_mdo.bem.metrics.METRICS): every metric is an
    # attribute equal to the BEM result's, and a column of the CSV file with its units.
    sweep = off_design_sweep(design_rotor(advance_ratio=0.8, **FAST), advance_ratios=[0.6, 0.8])
    header = sweep.to_csv(tmp_path / "perf.csv").read_text().splitlines()[1].split(",")
    for metric in METRICS:
        np.testing.assert_array_equal(getattr(sweep, metric.name), getattr(sweep.bem, metric.name))
        assert OffDesignResult.UNITS[metric.name] == metric.units
        assert f"{metric.name} [{metric.units or '-'}]" in header


# A blade twisted from +20 deg at the hub to -10 deg at the tip: in forward flight at 3000 rpm its outboard
# annuli push air forward against the freestream (dT < 0 with axial induction a > 0.4), the turbulent-wake /
# vortex-ring state where momentum theory has no valid solution (Glauert; Buhl 2005, NREL/TP-500-36834).
NEGATIVE_TIP = dict(radii=np.linspace(0.25, 0.98, 20), chord=np.full(20, 0.1),
                    twist=np.radians(np.linspace(20.0, -10.0, 20)), radius=1.0, hub_radius=0.2, num_blades=3,
                    airfoil="analytic", loss_model="tip_hub")


def test_failed_points_are_recorded_and_the_sweep_goes_on():
    # Negative tip pitch: the outboard annuli push air against the flow (vortex ring, flagged) at low J;
    # at J = 1.5 the freestream carries every annulus in a valid state.
    sweep = off_design_sweep(NEGATIVE_TIP, advance_ratios=[1.5, 0.1], rpm=3000.0, on_invalid="raise")
    assert sweep.status[0] == "ok" and np.isfinite(sweep.thrust[0])
    assert "turbulent wake / vortex ring" in sweep.status[1] and np.isnan(sweep.thrust[1])
    np.testing.assert_array_equal(sweep.ok, [True, False])
    assert "failed: BEM analysis" in sweep.summary()
    with pytest.warns(UserWarning, match="turbulent wake"):
        warned = off_design_sweep(NEGATIVE_TIP, advance_ratios=[1.5, 0.1], rpm=3000.0)
    assert list(warned.status) == ["ok", "ok"] and np.all(np.isfinite(warned.thrust))


def test_points_that_raise_are_isolated_by_bisection():
    # Logic of the fallback: only the points whose analysis raises are marked, each with its own message.
    failing = {2, 5}

    class Result:
        def __init__(self, points):
            self.flow_state = np.ones((points.size, 3), dtype=int)
            self.mach = np.full((points.size, 3), 0.1)
            for metric in METRICS:
                setattr(self, metric.name, points.astype(float))

    def run(points, mode):
        if failing & set(points.tolist()):
            raise off_design_module.om.AnalysisError(f"'performance' <class X>: Error calling compute(), "
                                                     f"torque = 0.0 at node 0 of {points.tolist()}")
        return Result(points)

    r_over_r = np.ones((7, 3))
    bem, performance, stations, status = point_analysis.analyze_points(run, 7, "raise", r_over_r)
    flow_state = stations["flow_state"]
    assert bem is None
    assert [s == "ok" for s in status] == [True, True, False, True, True, False, True]
    assert status[2] == "torque = 0.0 at node 0 of [2]"
    np.testing.assert_array_equal(performance["thrust"], [0, 1, np.nan, 3, 4, np.nan, 6])
    assert np.all(flow_state[[2, 5]] == -1) and np.all(np.isnan(stations["mach"][[2, 5]]))


@pytest.mark.parametrize("design, message", [
    (True, "design must be an integer >= -2, got True"),
    ("0", "design must be an integer >= -2, got '0'"),
    (1.5, "design must be an integer >= -2, got 1.5"),
    (-3, "design must be an integer >= -2, got -3"),
    (2, "design must be an index of the DesignResult's 2 design.s., got 2"),
])
def test_design_index_is_checked(design, message):
    batch = design_rotor(advance_ratio=[0.5, 1.0], **FAST)
    with pytest.raises(ValueError, match=message):
        off_design_sweep(batch, advance_ratios=[0.5], design=design)
    assert off_design_sweep(batch, advance_ratios=[1.0], design=-1).thrust[0] == pytest.approx(batch.thrust[1])


def test_collective_pitch_is_a_twist_offset():
    # The collective pitch turns every section by the same angle: the blade analysed with pitch d is the
    # blade with twist + d (to round-off).  Several pitches with a J sweep give every pitch at every J.
    rotor = design_rotor(advance_ratio=0.8, **FAST)
    pitches = np.radians([-2.0, 3.0])
    sweep = off_design_sweep(rotor, advance_ratios=[0.6, 0.8, 1.0], collective_pitch=pitches)
    np.testing.assert_allclose(sweep.collective_pitch, np.repeat(pitches, 3), rtol=0, atol=0)
    np.testing.assert_allclose(sweep.advance_ratio, np.tile([0.6, 0.8, 1.0], 2), rtol=1e-15)
    for k, pitch in enumerate(pitches):
        turned = dict(radii=rotor.radii, chord=rotor.chord, twist=rotor.twist + pitch, radius=1.5, hub_radius=0.3,
                      num_blades=3)
        reference = off_design_sweep(turned, advance_ratios=[0.6, 0.8, 1.0], rpm=800.0, polar=rotor.polar)
        np.testing.assert_allclose(sweep.thrust[3 * k:3 * k + 3], reference.thrust, rtol=1e-12)
        np.testing.assert_allclose(sweep.torque[3 * k:3 * k + 3], reference.torque, rtol=1e-12)
    # Alone, a list of pitches sweeps them at the design point; more pitch, more thrust (attached flow).
    alone = off_design_sweep(rotor, collective_pitch=np.radians([-1.0, 0.0, 1.0]))
    assert alone.sweep == "collective_pitch" and np.all(np.diff(alone.thrust) > 0)
    assert alone.thrust[1] == pytest.approx(rotor.thrust, rel=1e-6)
    assert "pitch [deg]" in alone.summary() and "pitch [deg]" not in off_design_sweep(rotor, rpms=[800.0]).summary()


def test_sweep_size_is_bounded_before_running():
    with pytest.raises(ValueError, match=r"sweep points = 100000000 with 16 stations would need about 4.8 TB"):
        off_design_sweep(design_rotor(advance_ratio=0.5, **FAST), advance_ratios=np.linspace(0.0, 1.0, 100_000),
                         collective_pitch=np.zeros(1000))


def test_mach_numbers():
    # Tip Mach number sqrt(V^2 + (Omega R)^2) / a with the ISA sea-level speed of sound a0 = 340.294 m/s.
    sweep = off_design_sweep(design_rotor(advance_ratio=0.8, **FAST), advance_ratios=[0.4, 0.8])
    tip_speed = np.hypot(sweep.v_axial, 800.0 * np.pi / 30.0 * 1.5)
    np.testing.assert_allclose(sweep.tip_mach, tip_speed / 340.294, rtol=1e-5)
    # Each station's Mach number uses W0 = sqrt(V^2 + (Omega r)^2) < the tip speed.
    assert sweep.mach.shape == (2, 16) and np.all(sweep.mach < sweep.tip_mach[:, None])
