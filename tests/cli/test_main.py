"""The bild-mdo command: help texts with units, one-line errors with exit code 2, the subcommand wiring."""
import functools
import subprocess
import sys

import pytest

from bild_mdo import __version__
from bild_mdo.cli import main as cli_main
from tests.cli.runner import run
from tests.verification import standins


@pytest.mark.parametrize("argv, units", [
    ([], ["m/s", "rpm"]),
    (["design"], ["[m/s]", "[m]", "[rpm]", "[deg]"]),
    (["analyze"], ["[m/s]", "[rpm]", "[m]", "[kW]"]),
    (["verify"], ["m)", "rpm"]),
    (["demo"], ["[m]", "[deg]", "kW"]),
])
def test_help_exits_zero_and_mentions_units(capsys, argv, units):
    code, out, _ = run(capsys, *argv, "--help")
    assert code == 0
    for unit in units:
        assert unit in out


def test_version(capsys):
    code, out, _ = run(capsys, "--version")
    assert code == 0 and out.strip() == f"bild-mdo {__version__}"


@pytest.mark.parametrize("argv, message", [
    (["design", "--radius", "-1"], "radius must be a positive finite number in m, got -1"),
    (["design", "--radius", "nan"], "radius must be a positive finite number in m, got nan"),
    (["design", "--rpm", "abc"], "invalid float value"),
    (["design", "--v-axial", "1", "--advance-ratio", "1"], "not allowed with"),
    (["design", "--airfoil", "foo"], "invalid choice"),
    (["design", "--hub-radius-ratio", "0.6"], "hub_radius_ratio must be smaller"),
    (["design", "--rpm", "800", "900", "--ref-chord", "0.1", "0.2", "0.3"], "batch sizes disagree"),
    (["analyze", "missing.csv", "--rpm", "500", "900", "3"], "not found"),
    (["analyze", "missing.csv"], "one of the arguments --advance-ratio --rpm is required"),
    (["analyze", "missing.csv", "--rpm", "500", "900", "2.5"], "--rpm N must be an integer >= 1, got 2.5"),
    (["analyze", "missing.csv", "--advance-ratio", "0", "1", "0"], "--advance-ratio N must be an integer >= 1, got 0"),
    (["verify", "--levels", "x"], "invalid int value"),
    (["bogus"], "invalid choice"),
    ([], "give a command"),
])
def test_bad_arguments_give_one_line_and_exit_2(tmp_path, monkeypatch, capsys, argv, message):
    monkeypatch.chdir(tmp_path)
    code, out, err = run(capsys, *argv)
    assert code == 2
    assert len(err.strip().splitlines()) == 1, err
    assert message in err and "error" in err
    assert "Traceback" not in err + out


def test_debug_shows_the_traceback(capsys):
    code, _, err = run(capsys, "design", "--radius", "-1", "--debug")
    assert code == 2
    assert "Traceback" in err and err.strip().splitlines()[-1].startswith("bild-mdo design: error:")


def test_entry_point_process_exit_code():
    # The real process: one line on stderr, exit status 2, no traceback.
    proc = subprocess.run([sys.executable, "-m", "bild_mdo.cli.main", "design", "--ref-chord", "0"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2
    assert proc.stderr.strip().splitlines() == [
        "bild-mdo design: error: ref_chord must be a positive finite number in m, got 0"]


def test_verify_is_wired_to_the_runner(tmp_path, monkeypatch, capsys):
    # The sweep machinery runs end to end through the CLI with deterministic stand-ins for the science.
    module, add_arguments, run_verify = cli_main.COMMANDS["verify"]
    monkeypatch.setitem(cli_main.COMMANDS, "verify", (module, add_arguments, functools.partial(
        run_verify, bild_batch_fn=standins.bild_batch, optimize_fn=standins.optimize)))
    code, out, err = run(capsys, "verify", "--levels", "2", "--workers", "1", "--db", str(tmp_path / "v.sqlite"),
                         "--no-progress")
    assert code == 0, err
    assert "Sweep of 16 cases" in out
