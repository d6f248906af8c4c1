"""BILDGroup: exact totals, the invariants of the method, and the trends of the paper's Sec. 5.2."""
import warnings

import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.bem.analyze import analyze_rotor
from bild_mdo.bild import BILDGroup
from bild_mdo.utils.testing import assert_totals_match, check_group_totals

# Midpoints of 12 equal annuli from r/R = 0.2 put station 4 at r/R = 0.2 + 4.5 * 0.8/12 = 0.5 (hand derivation).
NR_REF = 12
REF_STATION = 4
OPERATING = {
    "hover": dict(v_axial=[0.0, 0.0, 0.0]),
    "cruise": dict(v_axial=[10.0, 25.0, 40.0]),
}
TOTALS_OF = ["thrust", "torque", "energy_loss", "efficiency", "figure_of_merit", "chord", "twist"]
TOTALS_WRT = ["v_axial", "rpm", "radius", "ref_chord", "ref_radius_ratio", "altitude", "hub_radius_ratio"]


def _problem(kind, num_radial=NR_REF, mode="auto", complex_step=False, values=None, **options):
    prob = om.Problem(BILDGroup(num_nodes=3, num_radial=num_radial, **options), reports=False)
    prob.setup(mode=mode, force_alloc_complex=complex_step)
    settings = dict(OPERATING[kind], ref_chord=[0.1, 0.2, 0.3], rpm=[800.0, 900.0, 1000.0],
                    altitude=[0.0, 1000.0, 2500.0])
    if options.get("input_mode") == "advance_ratio":
        settings.pop("v_axial")
    settings.update(values or {})
    for name, value in settings.items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


@pytest.mark.parametrize("mode", ["fwd", "rev"])
def test_totals_complex_step(kind, mode):
    # Both implicit components apply a complex Newton update after their real solve, so complex step
    # through the whole chain is exact; the analytic totals must match it to round-off.
    prob = _problem(kind, mode=mode, complex_step=True)
    data = prob.check_totals(of=TOTALS_OF, wrt=TOTALS_WRT, method="cs", out_stream=None)
    assert_totals_match(data, atol=1e-10, rtol=1e-6)
    analytic = "J_fwd" if mode == "fwd" else "J_rev"
    worst = max(np.max(np.abs(d[analytic] - d["J_fd"])) / max(np.max(np.abs(d["J_fd"])), 1e-300)
                for d in data.values())
    assert worst < 1e-9  # measured ~3e-13
    assert_no_approx_partials(prob.model, method="cs")
    assert_no_approx_partials(prob.model, method="fd")


def test_totals_advance_ratio_mode():
    values = dict(advance_ratio=[0.25, 0.6, 1.0], ref_chord=[0.1, 0.2, 0.3], rpm=[800.0, 900.0, 1000.0],
                  altitude=[0.0, 1000.0, 2500.0])
    check_group_totals(lambda: BILDGroup(num_nodes=3, num_radial=NR_REF, input_mode="advance_ratio"),
                       of=["thrust", "efficiency", "chord", "twist"], wrt=["advance_ratio", "rpm", "radius"],
                       values=values, atol=1e-10, rtol=1e-6)


def test_advance_ratio_mode_matches_v_axial(kind):
    # Table 2: V_x = J n D.
    v_axial = np.array(OPERATING[kind]["v_axial"])
    rpm = np.array([800.0, 900.0, 1000.0])
    direct = _problem(kind)
    via_j = _problem(kind, input_mode="advance_ratio", values=dict(advance_ratio=v_axial / (rpm / 60.0 * 3.0)))
    for name in ("thrust", "torque", "chord", "twist"):
        np.testing.assert_allclose(via_j.get_val(name), direct.get_val(name), rtol=1e-12, atol=1e-14)


@pytest.mark.parametrize("num_radial, station", [(NR_REF, REF_STATION), (20, 7)])
def test_chord_at_reference_radius_is_reference_chord(kind, num_radial, station):
    # Physical invariant of Algorithm 1: the BEM solve at r_ref used c_ref, so the back-computed chord
    # there is c_ref (r/R = 0.5 is station 7 of 20 equal annuli from 0.2: 0.2 + 7.5 * 0.04).
    prob = _problem(kind, num_radial=num_radial)
    np.testing.assert_allclose(prob.get_val("radii")[:, station] / prob.get_val("radius"), 0.5, rtol=1e-14)
    np.testing.assert_allclose(prob.get_val("chord")[:, station], [0.1, 0.2, 0.3], rtol=1e-9)


def test_chord_at_reference_radius_with_user_stations():
    fractions = np.array([0.25, 0.35, 0.5, 0.7, 0.9])
    widths = np.array([0.1, 0.1, 0.2, 0.2, 0.2])
    prob = _problem("cruise", num_radial=5, radial_fractions=fractions, width_fractions=widths)
    np.testing.assert_allclose(prob.get_val("chord")[:, 2], [0.1, 0.2, 0.3], rtol=1e-9)


