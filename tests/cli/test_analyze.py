"""bild-mdo analyze: reads back what design writes, J and rpm sweeps, tables, CSV and PNG files."""
import numpy as np
import pytest

from bild_mdo.io.files import read_geometry
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
