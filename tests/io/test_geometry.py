"""RotorGeometry: its checks, and as_geometry from a dict or an object with a geometry method."""
import numpy as np
import pytest

from bild_mdo.io.geometry import RotorGeometry, as_geometry

BLADE = dict(radii=[0.3, 0.6, 0.9], chord=[0.1, 0.09, 0.05], twist=[0.4, 0.3, 0.2], radius=1.0, hub_radius=0.2,
             num_blades=2)


@pytest.mark.parametrize("change, message", [
    (dict(radii=[0.5, 0.4, 0.9]), "strictly increasing"),
    (dict(radii=[0.5, 0.6, 1.4]), "within hub and tip"),
    (dict(chord=[0.1, -0.1, 0.1]), "chord must be non-negative"),
    (dict(twist=[0.1, 0.2]), "the same length"),
    (dict(num_blades=True), "num_blades must be an integer >= 1, got True"),
    (dict(num_blades=2.5), "num_blades must be an integer >= 1, got 2.5"),
    (dict(hub_radius=1.2), "need 0 <= hub_radius < radius"),
])
def test_invalid_geometry(change, message):
    with pytest.raises(ValueError, match=message):
        RotorGeometry(**{**BLADE, **change})


def test_as_geometry_sources(design):
    geometry = as_geometry(BLADE)
    assert as_geometry(geometry) is geometry
    np.testing.assert_allclose(geometry.radial_fractions, [0.3, 0.6, 0.9])
    assert geometry.num_radial == 3
    # A BILD design hands over its blade and the polar it was designed with.
    from_design = as_geometry(design)
    np.testing.assert_array_equal(from_design.chord, design.chord)
    assert from_design.polar is design.polar
    with pytest.raises(ValueError, match="cannot make a rotor geometry from int"):
        as_geometry(3)
