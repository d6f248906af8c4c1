"""design_rotor / DesignResult: batch = singles, physical invariants, validation, export."""
import json

import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.bem.metrics import METRICS
from bild_mdo.results.design import DesignResult, design_rotor

# Midpoints of 20 equal annuli from r/R = 0.2 put station 7 at 0.2 + 7.5 * 0.04 = 0.5 = r_ref/R (hand derivation).
NR_REF, REF_STATION = 20, 7
FAST = dict(airfoil="analytic", num_radial=NR_REF)


def test_batch_equals_single_designs():
    # One vectorised run must give each design exactly what a run of that design alone gives.
    j = [0.0, 0.5, 1.2]
    chords = [0.1, 0.15, 0.2]
    batch = design_rotor(advance_ratio=j, ref_chord=chords, altitude=[0.0, 500.0, 2000.0], **FAST)
    assert batch.is_batch and len(batch) == 3
    for i in range(3):
        single = design_rotor(advance_ratio=j[i], ref_chord=chords[i], altitude=[0.0, 500.0, 2000.0][i], **FAST)
        assert not single.is_batch and len(single) == 1
        for name in ("thrust", "torque", "power", "efficiency", "figure_of_merit", "reynolds_ref"):
            np.testing.assert_allclose(getattr(batch, name)[i], getattr(single, name), rtol=1e-12)
            assert getattr(batch[i], name) == pytest.approx(getattr(single, name), rel=1e-12)
        for name in ("chord", "twist", "radii", "dthrust_dr", "eta2"):
            np.testing.assert_allclose(getattr(batch, name)[i], getattr(single, name), rtol=1e-12, atol=1e-15)


def test_scalars_broadcast_against_lists():
    batch = design_rotor(v_axial=[0.0, 20.0], rpm=900.0, **FAST)
    np.testing.assert_array_equal(batch.rpm, [900.0, 900.0])
    assert batch.chord.shape == (2, NR_REF)
    assert batch.thrust.shape == (2,)


@pytest.mark.parametrize("root_chord_correction", [None, 1.5])
@pytest.mark.parametrize("advance_ratio", [0.0, 1.0])
def test_chord_at_reference_station_is_reference_chord(advance_ratio, root_chord_correction):
    # Physical invariant of Alg. 1: the reference BEM solve used c_ref at r_ref, so the back-computed chord
    # there is c_ref; Eq. (32) averages c_ref with the back-computed chord, which leaves it unchanged there.
    result = design_rotor(advance_ratio=advance_ratio, ref_chord=[0.08, 0.15, 0.22],
                          root_chord_correction=root_chord_correction, **FAST)
    np.testing.assert_allclose(result.radial_fractions[:, REF_STATION], 0.5, rtol=1e-14)
    np.testing.assert_allclose(result.chord[:, REF_STATION], [0.08, 0.15, 0.22], rtol=1e-9)


def test_advance_ratio_and_v_axial_give_the_same_design():
    # Table 2: V_x = J n D, n = rpm/60, D = 2R.
    j = np.array([0.3, 1.1])
    by_j = design_rotor(advance_ratio=j, rpm=850.0, radius=1.2, **FAST)
    by_v = design_rotor(v_axial=j * 850.0 / 60.0 * 2.4, rpm=850.0, radius=1.2, **FAST)
    np.testing.assert_allclose(by_j.v_axial, by_v.v_axial, rtol=1e-14)
    np.testing.assert_allclose(by_v.advance_ratio, j, rtol=1e-14)
    np.testing.assert_allclose(by_j.chord, by_v.chord, rtol=1e-11)
    np.testing.assert_allclose(by_j.thrust, by_v.thrust, rtol=1e-11)


