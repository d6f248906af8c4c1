"""read_geometry / write_geometry: every format round-trips a BILD design and analyses as the design; the format
follows the file name; missing and binary files are one line, in the library and on the command line."""
import os

import numpy as np
import pytest

from bild_mdo.bem.analyze import analyze_rotor
from bild_mdo.io.airfoil import resolve_airfoil
from bild_mdo.io.files import check_output_file, read_geometry, write_geometry
from bild_mdo.results.off_design import off_design_sweep
from tests.cli.runner import run


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


@pytest.mark.parametrize("suffix", [".csv", ".json", ".prop"])
def test_a_file_analyses_exactly_as_the_design(tmp_path, design, suffix):
    # The design's own BEM analysis: its stations are the midpoints of equal annuli (analyze_rotor's default).
    point = design.geometry().design_point
    own = analyze_rotor(design.chord, design.twist, design.radius, design.hub_radius, point["rpm"], point["v_axial"],
                        design.num_blades, design.polar, altitude=point["altitude"], loss_model=design.loss_model)
    path = write_geometry(tmp_path / f"blade{suffix}", design)
    sweep = off_design_sweep(path, advance_ratios=[point["advance_ratio"]])
    # Invariant: the analysis of the file integrates over the widths the file carries, which are the design's
    # equal annuli (to the radii's 12 digits: each within 0.75e-12 m at R = 1.5 m); then the thrust and torque
    # agree to the file's 12 digits.
    np.testing.assert_allclose(sweep.bem.dr[0], read_geometry(path).dr, rtol=0.0, atol=1e-14)
    np.testing.assert_allclose(sweep.bem.dr[0], own.dr, rtol=0.0, atol=4e-12)
    assert sweep.thrust[0] == pytest.approx(float(own.thrust), rel=1e-10)
    assert sweep.torque[0] == pytest.approx(float(own.torque), rel=1e-10)


def test_missing_file(tmp_path):
    with pytest.raises(FileNotFoundError, match=r"^geometry file not found: .*missing\.csv$"):
        read_geometry(tmp_path / "missing.csv")


def test_missing_and_binary_files_on_the_command_line(tmp_path, capsys):
    missing = tmp_path / "y.prop"
    code, _, err = run(capsys, "analyze", str(missing), "--rpm", "800", "800", "1")
    assert (code, err) == (2, f"bild-mdo analyze: error: geometry file not found: {missing}\n")
    code, _, err = run(capsys, "design", "--airfoil", str(tmp_path / "polars" / "naca2412"))
    assert (code, err) == (2, f"bild-mdo design: error: --airfoil: airfoil file or folder not found: "
                              f"{tmp_path / 'polars' / 'naca2412'}\n")
    image = tmp_path / "polar.png"
    image.write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(range(256)))
    code, _, err = run(capsys, "design", "--airfoil", str(image))
    assert (code, err) == (2, f"bild-mdo design: error: --airfoil: {image}: not a text polar file (a control byte "
                              "0x1a at byte 6); is it the right file?\n")


def test_text_polar_files_in_other_encodings_pass_the_text_check(tmp_path):
    # A Latin-1 comment ('Profil für ...') is text: the check passes it on to the polar reader.  The table is the
    # line cl = 0.4 + 0.1 alpha_deg, so the polar gives cl(0) = 0.4 (hand evaluation).
    rows = "".join(f"{a},{0.4 + 0.1 * a:.2f},0.01\n" for a in range(-4, 8))
    path = tmp_path / "polar.txt"
    path.write_bytes(f"# Profil f\u00fcr Rotor\n# reynolds = 1e6\nalpha_deg,cl,cd\n{rows}".encode("latin-1"))
    assert b"\xfc" in path.read_bytes()
    polar = resolve_airfoil(str(path))
    assert float(polar.evaluate(0.0, 1e6).cl) == pytest.approx(0.4, abs=1e-6)


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
