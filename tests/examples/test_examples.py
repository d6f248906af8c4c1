"""The examples, run small, with their key numbers and the paper's trends asserted.

Each example's ``main`` runs once per module (fixtures) at a reduced size:
fewer stations, fewer sweep points.  Figures go to pytest's ``tmp_path``.
"""
import pathlib
import sys

import numpy as np
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials

from bild_mdo.atmosphere import isa
from bild_mdo.utils.testing import assert_totals_match

ROOT = pathlib.Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from examples import design_sweeps, evtol_sizing, off_design, vahana_hover  # noqa: E402

try:
    import cyipopt  # noqa: F401
except ImportError:
    HAVE_IPOPT = False
else:
    HAVE_IPOPT = True

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def _is_png(path):
    path = pathlib.Path(path)
    return path.is_file() and path.stat().st_size > 10_000 and path.read_bytes()[:8] == PNG_SIGNATURE


# The built-in polar warns once when a Reynolds number leaves its table; not what these tests check.
pytestmark = pytest.mark.filterwarnings("ignore:.*Reynolds numbers outside the tabulated range:UserWarning")


# ---------------------------------------------------------------------------------------------- eVTOL sizing

@pytest.fixture(scope="module")
def sizing():
    return evtol_sizing.main(num_radial=8, verbose=False)


def test_evtol_sizing_converges_to_a_feasible_closed_design(sizing):
    prob = sizing.problem
    a = evtol_sizing.VehicleAssumptions()
    assert sizing.success, sizing.message
    assert 0 < sizing.model_evaluations < 200

    # Constraints of the problem statement (module docstring), to 1e-6 relative.
    margin = prob.get_val("thrust_margin")
    assert np.all(margin >= -1e-6)
    assert np.all(prob.get_val("tip_mach") <= np.array(a.tip_mach_limits) * (1.0 + 1e-6))
    for name, (lower, upper, units, _) in evtol_sizing.DESIGN_BOUNDS.items():
        value = prob.get_val(name, units=units)
        assert np.all(value >= lower * (1.0 - 1e-6)) and np.all(value <= upper * (1.0 + 1e-6)), name

    # Both thrust constraints are active: excess thrust only costs power, hence battery and motor mass.
    assert np.all(np.abs(margin) <= 1e-6)
    mass = prob.get_val("gross_mass", units="kg")[0]
    thrust = prob.get_val("thrust", units="N")
    assert thrust[0] * a.num_lift_rotors == pytest.approx(mass * evtol_sizing.GRAVITY, rel=1e-6)
    assert thrust[1] * a.lift_to_drag == pytest.approx(mass * evtol_sizing.GRAVITY, rel=1e-6)
    # Momentum theory: at fixed thrust the induced power falls with the disk area, so the lift rotor
    # takes the largest radius allowed.
    assert prob.get_val("radius", units="m")[0] == pytest.approx(evtol_sizing.DESIGN_BOUNDS["radius"][1][0],
                                                                 rel=1e-6)


def test_evtol_sizing_mass_closure_and_energy_bookkeeping(sizing):
    prob = sizing.problem
    a = evtol_sizing.VehicleAssumptions()

    def val(name, units=None):
        return prob.get_val(name, units=units)

    mass = val("gross_mass", "kg")[0]
    battery, motors = val("battery_mass", "kg")[0], val("motor_mass", "kg")[0]
    # The closure equation m = m_payload + f_s m + m_battery + m_motors (module docstring), solved by Newton.
    assert mass == pytest.approx(a.payload_mass + a.structural_mass_fraction * mass + battery + motors, rel=1e-12)
    # Hand bookkeeping from the BILD shaft powers (module docstring formulas).
    power = val("power", "W")
    p_hover = a.num_lift_rotors * power[0] / a.drivetrain_efficiency
    p_cruise = power[1] / a.drivetrain_efficiency
    energy = a.hover_time * p_hover + a.cruise_range / a.cruise_speed * p_cruise
    assert val("mission_energy", "J")[0] == pytest.approx(energy, rel=1e-12)
    assert battery == pytest.approx(energy / (a.battery_specific_energy * a.battery_usable_fraction), rel=1e-12)
    assert motors == pytest.approx((a.num_lift_rotors * power[0] + power[1]) / a.motor_specific_power, rel=1e-12)
    # Momentum theory bounds every rotor's shaft power from below (actuator disk, hand derivation):
    # hover P >= T sqrt(T / (2 rho A)); cruise P >= T V / eta_ideal, eta_ideal = 2 / (1 + sqrt(1 + T / (q A))).
    thrust, radius = val("thrust", "N"), val("radius", "m")
    area = np.pi * radius**2
    rho = isa(np.array([0.0, a.cruise_altitude])).rho
    assert power[0] > thrust[0] * np.sqrt(thrust[0] / (2.0 * rho[0] * area[0]))
    froude = 2.0 / (1.0 + np.sqrt(1.0 + thrust[1] / (0.5 * rho[1] * a.cruise_speed**2 * area[1])))
    assert power[1] > thrust[1] * a.cruise_speed / froude


