"""Geometry CSV files: declared units, other length and angle units, hub and tip from the stations, and the
checks that keep a file from lying (station widths, format version, byte-order mark, binary files)."""
import numpy as np
import pytest

from bild_mdo.io.csv import read_csv, write_csv


def test_csv_declares_units(tmp_path, design):
    text = write_csv(tmp_path / "blade.csv", design).read_text()
    assert text.startswith("# bild-mdo rotor geometry, format 2\n")
    assert "\nr [m],chord [m],twist [deg],dr [m]\n" in text
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
    ("# num_blades: 3\nr [m],chord [m],twist [deg]\n0.3,0.1,1\n0.4,0.1\x00,1\n",
     "bad.csv: not a text geometry file (a NUL byte on line 4); is it the right file?"),
    ("# num_blades: 3\n# loss_model: prandtl\nr [m],chord [m],twist [deg]\n0.3,0.1,1\n0.4,0.1,1\n",
     "loss_model must be one of tip_hub, tip, none"),
])
def test_damaged_csv_gives_one_line_naming_the_file(tmp_path, text, message):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(ValueError) as info:
        read_csv(path)
    assert str(info.value).startswith(str(path)) and message in str(info.value)


@pytest.mark.parametrize("content, message", [
    (b"# num_blades: 3\n\x89PNG\r\n\x1a\n\xff\x00", r"blade\.csv: not a text geometry file \(byte 16 is not UTF-8\); "),
    ("r [m]".encode("utf-16"), r"blade\.csv: the geometry file is UTF-16 text; save it as UTF-8 "),
])
def test_binary_file_is_not_text(tmp_path, content, message):
    path = tmp_path / "blade.csv"
    path.write_bytes(content)
    with pytest.raises(ValueError, match=message):
        read_csv(path)


def test_missing_file_is_one_line(tmp_path):
    with pytest.raises(FileNotFoundError, match=r"^geometry file not found: .*missing\.csv$"):
        read_csv(tmp_path / "missing.csv")


def test_byte_order_mark_is_read(tmp_path, design, assert_same_geometry):
    # A spreadsheet saves "CSV UTF-8" with the byte-order mark EF BB BF in front of the first line.
    path = write_csv(tmp_path / "blade.csv", design)
    path.write_bytes(b"\xef\xbb\xbf" + path.read_bytes())
    assert_same_geometry(read_csv(path), design.geometry())


def _rows_cut(path, keep):
    """Keep the first ``keep`` station rows of a CSV (a file cut short)."""
    lines = path.read_text().splitlines()
    header = next(i for i, line in enumerate(lines) if line.startswith("r [m]"))
    path.write_text("\n".join(lines[:header + 1 + keep]) + "\n")
    return path


def _format_1(path):
    """The CSV as format 1 wrote it: no 'dr' column, 'format 1' in the first line."""
    lines = path.read_text().replace("format 2", "format 1").splitlines()
    path.write_text("\n".join(line.rsplit(",", 1)[0] if not line.startswith("#") else line for line in lines) + "\n")
    return path


def test_cut_csv_is_refused(tmp_path, design):
    # 9 stations of 0.8 * 1.5 m / 9 each; 4 kept add up to 4/9 of the span 1.2 m (hand derivation: 0.533333 m).
    path = _rows_cut(write_csv(tmp_path / "blade.csv", design), 4)
    with pytest.raises(ValueError, match=r"^\S*blade\.csv: the station widths 'dr \[m\]' add up to 0\.533333 m, but "
                                         r"hub to tip is 1\.2 m \(0\.3 \.\.\. 1\.5 m\): stations are missing"):
        read_csv(path)


def test_format_1_files_are_read_and_checked(tmp_path, design, assert_same_geometry):
    # An honest format-1 file (BILD's equal annuli, no widths) reads as before ...
    path = _format_1(write_csv(tmp_path / "blade.csv", design))
    assert "dr [m]" not in path.read_text()
    assert_same_geometry(read_csv(path), design.geometry())
    # ... and one cut by a single station is refused (hand derivation: spacing 1.2 m / 9 = 0.133333 m, the 8th
    # station at 0.3 + 7.5 * 0.133333 = 1.3 m lies 0.2 m = 1.5 spacings from the tip; its cell 0.2 + 0.066667 m is
    # twice its neighbour's).
    _rows_cut(path, 8)
    with pytest.raises(ValueError, match=r"the last station \(r = 1\.3 m\) is 0\.2 m from the tip \(R = 1\.5 m\), "
                                         r"more than the 0\.133333 m to its neighbour: its annulus would stretch to "
                                         r"the tip, 2 times as wide as its neighbour's"):
        read_csv(path)


def test_cut_to_one_station_is_refused(tmp_path, design):
    # With one row left there is no annulus to compare; the geometry check asks for two stations.
    with pytest.raises(ValueError, match=r"blade\.csv: a geometry needs at least 2 stations"):
        read_csv(_rows_cut(write_csv(tmp_path / "blade.csv", design), 1))


def test_newer_format_is_refused(tmp_path, design):
    path = write_csv(tmp_path / "blade.csv", design)
    path.write_text(path.read_text().replace("format 2", "format 99").replace("r [m],", "r [m],new [1/s],"))
    with pytest.raises(ValueError, match=r"^\S*blade\.csv: format version 99 is newer than this bild-mdo reads "):
        read_csv(path)


def test_twist_in_rad_that_looks_like_degrees_is_refused(tmp_path):
    (tmp_path / "deg.csv").write_text("# num_blades: 2\nr [m],chord [m],twist [rad]\n0.3,0.1,25\n0.5,0.1,12\n")
    with pytest.raises(ValueError, match=r"deg\.csv: 'twist \[rad\]' holds 25, more than one turn .* look like "
                                         r"degrees, but the file gives them in rad"):
        read_csv(tmp_path / "deg.csv")
