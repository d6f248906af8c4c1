"""analyze_rotor: single case vs batch, result object, and input validation."""
import numpy as np
import pytest

from bild_mdo.bem import BEMResult, analyze_rotor, station_radii

NR = 12


@pytest.fixture(scope="module")
def case():
    radius, hub = 1.0, 0.15
    r = station_radii(radius, hub, NR)
    chord = 0.12 - 0.07 * (r - hub) / (radius - hub)
    twist = np.arctan(0.15 / r)  # constant-pitch blade, pitch 2 pi 0.15 m (hand choice)
    return dict(chord=chord, twist=twist, radius=radius, hub_radius=hub, rpm=2200.0, v_axial=20.0,
                num_blades=3)


def test_single_case_shapes_and_units(case, analytic_polar):
    res = analyze_rotor(polar=analytic_polar, **case)
    assert isinstance(res, BEMResult)
    assert np.shape(res.thrust) == () and res.phi.shape == (NR,)
    d = res.to_dict()
    assert set(d) == set(BEMResult.UNITS)
    assert BEMResult.UNITS["thrust"] == "N" and BEMResult.UNITS["dtorque_dr"] == "N*m/m"
    assert np.max(np.abs(res.residual)) < 1e-12
    # Positive-thrust propeller: 0 < eta < 1 (momentum theory bound).
    assert res.thrust > 0 and 0 < res.efficiency < 1
    # Sea-level ISA density (altitude defaults to 0).
    assert res.rho == pytest.approx(1.225, abs=1e-6)
    # The section coefficients are the polar's at the solved angle of attack and Reynolds number.
    polar_values = analytic_polar.evaluate(res.alpha, res.reynolds)
    np.testing.assert_allclose(res.lift_coefficient, polar_values.cl, rtol=1e-14)
    np.testing.assert_allclose(res.drag_coefficient, polar_values.cd, rtol=1e-14)


def test_batch_matches_single_cases(case, analytic_polar):
    v = np.array([0.0, 10.0, 20.0, 35.0])
    batch = analyze_rotor(polar=analytic_polar, **{**case, "v_axial": v})
    assert batch.thrust.shape == (4,) and batch.phi.shape == (4, NR)
    for i, vi in enumerate(v):
        single = analyze_rotor(polar=analytic_polar, **{**case, "v_axial": vi})
        assert single.thrust == pytest.approx(batch.thrust[i], rel=1e-13)
        assert single.torque == pytest.approx(batch.torque[i], rel=1e-13)
    # Same rotor, same rpm: thrust falls as the advance ratio rises (propeller physics).
    assert np.all(np.diff(batch.thrust) < 0)


def test_given_radii_without_widths_use_cell_widths(case, analytic_polar):
    r = station_radii(case["radius"], case["hub_radius"], NR)
    res = analyze_rotor(polar=analytic_polar, radii=r, **case)
    default = analyze_rotor(polar=analytic_polar, **case)
    # Midpoint stations: the cells between neighbouring midpoints are the equal annuli (hand).
    np.testing.assert_allclose(res.dr, default.dr, rtol=1e-12)
    assert res.thrust == pytest.approx(default.thrust, rel=1e-12)


def test_rho_mu_override(case, analytic_polar):
    res = analyze_rotor(polar=analytic_polar, rho=1.0, mu=1.5e-5, **case)
    assert res.rho == 1.0 and res.mu == 1.5e-5


@pytest.mark.parametrize("change, match", [
    (dict(radius=-1.0), "radius"),
    (dict(radius=0.1), "hub_radius must be smaller"),
    (dict(hub_radius=0.0), "hub_radius must be positive"),
    (dict(rpm=0.0), "rpm"),
    (dict(v_axial=-5.0), "v_axial"),
    (dict(chord=-np.ones(NR)), "chord"),
    (dict(twist=np.zeros(NR + 1)), "twist"),
    (dict(v_axial=np.zeros(3), rpm=np.ones(2) * 1000.0), "batch sizes disagree"),
    (dict(chord=np.full(NR, np.nan)), "chord must be a positive finite number"),
    (dict(num_blades=0), "num_blades"),
    (dict(altitude=20000.0), "altitude"),
    (dict(loss_model="glauert"), "loss_model"),
    (dict(radii=np.linspace(0.05, 0.9, NR)), "radii must be within"),
    (dict(dr=np.full(NR, 0.05)), "dr needs radii"),
    # Magnitudes far beyond any rotor would overflow the arithmetic (bem.analyze.PLAUSIBLE_RANGES).
    (dict(radius=1e300), "radius must be within 1e-06 ... 1e"),
    (dict(rpm=1e300), "rpm must be within"),
    (dict(rpm=1e-300), "rpm must be within"),
    (dict(v_axial=1e10), "v_axial must be within"),
    (dict(num_blades=10**300), "num_blades must be within"),
    (dict(twist=np.full(NR, 30.0)), "twist must be within"),
    (dict(collective_pitch=1e300), "collective_pitch must be within"),
    (dict(polar=42), "airfoil must be"),
])
def test_invalid_input_raises_value_error_naming_argument(case, analytic_polar, change, match):
    with pytest.raises(ValueError, match=match):
        analyze_rotor(**{"polar": analytic_polar, **case, **change})


def test_extreme_accepted_inputs_give_finite_numbers(case, analytic_polar, recwarn):
    # A hub of 1e-300 m makes the Prandtl hub exponent overflow unless it is capped (bem.prandtl):
    # the hub loss vanishes (F_hub = 1), as for a hub of zero size.
    res = analyze_rotor(polar=analytic_polar, **{**case, "hub_radius": 1e-300})
    tip_only = analyze_rotor(polar=analytic_polar, **{**case, "hub_radius": 1e-300, "loss_model": "tip"})
    assert np.isfinite(res.thrust) and res.thrust == pytest.approx(tip_only.thrust, rel=1e-9)
    assert not [w for w in recwarn if issubclass(w.category, RuntimeWarning)]


def test_airfoil_text_is_read_as_the_sweep_reads_it(case):
    # analyze_rotor takes the airfoil text of the verification sweep (bild_mdo.airfoil.text.sweep_polar): a
    # polar frozen at one Reynolds number and a spanwise set give, bit for bit, what the polars built from their
    # parts give (the text names that polar); text that names none is one ValueError.
    from bild_mdo.airfoil import FixedReynoldsPolar, resolve_polar, spanwise_polar

    frozen = FixedReynoldsPolar(resolve_polar("naca4412"), 2e6)
    spanwise = spanwise_polar([(0.5, resolve_polar("analytic")), (1.0, resolve_polar("naca4412"))])
    for text, polar in (("naca4412@re=2e6", frozen), ("0.5:analytic;1:naca4412", spanwise)):
        by_text = analyze_rotor(polar=text, **case)
        by_object = analyze_rotor(polar=polar, **case)
        assert np.isfinite(by_text.thrust) and by_text.thrust == by_object.thrust
        np.testing.assert_array_equal(by_text.dthrust_dr, by_object.dthrust_dr)
    # The frozen polar is not the Reynolds-dependent one (the stations run at Re 4e5-8e5 here, not 2e6).
    assert analyze_rotor(polar="naca4412@re=2e6", **case).thrust != analyze_rotor(polar="naca4412", **case).thrust
    with pytest.raises(ValueError, match="unknown airfoil"):
        analyze_rotor(polar="not-an-airfoil", **case)
