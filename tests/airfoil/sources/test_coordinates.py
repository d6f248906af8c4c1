"""The airfoil argument of the polar generators: NACA 4- and 5-digit designations and Selig coordinate files."""
import re

import numpy as np
import pytest

from bild_mdo.airfoil.sources.coordinates import parse_airfoil, read_coordinates


@pytest.mark.parametrize("name", ["NACA 4412", "naca4412", "4412", " naca-4412 "])
def test_parse_naca_designations(name):
    assert parse_airfoil(name) == ("naca", "4412")


@pytest.mark.parametrize("name", ["NACA 23012", "naca23015", "23112"])
def test_parse_naca_five_digit_designations(name):
    # NACA 5-digit series (Jacobs & Pinkerton 1935): L P Q TT, P = 1..5, Q = 0 or 1.
    assert parse_airfoil(name) == ("naca", name.lower().replace("naca", "").strip())


@pytest.mark.parametrize("name, pattern", [
    ("NACA 230120", "only NACA 4- and 5-digit designations"),
    ("naca 441", "only NACA 4- and 5-digit designations"),
    ("naca 29012", "L P Q TT with P in 1-5"),
    ("naca4400", "must not be 00"),
    ("naca23000", "must not be 00"),
    ("clark-y", "neither a NACA 4- or 5-digit designation"),
])
def test_parse_airfoil_rejects(name, pattern):
    with pytest.raises(ValueError, match=pattern):
        parse_airfoil(name)


def test_parse_airfoil_accepts_existing_file(tmp_path):
    path = tmp_path / "section.dat"
    path.write_text("x\n")
    assert parse_airfoil(str(path)) == ("file", path)
    assert parse_airfoil(path) == ("file", path)


def test_read_selig_file_with_name_line(tmp_path):
    # Selig order: trailing edge, upper surface, leading edge, lower surface.
    x = np.concatenate([np.linspace(1.0, 0.0, 8), np.linspace(0.0, 1.0, 8)[1:]])
    y = np.concatenate([0.06 * np.sin(np.pi * x[:8]), -0.04 * np.sin(np.pi * x[8:])])
    path = tmp_path / "section.dat"
    path.write_text("MY SECTION\n" + "".join(f"{a:.6f} {b:.6f}\n" for a, b in zip(x, y)))
    name, xy = read_coordinates(path)
    assert name == "MY SECTION"
    assert xy.shape == (15, 2)
    np.testing.assert_allclose(xy[:, 0], x, atol=5e-7)


def test_coordinate_file_checks(tmp_path):
    lednicer = tmp_path / "led.dat"
    lednicer.write_text("NACA 4412\n61. 61.\n" + "0.0 0.0\n" * 20)
    with pytest.raises(ValueError, match="Lednicer"):
        read_coordinates(lednicer)
    bad = tmp_path / "bad.dat"
    bad.write_text("name\n1.0 0.0\n0.5 0.1 3\n")
    with pytest.raises(ValueError, match=rf"{re.escape(str(bad))}:3: expected two numbers"):
        read_coordinates(bad)
    short = tmp_path / "short.dat"
    short.write_text("1.0 0.0\n0.0 0.0\n1.0 0.0\n")
    with pytest.raises(ValueError, match="3 coordinate points; at least 10"):
        read_coordinates(short)
