"""TurbineDesign's chord Reynolds numbers and the summary's note on stations outside the polar's data.

Sources: the velocity triangle of a turbine annulus, ``W = sqrt((V (1 - a))**2 + (Omega r (1 + a'))**2)``
(hand), and the data range of the built-in NACA 4412 table, Re = 1e4 ... 2e6 (its own ``reynolds`` grid).
"""
import warnings

import numpy as np
import pytest

from bild_mdo import design_turbine
from bild_mdo.airfoil import AnalyticPolar, naca4412


def _design(radius, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # the NACA 4412 table's own extrapolation warning
        return design_turbine(wind_speed=10.0, tip_speed_ratio=7.0, radius=radius, num_radial=8, **options)


@pytest.mark.parametrize("radius", [3.0, 63.0])
def test_station_reynolds_numbers_from_the_velocity_triangle(radius):
    design = _design(radius)
    omega = design.rpm * np.pi / 30.0
    w = np.hypot(10.0 * (1.0 - design.axial_induction), omega * design.radii * (1.0 + design.tangential_induction))
    np.testing.assert_allclose(design.reynolds, design.rho * w * design.chord / design.mu, rtol=1e-12)
    low, high = naca4412().reynolds.min(), naca4412().reynolds.max()
    assert (low, high) == (1e4, 2e6)
    expected = (design.reynolds < low) | (design.reynolds > high)
    np.testing.assert_array_equal(design.reynolds_outside_data > 0.0, expected)
    note = "outside the polar's Reynolds-number data" in design.summary()
    assert note == bool(expected.any())


def test_the_63_m_rotor_is_flagged_and_the_3_m_rotor_is_not():
    # A 63-m blade runs at Re of order 1e7, beyond the table's 2e6; a 3-m one at 2e5 ... 3e5, inside it.
    assert np.all(_design(63.0).reynolds_outside_data == 1.0)
    assert np.all(_design(3.0).reynolds_outside_data == 0.0)
    # A polar without a data range flags nothing.
    assert np.all(_design(63.0, airfoil=AnalyticPolar()).reynolds_outside_data == 0.0)
