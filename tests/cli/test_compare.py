"""bild-mdo compare: one row per geometry file and an overlay figure.

Sources: hand derivations.  A file compared with itself differs by 0 %; a blade whose chord is scaled by
(1 + k) differs by 100 k % in chord and 0 % in twist (||(1 + k) c - c|| / ||c|| = k).
"""
import dataclasses

import numpy as np
import pytest

from bild_mdo.io import write_geometry
from bild_mdo.results.design import design_rotor
from tests.cli.runner import run


def test_compare_prints_the_differences_and_writes_the_overlay(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    design = design_rotor(advance_ratio=0.5, airfoil="analytic", num_radial=12, bem_analysis=False)
    geometry = design.geometry()
    first, second = tmp_path / "a.json", tmp_path / "b.csv"
    write_geometry(first, geometry)
    write_geometry(second, dataclasses.replace(geometry, chord=1.1 * geometry.chord))
    figure = tmp_path / "overlay.png"
    code, out, err = run(capsys, "compare", str(first), str(second), str(first), "--plot", str(figure))
    assert code == 0, err
    rows = out.splitlines()[1:4]
    assert rows[0].split()[-3:-1] == ["ref", "ref"]
    assert [float(x) for x in rows[1].split()[-3:-1]] == pytest.approx([10.0, 0.0], abs=1e-6)
    assert [float(x) for x in rows[2].split()[-3:-1]] == [0.0, 0.0]
    assert f"{design.thrust:.5g}" in rows[0] and f"{design.efficiency:.4f}" in rows[0]
    assert figure.stat().st_size > 0


def test_compare_needs_two_files(tmp_path, capsys):
    code, _, err = run(capsys, "compare", str(tmp_path / "a.json"))
    assert code == 2 and "at least two geometry files" in err
