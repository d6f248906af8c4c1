"""read_geometry / write_geometry: every format round-trips a BILD design; the format follows the file name."""
import pytest

from bild_mdo.io.files import read_geometry, write_geometry


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