def test_bem_analysis_reproduces_bild(kind):
    # With a Reynolds-independent polar the blade elements of the BILD blade work exactly at alpha*, and
    # Eq. (25) makes the BEM residual vanish at BILD's inflow angle: a BEM analysis of the BILD
    # geometry must return BILD's loads (measured ~1e-14 relative).
    polar = AnalyticPolar()
    prob = _problem(kind, polar=polar)
    result = analyze_rotor(prob.get_val("chord"), prob.get_val("twist"), prob.get_val("radius"),
                           prob.get_val("hub_radius"), prob.get_val("rpm"), prob.get_val("v_axial"), 3, polar,
                           altitude=prob.get_val("altitude"))
    np.testing.assert_allclose(result.thrust, prob.get_val("thrust"), rtol=1e-6)
    np.testing.assert_allclose(result.torque, prob.get_val("torque"), rtol=1e-6)
    np.testing.assert_allclose(result.phi, prob.get_val("phi"), atol=1e-9)


def test_torque_form_gives_the_same_chord(kind):
    # Eq. (31) and the torque form of Eq. (6) agree because Eq. (26) solves Eq. (25).
    thrust_form = _problem(kind)
    torque_form = _problem(kind, chord_form="torque")
    np.testing.assert_allclose(torque_form.get_val("chord"), thrust_form.get_val("chord"), rtol=1e-9)


def test_energy_loss_is_power_minus_useful_power(kind):
    # Eq. (12) integrated: E = Omega Q - V_x T, and sum(dE/dr dr) equals it.
    prob = _problem(kind)
    energy = np.sum(prob.get_val("denergy_loss_dr") * prob.get_val("dr"), axis=1)
    np.testing.assert_allclose(prob.get_val("energy_loss"), energy, rtol=1e-12)
    omega = prob.get_val("rpm") * np.pi / 30.0
    thrust_power = prob.get_val("v_axial") * prob.get_val("thrust")
    np.testing.assert_allclose(energy, omega * prob.get_val("torque") - thrust_power, rtol=1e-12)


def test_root_chord_correction_changes_only_the_chord():
    # Sec. 5.2.2: Eq. (32) only touches the chord; twist and the ideal loads stay.
    plain = _problem("cruise")
    corrected = _problem("cruise", root_chord_correction=10.0)
    for name in ("twist", "thrust", "torque", "chord_raw"):
        np.testing.assert_allclose(corrected.get_val(name), plain.get_val(name), rtol=1e-14)
    raw, chord = plain.get_val("chord"), corrected.get_val("chord")
    # The small forward-flight root chord (Fig. 6) moves towards c_ref; the tip hardly changes.
    assert np.all(chord[:, 0] > raw[:, 0]) and np.all(chord[:, 0] < np.array([0.1, 0.2, 0.3]))
    np.testing.assert_allclose(chord[:, -1], raw[:, -1], rtol=1e-3)


def test_unloaded_stations_in_hover_have_zero_chord():
    # Hover with a low L/D airfoil (cd0 = k = 0.05 gives L/D = 14.8) and a tiny reference chord:
    # lambda < V_theta C_d / (2 C_l) at the tip, so the outer station is unloaded (eta2 = 1, zero chord),
    # with finite values and exact totals.
    prob = om.Problem(BILDGroup(num_nodes=2, num_radial=NR_REF, polar=AnalyticPolar(cd0=0.05, k=0.05)),
                      reports=False)
    prob.setup(force_alloc_complex=True)
    prob.set_val("ref_chord", [0.002, 0.005])
    prob.run_model()
    assert prob.get_val("eta2")[0, -1] == 1.0 and prob.get_val("chord")[0, -1] == 0.0
    for name in ("chord", "twist", "thrust", "torque", "figure_of_merit"):
        assert np.all(np.isfinite(prob.get_val(name)))
    data = prob.check_totals(of=["thrust", "chord", "twist"], wrt=["ref_chord", "rpm"], method="cs",
                             out_stream=None)
    assert_totals_match(data, atol=1e-10, rtol=1e-6)


