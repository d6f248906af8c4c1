"""Geometry CSV files: declared units, other length and angle units, hub and tip from the stations."""
import numpy as np
import pytest

from bild_mdo.io.csv import read_csv, write_csv


def test_csv_declares_units(tmp_path, design):
    text = write_csv(tmp_path / "blade.csv", design).read_text()
    assert "r [m],chord [m],twist [deg]" in text
    assert "# radius [m]: 1.5" in text and "# design_point.rpm [rpm]: 800" in text


def test_csv_in_other_units_and_without_radii(tmp_path):
    # Stations at the midpoints of 4 equal annuli from 0.2 m to 1.0 m: hub and tip follow by extending
    # the end stations half a spacing (hand derivation: 0.3 - 0.1 = 0.2, 0.9 + 0.1 = 1.0).
    (tmp_path / "mm.csv").write_text("# num_blades: 2\nr [mm],chord [mm],twist [rad]\n"
                                     "300,100,0.5\n500,90,0.4\n700,80,0.3\n900,70,0.2\n")
    geometry = read_csv(tmp_path / "mm.csv")
    np.testing.assert_allclose(geometry.radii, [0.3, 0.5, 0.7, 0.9])
    np.testing.assert_allclose(geometry.chord, [0.1, 0.09, 0.08, 0.07])
    np.testing.assert_allclose(geometry.twist, [0.5, 0.4, 0.3, 0.2])
    assert geometry.hub_radius == pytest.approx(0.2) and geometry.radius == pytest.approx(1.0)
    assert geometry.num_blades == 2 and geometry.airfoil is None


def test_unreadable_csv_files(tmp_path):
    (tmp_path / "bad.csv").write_text("# num_blades: 3\nr [m],chord [m],twist [deg]\n0.3,0.1,abc\n")
    with pytest.raises(ValueError, match="bad.csv:3"):
        read_csv(tmp_path / "bad.csv")
    (tmp_path / "units.csv").write_text("# num_blades: 3\nr [ft],chord [m],twist [deg]\n0.3,0.1,1\n0.4,0.1,1\n")
    with pytest.raises(ValueError, match="unknown units 'ft'"):
        read_csv(tmp_path / "units.csv")
    (tmp_path / "blades.csv").write_text("r [m],chord [m],twist [deg]\n0.3,0.1,1\n0.4,0.1,1\n")
    with pytest.raises(ValueError, match="number of blades is missing"):
        read_csv(tmp_path / "blades.csv")


@pytest.mark.parametrize("text, message", [
    ("# num_blades: two\nr [m],chord [m],twist [deg]\n0.3,0.1,1\n0.4,0.1,1\n", "num_blades must be a number"),
    ("# num_blades: 3\n# radius [m]: x\nr [m],chord [m],twist [deg]\n0.3,0.1,1\n0.4,0.1,1\n",
     "radius must be a number, got 'x'"),
    ("# num_blades: 3\n# design_point.rpm [rpm]: fast\nr [m],chord [m],twist [deg]\n0.3,0.1,1\n",
     "bad.csv:2: design_point.rpm must be a number"),
    ("# num_blades: 3\nr [m],chord [m],twist [deg]\n0.3,0.1,1\n0.4,nan,1\n", "must be finite numbers"),
    ("# num_blades: 3\nr [m],chord [m],twist [deg]\n0.3,0.1,1\n0.4,0.1\x00,1\n", "bad.csv:4:"),
    ("# num_blades: 3\n# loss_model: prandtl\nr [m],chord [m],twist [deg]\n0.3,0.1,1\n0.4,0.1,1\n",
     "loss_model must be one of tip_hub, tip, none"),
])
def test_damaged_csv_gives_one_line_naming_the_file(tmp_path, text, message):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(ValueError) as info:
        read_csv(path)
    assert str(info.value).startswith(str(path)) and message in str(info.value)


def test_binary_file_is_not_text(tmp_path):
    path = tmp_path / "blade.csv"
    path.write_bytes(b"\xff\xfe\x00r [m]")
    with pytest.raises(ValueError, match="blade.csv: not a UTF-8 text file"):
        read_csv(path)
