"""Geometry files carry their airfoil: the polar embedded in JSON, a polar file next to CSV and QPROP files."""
import json

import numpy as np
import pytest

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.airfoil.builtin import get_polar
from bild_mdo.io.airfoil import airfoil_text, read_polar_file, resolve_airfoil, write_polar_file
from bild_mdo.io.files import read_geometry, write_geometry

# A polar that no name rebuilds: its parameters must travel with the blade.
OWN_POLAR = AnalyticPolar(cl_alpha=5.9, cd0=0.011, k=0.012)


@pytest.fixture
def own_geometry(design):
    geometry = design.geometry()
    geometry.polar = OWN_POLAR
    geometry.airfoil = "my-airfoil"
    return geometry


def _same_polar(polar):
    alpha = np.radians(np.linspace(-5.0, 15.0, 9))
    reynolds = np.full(alpha.shape, 4e5)
    np.testing.assert_array_equal(polar.evaluate(alpha, reynolds).cl, OWN_POLAR.evaluate(alpha, reynolds).cl)
    np.testing.assert_array_equal(polar.evaluate(alpha, reynolds).cd, OWN_POLAR.evaluate(alpha, reynolds).cd)


@pytest.mark.parametrize("suffix", [".json", ".csv", ".prop"])
def test_files_carry_a_polar_that_no_name_rebuilds(tmp_path, own_geometry, suffix):
    path = write_geometry(tmp_path / f"blade{suffix}", own_geometry)
    sidecar = tmp_path / "blade.polar.json"
    # JSON embeds the polar; CSV and QPROP name the polar file written next to them.
    assert sidecar.exists() == (suffix != ".json")
    read = read_geometry(path)
    assert read.airfoil == "my-airfoil"
    _same_polar(read.polar)
    assert read_geometry(path, load_polar=False).polar is None


@pytest.mark.parametrize("suffix", [".csv", ".prop"])
def test_a_builtin_airfoil_needs_no_polar_file(tmp_path, design, suffix):
    geometry = design.geometry()
    geometry.polar, geometry.airfoil = get_polar("naca4412"), "naca4412"
    path = write_geometry(tmp_path / f"blade{suffix}", geometry)
    assert not (tmp_path / "blade.polar.json").exists()
    assert "polar_file" not in path.read_text()
    assert read_geometry(path).polar is None  # the name rebuilds it when analysed


def test_json_embeds_a_builtin_polar_by_name(tmp_path, design):
    geometry = design.geometry()
    geometry.polar, geometry.airfoil = get_polar("naca4412"), "naca4412"
    entry = json.loads(write_geometry(tmp_path / "blade.json", geometry).read_text())["designs"][0]
    assert entry["polar"] == {"type": "builtin", "name": "naca4412"}
    assert read_geometry(tmp_path / "blade.json").polar is get_polar("naca4412")


def test_missing_polar_file_is_one_line_naming_it(tmp_path, own_geometry):
    path = write_geometry(tmp_path / "blade.csv", own_geometry)
    (tmp_path / "blade.polar.json").unlink()
    with pytest.raises(ValueError, match=r"^polar file .*blade\.polar\.json not found \(it goes with the "
                                         r"geometry file: copy both\)$"):
        read_geometry(path)


@pytest.mark.parametrize("text, message", [
    ("{", r"blade\.polar\.json:1: not valid JSON"),
    ('{"format": "other"}', r"blade\.polar\.json: not a 'bild-mdo airfoil polar' file"),
    ('{"format": "bild-mdo airfoil polar", "airfoil": {"type": "tables"}}',
     r"blade\.polar\.json: airfoil polar: airfoil description is incomplete"),
])
def test_damaged_polar_file_is_one_line_naming_it(tmp_path, text, message):
    path = tmp_path / "blade.polar.json"
    path.write_text(text)
    with pytest.raises(ValueError, match=message):
        read_polar_file(path)


def test_damaged_embedded_polar_names_file_and_design(tmp_path, own_geometry):
    path = write_geometry(tmp_path / "blade.json", own_geometry)
    doc = json.loads(path.read_text())
    doc["designs"][0]["polar"] = {"type": "analytic", "parameters": {"bogus": 1.0}}
    path.write_text(json.dumps(doc))
    with pytest.raises(ValueError, match=r"blade\.json: design 0: airfoil polar: "):
        read_geometry(path)


def test_polar_file_is_an_airfoil_argument(tmp_path):
    path = write_polar_file(tmp_path / "mine.polar.json", OWN_POLAR)
    _same_polar(resolve_airfoil(str(path)))


def test_spanwise_sets_with_commas_or_semicolons_are_one_text():
    assert airfoil_text(" 0.2:naca4415, 1:naca4412 ") == "0.2:naca4415;1:naca4412"
    assert airfoil_text("a.txt,b.txt") == "a.txt,b.txt"  # a list of polar files stays one
    assert resolve_airfoil("0:analytic,1:naca4412") is resolve_airfoil("0:analytic;1:naca4412")