def test_result_quantities_and_units():
    result = design_rotor(v_axial=15.0, **FAST)
    # Table 2: P = Omega Q, E = P - V T, C_T / sigma = blade loading.
    assert result.power == pytest.approx(result.torque * 800.0 * np.pi / 30.0, rel=1e-12)
    assert result.energy_loss == pytest.approx(result.power - 15.0 * result.thrust, rel=1e-10)
    assert result.blade_loading == pytest.approx(result.thrust_coefficient / result.solidity, rel=1e-12)
    np.testing.assert_allclose(result.twist_deg, np.degrees(result.twist))
    assert result.alpha_star_deg == pytest.approx(np.degrees(result.alpha_star))
    # The analytic polar's max L/D point in closed form (AnalyticPolar.max_lift_to_drag_closed_form).
    alpha, cl, cd = AnalyticPolar().max_lift_to_drag_closed_form(1e6)
    assert result.alpha_star == pytest.approx(float(alpha), rel=1e-9)
    np.testing.assert_allclose(result.lift_coefficient, cl, rtol=1e-9)
    np.testing.assert_allclose(result.drag_coefficient, cd, rtol=1e-9)
    for name in ("thrust", "torque", "chord", "twist", "radii", "dthrust_dr", "v_axial", "rpm", "altitude"):
        assert name in DesignResult.UNITS
    assert DesignResult.UNITS["thrust"] == "N" and DesignResult.UNITS["twist"] == "rad"
    assert set(result.to_dict()) >= {"thrust", "chord", "twist", "num_blades", "airfoil"}


def test_indexing_and_iteration():
    batch = design_rotor(ref_chord=[0.1, 0.12, 0.14, 0.16], **FAST)
    assert batch[-1].ref_chord == pytest.approx(0.16)
    assert len(batch[1:3]) == 2 and batch[1:3][0].ref_chord == pytest.approx(0.12)
    assert [d.ref_chord for d in batch] == pytest.approx([0.1, 0.12, 0.14, 0.16])
    with pytest.raises(IndexError):
        batch[4]
    with pytest.raises(ValueError, match="pick one"):
        batch.geometry()


def test_summary_and_station_table():
    single = design_rotor(**FAST)
    text = single.summary()
    for expected in ("thrust T", " N", "kW", "figure of merit", "m/s", "rpm", "Reynolds"):
        assert expected in text
    table = single.station_table().splitlines()
    assert table[0].split() == ["r", "[m]", "r/R", "[-]", "chord", "[m]", "twist", "[deg]", "C_l", "[-]",
                                "C_d", "[-]"]
    assert len(table) == 1 + NR_REF
    batch_text = design_rotor(advance_ratio=np.linspace(0.0, 2.0, 30), **FAST).summary(max_rows=10)
    assert "30 designs" in batch_text and "..." in batch_text and "T [N]" in batch_text


def test_every_registry_metric_is_a_result_quantity():
    # The result follows the registry of per-design outputs (bild_mdo.bem.metrics.METRICS) with its units.
    result = design_rotor(ref_chord=[0.1, 0.2], **FAST)
    for metric in METRICS:
        assert DesignResult.UNITS[metric.name] == metric.units
        assert getattr(result, metric.name).shape == (2,)
        assert isinstance(getattr(result[0], metric.name), float)
    with pytest.raises(AttributeError):
        result.no_such_quantity
    # Angles (units rad) also read in degrees; other quantities have no *_deg form.
    np.testing.assert_allclose(result.phi_deg, np.degrees(result.phi))
    with pytest.raises(AttributeError):
        result.chord_deg


def test_exports(tmp_path):
    batch = design_rotor(advance_ratio=[0.5, 1.0], **FAST)
    paths = batch.to_csv(tmp_path / "blade.csv")
    assert [p.name for p in paths] == ["blade_0.csv", "blade_1.csv"]
    assert all(p.stat().st_size > 0 for p in paths)
    doc = json.loads(batch.to_json(tmp_path / "blades.json").read_text())
    assert len(doc["designs"]) == 2
    perf = doc["designs"][1]["performance"]
    assert perf["thrust [N]"] == pytest.approx(batch.thrust[1], rel=1e-11)
    assert doc["designs"][1]["distributions"]["chord [m]"] == pytest.approx(batch.chord[1].tolist(), rel=1e-11)