@pytest.mark.parametrize("chord_form", ["thrust", "torque"])
def test_windmilling_inboard_station_is_reported_with_its_remedy(chord_form):
    # C_l*/C_d* = 3.69 (cd0 = k = 0.2) at J = 3: the innermost of 12 annuli from r/R = 0.2 (r/R = 0.233,
    # V_theta = 29.3 m/s) needs V_x < eta2 V_theta C_l*/C_d* ~ 102 m/s but V_x = J n D = 120 m/s (hand).
    # Both chord forms must stop at the induced velocities (the torque form used to return a windmilling
    # station with dT/dr < 0, the thrust form a ChordComp error naming no station).
    def run(hub_radius_ratio):
        prob = om.Problem(BILDGroup(num_nodes=1, num_radial=NR_REF, polar=AnalyticPolar(cd0=0.2, k=0.2),
                                    input_mode="advance_ratio", chord_form=chord_form), reports=False)
        prob.setup()
        prob.set_val("advance_ratio", [3.0])
        prob.set_val("ref_chord", [0.1])
        prob.set_val("hub_radius_ratio", [hub_radius_ratio])
        prob.run_model()
        return prob

    with pytest.raises(om.AnalysisError, match=r"(?s)BILD: 1 of 1 node.*u_axial > V_x.*"
                                               r"needs V_x < eta2 V_theta C_l\*/C_d\*.*hub_radius_ratio.*"
                                               r"node 0, station 0 \("):
        run(0.2)
    # The suggested remedy works: from r/R = 0.35 on, V_theta >= 47 m/s and every station produces thrust.
    prob = run(0.35)
    assert np.all(prob.get_val("dthrust_dr") > 0.0) and np.all(prob.get_val("chord") > 0.0)


def test_hover_rotor_without_a_loaded_station_raises():
    # Two stations at r/R = 0.4 and 0.8 with r_ref/R = 0.21 and a tiny c_ref: lambda < V_theta / (2 L/D) at both,
    # so no station is loaded (eta2 = 1), T = Q = 0 and the efficiency / figure of merit would be 0/0.
    prob = om.Problem(BILDGroup(num_nodes=1, num_radial=2, polar=AnalyticPolar(cd0=0.05, k=0.05)), reports=False)
    prob.setup()
    prob.set_val("ref_chord", [2e-4])
    prob.set_val("ref_radius_ratio", [0.21])
    with pytest.raises(om.AnalysisError, match=r"(?s)BILD: 1 of 1 node.*no station can be loaded.*zero torque"):
        prob.run_model()


def test_invalid_options():
    with pytest.raises(ValueError, match="polar"):
        BILDGroup(polar="naca4412")
    with pytest.raises(ValueError, match="root_chord_correction"):
        BILDGroup(root_chord_correction=-1.0)


# ---------------------------------------------------------------------------------------------------
# Trends of the paper's Sec. 5.2: R = 1.5 m, B = 3, 800 rpm, r_ref = 0.5 R, c_ref = 0.1 ... 0.4 m, NACA 4412,
# hub at 0.2 R.  The paper uses Prandtl's tip loss ("tip"), stated in Sec. 3.
C_REF = np.array([0.1, 0.2, 0.3, 0.4])


def _sweep(advance_ratio):
    prob = om.Problem(BILDGroup(num_nodes=4, num_radial=20, input_mode="advance_ratio", loss_model="tip"),
                      reports=False)
    prob.setup()
    prob.set_val("advance_ratio", np.full(4, advance_ratio))
    prob.set_val("ref_chord", C_REF)
    with warnings.catch_warnings():
        # Above Re = 2e6 the built-in NACA 4412 table is clamped (the polar warns); harmless here.
        warnings.simplefilter("ignore", UserWarning)
        prob.run_model()
    return prob


@pytest.fixture(scope="module")
def sweeps():
    return {j: _sweep(j) for j in (0.0, 1.0, 2.0)}


def test_fig6_hover_chord_and_twist(sweeps):
    prob = sweeps[0.0]
    chord = prob.get_val("chord")
    twist = np.degrees(prob.get_val("twist"))
    # Fig. 6, J = 0: the chord is largest at the hub and falls towards the tip (measured c_root/c_ref 1.5-2.0).
    assert np.all(np.argmax(chord, axis=1) == 0)
    assert np.all(np.diff(chord, axis=1) < 0.0)
    assert np.all(chord[:, 0] > 1.4 * C_REF)
    # Fig. 6, J = 0: twist from about 30 deg at the root to 10-20 deg at the tip (measured 23-32 -> 10.5-12.5),
    # and both rise with c_ref.
    assert np.all((twist[:, 0] > 20.0) & (twist[:, 0] < 35.0))
    assert np.all((twist[:, -1] > 10.0) & (twist[:, -1] < 20.0))
    assert np.all(np.diff(twist, axis=1) < 0.0)
    assert np.all(np.diff(twist[:, 0]) > 0.0) and np.all(np.diff(twist[:, -1]) > 0.0)


