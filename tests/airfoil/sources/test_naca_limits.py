"""NACA designations outside what XFOIL's polars hold are refused at once, with one line (not after a minute).

Source: the NACA 4-digit definition (Abbott & von Doenhoff, Theory of Wing Sections, Sec. 6.4): M P TT is a
maximum camber of M % of the chord at P tenths of the chord and a thickness of TT %; a camber needs a position.
"""
import pytest

from bild_mdo.airfoil.sources.coordinates import MAX_NACA_THICKNESS, parse_airfoil
from bild_mdo.io.airfoil import resolve_airfoil


@pytest.mark.parametrize("name, pattern", [
    ("naca9999", r"thickness of 99 % of chord is beyond"),
    (f"naca00{MAX_NACA_THICKNESS + 1}", rf"thickness of {MAX_NACA_THICKNESS + 1} %"),
    ("naca4012", r"camber needs a position P of 1-9"),
])
def test_sections_xfoil_cannot_hold_are_refused(name, pattern):
    with pytest.raises(ValueError, match=pattern):
        parse_airfoil(name)


def test_the_refusal_comes_before_any_xfoil_run(monkeypatch):
    def no_xfoil(*args, **kwargs):
        raise AssertionError("XFOIL was started")

    monkeypatch.setattr("bild_mdo.airfoil.sources.xfoil.run_xfoil", no_xfoil)
    with pytest.raises(ValueError, match="thickness of 99 %"):
        resolve_airfoil("naca9999")


@pytest.mark.parametrize("name", ["naca0012", "naca4412", f"naca00{MAX_NACA_THICKNESS}", "naca23015"])
def test_ordinary_sections_pass(name):
    assert parse_airfoil(name)[0] == "naca"