@pytest.mark.parametrize("kwargs, message", [
    (dict(radius=-1.0), "radius"),
    (dict(radius=[1.0, 0.0]), r"radius must be a positive finite number in m, got 0 \(design 1\)"),
    (dict(radius="1.5"), "radius must be a positive finite number in m, got '1.5'"),
    (dict(rpm=True), "rpm must be a positive finite number in rpm, got True"),
    (dict(ref_chord=[0.1, True]), "ref_chord must be a positive finite number"),
    (dict(ref_chord=0.0), "ref_chord"),
    (dict(rpm=-800.0), "rpm"),
    (dict(hub_radius_ratio=0.0), r"hub_radius_ratio must be a finite number within \(0, 1\)"),
    (dict(ref_radius_ratio=1.0), r"ref_radius_ratio must be a finite number within \(0, 1\)"),
    (dict(hub_radius_ratio=0.6, ref_radius_ratio=0.5), "hub_radius_ratio must be smaller"),
    (dict(v_axial=-1.0), "v_axial"),
    (dict(advance_ratio=-0.1), "advance_ratio"),
    (dict(v_axial=1.0, advance_ratio=0.1), "not both"),
    (dict(airfoil="no_such_airfoil"), "unknown airfoil 'no_such_airfoil'; available: analytic, naca4412"),
    (dict(altitude=20000.0), "altitude"),
    (dict(num_blades=0), "num_blades"),
    (dict(num_radial=2.5), "num_radial must be an integer >= 1, got 2.5"),
    (dict(num_blades=True), "num_blades must be an integer >= 1, got True"),
    (dict(loss_model="prandtl"), "loss_model"),
    (dict(chord_form="power"), "chord_form"),
    (dict(root_chord_correction=-1.0), "root_chord_correction"),
    (dict(rpm=[800.0, 900.0], ref_chord=[0.1, 0.2, 0.3]), "batch sizes disagree"),
    (dict(rpm="fast"), "rpm must be a positive finite number in rpm, got 'fast'"),
    (dict(rpm=[[800.0]]), "1-D"),
    (dict(radius=np.nan), "finite"),
])
def test_validation_errors(kwargs, message):
    with pytest.raises(ValueError, match=message):
        design_rotor(**{**dict(airfoil="analytic", num_radial=5), **kwargs})


# A design whose reference station is overloaded: BILD's reference BEM solve at r_ref = 0.3006 R gives
# u_theta_ref = 42.7 m/s > V_theta_ref = Omega r_ref = 33.1 m/s, against the paper's Assumption 3
# (0 < u_theta < V_theta), so Eq. (22) has no ideal-loading constant (V = 26.8 m/s, 824 rpm, R = 1.277 m,
# c_ref = 0.2 m, hub ratio 0.2970, 3533 m).
OVERLOADED = dict(v_axial=26.8, rpm=824.0, radius=1.277, ref_chord=0.200, ref_radius_ratio=0.3006,
                  hub_radius_ratio=0.2970, altitude=3533.0)
# Feasible designs around it: the paper's hover rotor (R = 1.5 m, 800 rpm) and two forward-flight points.
FEASIBLE = dict(v_axial=0.0, rpm=800.0, radius=1.5, ref_chord=0.15, ref_radius_ratio=0.5, hub_radius_ratio=0.2,
                altitude=0.0)
NR_INFEASIBLE = 12


def _batch(designs):
    return {name: np.array([design[name] for design in designs]) for name in FEASIBLE}


def _mixed():
    cruise = dict(FEASIBLE, v_axial=20.0)
    fast = dict(FEASIBLE, v_axial=40.0, ref_chord=0.1)
    return [FEASIBLE, OVERLOADED, cruise, fast], [FEASIBLE, cruise, fast]


def _assert_identical(a, b):
    assert a.values.keys() == b.values.keys()
    for name, value in a.values.items():
        assert np.array_equal(value, b.values[name]), name


def test_skip_returns_the_whole_batch_with_mask_status_and_nan(tmp_path):
    mixed, feasible_only = _mixed()
    result = design_rotor(**_batch(mixed), num_radial=NR_INFEASIBLE, on_infeasible="skip")
    np.testing.assert_array_equal(result.feasible, [True, False, True, True])
    assert list(result.status[[0, 2, 3]]) == ["ok"] * 3
    assert result.status[1].startswith("Assumption 3 violated at the reference station: u_theta_ref < V_theta_ref")
    # The infeasible design keeps its inputs; every computed quantity is NaN (documented in DesignResult).
    bad = result[1]
    assert not bad.feasible and bad.v_axial == 26.8 and bad.ref_chord == 0.2
    assert np.isnan(bad.thrust) and np.all(np.isnan(bad.chord)) and np.isnan(bad.figure_of_merit)
    assert "INFEASIBLE" in bad.summary() and "infeasible" in result.summary()
    # The feasible designs are bitwise those of a batch without the infeasible one, and of each alone.
    subset = result.feasible_designs()
    assert len(subset) == 3 and np.all(subset.feasible)
    _assert_identical(subset, design_rotor(**_batch(feasible_only), num_radial=NR_INFEASIBLE))
    _assert_identical(result[3], design_rotor(**feasible_only[2], num_radial=NR_INFEASIBLE))
    with pytest.raises(ValueError, match="1 of 4 designs are infeasible"):
        result.to_csv(tmp_path / "rotor.csv")
    assert not list(tmp_path.iterdir())  # nothing written


