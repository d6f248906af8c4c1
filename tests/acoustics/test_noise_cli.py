"""bild-mdo noise: the table of a geometry file's noise at observers, its figures, and one-line errors."""
import numpy as np
import pytest

from bild_mdo.results.design import design_rotor
from tests.cli.runner import run


@pytest.fixture(scope="module")
def blade(tmp_path_factory):
    """A small BILD hover blade (R = 0.5 m, B = 2, 2000 rpm) written as JSON."""
    path = tmp_path_factory.mktemp("noise") / "blade.json"
    design_rotor(v_axial=0.0, rpm=2000.0, radius=0.5, ref_chord=0.05, num_radial=8, num_blades=2,
                 bem_analysis=False).to_json(path)
    return path


def test_table_of_two_observers(blade, capsys):
    code, out, err = run(capsys, "noise", str(blade), "--observer", "-10", "0", "2", "--observer", "-7", "7", "0",
                         "--harmonics", "3")
    assert code == 0, err
    assert "Rotor noise: B = 2, 2000 rpm" in out and "3 harmonics" in out and "tripped" in out
    rows = [line.split() for line in out.splitlines() if line.split()[:2] in (["0", "0"], ["0", "1"])]
    assert len(rows) == 2
    oaspl, dba = float(rows[0][6]), float(rows[0][7])
    assert 20.0 < oaspl < 140.0 and np.isfinite(dba)


def test_untripped_and_other_rpm(blade, capsys):
    code, out, err = run(capsys, "noise", str(blade), "--observer", "-10", "0", "0", "--untripped", "--rpm", "2100",
                         "--harmonics", "2")
    assert code == 0, err
    assert "untripped boundary layer" in out and "2100 rpm" in out


def test_plots(blade, capsys, tmp_path):
    pytest.importorskip("matplotlib")
    spectrum, arc = tmp_path / "spectrum.png", tmp_path / "arc"
    code, out, err = run(capsys, "noise", str(blade), "--observer", "-8", "6", "0", "--harmonics", "2",
                         "--plot", str(spectrum), "--directivity", str(arc))
    assert code == 0, err
    assert spectrum.stat().st_size > 1000 and (tmp_path / "arc.png").stat().st_size > 1000
    assert f"wrote {arc}.png" in out


def test_blunt_trailing_edge(blade, capsys):
    """--trailing-edge-thickness adds the BPM bluntness noise (Eq. 70): the summary names the edge, and the
    broadband level rises (the other mechanisms are unchanged, tests/acoustics/test_broadband_noise.py)."""
    argv = ["noise", str(blade), "--observer", "-10", "0", "2", "--harmonics", "2"]
    levels = []
    for extra in ([], ["--trailing-edge-thickness", "0.0008", "--trailing-edge-angle", "16"]):
        code, out, err = run(capsys, *argv, *extra)
        assert code == 0, err
        row = next(line.split() for line in out.splitlines() if line.split()[:2] == ["0", "0"])
        levels.append(float(row[9]))
    assert "trailing edge 0.8 mm, Psi 16 deg" in out
    assert levels[1] > levels[0]


@pytest.mark.parametrize("extra, message", [
    (["--trailing-edge-thickness", "-1e-3"], "--trailing-edge-thickness"),
    (["--trailing-edge-angle", "120"], "--trailing-edge-angle"), (["--azimuths", "0"], "--azimuths")])
def test_bad_trailing_edge_exits_2(blade, capsys, extra, message):
    code, _, err = run(capsys, "noise", str(blade), "--observer", "-10", "0", "0", *extra)
    assert code == 2 and message in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("observer, message", [
    (["0.1", "0.1", "0"], "inside the rotor"), (["nan", "0", "-5"], "not finite")])
def test_bad_observer_is_one_line(blade, capsys, observer, message):
    code, out, err = run(capsys, "noise", str(blade), "--observer", *observer)
    assert code == 2 and message in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


@pytest.mark.parametrize("argv, message", [
    (["--observer", "1", "2"], "--observer"), ([], "--observer"), (["--observer", "-5", "0", "x"], "invalid float"),
    (["--observer", "-5", "0", "0", "--harmonics", "0"], "--harmonics")])
def test_bad_arguments_exit_2(blade, capsys, argv, message):
    code, _, err = run(capsys, "noise", str(blade), *argv)
    assert code == 2 and message in err and len(err.strip().splitlines()) == 1


def test_missing_file(capsys, tmp_path):
    code, _, err = run(capsys, "noise", str(tmp_path / "nope.json"), "--observer", "-5", "0", "0")
    assert code == 2 and "nope.json" in err and len(err.strip().splitlines()) == 1
