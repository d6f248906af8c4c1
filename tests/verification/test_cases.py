import numpy as np
import pytest

from bild_mdo.verification.cases import AXES, SweepSpec


def test_paper_sweep_has_10000_unique_stable_cases():
    spec = SweepSpec(levels=10)
    cases = spec.cases()
    # Paper Sec. 5.1: ten levels of four inputs, 10,000 combinations.
    assert spec.num_cases == 10_000
    assert len(cases) == 10_000
    assert [c.case_id for c in cases] == list(range(10_000))
    # Every combination occurs once: the four swept values identify the case.
    assert len({tuple(c.inputs[a] for a in AXES) for c in cases}) == 10_000
    # Building again (or one case alone) gives the same inputs for the same id.
    again = SweepSpec(levels=10).cases([9999, 0, 4321])
    assert [c.inputs for c in again] == [cases[0].inputs, cases[4321].inputs, cases[9999].inputs]
    assert spec.case(4321) == cases[4321]


def test_bounds_are_exact_and_levels_even():
    spec = SweepSpec(levels=10)
    cases = spec.cases()
    # Paper Sec. 5.1 ranges: J 0..3, R 0.5..1.5 m, altitude 0..3000 m, c_ref 0.08..0.22 m.
    expected = {
        "advance_ratio": (0.0, 3.0),
        "radius": (0.5, 1.5),
        "altitude": (0.0, 3000.0),
        "reference_chord": (0.08, 0.22),
    }
    for axis, (lo, hi) in expected.items():
        values = sorted({c.inputs[axis] for c in cases})
        assert len(values) == 10
        assert values[0] == lo and values[-1] == hi
        np.testing.assert_allclose(np.diff(values), (hi - lo) / 9, rtol=1e-12)


def test_case_id_layout_and_fixed_inputs():
    spec = SweepSpec(levels=10)
    # Hand derivation: id 1234 = ((1*10 + 2)*10 + 3)*10 + 4 -> levels (1, 2, 3, 4) of (J, R, h, c).
    inputs = spec.case(1234).inputs
    assert inputs["advance_ratio"] == pytest.approx(3.0 / 9)
    assert inputs["radius"] == pytest.approx(0.5 + 2.0 / 9)
    assert inputs["altitude"] == pytest.approx(1000.0)
    assert inputs["reference_chord"] == pytest.approx(0.08 + 4 * 0.14 / 9)
    # V_x = J n D with n = 800/60 rev/s and D = 2R.
    assert inputs["v_axial"] == pytest.approx((3.0 / 9) * (800.0 / 60.0) * 2 * (0.5 + 2.0 / 9), rel=1e-14)
    # Fixed inputs of the brief / paper Sec. 5.1: 800 rpm, r_ref = 0.5 R, hub 0.2 R, B = 3, 30 stations.
    assert inputs["rpm"] == 800.0
    assert inputs["reference_radius"] == pytest.approx(0.5 * inputs["radius"])
    assert inputs["hub_radius"] == pytest.approx(0.2 * inputs["radius"])
    assert (inputs["num_blades"], inputs["num_radial"], inputs["airfoil"]) == (3, 30, "naca4412")
    assert spec.case(1234).optimizer == "slsqp"


def test_fingerprint_identifies_the_sweep():
    base = SweepSpec(levels=10)
    # A pinned identifier, not a computed quantity: a change of the case layout or the defaults must be
    # noticed, since it orphans existing stores; bump CASE_LAYOUT_VERSION then.
    assert base.fingerprint() == SweepSpec().fingerprint() == "a1c89e229d75513b"
    assert len({base.fingerprint(), SweepSpec(levels=9).fingerprint(), SweepSpec(optimizer="ipopt").fingerprint(),
                SweepSpec(num_radial=20).fingerprint()}) == 4


@pytest.mark.parametrize("kwargs, match", [
    ({"levels": 1}, "levels must be an integer >= 2"),
    ({"levels": 2.5}, "levels must be an integer >= 2"),
    ({"optimizer": "fmincon"}, "optimizer must be one of"),
    ({"radius_range": (1.5, 0.5)}, "radius_range must be finite with min <= max"),
    ({"hub_radius_fraction": 0.6}, "hub_radius_fraction < reference_radius_fraction"),
])
def test_invalid_specs_are_refused(kwargs, match):
    with pytest.raises(ValueError, match=match):
        SweepSpec(**kwargs)


def test_case_id_out_of_range():
    with pytest.raises(ValueError, match=r"case_id must be in \[0, 16\)"):
        SweepSpec(levels=2).case(16)
