"""read_geometry / write_geometry: every format round-trips a BILD design; the format follows the file name."""
import os

import pytest

from bild_mdo.io.files import check_output_file, read_geometry, write_geometry


@pytest.mark.parametrize("suffix", [".csv", ".json", ".qprop", ".prop"])
def test_round_trip(tmp_path, design, assert_same_geometry, suffix):
    path = write_geometry(tmp_path / f"blade{suffix}", design)
    assert_same_geometry(read_geometry(path), design.geometry())


def test_explicit_format_overrides_the_suffix(tmp_path, design, assert_same_geometry):
    path = write_geometry(tmp_path / "blade.txt", design, fmt="csv")
    assert path.read_text().startswith("# bild-mdo rotor geometry")
    assert_same_geometry(read_geometry(path, fmt="csv"), design.geometry())
    with pytest.raises(ValueError, match="unknown geometry format 'xls'"):
        read_geometry(path, fmt="xls")


def test_missing_file(tmp_path):
    with pytest.raises(FileNotFoundError, match="geometry file not found"):
        read_geometry(tmp_path / "missing.csv")


def test_a_folder_is_not_a_geometry_file(tmp_path):
    with pytest.raises(ValueError, match="is a folder, not a geometry file"):
        read_geometry(tmp_path)


def test_output_file_checks_create_nothing(tmp_path):
    (tmp_path / "folder").mkdir()
    (tmp_path / "file.txt").write_text("x")
    assert check_output_file(tmp_path / "new.csv", "--csv") == tmp_path / "new.csv"
    for target, message in [(tmp_path / "folder", "is a folder"),
                            (tmp_path / "missing" / "x.csv", "does not exist"),
                            (tmp_path / "file.txt" / "x.csv", "is not a folder")]:
        with pytest.raises(ValueError, match=message):
            check_output_file(target, "--csv")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file.txt", "folder"]


@pytest.mark.skipif(os.geteuid() == 0, reason="root may write into any folder")
def test_unwritable_folder(tmp_path):
    folder = tmp_path / "locked"
    folder.mkdir(mode=0o500)
    with pytest.raises(ValueError, match="is not writable"):
        check_output_file(folder / "x.csv", "--csv")
