"""Geometry JSON files: several designs in one file, picked by index; the checks that keep a file from lying."""
import json

import numpy as np
import pytest

from bild_mdo.io.json import read_json, write_json
from bild_mdo.results.design import design_rotor

STATION_KEYS = ("r [m]", "chord [m]", "twist [deg]", "dr [m]")


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


def _edited(path, change):
    doc = json.loads(path.read_text())
    change(doc)
    path.write_text(json.dumps(doc))
    return path


def test_json_carries_version_and_widths(tmp_path, design):
    doc = json.loads(write_json(tmp_path / "blade.json", design).read_text())
    assert doc["version"] == 2
    # BILD's stations are the midpoints of 9 equal annuli from 0.3 m to 1.5 m: each 1.2 m / 9 wide.
    np.testing.assert_allclose(doc["designs"][0]["dr [m]"], np.full(9, 1.2 / 9), rtol=1e-14)


def test_cut_json_is_refused(tmp_path, design):
    def cut(doc):
        for key in STATION_KEYS:
            doc["designs"][0][key] = doc["designs"][0][key][:5]

    # 5 of 9 annuli of 1.2 m / 9 add up to 0.666667 m (hand derivation).
    path = _edited(write_json(tmp_path / "blade.json", design), cut)
    with pytest.raises(ValueError, match=r"^\S*blade\.json: the station widths 'dr \[m\]' add up to 0\.666667 m, "
                                         r"but hub to tip is 1\.2 m"):
        read_json(path)


def test_cut_stations_with_all_widths_are_refused(tmp_path, design):
    def cut(doc):
        for key in STATION_KEYS[:3]:
            doc["designs"][0][key] = doc["designs"][0][key][:5]

    path = _edited(write_json(tmp_path / "blade.json", design), cut)
    with pytest.raises(ValueError, match=r"blade\.json: 5 stations but 9 widths 'dr \[m\]': the file was cut"):
        read_json(path)


def test_format_1_json_is_read_and_checked(tmp_path, design, assert_same_geometry):
    def format_1(doc):
        doc["version"] = 1
        del doc["designs"][0]["dr [m]"]

    path = _edited(write_json(tmp_path / "blade.json", design), format_1)
    assert_same_geometry(read_json(path), design.geometry())

    def cut(doc):
        for key in STATION_KEYS[:3]:
            doc["designs"][0][key] = doc["designs"][0][key][:5]

    # Hand derivation: the 5th station at 0.3 + 4.5 * 0.133333 = 0.9 m is 0.6 m (4.5 spacings) from the tip.
    with pytest.raises(ValueError, match=r"blade\.json: the last station \(r = 0\.9 m\) is 0\.6 m from the tip"):
        read_json(_edited(path, cut))


def test_newer_json_is_refused(tmp_path, design):
    path = _edited(write_json(tmp_path / "blade.json", design), lambda doc: doc.update(version=99))
    with pytest.raises(ValueError, match=r"^\S*blade\.json: format version 99 is newer than this bild-mdo reads "
                                         r"\(1 \.\.\. 2\); update bild-mdo"):
        read_json(path)


def test_twist_in_rad_that_looks_like_degrees_is_refused(tmp_path, design):
    def in_rad(doc):
        entry = doc["designs"][0]
        entry["twist [rad]"] = entry.pop("twist [deg]")

    path = _edited(write_json(tmp_path / "blade.json", design), in_rad)
    largest = float(np.max(np.abs(design.twist_deg)))
    with pytest.raises(ValueError, match=rf"blade\.json: 'twist \[rad\]' holds {largest:g}, more than one turn "
                                         r"\(2 pi = 6\.28319 rad\): the values look like degrees, but the file "
                                         r"gives them in rad; write the key as 'twist \[deg\]'"):
        read_json(path)


def test_byte_order_mark_is_read(tmp_path, design, assert_same_geometry):
    path = write_json(tmp_path / "blade.json", design)
    path.write_bytes(b"\xef\xbb\xbf" + path.read_bytes())
    assert_same_geometry(read_json(path), design.geometry())
