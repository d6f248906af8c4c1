"""The bild-mdo command: design / analyze / verify, files, help texts, one-line errors."""
import subprocess
import sys

import numpy as np
import pytest

from bild_mdo import __version__
from bild_mdo.cli import main
from bild_mdo.design import design_rotor
from bild_mdo.geometry_io import read_geometry

FILE_RTOL = 5.1e-12  # 12 significant digits in the files (see test_geometry_io)


def _run(capsys, *argv):
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_design_defaults_print_table_and_write_files(tmp_path, capsys):
    files = {ext: tmp_path / f"blade.{ext}" for ext in ("csv", "json", "prop", "png")}
    code, out, err = _run(capsys, "design", "--csv", str(files["csv"]), "--json", str(files["json"]),
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
    code, out, _ = _run(capsys, "design", "--airfoil", "analytic", "--num-radial", "8", "--ref-chord", "0.1", "0.2",
                        "--csv", str(tmp_path / "b.csv"))
    assert code == 0
    assert "2 designs" in out
    assert (tmp_path / "b_0.csv").is_file() and (tmp_path / "b_1.csv").is_file()


@pytest.mark.parametrize("suffix", [".csv", ".json", ".prop"])
def test_analyze_reads_back_what_design_writes(tmp_path, capsys, suffix):
    geometry_file = tmp_path / f"blade{suffix}"
    option = {".csv": "--csv", ".json": "--json", ".prop": "--qprop"}[suffix]
    code, _, _ = _run(capsys, "design", "--airfoil", "analytic", "--advance-ratio", "0.8", "--num-radial", "12",
                      option, str(geometry_file))
    assert code == 0
    reference = design_rotor(advance_ratio=0.8, airfoil="analytic", num_radial=12)
    geometry = read_geometry(geometry_file)
    np.testing.assert_allclose(geometry.radii, reference.radii, rtol=FILE_RTOL)
    np.testing.assert_allclose(geometry.chord, reference.chord, rtol=FILE_RTOL)
    np.testing.assert_allclose(geometry.twist, reference.twist, rtol=FILE_RTOL)
    perf = tmp_path / "perf.csv"
    code, out, err = _run(capsys, "analyze", str(geometry_file), "--advance-ratio", "0.4", "1.2", "3",
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
    assert _run(capsys, "design", "--airfoil", "analytic", "--num-radial", "10", "--csv", str(geometry_file))[0] == 0
    code, out, _ = _run(capsys, "analyze", str(geometry_file), "--rpm", "600", "1000", "3",
                        "--plot", str(tmp_path / "perf.png"))
    assert code == 0
    assert (tmp_path / "perf.png").stat().st_size > 0
    assert "swept rpm" in out


@pytest.mark.parametrize("argv, units", [
    ([], ["m/s", "rpm"]),
    (["design"], ["[m/s]", "[m]", "[rpm]", "[deg]"]),
    (["analyze"], ["[m/s]", "[rpm]", "[m]", "[kW]"]),
    (["verify"], ["m)", "rpm"]),
    (["demo"], ["[m]", "[deg]", "kW"]),
])
def test_help_exits_zero_and_mentions_units(capsys, argv, units):
    code, out, _ = _run(capsys, *argv, "--help")
    assert code == 0
    for unit in units:
        assert unit in out


def test_demo_writes_tables_and_files(tmp_path, capsys):
    code, out, err = _run(capsys, "demo", "--output-dir", str(tmp_path / "demo"))
    assert code == 0, err
    assert "stations:" in out and "maximum efficiency" in out
    for name in ("hover_blade.csv", "hover_blade.json", "hover_blade.prop", "hover_blade.png", "blades_J0-2.png",
                 "efficiency_Jdes1.png"):
        assert (tmp_path / "demo" / name).stat().st_size > 0


def test_version(capsys):
    code, out, _ = _run(capsys, "--version")
    assert code == 0 and out.strip() == f"bild-mdo {__version__}"


@pytest.mark.parametrize("argv, message", [
    (["design", "--radius", "-1"], "radius [m] must be positive"),
    (["design", "--rpm", "abc"], "invalid float value"),
    (["design", "--v-axial", "1", "--advance-ratio", "1"], "not allowed with"),
    (["design", "--airfoil", "foo"], "invalid choice"),
    (["design", "--hub-radius-ratio", "0.6"], "hub_radius_ratio must be smaller"),
    (["design", "--rpm", "800", "900", "--ref-chord", "0.1", "0.2", "0.3"], "equal lengths"),
    (["analyze", "missing.csv", "--rpm", "500", "900", "3"], "not found"),
    (["analyze", "missing.csv"], "one of the arguments --advance-ratio --rpm is required"),
    (["analyze", "missing.csv", "--rpm", "500", "900", "2.5"], "N must be a positive integer"),
    (["verify", "--levels", "x"], "invalid int value"),
    (["bogus"], "invalid choice"),
    ([], "give a command"),
])
def test_bad_arguments_give_one_line_and_exit_2(tmp_path, monkeypatch, capsys, argv, message):
    monkeypatch.chdir(tmp_path)
    code, out, err = _run(capsys, *argv)
    assert code == 2
    assert len(err.strip().splitlines()) == 1, err
    assert message in err and "error" in err
    assert "Traceback" not in err + out


def test_debug_shows_the_traceback(capsys):
    code, _, err = _run(capsys, "design", "--radius", "-1", "--debug")
    assert code == 2
    assert "Traceback" in err and err.strip().splitlines()[-1].startswith("bild-mdo design: error:")


def test_entry_point_process_exit_code():
    # The real process: one line on stderr, exit status 2, no traceback.
    proc = subprocess.run([sys.executable, "-m", "bild_mdo.cli", "design", "--ref-chord", "0"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2
    assert proc.stderr.strip().splitlines() == ["bild-mdo design: error: ref_chord [m] must be positive, got 0"]


def test_verify_is_wired_to_the_runner(tmp_path, monkeypatch, capsys):
    # The sweep machinery runs end to end through the CLI with deterministic stand-ins for the science.
    case_functions = pytest.importorskip("bild_mdo.verification.case_functions")
    from tests.verification import standins

    monkeypatch.setattr(case_functions, "bild_batch", standins.bild_batch)
    monkeypatch.setattr(case_functions, "optimize_case", standins.optimize)
    code, out, err = _run(capsys, "verify", "--levels", "2", "--workers", "1", "--db", str(tmp_path / "v.sqlite"),
                          "--no-progress")
    assert code == 0, err
    assert "Sweep of 16 cases" in out
