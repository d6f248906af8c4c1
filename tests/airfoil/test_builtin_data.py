"""The NACA 4412 XFOIL polars shipped in bild_mdo/airfoil/data (see its README.md)."""
import importlib.resources
import re

import numpy as np
import pytest

from bild_mdo.airfoil.sources.readers import load_builtin_polars

DATA = importlib.resources.files("bild_mdo.airfoil") / "data"
# Paper Appendix 7.2: ten Reynolds numbers from 5e4 to 2e6.
EXPECTED_RE = [5e4, 1e5, 2e5, 3e5, 5e5, 7e5, 1e6, 1.3e6, 1.6e6, 2e6]


@pytest.fixture(scope="module")
def polars():
    return load_builtin_polars("naca4412")


def test_ten_files_from_5e4_to_2e6(polars):
    files = sorted(e.name for e in DATA.iterdir() if e.name.endswith(".txt"))
    assert len(files) == 10
    assert [p.reynolds for p in polars] == EXPECTED_RE


def test_files_are_small():
    for entry in DATA.iterdir():
        if entry.name.endswith(".txt"):
            assert len(entry.read_bytes()) < 10_000, entry.name


def test_settings_and_grid(polars):
    for p in polars:
        # Generated at Mach 0, Ncrit 9 on a 0.25 deg grid over -10..20 deg (data/README.md).
        assert p.mach == 0.0 and p.ncrit == 9.0
        assert p.source.startswith("XFOIL ") and "NACA 4412" in p.source
        assert p.alpha_deg[0] == -10.0 and p.alpha_deg[-1] == 20.0
        np.testing.assert_array_equal(np.round(p.alpha_deg * 4), p.alpha_deg * 4)
        # At most 5 of the 121 angles were dropped at any Re (data/README.md table).
        assert p.alpha_deg.size >= 116


def test_max_lift_to_drag_at_re_1e6(polars):
    # Source: XFOIL 6.99 itself, NACA 4412, Re = 1e6, Ncrit 9 (the shipped file):
    # max cl/cd = 132.8 at 5.5 deg; the brief's acceptance band is 130..150 at 4..6 deg.
    p = polars[EXPECTED_RE.index(1e6)]
    k = np.argmax(p.lift_to_drag)
    assert 130.0 < p.lift_to_drag[k] < 150.0
    assert 4.0 <= p.alpha_deg[k] <= 6.0


def test_max_lift_to_drag_grows_with_reynolds(polars):
    # Physical invariant: skin friction falls as Re grows, so the best cl/cd rises.
    best = [p.lift_to_drag.max() for p in polars]
    assert np.all(np.diff(best) > 0.0)


def test_attached_flow_is_consistent_across_reynolds(polars):
    # At Re >= 5e5 the lift at 4 deg varies little with Re (thin boundary layer):
    # XFOIL gives 0.905..0.924 for these files; the drag bucket minimum is below 0.01.
    for p in polars[4:]:
        i4 = np.flatnonzero(p.alpha_deg == 4.0)[0]
        assert 0.85 < p.cl[i4] < 0.97
        assert p.cd.min() < 0.01


def test_readme_table_matches_the_files(polars):
    text = (DATA / "README.md").read_text()
    assert "python -m bild_mdo.airfoil.sources.xfoil --airfoil 4412" in text
    assert "XFOIL 6.99" in text
    number, cell = r"\s*([\d.e]+)\s*", r"[^|]*"
    row = rf"^\|{number}\|{number}\|{number}\|{cell}\|{number}\|{number}\|$"
    rows = re.findall(row, text, flags=re.MULTILINE)
    assert len(rows) == 10
    for p, (re_text, points, dropped, best, at_alpha) in zip(polars, rows):
        assert float(re_text) == p.reynolds
        assert int(points) == p.alpha_deg.size and int(points) + int(dropped) == 121
        k = np.argmax(p.lift_to_drag)
        assert abs(float(best) - p.lift_to_drag[k]) < 0.051
        assert float(at_alpha) == p.alpha_deg[k]
