"""bild-mdo analyze: reads back what design writes, J and rpm sweeps, tables, CSV and PNG files."""
import json

import numpy as np
import pytest

from bild_mdo.io.csv import write_csv
from bild_mdo.io.files import read_geometry
from bild_mdo.io.json import write_json
from bild_mdo.io.qprop import write_qprop
from bild_mdo.results.design import design_rotor
from tests.cli.runner import run
from tests.io import FILE_RTOL


@pytest.mark.parametrize("suffix", [".csv", ".json", ".prop"])
def test_analyze_reads_back_what_design_writes(tmp_path, capsys, suffix):
    geometry_file = tmp_path / f"blade{suffix}"
    option = {".csv": "--csv", ".json": "--json", ".prop": "--qprop"}[suffix]
    code, _, _ = run(capsys, "design", "--airfoil", "analytic", "--advance-ratio", "0.8", "--num-radial", "12",
                      option, str(geometry_file))
    assert code == 0
    reference = design_rotor(advance_ratio=0.8, airfoil="analytic", num_radial=12)
    geometry = read_geometry(geometry_file)
    np.testing.assert_allclose(geometry.radii, reference.radii, rtol=FILE_RTOL)
    np.testing.assert_allclose(geometry.chord, reference.chord, rtol=FILE_RTOL)
    np.testing.assert_allclose(geometry.twist, reference.twist, rtol=FILE_RTOL)
    perf = tmp_path / "perf.csv"
    code, out, err = run(capsys, "analyze", str(geometry_file), "--advance-ratio", "0.4", "1.2", "3",
                          "--csv", str(perf))
    assert code == 0, err
    assert "maximum efficiency" in out and "T [N]" in out
    table = np.loadtxt(perf, delimiter=",", comments="#", skiprows=2)
    # At its design point (J = 0.8, the middle point) the BEM analysis of a BILD blade with a
    # Re-independent polar reproduces BILD's thrust (see test_off_design); the file adds 12-digit rounding.
    assert table[1, 0] == pytest.approx(0.8)
    assert table[1, 3] == pytest.approx(reference.thrust, rel=1e-8)


def test_analyze_rpm_sweep_with_plot(tmp_path, capsys):
    geometry_file = tmp_path / "hover.csv"
    assert run(capsys, "design", "--airfoil", "analytic", "--num-radial", "10", "--csv", str(geometry_file))[0] == 0
    code, out, _ = run(capsys, "analyze", str(geometry_file), "--rpm", "600", "1000", "3",
                        "--plot", str(tmp_path / "perf.png"))
    assert code == 0
    assert (tmp_path / "perf.png").stat().st_size > 0
    assert "swept rpm" in out


BLADE = dict(radii=[0.3, 0.5, 0.7, 0.9], chord=[0.12, 0.1, 0.08, 0.06], twist=np.radians([30.0, 20.0, 15.0, 12.0]),
             radius=1.0, hub_radius=0.2, num_blades=2, airfoil="analytic", design_point={"rpm": 1200.0})


def _damaged_json(path):
    write_json(path, BLADE)
    doc = json.loads(path.read_text())
    doc["designs"] = "x"
    path.write_text(json.dumps(doc))


def _json_without_blades(path):
    write_json(path, BLADE)
    doc = json.loads(path.read_text())
    del doc["designs"][0]["num_blades"]
    path.write_text(json.dumps(doc))


def _qprop_without_lift_slope(path):
    # A foreign QPROP file (no airfoil name) whose lift line has CL_a = 0: QPROP's model has no lift slope.
    write_qprop(path, {**BLADE, "airfoil": None, "polar_coefficients": {
        "CL0": 0.5, "CL_a": 0.0, "CLmin": -0.3, "CLmax": 1.2, "CD0": 0.028, "CD2u": 0.05, "CD2l": 0.02,
        "CLCD0": 0.5, "REref": 7e4, "REexp": -0.7}})


@pytest.mark.parametrize("name, make, message", [
    ("designs.json", _damaged_json, "designs.json: 'designs' must be a non-empty list of design entries, got 'x'"),
    ("blades.json", _json_without_blades, "blades.json: design 0 lacks 'num_blades'"),
    ("slope.prop", _qprop_without_lift_slope, "slope.prop:5: CL_a must be a positive finite number in 1/rad"),
])
def test_damaged_geometry_files_give_one_line(tmp_path, capsys, name, make, message):
    make(tmp_path / name)
    code, out, err = run(capsys, "analyze", str(tmp_path / name), "--rpm", "500", "900", "3")
    assert code == 2 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"bild-mdo analyze: error: {tmp_path}/{message}"), err


def test_output_files_are_checked_before_the_analysis(tmp_path, capsys):
    geometry_file = write_csv(tmp_path / "blade.csv", BLADE)
    (tmp_path / "out").mkdir()
    for argv, message in [
        (["--plot", str(tmp_path / "out")], f"--plot {tmp_path / 'out'}: is a folder; give a file name"),
        (["--plot", str(tmp_path / "curves.xyz")], "unknown figure format '.xyz'"),
        (["--csv", str(tmp_path / "missing" / "perf.csv")], f"folder {tmp_path / 'missing'} does not exist"),
        (["--csv", str(tmp_path / "out")], f"--csv {tmp_path / 'out'}: is a folder"),
        (["--csv", str(geometry_file / "perf.csv")], f"{geometry_file} is not a folder"),
    ]:
        code, out, err = run(capsys, "analyze", str(geometry_file), "--rpm", "500", "900", "3", *argv)
        assert code == 2 and out == "", argv  # no table printed: the sweep did not run
        assert len(err.strip().splitlines()) == 1 and message in err, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["blade.csv", "out"]
    assert list((tmp_path / "out").iterdir()) == []


def test_plot_without_suffix_says_the_file_it_wrote(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    geometry_file = write_csv(tmp_path / "blade.csv", BLADE)
    code, out, _ = run(capsys, "analyze", str(geometry_file), "--rpm", "500", "900", "2",
                       "--plot", str(tmp_path / "curves"))
    assert code == 0
    assert f"wrote {tmp_path / 'curves.png'}" in out and (tmp_path / "curves.png").is_file()


def test_collective_pitch_sweep(tmp_path, capsys):
    blade = tmp_path / "blade.json"
    design_rotor(advance_ratio=0.8, airfoil="analytic", num_radial=12).to_json(blade)
    perf = tmp_path / "perf.csv"
    code, out, err = run(capsys, "analyze", str(blade), "--collective-pitch", "-2", "2", "3", "--csv", str(perf))
    assert code == 0, err
    assert "swept collective_pitch" in out and "pitch [deg]" in out
    lines = [line for line in perf.read_text().splitlines() if not line.startswith("#")]
    table = dict(zip(lines[0].split(","), np.array([line.split(",") for line in lines[1:]], dtype=float).T))
    np.testing.assert_allclose(np.degrees(table["collective_pitch [rad]"]), [-2.0, 0.0, 2.0], atol=1e-9)
    np.testing.assert_allclose(table["advance_ratio [-]"], 0.8, rtol=1e-9)  # the design point of the file
    assert np.all(np.diff(table["thrust [N]"]) > 0)  # more pitch, more thrust in attached flow
    code, out, err = run(capsys, "analyze", str(blade), "--advance-ratio", "0.6", "1.0", "3", "--collective-pitch",
                         "0", "1", "2")
    assert code == 0, err
    assert len([line for line in out.splitlines() if line.strip().startswith(("0.6", "0.8", "1.0"))]) == 6
