"""analyze_rotor with rotor_type='turbine' and the inclined-flow options: results, signs, validation, table."""
import numpy as np
import pytest

from bild_mdo.bem import analyze_rotor
from bild_mdo.bem.analyze import BEMResult
from bild_mdo.bem.analyze_inclined import InclinedBEMResult, TurbineBEMResult
from bild_mdo.results.turbine_table import turbine_table

R, HUB, NR = 10.0, 1.0, 8


def _turbine(**options):
    x = np.linspace(0.0, 1.0, NR)
    chord, twist = 0.8 - 0.5 * x, np.radians(14.0 - 12.0 * x)
    options = {"rotor_type": "turbine", "on_invalid": "ignore", **options}
    return analyze_rotor(chord, twist, R, HUB, options.pop("rpm", 50.0), options.pop("v_axial", 9.0), 3,
                         options.pop("polar", "analytic"), **options)


def test_turbine_result_signs_and_definitions():
    res = _turbine(v_axial=[8.0, 9.0], rpm=[45.0, 50.0])
    assert isinstance(res, TurbineBEMResult)
    assert np.all(res.power > 0.0) and np.all(res.thrust > 0.0) and np.all(res.torque > 0.0)
    omega = np.array([45.0, 50.0]) * np.pi / 30.0
    np.testing.assert_allclose(res.tip_speed_ratio, omega * R / np.array([8.0, 9.0]))
    np.testing.assert_allclose(res.power, omega * res.torque)
    np.testing.assert_allclose(res.thrust, np.sum(res.dthrust_dr * res.dr, axis=1))
    assert res.phi.shape == (2, 1, NR) and res.azimuth.shape == (1,)
    # The turbine's own convention: alpha = phi - theta.
    np.testing.assert_allclose(res.alpha[:, 0], res.phi[:, 0] - np.radians(14.0 - 12.0 * np.linspace(0, 1, NR)))
    assert np.max(np.abs(res.residual)) < 1e-10


def test_inclined_propeller_and_axial_path():
    args = (np.full(6, 0.05), np.radians(np.linspace(40.0, 15.0, 6)), 0.5, 0.08, 4000.0, 15.0, 2, "analytic")
    assert isinstance(analyze_rotor(*args), BEMResult)
    axial = analyze_rotor(*args)
    one = analyze_rotor(*args, num_sectors=1, yaw=0.0)
    assert isinstance(one, BEMResult)  # all options at their defaults: the axial analysis itself
    tilted = analyze_rotor(*args, tilt=np.radians(30.0), num_sectors=6)
    assert isinstance(tilted, InclinedBEMResult) and tilted.alpha.shape == (6, 6)
    np.testing.assert_allclose(tilted.v_axial_local, 15.0 * np.cos(np.radians(30.0)), rtol=1e-14)  # no precone
    assert np.all(tilted.flow_state == 1) and tilted.thrust > 0.0
    four = analyze_rotor(*args, num_sectors=4)
    np.testing.assert_allclose(four.thrust, axial.thrust, rtol=1e-13)  # sectors of an axial flow are identical


@pytest.mark.parametrize("kwargs, match", [
    (dict(rotor_type="windmill"), "rotor_type"),
    (dict(yaw=2.0), "yaw"),
    (dict(shear_exponent=0.2), "hub_height"),
    (dict(shear_exponent=0.2, hub_height=5.0), "clear the ground"),
    (dict(num_sectors=0), "num_sectors"),
    (dict(yaw=1.2, rpm=5.0), "reverses the flow"),
    (dict(v_axial=0.0), "v_axial"),
])
def test_validation_one_line(kwargs, match):
    with pytest.raises(ValueError, match=match):
        _turbine(**kwargs)


def test_turbine_table():
    text = turbine_table(_turbine(v_axial=[8.0, 9.0], rpm=[45.0, 50.0], precone=0.04, tilt=0.08,
                                  hub_height=30.0, shear_exponent=0.14, num_sectors=4))
    lines = text.splitlines()
    assert len(lines) == 3 and "C_P [-]" in lines[0] and "TSR [-]" in lines[0]
    with pytest.raises(ValueError, match="turbine result"):
        turbine_table(object())
