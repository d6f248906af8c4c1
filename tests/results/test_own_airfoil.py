"""Your own airfoil: the README's three paths (a NACA designation, polar files, airfoils along the span).

The snippets are those of the README section "Your own airfoil", run as written.  A designation's
first use runs XFOIL (about 45 s for seven Reynolds numbers); here XFOIL's output is replaced by
stored XFOIL 6.99 tables of the same airfoils (``tests/results/data``, two Reynolds numbers each;
its README gives the command), so the tests check the plumbing, not XFOIL.

Invariant checked on every path: a blade written to a file and read back (its airfoil with it)
gives the same BEM thrust and torque as the blade in memory with the polar it was designed with.
"""
import json
import shlex
import shutil
from pathlib import Path

import numpy as np
import pytest

import bild_mdo.airfoil.builtin as builtin
import bild_mdo.airfoil.text as sweep_airfoils
from bild_mdo import design_rotor, off_design_sweep
from bild_mdo.airfoil.sources.coordinates import parse_airfoil
from bild_mdo.airfoil.sources.readers import read_polar_files
from bild_mdo.cli.main import main
from bild_mdo.io.airfoil import resolve_airfoil

DATA = Path(__file__).parent / "data"

XFOIL_DESIGNATION = """
bild-mdo design --airfoil naca2412 --advance-ratio 0.5 --json blade.json
bild-mdo analyze blade.json --advance-ratio 0.2 1.0 5
"""

POLAR_FILES = """
from bild_mdo import design_rotor, off_design_sweep

rotor = design_rotor(advance_ratio=0.5, airfoil="polars/naca2412")  # a folder of XFOIL polar files
rotor.to_csv("blade.csv")  # also writes blade.polar.json, which blade.csv names
sweep = off_design_sweep("blade.csv", advance_ratios=[0.2, 0.5, 1.0])  # the airfoil comes with the file
print(sweep.summary())
"""

SPANWISE_CLI = """
bild-mdo design --airfoil "0.2:naca4415;1:naca4412" --advance-ratio 0.5 --json blade.json
bild-mdo analyze blade.json --advance-ratio 0.2 1.0 5
"""

SPANWISE_PYTHON = """
from bild_mdo import design_rotor, spanwise_polar

polar = spanwise_polar({0.2: "naca4415", 1.0: "naca4412"})  # NACA 4415 at the root blending to 4412 at the tip
rotor = design_rotor(advance_ratio=0.5, airfoil=polar)
rotor.to_json("blade_spanwise.json")
print(rotor.cl_star)  # the max-L/D point of each station's own airfoil
"""


@pytest.fixture
def stored_xfoil(monkeypatch, tmp_path):
    """XFOIL replaced by the stored tables of the designation; fresh in-process polar memos; run in tmp_path."""
    def tables(airfoil, **settings):
        return read_polar_files([DATA / f"naca{parse_airfoil(airfoil)[1]}"])

    monkeypatch.setattr(builtin, "xfoil_polars", tables)
    monkeypatch.setattr(builtin, "_RESOLVED", {})
    monkeypatch.setattr(sweep_airfoils, "_POLARS", {})
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _shell(capsys, script):
    outputs = []
    for line in script.strip().splitlines():
        argv = shlex.split(line)
        assert argv[0] == "bild-mdo"
        code = main(argv[1:])
        captured = capsys.readouterr()
        assert code == 0, captured.err
        outputs.append(captured.out)
    return outputs


def _same_analysis(path, rotor, advance_ratios=(0.2, 0.4, 0.6, 0.8, 1.0), rtol=1e-14):
    from_file = off_design_sweep(path, advance_ratios=advance_ratios)
    in_memory = off_design_sweep(rotor, advance_ratios=advance_ratios)
    np.testing.assert_allclose(from_file.thrust, in_memory.thrust, rtol=rtol, atol=0.0)
    np.testing.assert_allclose(from_file.torque, in_memory.torque, rtol=rtol, atol=0.0)
    return from_file


def test_xfoil_designation_round_trips_through_json(stored_xfoil, capsys):
    design_out, analyze_out = _shell(capsys, XFOIL_DESIGNATION)
    assert "airfoil naca2412" in design_out and "maximum efficiency" in analyze_out
    entry = json.loads((stored_xfoil / "blade.json").read_text())["designs"][0]
    assert entry["polar"]["type"] == "tables" and len(entry["polar"]["tables"]) == 2
    # JSON keeps every digit (the twist, in degrees, to one rounding of the conversion): the file's
    # blade and polar give the same BEM numbers to round-off.
    rotor = design_rotor(advance_ratio=0.5, airfoil=resolve_airfoil("naca2412"))
    sweep = _same_analysis(stored_xfoil / "blade.json", rotor)
    assert all(f"{thrust:.5g}" in analyze_out for thrust in sweep.thrust)


def test_polar_files_round_trip_through_csv(stored_xfoil, capsys):
    shutil.copytree(DATA / "naca2412", stored_xfoil / "polars" / "naca2412")
    namespace = {}
    exec(compile(POLAR_FILES, "README: polar files", "exec"), namespace)
    assert "maximum efficiency" in capsys.readouterr().out
    assert "# polar_file: blade.polar.json" in (stored_xfoil / "blade.csv").read_text()
    # The CSV keeps 12 significant digits of r, chord and twist.
    _same_analysis(stored_xfoil / "blade.csv", namespace["rotor"], rtol=1e-9)


def test_spanwise_set_round_trips_through_json(stored_xfoil, capsys):
    _, analyze_out = _shell(capsys, SPANWISE_CLI)
    polar = json.loads((stored_xfoil / "blade.json").read_text())["designs"][0]["polar"]
    assert polar["type"] == "spanwise" and polar["radial_fractions"] == [0.2, 1.0]
    namespace = {}
    exec(compile(SPANWISE_PYTHON, "README: spanwise set", "exec"), namespace)
    rotor = namespace["rotor"]
    # Each station takes its own airfoil's max-L/D point: cl* varies along the span.
    assert np.ptp(rotor.cl_star) > 0.01
    _same_analysis(stored_xfoil / "blade_spanwise.json", rotor)
    # The command line and the Python snippet make the same blade, to round-off: the max-L/D solve starts
    # from the polar's table warmed by earlier queries, so its last bits can depend on what ran before.
    cli_blade = off_design_sweep(stored_xfoil / "blade.json", advance_ratios=[0.5])
    assert cli_blade.thrust[0] == pytest.approx(off_design_sweep(rotor, advance_ratios=[0.5]).thrust[0], rel=1e-12)
