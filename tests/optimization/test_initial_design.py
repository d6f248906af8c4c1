"""Objective reference, cold start and twist bounds of the BEM optimisation."""
import numpy as np
import pytest

from bild_mdo.optimization.initial_design import (TWIST_LIMITS, TWIST_MARGINS, ideal_energy_loss,
                                                  linear_initial_design, twist_bounds)
from bild_mdo.optimization.parameterization import station_fractions


def test_ideal_energy_loss_is_momentum_theory():
    # Hand derivation, hover: T = 2 rho A w^2, so w = sqrt(T / (2 rho A)) and E = T w.
    thrust, radius, hub, rho = 420.0, 1.0, 0.2, 1.225
    area = np.pi * (radius**2 - hub**2)
    w = np.sqrt(thrust / (2.0 * rho * area))
    assert ideal_energy_loss(thrust, 0.0, radius, hub, rho) == pytest.approx(thrust * w, rel=1e-14)
    # In climb at V_x the induced velocity solves T = 2 rho A (V_x + w) w.
    v = 10.0
    e = ideal_energy_loss(thrust, v, radius, hub, rho)
    w = e / thrust
    assert 2.0 * rho * area * (v + w) * w == pytest.approx(thrust, rel=1e-12)


def test_twist_bounds_follow_the_inflow_angle_without_induction():
    fractions = station_fractions(5)
    lower, upper = twist_bounds(20.0, 800.0, 1.0, 0.2, fractions)
    radii = 0.2 + fractions * 0.8
    phi0 = np.arctan2(20.0, 800.0 * np.pi / 30.0 * radii)
    np.testing.assert_allclose(lower, np.clip(phi0 + TWIST_MARGINS[0], *TWIST_LIMITS))
    np.testing.assert_allclose(upper, np.clip(phi0 + TWIST_MARGINS[1], *TWIST_LIMITS))
    # Hover: phi_0 = 0, so the lower bound is the absolute limit of 0 deg.
    lower, upper = twist_bounds(0.0, 800.0, 1.0, 0.2, fractions)
    np.testing.assert_array_equal(lower, 0.0)
    np.testing.assert_allclose(upper, TWIST_MARGINS[1])


def test_linear_initial_design_is_linear_from_root_to_tip():
    chord, twist = linear_initial_design(0.0, 800.0, 1.0, 0.2, 420.0, 1.225, 10, reference_chord=0.1)
    x = station_fractions(10)
    # Chord from 1.5 c_ref at the root (x = 0) to 0.5 c_ref at the tip (x = 1).
    np.testing.assert_allclose(chord, 0.1 * (1.5 - x), rtol=1e-14)
    np.testing.assert_allclose(np.diff(twist, 2), 0.0, atol=1e-14)
    assert twist[0] > twist[-1] > 0.0
