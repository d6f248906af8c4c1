"""design_rotor(ideal_loading=...): the paper's method by default, the exact ideal loading on request."""
import numpy as np
import pytest

from bild_mdo.results.design import design_rotor


def test_default_is_the_paper_loading_bit_for_bit():
    default = design_rotor(v_axial=[0.0, 10.0], num_radial=12)
    paper = design_rotor(v_axial=[0.0, 10.0], num_radial=12, ideal_loading="paper")
    np.testing.assert_array_equal(default.chord, paper.chord)
    np.testing.assert_array_equal(default.twist, paper.twist)


def test_exact_loading_batch_and_thrust_target():
    exact = design_rotor(v_axial=[0.0, 10.0], num_radial=12, ideal_loading="exact")
    paper = design_rotor(v_axial=[0.0, 10.0], num_radial=12)
    # Same reference chord and radius: r/R = 0.5 is station 4 of 12 equal annuli from 0.2 (hand derivation).
    np.testing.assert_allclose(exact.chord[:, 4], 0.15, rtol=1e-9)
    assert not np.allclose(exact.chord, paper.chord)
    # With a thrust target the solved reference chord meets it (to the solver's 1e-12 relative).
    sized = design_rotor(v_axial=[0.0, 10.0], num_radial=12, ideal_loading="exact", thrust=[900.0, 1100.0])
    np.testing.assert_allclose(sized.thrust, [900.0, 1100.0], rtol=1e-10)


def test_invalid_ideal_loading_choices():
    with pytest.raises(ValueError, match="ideal_loading"):
        design_rotor(ideal_loading="optimal")