def test_evtol_sizing_total_derivatives_at_optimum(sizing):
    prob = sizing.problem
    assert_no_approx_partials(prob.model, include_self=True, recurse=True)
    # Through BILD, the Newton-solved closure and every sizing component, against complex step.
    data = prob.check_totals(method="cs", out_stream=None)
    assert_totals_match(data, atol=1e-8, rtol=1e-8)


@pytest.mark.skipif(not HAVE_IPOPT, reason="cyipopt not installed")
def test_evtol_sizing_ipopt_finds_the_slsqp_optimum(sizing):
    other = evtol_sizing.main(num_radial=8, optimizer="ipopt", verbose=False)
    assert other.success, other.message
    # Two independent optimisers agree on the optimum (a converged, well-posed problem).
    assert other.optimum["gross_mass"][0] == pytest.approx(sizing.optimum["gross_mass"][0], rel=1e-6)
    for name in ("radius", "rpm", "ref_chord"):
        np.testing.assert_allclose(other.optimum[name], sizing.optimum[name], rtol=1e-5)


# ---------------------------------------------------------------------------------------------- Vahana hover

@pytest.fixture(scope="module")
def vahana(tmp_path_factory):
    path = tmp_path_factory.mktemp("vahana") / "vahana_hover.png"
    return vahana_hover.main(num_radial=10, figure_path=path, verbose=False)


def test_vahana_rotor_carries_its_share_of_the_weight(vahana):
    # Paper Sec. 5.1: 725 kg Airbus Vahana; eight rotors share the weight in hover.
    required = 725.0 * 9.80665 / 8
    assert vahana_hover.REQUIRED_THRUST == pytest.approx(required, rel=1e-15)
    assert vahana.bild["thrust"] == pytest.approx(required, rel=1e-8)
    # The optimisation's equality constraint T = T_BILD (optimize_rotor's THRUST_TOLERANCE = 1e-6).
    assert vahana.optimization.converged, vahana.optimization.status
    assert vahana.optimized["thrust"] == pytest.approx(required, rel=1e-6)
    # BILD's chord at the reference station is the solved reference chord (Algorithm 1, step 1).
    x = vahana.bild["radii"] / vahana_hover.RADIUS
    assert np.interp(vahana_hover.REF_RADIUS_RATIO, x, vahana.bild["chord"]) == pytest.approx(vahana.ref_chord,
                                                                                              rel=2e-2)


def test_vahana_bild_matches_the_full_bem_optimum(vahana):
    b, o = vahana.bild, vahana.optimized
    # The brief's 1 % (paper Table 3 reports C_P and eta within 0.2 % on average); measured 6.5e-5 here.
    assert o["energy_loss"] == pytest.approx(b["energy_loss"], rel=1e-2)
    # Paper Sec. 5.1: the optimised C_l is nearly constant along the span away from hub and tip, as BILD
    # assumes (Assumption 2); measured spread 0.14 % over 0.3 < r/R < 0.9.
    x = o["radii"] / vahana_hover.RADIUS
    mid = (x > 0.3) & (x < 0.9)
    lift = o["lift_coefficient"][mid]
    assert np.std(lift) / np.mean(lift) < 0.01
    # BILD's sections all work at C_l* (Assumption 2).
    np.testing.assert_allclose(b["lift_coefficient"], b["lift_coefficient"][0], rtol=1e-12)
    assert _is_png(vahana.figure_path)


# ---------------------------------------------------------------------------------------------- design sweeps

@pytest.fixture(scope="module")
def sweeps(tmp_path_factory):
    out = tmp_path_factory.mktemp("sweeps")
    return design_sweeps.main(num_radial=12, num_ref_chords=4, num_ref_radii=3, output_dir=out, verbose=False)


def test_design_sweeps_one_bild_run_per_figure(sweeps):
    assert sweeps["fig6"].num_designs == 4 * 1 * 4
    assert sweeps["fig7"].num_designs == 4 * 1 * 4
    assert sweeps["fig8"].num_designs == 4 * 3 * 4
    for path in sweeps["figures"].values():
        assert _is_png(path)


