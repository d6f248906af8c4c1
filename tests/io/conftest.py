"""Shared fixtures of the geometry-file tests: a BILD design and the file round-trip tolerance."""
import numpy as np
import pytest

from bild_mdo.results.design import design_rotor
from tests.io import FILE_RTOL


@pytest.fixture(scope="package")
def design():
    return design_rotor(advance_ratio=0.7, ref_chord=0.13, altitude=1200.0, airfoil="analytic", num_radial=9)


@pytest.fixture
def assert_same_geometry():
    """Assert that a geometry read from a file is the one written, to the digits the file carries."""

    def check(read, geometry):
        np.testing.assert_allclose(read.radii, geometry.radii, rtol=FILE_RTOL)
        np.testing.assert_allclose(read.chord, geometry.chord, rtol=FILE_RTOL)
        np.testing.assert_allclose(read.twist, geometry.twist, rtol=FILE_RTOL)
        assert read.radius == pytest.approx(geometry.radius, rel=FILE_RTOL)
        assert read.hub_radius == pytest.approx(geometry.hub_radius, rel=FILE_RTOL)
        assert read.num_blades == geometry.num_blades
        assert read.airfoil == geometry.airfoil
        assert read.loss_model == geometry.loss_model
        assert set(read.design_point) == set(geometry.design_point)
        for key, value in geometry.design_point.items():
            assert read.design_point[key] == pytest.approx(value, rel=FILE_RTOL, abs=1e-300)

    return check