def test_raise_counts_all_and_lists_the_first_ten():
    mixed, _ = _mixed()
    with pytest.raises(om.AnalysisError, match=r"(?s)1 of 4 design\(s\) infeasible:.*u_theta_ref < V_theta_ref.*"
                                               r"design\(s\) 1 \[design 1 \(u_axial_ref"):
        design_rotor(**_batch(mixed), num_radial=NR_INFEASIBLE)
    many = [FEASIBLE] + [OVERLOADED] * 12
    with pytest.raises(om.AnalysisError, match=r"(?s)12 of 13 design\(s\) infeasible \(the first 10 listed\).*"
                                               r"design\(s\) 1-10 \["):
        design_rotor(**_batch(many), num_radial=NR_INFEASIBLE)


def test_single_infeasible_design():
    with pytest.raises(om.AnalysisError, match="1 of 1 design"):
        design_rotor(**OVERLOADED, num_radial=NR_INFEASIBLE)
    single = design_rotor(**OVERLOADED, num_radial=NR_INFEASIBLE, on_infeasible="skip")
    assert not single.is_batch and single.feasible is False and np.isnan(single.power)
    with pytest.raises(ValueError, match="infeasible"):
        single.feasible_designs()
    with pytest.raises(ValueError, match="on_infeasible"):
        design_rotor(on_infeasible="ignore")


def test_thrust_target_design_meets_its_thrust():
    # BILDGroup(thrust_target=True) solves the reference chord for T = T*: the design with that chord given
    # is the same rotor.
    targets = np.array([1500.0, 800.0, 2500.0])
    batch = design_rotor(thrust=targets, v_axial=[0.0, 10.0, 5.0], airfoil="analytic", num_radial=12)
    np.testing.assert_allclose(batch.thrust, targets, rtol=1e-10)
    again = design_rotor(ref_chord=batch.ref_chord, v_axial=[0.0, 10.0, 5.0], airfoil="analytic", num_radial=12)
    np.testing.assert_allclose(again.thrust, targets, rtol=1e-10)
    np.testing.assert_allclose(again.chord, batch.chord, rtol=1e-10)
    with pytest.raises(ValueError, match="give either ref_chord .m. or thrust .N."):
        design_rotor(thrust=1000.0, ref_chord=0.1)
    with pytest.raises(ValueError, match="thrust must be a positive finite number in N, got -1"):
        design_rotor(thrust=-1.0)


def test_batch_size_is_bounded_before_the_model_is_built():
    with pytest.raises(ValueError, match=r"designs = 10000 with 10000 stations would need about 300 GB"):
        design_rotor(ref_chord=np.full(10_000, 0.15), num_radial=10_000)


def test_tip_mach_number():
    # sqrt(V^2 + (Omega R)^2) / a with the ISA sea-level speed of sound a0 = 340.294 m/s.
    rotor = design_rotor(v_axial=[0.0, 30.0], airfoil="analytic", num_radial=12)
    np.testing.assert_allclose(rotor.tip_mach, np.hypot([0.0, 30.0], 800.0 * np.pi / 30.0 * 1.5) / 340.294,
                               rtol=1e-5)
    assert rotor.mach.shape == (2, 12) and np.all(rotor.mach < rotor.tip_mach[:, None])
    assert "tip Mach number" in rotor[0].summary()


def test_local_section_point_design_keeps_the_reference_chord():
    # Invariant (issue 12): chord(r_ref) = c_ref with the local section point too; r/R = 0.5 is station 4 of
    # 12 equal annuli from 0.2 (0.2 + 4.5 * 0.8 / 12).
    result = design_rotor(v_axial=[0.0, 20.0], ref_chord=[0.12, 0.18], num_radial=12, section_point="local")
    np.testing.assert_allclose(result.chord[:, 4], [0.12, 0.18], rtol=1e-9)


def test_section_point_is_validated():
    with pytest.raises(ValueError, match="section_point must be one of reference, local"):
        design_rotor(section_point="global")