def test_fig6_forward_flight_root_chord_and_twist(sweeps):
    hover = sweeps[0.0]
    for j in (1.0, 2.0):
        chord = sweeps[j].get_val("chord")
        # Fig. 6, J > 0: the root chord becomes small (measured c_root/c_ref 0.27-0.66) and the maximum chord
        # moves away from the hub, out to about the reference station (index 7) and beyond.
        assert np.all(chord[:, 0] < 0.7 * C_REF)
        assert np.all(np.argmax(chord, axis=1) >= 6)
    # Fig. 6: the blade is more twisted as J grows (every station, every c_ref).
    twists = [np.degrees(sweeps[j].get_val("twist")) for j in (0.0, 1.0, 2.0)]
    assert np.all(twists[1] > twists[0] + 10.0) and np.all(twists[2] > twists[1] + 10.0)
    assert np.argmax(hover.get_val("chord")[0]) == 0


def test_fig8_performance_against_reference_chord(sweeps):
    for j, prob in sweeps.items():
        # Fig. 8: thrust and torque grow with c_ref at every advance ratio.
        assert np.all(np.diff(prob.get_val("thrust")) > 0.0)
        assert np.all(np.diff(prob.get_val("torque")) > 0.0)
        if j > 0.0:
            # Fig. 8: efficiency falls with c_ref in forward flight (measured 0.91 -> 0.78 at J = 1).
            assert np.all(np.diff(prob.get_val("efficiency")) < 0.0)
            assert 0.85 < prob.get_val("efficiency")[0] < 0.95
    # Fig. 8, hover: the figure of merit falls with c_ref from 0.2 m on (measured 0.861 -> 0.843); below that
    # profile drag of the lightly loaded rotor dominates and FM rises with c_ref (0.853 at 0.1 m), also with a
    # Reynolds-independent polar, so the paper's monotone fall is not reproduced over the full range.
    fm = sweeps[0.0].get_val("figure_of_merit")
    assert np.all(np.diff(fm[1:]) < 0.0)
    assert np.all((fm > 0.8) & (fm < 0.9))


def _infeasible_batch(on_infeasible):
    # AnalyticPolar(cd0=0.2, k=0.2): C_l*/C_d* = 3.69.  Node 0 windmills at its innermost station (see
    # test_windmilling_inboard_station_is_reported_with_its_remedy); node 1 is the same point with the remedy
    # hub_radius_ratio = 0.35.  Node 2 hovers with c_ref = 0.1 mm at r_ref/R = 0.201, inboard of every station:
    # lambda <= V_theta C_d*/(2 C_l*) everywhere, so no station is loaded and Q = 0.  Node 3 (J = 3, c_ref = 0.5 m
    # at r_ref/R = 0.3) has u_axial_ref < V_x at the reference station (Assumption 3).  Node 4: J = 1, feasible.
    prob = om.Problem(BILDGroup(num_nodes=5, num_radial=NR_REF, polar=AnalyticPolar(cd0=0.2, k=0.2),
                                input_mode="advance_ratio", on_infeasible=on_infeasible), reports=False)
    prob.setup()
    for name, value in dict(advance_ratio=[3.0, 3.0, 0.0, 3.0, 1.0], ref_chord=[0.1, 0.1, 1e-4, 0.5, 0.1],
                            hub_radius_ratio=[0.2, 0.35, 0.2, 0.2, 0.2],
                            ref_radius_ratio=[0.5, 0.5, 0.201, 0.3, 0.5]).items():
        prob.set_val(name, value)
    return prob


def test_one_error_names_every_infeasible_node_with_its_reason():
    prob = _infeasible_batch("raise")
    with pytest.raises(om.AnalysisError) as info:
        prob.run_model()
    message = str(info.value)
    assert "3 of 5 node(s) infeasible" in message
    assert "u_axial_ref > V_x fails" in message and "node(s) 3 [" in message
    assert "no station can be loaded" in message and "node(s) 2 [" in message
    assert "u_axial > V_x, positive local thrust" in message and "node(s) 0 [node 0, station 0 (" in message


def test_flagged_nodes_leave_the_feasible_ones_unchanged():
    prob = _infeasible_batch("flag")
    prob.run_model()
    np.testing.assert_array_equal(prob.get_val("feasible"), [0.0, 1.0, 0.0, 0.0, 1.0])
    assert list(prob.model.feasibility.status() == "ok") == [False, True, False, False, True]
    alone = om.Problem(BILDGroup(num_nodes=2, num_radial=NR_REF, polar=AnalyticPolar(cd0=0.2, k=0.2),
                                 input_mode="advance_ratio"), reports=False)
    alone.setup()
    for name, value in dict(advance_ratio=[3.0, 1.0], ref_chord=[0.1, 0.1], hub_radius_ratio=[0.35, 0.2],
                            ref_radius_ratio=[0.5, 0.5]).items():
        alone.set_val(name, value)
    alone.run_model()
    for name in ("thrust", "power", "chord", "twist", "eta2", "dtorque_dr"):
        assert np.array_equal(prob.get_val(name)[[1, 4]], alone.get_val(name)), name