def test_design_sweeps_blade_shapes_follow_the_paper(sweeps):
    s6 = sweeps["fig6"]
    x = s6.radii[:, 0] / design_sweeps.RADIUS
    chord = s6.chord[:, 0]
    i_max = np.argmax(chord, axis=-1)
    x_max = np.take_along_axis(x, i_max[..., None], axis=-1)[..., 0]
    # Paper Sec. 5.2.1: in hover the chord is largest near the hub and falls towards the tip ...
    assert np.all(x_max[0] < 0.4)
    for k in range(s6.ref_chords.size):
        assert np.all(np.diff(chord[0, k, i_max[0, k]:]) < 0.0)
    # ... and as J grows the maximum moves outboard and the root chord becomes small.
    assert np.all(np.diff(x_max, axis=0) > 0.0)
    root_over_max = chord[..., 0] / chord.max(axis=-1)
    assert np.all(root_over_max[0] > 0.5)
    assert np.all(root_over_max[1:] < 0.35)
    # Paper Sec. 5.2.1: in hover the twist falls from the root to 10 ... 20 deg at the tip.
    tip_twist = np.degrees(s6.twist[0, 0, :, -1])
    assert np.all((tip_twist > 10.0) & (tip_twist < 20.0))
    assert np.all(s6.twist[0, 0, :, 0] > s6.twist[0, 0, :, -1])


def test_design_sweeps_root_chord_correction(sweeps):
    s6, s7 = sweeps["fig6"], sweeps["fig7"]
    # Paper Sec. 5.2.2: the correction raises the thin root chord of forward-flight designs ...
    assert np.all(s7.chord[1:, 0, :, 0] > 1.2 * s6.chord[1:, 0, :, 0])
    # ... to at least the reference chord's weight in Eq. (32), exp(-k r/R) c_ref (the back-computed part
    # is positive).
    weight = np.exp(-design_sweeps.ROOT_CHORD_CORRECTION * s7.radii[1:, 0, :, 0] / design_sweeps.RADIUS)
    assert np.all(s7.chord[1:, 0, :, 0] > weight * s7.ref_chords)
    # ... and changes neither the twist nor the ideal loads.
    np.testing.assert_array_equal(s7.twist, s6.twist)
    np.testing.assert_array_equal(s7.thrust, s6.thrust)
    np.testing.assert_array_equal(s7.chord_raw, s6.chord)


def test_design_sweeps_performance_trends(sweeps):
    s8 = sweeps["fig8"]
    # Paper Sec. 5.2.3: thrust and torque grow with c_ref for every J and r_ref ...
    assert np.all(np.diff(s8.thrust, axis=-1) > 0.0)
    assert np.all(np.diff(s8.torque, axis=-1) > 0.0)
    # ... and in forward flight the efficiency falls with it.
    assert np.all(np.diff(s8.efficiency[1:], axis=-1) < 0.0)
    # Hover has no propulsive efficiency (eta = V T / P, Table 2).
    np.testing.assert_array_equal(s8.efficiency[0], 0.0)


# ---------------------------------------------------------------------------------------------- off-design

@pytest.fixture(scope="module")
def off(tmp_path_factory):
    path = tmp_path_factory.mktemp("off_design") / "off_design.png"
    return off_design.main(num_radial=12, num_points=60, figure_path=path, verbose=False)


def test_off_design_reproduces_bild_at_the_design_point(off):
    for curve in off["curves"]:
        # Same blade, same operating point: only the polar model differs (BILD: max-L/D point at the
        # reference Reynolds number everywhere; BEM: each station's own).  Measured 0.03 ... 0.19 %.
        assert curve.design_efficiency == pytest.approx(curve.bild_efficiency, rel=3e-3)
    assert _is_png(off["figure_path"])


def test_off_design_maximum_efficiency_beyond_the_design_point(off):
    widths = []
    for curve in off["curves"]:
        # Paper Sec. 5.2.3 (Fig. 9): every rotor's maximum efficiency is above its design-point efficiency,
        # reached at a higher advance ratio, and above 80 %.
        assert curve.max_efficiency > curve.design_efficiency + 1e-3
        assert curve.max_efficiency_advance_ratio > curve.design_advance_ratio
        assert curve.max_efficiency > 0.8
        low, high = off_design.efficiency_range(curve, 0.8)
        widths.append(high - low)
    # Paper Sec. 5.2.3: rotors designed for higher J keep eta >= 0.8 over a wider range of J.
    assert np.all(np.diff(widths) > 0.0)
