"""The bild-mdo command: help texts with units, one-line errors with exit code 2, the subcommand wiring."""
import functools
import warnings
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
    (["design", "--airfoil", "foo"], "--airfoil: unknown airfoil 'foo'"),
    (["analyze", "missing.csv", "--rpm", "500", "900", "3", "--airfoil", "foo"], "--airfoil: unknown airfoil 'foo'"),
    (["analyze", "missing.csv", "--advance-ratio", "0", "1", "1e9"], "would need about 6 TB of memory"),
    (["analyze", "missing.csv", "--advance-ratio", "-1", "1", "3"], "--advance-ratio START must be a finite number >= 0, got -1"),
    (["analyze", "missing.csv", "--rpm", "nan", "900", "3"], "--rpm START must be a positive finite number in rpm, got nan"),
    (["design", "--num-radial", "100000000"], "would need about 300 GB of memory"),
    (["design", "--num-radial", "1"], "--num-radial must be an integer >= 2, got 1"),
    (["design", "--hub-radius-ratio", "0.6"], "hub_radius_ratio must be smaller"),
    (["design", "--rpm", "800", "900", "--ref-chord", "0.1", "0.2", "0.3"], "batch sizes disagree"),
    (["analyze", "missing.csv", "--rpm", "500", "900", "3"], "not found"),
    (["analyze", "missing.csv"], "give the sweep: --advance-ratio START STOP N, --v-axial START STOP N, --rpm "
                                    "START STOP N or --collective-pitch START STOP N, or a trim: --thrust T"),
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


def test_warnings_show_once_as_one_line_without_source(monkeypatch, capsys):
    def handler(args, out):
        for _ in range(3):  # the same message from one place and from another: shown once
            warnings.warn("Reynolds number clamped\n  to the table", UserWarning)
        warnings.warn("Reynolds number clamped to the table", UserWarning)
        warnings.warn("another message", RuntimeWarning)
        return 0

    module, add_arguments, _ = cli_main.COMMANDS["demo"]
    monkeypatch.setitem(cli_main.COMMANDS, "demo", (module, add_arguments, handler))
    code, _, err = run(capsys, "demo")
    assert code == 0
    assert err.splitlines() == ["bild-mdo: warning: Reynolds number clamped to the table",
                                "bild-mdo: warning: another message"]


def test_an_unexpected_error_is_one_line_with_exit_1(monkeypatch, capsys):
    def handler(args, out):
        raise KeyError("station")

    module, add_arguments, _ = cli_main.COMMANDS["demo"]
    monkeypatch.setitem(cli_main.COMMANDS, "demo", (module, add_arguments, handler))
    code, _, err = run(capsys, "demo")
    assert code == 1
    assert err.strip().splitlines() == ["bild-mdo demo: internal error: KeyError: 'station' (rerun with --debug "
                                        "for the traceback and report it)"]


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
