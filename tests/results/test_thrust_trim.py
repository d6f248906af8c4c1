"""Off-design sweeps trimmed to a thrust: ``off_design_sweep(..., thrust=T, trim=...)`` and ``analyze --thrust``.

Sources: invariants.  At the design point the blade BILD designed for T* needs no trim (pitch 0, its own rpm):
with a Reynolds-independent polar its BEM analysis gives T* there (see test_design_analysis).  Every trimmed
point meets T* to the trim's tolerance; thrust rises with pitch in attached flow, so a faster airspeed needs
more pitch (a hand argument: the inflow angle grows with V at a fixed rotor speed).
"""
import numpy as np
import pytest

from bild_mdo.results.design import design_rotor
from bild_mdo.results.off_design import off_design_sweep
from bild_mdo.results.thrust_trim import THRUST_RTOL
from tests.cli.runner import run


@pytest.fixture(scope="module")
def propeller():
    return design_rotor(v_axial=20.0, rpm=6000.0, radius=0.2, hub_radius_ratio=0.15, num_blades=2, thrust=25.0,
                        airfoil="analytic", bem_analysis=False)


def test_pitch_trim_over_an_airspeed_sweep(propeller):
    sweep = off_design_sweep(propeller, v_axial=[10.0, 20.0, 30.0], thrust=25.0)
    np.testing.assert_allclose(sweep.thrust, 25.0, rtol=10 * THRUST_RTOL)
    assert abs(sweep.collective_pitch[1]) < 1e-9  # the design point needs no trim
    assert np.all(np.diff(sweep.collective_pitch) > 0.0)


def test_rpm_trim_and_an_unreachable_thrust(propeller):
    sweep = off_design_sweep(propeller, v_axial=[10.0, 20.0], thrust=25.0, trim="rpm")
    np.testing.assert_allclose(sweep.thrust, 25.0, rtol=10 * THRUST_RTOL)
    assert sweep.rpm[1] == pytest.approx(6000.0, rel=1e-9)
    far = off_design_sweep(propeller, thrust=1e6)
    assert far.status[0].startswith("thrust 1e+06 N not reached") and np.isnan(far.thrust[0])
    with pytest.raises(ValueError, match="sets each point's rpm"):
        off_design_sweep(propeller, advance_ratios=[0.4], thrust=25.0, trim="rpm")
    with pytest.raises(ValueError, match="give no pitch sweep"):
        off_design_sweep(propeller, collective_pitch=[0.0, 0.1], thrust=25.0)


def test_cli_trims_to_a_thrust(tmp_path, capsys, propeller):
    path = tmp_path / "prop.json"
    propeller.to_json(path)
    code, out, err = run(capsys, "analyze", str(path), "--thrust", "30", "--airfoil", "analytic")
    assert code == 0, err
    row = next(line.split() for line in out.splitlines() if line.strip().startswith("0.5000"))
    assert float(row[4]) == pytest.approx(30.0, rel=1e-4)  # J, V, rpm, pitch, T
    code, _, err = run(capsys, "analyze", str(path), "--thrust", "-3")
    assert code == 2 and "--thrust must be a positive" in err
