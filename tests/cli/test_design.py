"""bild-mdo design: the paper's rotor printed and written to every file format, batches."""
import re

import numpy as np
import pytest

from bild_mdo.io.files import read_geometry
from bild_mdo.results.design import design_rotor
from tests.cli.runner import run
from tests.io import FILE_RTOL


def test_design_defaults_print_table_and_write_files(tmp_path, capsys):
    files = {ext: tmp_path / f"blade.{ext}" for ext in ("csv", "json", "prop", "png")}
    code, out, err = run(capsys, "design", "--csv", str(files["csv"]), "--json", str(files["json"]),
                          "--qprop", str(files["prop"]), "--plot", str(files["png"]))
    assert code == 0, err
    # The paper's rotor: R = 1.5 m, B = 3, 800 rpm, NACA 4412, c_ref = 0.15 m, hover, 30 stations.
    reference = design_rotor()
    assert "airfoil naca4412, B = 3, 30 stations" in out
    lines = out.splitlines()
    header = lines.index("stations:") + 1
    assert lines[header].split()[:4] == ["r", "[m]", "r/R", "[-]"]
    rows = [line.split() for line in lines[header + 1:header + 31]]
    np.testing.assert_allclose([float(r[0]) for r in rows], reference.radii, atol=5e-5)
    np.testing.assert_allclose([float(r[2]) for r in rows], reference.chord, atol=5e-6)
    np.testing.assert_allclose([float(r[3]) for r in rows], reference.twist_deg, atol=5e-4)
    thrust_line = next(line for line in lines if line.strip().startswith("thrust T"))
    assert thrust_line.split()[-1] == "N"
    assert float(thrust_line.split()[-2]) == pytest.approx(reference.thrust, rel=1e-5)
    for path in files.values():
        assert path.stat().st_size > 0
        assert f"wrote {path}" in out
    geometry = read_geometry(files["csv"])
    np.testing.assert_allclose(geometry.chord, reference.chord, rtol=FILE_RTOL)


def test_design_batch(tmp_path, capsys):
    code, out, _ = run(capsys, "design", "--airfoil", "analytic", "--num-radial", "8", "--ref-chord", "0.1", "0.2",
                        "--csv", str(tmp_path / "b.csv"))
    assert code == 0
    assert "2 designs" in out
    assert (tmp_path / "b_0.csv").is_file() and (tmp_path / "b_1.csv").is_file()


def test_zero_chord_design_writes_no_file(tmp_path, capsys):
    # With c_ref = 0.1 mm on R = 1.5 m the BILD ideal load vanishes outboard (chord 0 at the outer stations):
    # the blade ends before R, so no geometry file is written; without files the design prints with a warning.
    code, out, err = run(capsys, "design", "--ref-chord", "0.0001", "--num-radial", "8", "--csv",
                         str(tmp_path / "z.csv"))
    assert code == 2 and out == ""
    # How many stations are unloaded depends on the polar far below its data (Re ~ 1e2); that they are the
    # outer ones, so the blade ends before R, does not.
    last = err.strip().splitlines()[-1]
    assert re.match(r"bild-mdo design: error: the design has zero chord at \d of 8 stations", last)
    assert "ends before the tip radius" in last
    assert list(tmp_path.iterdir()) == []
    code, out, err = run(capsys, "design", "--ref-chord", "0.0001", "--num-radial", "8")
    assert code == 0 and "stations:" in out
    assert re.search(r"bild-mdo: warning: the design has zero chord at \d of 8 stations", err)


@pytest.mark.parametrize("option, target, message", [
    ("--json", "missing/b.json", "does not exist"),
    ("--qprop", "folder", "is a folder"),
    ("--plot", "folder", "is a folder"),
    ("--csv", "folder/", "is a folder"),
])
def test_output_files_are_checked_before_the_design(tmp_path, capsys, option, target, message):
    (tmp_path / "folder").mkdir()
    code, out, err = run(capsys, "design", "--airfoil", "analytic", "--num-radial", "5", "--csv",
                         str(tmp_path / "ok.csv"), option, str(tmp_path / target))
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and message in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["folder"]


def test_thrust_target_option(capsys):
    code, out, err = run(capsys, "design", "--thrust", "1500", "900", "--v-axial", "0", "5", "--airfoil", "analytic",
                         "--num-radial", "10")
    assert code == 0, err
    rows = [line.split() for line in out.splitlines() if line.split()[:1] in (["0"], ["1"])]
    assert [float(row[7]) for row in rows] == [1500.0, 900.0]  # the T [N] column
    code, _, err = run(capsys, "design", "--thrust", "1500", "--ref-chord", "0.1")
    assert code == 2 and "give either ref_chord [m] or thrust [N]" in err


def test_infeasible_batch_is_one_line(capsys):
    # The paper's Assumption 3 fails at the reference station of this design (tests/results/test_design.py).
    code, out, err = run(capsys, "design", "--v-axial", "0", "26.8", "--rpm", "800", "824", "--radius", "1.5", "1.277",
                         "--ref-chord", "0.15", "0.2", "--ref-radius-ratio", "0.5", "0.3006", "--hub-radius-ratio",
                         "0.2", "0.297", "--altitude", "0", "3533", "--num-radial", "12")
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1
    assert "1 of 2 design(s) infeasible" in err and "on_infeasible='skip'" in err


def test_design_section_point_local(capsys):
    code, out, err = run(capsys, "design", "--section-point", "local", "--num-radial", "12", "--v-axial", "10")
    assert code == 0, err
    local = design_rotor(v_axial=10.0, num_radial=12, section_point="local")
    thrust_line = next(line for line in out.splitlines() if line.strip().startswith("thrust T"))
    assert float(thrust_line.split()[-2]) == pytest.approx(local.thrust, rel=1e-5)
    code, _, err = run(capsys, "design", "--section-point", "best")
    assert code == 2
    assert "--section-point" in err
