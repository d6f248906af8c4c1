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


@pytest.mark.parametrize("designs, message", [
    ('"x"', "'designs' must be a non-empty list of design entries, got 'x'"),
    ("[]", "'designs' must be a non-empty list"),
    ("[3]", "design 0 must be an object"),
    ('[{"r [m]": [0.3, 0.5]}]', "design 0 lacks 'num_blades'"),
    ('[{"num_blades": 2, "r [m]": "abc"}]', "'r [m]' must be a list of numbers, got 'abc'"),
    ('[{"num_blades": 2, "r [m]": [0.3, 0.5], "chord [m]": [0.1, 0.1], "twist [deg]": [1, 1], '
     '"radius [m]": [1], "hub_radius [m]": 0.2}]', "'radius [m]' must be a scalar"),
    ('[{"num_blades": 2, "r [m]": [0.3, 0.5], "chord [m]": [0.1, 0.1], "twist [deg]": [1, 1], '
     '"radius [m]": 1, "hub_radius [m]": 0.2, "design_point": 5}]', "'design_point' must be an object"),
    ('[{"num_blades": 2.5, "r [m]": [0.3, 0.5], "chord [m]": [0.1, 0.1], "twist [deg]": [1, 1], '
     '"radius [m]": 1, "hub_radius [m]": 0.2}]', "num_blades must be an integer >= 1, got 2.5"),
])
def test_damaged_entries_give_one_line_naming_the_file(tmp_path, designs, message):
    path = tmp_path / "damaged.json"
    path.write_text('{"format": "bild-mdo rotor geometry", "version": 1, "designs": ' + designs + "}")
    with pytest.raises(ValueError) as info:
        read_json(path)
    assert str(info.value).startswith(f"{path}: ") and message in str(info.value)
    assert "\n" not in str(info.value)


def test_invalid_json_names_the_line(tmp_path):
    path = tmp_path / "broken.json"
    path.write_text('{\n "format": ,\n}')
    with pytest.raises(ValueError, match=r"broken.json:2: not valid JSON"):
        read_json(path)
