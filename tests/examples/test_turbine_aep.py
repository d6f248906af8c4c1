"""examples/turbine_aep.py run small: an interior optimum of the AEP and its totals through the BILD design."""
import pathlib
import sys

import numpy as np
import pytest

from bild_mdo.utils.testing import assert_totals_match

ROOT = pathlib.Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from examples import turbine_aep  # noqa: E402

pytestmark = pytest.mark.filterwarnings("ignore:.*Reynolds numbers outside the tabulated range:UserWarning")


@pytest.fixture(scope="module")
def run():
    return turbine_aep.main(num_radial=10, verbose=False, num_wind_speeds=9)


def test_the_optimum_is_interior_and_stationary(run):
    prob, start, best, success, _ = run
    assert success
    low, high = turbine_aep.TSR_BOUNDS
    # Optimality (a first-order condition): inside its bounds the AEP's derivative in the rotor speed vanishes.
    assert low + 0.5 < best["tip-speed ratio"] < high - 0.5
    grad = prob.compute_totals(of=["annual_energy"], wrt=["rpm"])["annual_energy", "rpm"][0, 0]
    scale = best["AEP (GWh)"] * 3.6e12 / prob.get_val("rpm")[0]
    assert abs(grad) < 1e-4 * scale
    assert best["AEP (GWh)"] >= start["AEP (GWh)"]
    # The design meets its thrust limit (the member 'thrust' of the family) at the design wind speed.
    assert prob.get_val("thrust")[0] == pytest.approx(turbine_aep.THRUST_LIMIT, rel=1e-9)
    # Region 2 ends where the design's power reaches rated: 1/2 rho pi R^2 C_P V_r^3 = P_r.
    rho = prob.get_val("rho")[0]
    gain = 0.5 * rho * np.pi * turbine_aep.RADIUS ** 2 * best["C_P"]
    assert gain * best["rated wind speed (m/s)"] ** 3 == pytest.approx(turbine_aep.RATED_POWER, rel=1e-12)


def test_aep_totals_through_the_model(run):
    prob = run[0]
    data = prob.check_totals(of=["annual_energy", "capacity_factor"],
                             wrt=["rpm", "radius", "thrust_target", "v_axial", "aep.rated_power", "aep.weibull_scale",
                                  "aep.weibull_shape"], method="cs", out_stream=None)
    assert_totals_match(data, atol=1e-6, rtol=1e-6)


def test_pitch_trimmed_curve_summary(run, capsys):
    prob, _, best, _, _ = run
    # The BEM curve of a Reynolds-frozen polar has the design C_P at every region-2 wind speed, so its rated
    # wind speed and AEP are the constant-C_P model's (AnnualEnergyComp) to solver tolerance and to the error of
    # the 5-point Gauss-Lobatto sum of region 2 at this size (its convergence: tests/energy, cubic curve).
    assert best["rated wind speed, BEM (m/s)"] == pytest.approx(best["rated wind speed (m/s)"], rel=1e-9)
    assert best["AEP, BEM curve (GWh)"] == pytest.approx(best["AEP (GWh)"], rel=1e-5)
    # Physical expectations: the thrust peaks at rated and falls as the blade feathers; the pitch at cut-out is
    # of the order of the NREL 5-MW rotor's 23 deg (NREL/TP-500-38060, Table 7-1).
    assert best["peak thrust (kN)"] == best["thrust at rated (kN)"]
    assert best["thrust at cut-out (kN)"] < 0.5 * best["peak thrust (kN)"]
    assert 10.0 < best["pitch at cut-out (deg)"] < 30.0
    np.testing.assert_allclose(prob.get_val("curve.power")[0, -1], turbine_aep.RATED_POWER, rtol=1e-9)
    turbine_aep.main(num_radial=6, num_wind_speeds=7)
    text = capsys.readouterr().out
    assert "Pitch-trimmed BEM power curve" in text and "pitch at cut-out (deg)" in text
    assert "AEP, BEM curve (GWh)" in text and "peak thrust (kN)" in text


def test_bem_curve_aep_totals_through_the_model(run):
    prob = run[0]
    data = prob.check_totals(of=["curve.annual_energy", "curve.capacity_factor"],
                             wrt=["rpm", "radius", "thrust_target", "v_axial", "curve.rated_power",
                                  "curve.weibull_scale", "curve.weibull_shape"], method="cs", out_stream=None)
    assert_totals_match(data, atol=1e-6, rtol=1e-6)
