"""How a design analyses: the BEM analysis of its own blade beside the design's numbers.

Sources: invariants of the BEM model.  A BILD design is a BEM state of its own blade wherever the design
evaluates each station as the analysis does (the BEM annuli are independent and the design's inflow angle,
section point and loads satisfy the same momentum and blade-element equations): with a Reynolds-independent
polar, or with the local section point, the analysis returns the design's thrust and power to round-off.
With the paper's reference section point and a Reynolds-dependent polar it does not (Assumption 2 runs every
station at the reference Reynolds number).
"""
import numpy as np
import pytest

from bild_mdo.results.design import design_rotor

#: A small UAV propeller: 2 blades, R = 0.2 m, 6000 rpm, 20 m/s, 25 N; its stations run at Re 1.5e4 ... 1.2e5.
UAV = dict(v_axial=20.0, rpm=6000.0, radius=0.2, hub_radius_ratio=0.15, num_blades=2, thrust=25.0)


@pytest.mark.parametrize("options", [
    dict(airfoil="naca4412@re=1e6"),
    dict(airfoil="naca4412@re=1e6", ideal_loading="exact"),
    dict(section_point="local"),
    dict(section_point="local", ideal_loading="exact"),
])
def test_consistent_designs_analyse_at_their_own_thrust_and_power(options):
    result = design_rotor(advance_ratio=[0.0, 0.5, 1.0], ref_chord=0.12, **options)
    np.testing.assert_allclose(result.bem_thrust, result.thrust, rtol=1e-10)
    np.testing.assert_allclose(result.bem_power, result.power, rtol=1e-10)
    assert np.all(result.bem_invalid_stations == 0)


def test_unloaded_stations_are_left_out_of_the_analysis():
    # The Reynolds-aware exact loading leaves an annulus unloaded at these advance ratios (README, verification):
    # the blade without it analyses at the design's thrust.
    result = design_rotor(advance_ratio=[1.5, 3.0], ref_chord=0.1, radius=1.0, section_point="local",
                          ideal_loading="exact")
    assert np.all(np.sum(result.chord <= 0.0, axis=1) >= 1)
    np.testing.assert_allclose(result.bem_thrust, result.thrust, rtol=1e-10)
    np.testing.assert_allclose(result.bem_power, result.power, rtol=1e-10)


def test_the_paper_design_of_a_small_propeller_says_how_it_analyses():
    design = design_rotor(**UAV)
    assert design.thrust == pytest.approx(25.0, rel=1e-10)
    # Its root stations run at Re ~ 1.5e4, an order below Re_ref: the analysis differs visibly.
    assert abs(design.bem_thrust / design.thrust - 1.0) > 1e-3
    text = design.summary()
    block = text.split("BEM analysis of this blade")[1]
    thrust_line = next(line for line in block.splitlines() if "thrust T" in line)
    assert f"{design.bem_thrust:.6g}" in thrust_line and "against the design's 25" in thrust_line
    assert f"{100.0 * (design.bem_thrust / 25.0 - 1.0):+.4f} %" in thrust_line
    assert "Assumption 2" in block
    # Forward flight: the efficiency, not the figure of merit.
    assert "efficiency eta" in block and "figure of merit" not in block
    # The local section point designs it at each station's own Reynolds number (30 N: at 25 N the target lies
    # in a jump of its design, where the reference station's section point changes branch).
    local = design_rotor(section_point="local", **{**UAV, "thrust": 30.0})
    assert local.bem_thrust == pytest.approx(30.0, rel=1e-10)
    assert "agree to round-off" in local.summary().split("BEM analysis of this blade")[1]


def test_hover_summary_shows_the_figure_of_merit_and_no_efficiency():
    text = design_rotor(num_blades=5, thrust=1200.0).summary()
    assert "efficiency eta                              n/a -  (hover: see FM)" in text
    block = text.split("BEM analysis of this blade")[1]
    assert "figure of merit FM" in block and "efficiency" not in block.split("notes:")[0]


def test_the_analysis_can_be_left_out():
    design = design_rotor(bem_analysis=False)
    assert "bem_thrust" not in design.values and "BEM analysis" not in design.summary()
