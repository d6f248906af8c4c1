"""examples/turbine_aep.py run small: the KKT conditions of the AEP optimum and its totals through the BILD design."""
import pathlib
import sys

import numpy as np
import pytest

from bild_mdo.energy.wind_speeds import region_sizes
from bild_mdo.utils.testing import assert_totals_match

ROOT = pathlib.Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from examples import turbine_aep  # noqa: E402

pytestmark = pytest.mark.filterwarnings("ignore:.*Reynolds numbers outside the tabulated range:UserWarning")

NUM_WIND_SPEEDS = 9


@pytest.fixture(scope="module")
def run():
    return turbine_aep.main(num_radial=10, verbose=False, num_wind_speeds=NUM_WIND_SPEEDS)


def test_the_optimum_meets_the_kkt_conditions(run):
    prob, start, best, success, _ = run
    assert success
    assert best["AEP (GWh)"] > start["AEP (GWh)"]
    # The thrust limit is active at rated (the curve's peak), not at the design wind speed.
    thrust = prob.get_val("curve.thrust")[0]
    rated = region_sizes(NUM_WIND_SPEEDS, tip_speed_limit=True)[0] - 1
    assert int(np.argmax(thrust)) == rated
    assert thrust[rated] == pytest.approx(turbine_aep.THRUST_LIMIT, rel=1e-6)
    # The design thrust is interior (so the multiplier below follows from its stationarity).
    low, high = turbine_aep.THRUST_BOUNDS
    assert low + 1e4 < best["design thrust (kN)"] * 1e3 < high - 1e4
    # The design tip-speed ratio sits at its upper bound (the tip-speed limit at the design wind speed).
    assert best["tip-speed ratio"] == pytest.approx(turbine_aep.TSR_BOUNDS[1], rel=1e-6)
    # Lagrangian stationarity: grad AEP = mu grad T_rated + nu e_rpm, with mu >= 0 (from the interior thrust_target)
    # and nu >= 0 (the multiplier of the rpm upper bound).
    totals = prob.compute_totals(of=["curve.annual_energy", "curve.thrust"], wrt=["rpm", "thrust_target"])
    mu = totals["curve.annual_energy", "thrust_target"][0, 0] / totals["curve.thrust", "thrust_target"][rated, 0]
    assert mu > 0.0
    nu = totals["curve.annual_energy", "rpm"][0, 0] - mu * totals["curve.thrust", "rpm"][rated, 0]
    scale = best["AEP (GWh)"] * 3.6e12 / prob.get_val("rpm")[0]
    assert nu > -1e-6 * scale


def test_tip_speed_limit_and_rated_power(run):
    prob, _, best, _, _ = run
    # Region 2.5 starts where the design tip-speed ratio reaches the limit: V = max tip speed / lambda; above it
    # the rotor turns at max tip speed / R (12.13 rpm, the NREL 5-MW rotor's 12.1 rpm).
    assert best["tip-speed limit from (m/s)"] == pytest.approx(
        turbine_aep.MAX_TIP_SPEED / best["tip-speed ratio"], rel=1e-9)
    omega_limit = turbine_aep.MAX_TIP_SPEED / turbine_aep.RADIUS * 30.0 / np.pi
    assert best["rotor speed at rated (rpm)"] == pytest.approx(omega_limit, rel=1e-9)
    # Between the limit and rated the blade runs below its design tip-speed ratio, so below its design C_P:
    # the curve's AEP is below the constant-C_P estimate, and its rated wind speed above.
    assert best["AEP (GWh)"] < best["AEP, constant C_P (GWh)"]
    assert best["rated wind speed (m/s)"] > prob.get_val("rated_wind_speed")[0]
    # Above rated the pitch holds rated power; the thrust falls as the blade feathers, to a pitch at cut-out of
    # the order of the NREL 5-MW rotor's 23 deg (NREL/TP-500-38060, Table 7-1).
    np.testing.assert_allclose(prob.get_val("curve.power")[0, -1], turbine_aep.RATED_POWER, rtol=1e-9)
    assert best["thrust at cut-out (kN)"] < 0.6 * best["peak thrust (kN)"]
    assert 10.0 < best["pitch at cut-out (deg)"] < 30.0


def test_aep_totals_through_the_model(run):
    prob = run[0]
    data = prob.check_totals(of=["curve.annual_energy", "curve.capacity_factor", "curve.thrust"],
                             wrt=["rpm", "radius", "thrust_target", "v_axial", "curve.rated_power",
                                  "curve.weibull_scale", "curve.weibull_shape", "curve.max_tip_speed"],
                             method="cs", out_stream=None)
    assert_totals_match(data, atol=1e-6, rtol=1e-6)
    data = prob.check_totals(of=["annual_energy", "capacity_factor"],
                             wrt=["rpm", "thrust_target", "aep.rated_power", "aep.weibull_scale"],
                             method="cs", out_stream=None)
    assert_totals_match(data, atol=1e-6, rtol=1e-6)


def test_printed_summary(capsys):
    turbine_aep.main(num_radial=6, num_wind_speeds=7)
    text = capsys.readouterr().out
    assert "tip-speed limit 80 m/s" in text and "AEP, constant C_P (GWh)" in text
    assert "Pitch-trimmed BEM power curve" in text and "rotor speed at rated (rpm)" in text
