"""Airspeed sweeps: ``off_design_sweep(v_axial=[...])`` and ``bild-mdo analyze --v-axial START STOP N``.

Source: the definition of the advance ratio, J = V / (n D): a sweep of the airspeed at a fixed rotor speed is
the advance-ratio sweep at J = V / (n D), point for point.
"""
import numpy as np
import pytest

from bild_mdo.results.design import design_rotor
from bild_mdo.results.off_design import off_design_sweep
from tests.cli.runner import run

RPM = 6000.0
RADIUS = 0.2


@pytest.fixture(scope="module")
def propeller():
    return design_rotor(v_axial=20.0, rpm=RPM, radius=RADIUS, hub_radius_ratio=0.15, num_blades=2, thrust=25.0,
                        airfoil="analytic", bem_analysis=False)


def test_an_airspeed_sweep_is_the_advance_ratio_sweep_at_v_over_nd(propeller):
    speeds = np.array([5.0, 12.5, 20.0, 31.0])
    by_speed = off_design_sweep(propeller, v_axial=speeds, rpm=RPM)
    by_ratio = off_design_sweep(propeller, advance_ratios=speeds / (RPM / 60.0 * 2.0 * RADIUS), rpm=RPM)
    assert by_speed.sweep == "v_axial"
    np.testing.assert_array_equal(by_speed.v_axial, speeds)
    np.testing.assert_allclose(by_speed.advance_ratio, by_ratio.advance_ratio, rtol=1e-14)
    np.testing.assert_allclose(by_speed.thrust, by_ratio.thrust, rtol=1e-12)
    np.testing.assert_allclose(by_speed.power, by_ratio.power, rtol=1e-12)
    # The design point (20 m/s, 6000 rpm) is in the sweep: the BEM analysis of its own blade gives its thrust.
    assert by_speed.thrust[2] == pytest.approx(25.0, rel=1e-9)


def test_an_advance_ratio_sweep_takes_no_airspeed(propeller):
    with pytest.raises(ValueError, match="fixes the airspeed by J and rpm"):
        off_design_sweep(propeller, advance_ratios=[0.2, 0.4], v_axial=10.0)
    with pytest.raises(ValueError, match="at most one of"):
        off_design_sweep(propeller, rpms=[4000.0, 5000.0], v_axial=[10.0, 20.0])
    with pytest.raises(ValueError, match="v_axial"):
        off_design_sweep(propeller, v_axial=[-1.0, 10.0])


def test_cli_sweeps_the_airspeed(tmp_path, capsys, propeller):
    path = tmp_path / "prop.json"
    propeller.to_json(path)
    code, out, err = run(capsys, "analyze", str(path), "--v-axial", "10", "30", "3", "--csv", str(tmp_path / "p.csv"))
    assert code == 0, err
    rows = [line.split() for line in out.splitlines() if line.strip().startswith(("0.", "1."))]
    assert [float(row[1]) for row in rows] == [10.0, 20.0, 30.0]
    assert float(rows[1][3]) == pytest.approx(25.0, rel=1e-4)
    for arguments, message in ((("--v-axial", "10", "30"), "one value V [m/s] or three"),
                               (("--v-axial", "10", "30", "3", "--rpm", "4000", "6000", "3"), "without --advance"),
                               (("--advance-ratio", "0.2", "0.6", "3", "--v-axial", "10"), "fixes the airspeed")):
        code, _, err = run(capsys, "analyze", str(path), *arguments)
        assert code == 2 and message in err and "Traceback" not in err
