"""Geometry JSON files: several designs in one file, picked by index."""
import pytest

from bild_mdo.io.json import read_json, write_json
from bild_mdo.results.design import design_rotor


def test_json_holds_several_designs(tmp_path, assert_same_geometry):
    batch = design_rotor(ref_chord=[0.1, 0.2, 0.3], airfoil="analytic", num_radial=6)
    path = write_json(tmp_path / "blades.json", [design.geometry() for design in batch])
    assert_same_geometry(read_json(path, design=2), batch.geometry(2))
    with pytest.raises(ValueError, match="holds 3 design"):
        read_json(path, design=3)


def test_not_a_geometry_file(tmp_path):
    (tmp_path / "other.json").write_text('{"designs": []}')
    with pytest.raises(ValueError, match="not a 'bild-mdo rotor geometry' JSON file"):
        read_json(tmp_path / "other.json")
