"""Geometry files: CSV / JSON / QPROP round trips, units, foreign QPROP files, the QPROP airfoil fit."""
import numpy as np
import pytest

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.design import design_rotor
from bild_mdo.geometry_io import (RotorGeometry, polar_from_qprop, qprop_airfoil_coefficients, read_geometry,
                                  read_json, write_geometry, write_json)

# Files carry 12 significant digits (SIGNIFICANT_DIGITS): rounding error <= 0.5e-11 relative, plus
# round-off of the deg/rad conversion of the twist.
FILE_RTOL = 5.1e-12


@pytest.fixture(scope="module")
def design():
    return design_rotor(advance_ratio=0.7, ref_chord=0.13, altitude=1200.0, airfoil="analytic", num_radial=9)


def _assert_same(read, geometry):
    np.testing.assert_allclose(read.radii, geometry.radii, rtol=FILE_RTOL)
    np.testing.assert_allclose(read.chord, geometry.chord, rtol=FILE_RTOL)
    np.testing.assert_allclose(read.twist, geometry.twist, rtol=FILE_RTOL)
    assert read.radius == pytest.approx(geometry.radius, rel=FILE_RTOL)
    assert read.hub_radius == pytest.approx(geometry.hub_radius, rel=FILE_RTOL)
    assert read.num_blades == geometry.num_blades
    assert read.airfoil == geometry.airfoil
    assert read.loss_model == geometry.loss_model
    assert set(read.design_point) == set(geometry.design_point)
    for key, value in geometry.design_point.items():
        assert read.design_point[key] == pytest.approx(value, rel=FILE_RTOL, abs=1e-300)


@pytest.mark.parametrize("suffix", [".csv", ".json", ".qprop", ".prop"])
def test_round_trip(tmp_path, design, suffix):
    geometry = design.geometry()
    path = write_geometry(tmp_path / f"blade{suffix}", design)
    _assert_same(read_geometry(path), geometry)


def test_csv_declares_units(tmp_path, design):
    text = write_geometry(tmp_path / "blade.csv", design).read_text()
    assert "r [m],chord [m],twist [deg]" in text
    assert "# radius [m]: 1.5" in text and "# design_point.rpm [rpm]: 800" in text


def test_json_holds_several_designs(tmp_path):
    batch = design_rotor(ref_chord=[0.1, 0.2, 0.3], airfoil="analytic", num_radial=6)
    path = write_json(tmp_path / "blades.json", batch)
    _assert_same(read_json(path, design=2), batch.geometry(2))
    with pytest.raises(ValueError, match="holds 3 design"):
        read_json(path, design=3)


def test_csv_in_other_units_and_without_radii(tmp_path):
    # Stations at the midpoints of 4 equal annuli from 0.2 m to 1.0 m: hub and tip follow by extending
    # the end stations half a spacing (hand derivation: 0.3 - 0.1 = 0.2, 0.9 + 0.1 = 1.0).
    (tmp_path / "mm.csv").write_text("# num_blades: 2\nr [mm],chord [mm],twist [rad]\n"
                                     "300,100,0.5\n500,90,0.4\n700,80,0.3\n900,70,0.2\n")
    geometry = read_geometry(tmp_path / "mm.csv")
    np.testing.assert_allclose(geometry.radii, [0.3, 0.5, 0.7, 0.9])
    np.testing.assert_allclose(geometry.chord, [0.1, 0.09, 0.08, 0.07])
    np.testing.assert_allclose(geometry.twist, [0.5, 0.4, 0.3, 0.2])
    assert geometry.hub_radius == pytest.approx(0.2) and geometry.radius == pytest.approx(1.0)
    assert geometry.num_blades == 2 and geometry.airfoil is None


FOREIGN_QPROP = """\
Test prop 10x5 (inches)

 2              ! Nblades  [ R ]

 0.50  5.8      ! CL0     CL_a
 -0.3  1.2      ! CLmin   CLmax

 0.028  0.050  0.020  0.5   !  CD0    CD2u   CD2l   CLCD0
 70000   -0.7               !  REref  REexp

 0.0254  0.0254   1.0  !  Rfac   Cfac   Bfac
 0.      0.       2.0  !  Radd   Cadd   Badd

#  r    chord    beta
 1.0   1.0    30.0
 3.0   0.9    20.0
 5.0   0.6    15.0   0.5 5.8 -0.3 1.2 0.028 0.05 0.02 0.5 70000 -0.7
"""


def test_foreign_qprop_file(tmp_path):
    path = tmp_path / "prop10x5.txt"
    path.write_text(FOREIGN_QPROP)
    geometry = read_geometry(path)
    # QPROP source: r = r_file*Rfac + Radd, c = c_file*Cfac + Cadd, beta = beta_file*Bfac + Badd; without R
    # on the Nblades line the tip is the last station, and the blade starts at the first station.
    np.testing.assert_allclose(geometry.radii, np.array([1.0, 3.0, 5.0]) * 0.0254)
    np.testing.assert_allclose(geometry.chord, np.array([1.0, 0.9, 0.6]) * 0.0254)
    np.testing.assert_allclose(geometry.twist_deg, [32.0, 22.0, 17.0])
    assert geometry.radius == pytest.approx(5.0 * 0.0254)
    assert geometry.hub_radius == pytest.approx(1.0 * 0.0254)
    assert geometry.num_blades == 2 and geometry.airfoil is None
    coeffs = geometry.polar_coefficients
    assert coeffs["CD2l"] == 0.020 and coeffs["REref"] == 70000.0 and coeffs["REexp"] == -0.7
    polar = polar_from_qprop(coeffs)
    # At alpha = 0 and Re = REref the model gives cl = CL0, cd = CD0 + CD2u (CL0 - CLCD0)^2 (hand evaluation).
    values = polar.evaluate(0.0, 70000.0)
    assert float(values.cl) == pytest.approx(0.5)
    assert float(values.cd) == pytest.approx(0.028 + 0.050 * 0.0**2)


def test_qprop_file_spans_hub_to_tip(tmp_path, design):
    # QPROP integrates from the first to the last row, so the file carries rows at the hub and tip radius
    # (linear extrapolation) around the BILD stations; R on the Nblades line is the tip radius.
    path = write_geometry(tmp_path / "blade.prop", design)
    rows = [line.split() for line in path.read_text().splitlines()
            if line.strip() and not line.lstrip().startswith("#")][8:]
    radii = np.array([float(row[0]) for row in rows])
    chords = np.array([float(row[1]) for row in rows])
    assert radii[0] == pytest.approx(design.hub_radius) and radii[-1] == pytest.approx(design.radius)
    np.testing.assert_allclose(radii[1:-1], design.radii, rtol=FILE_RTOL)
    assert np.all(chords > 0.0)
    r, c = design.radii, design.chord
    assert chords[-1] == pytest.approx(max(c[-1] + (c[-1] - c[-2]) / (r[-1] - r[-2]) * (1.5 - r[-1]),
                                           0.5 * c[-1]), rel=FILE_RTOL)


def test_qprop_airfoil_fit_of_the_analytic_polar():
    # The analytic polar's attached flow IS QPROP's model: cl = 0.4 + 0.9*2*pi*alpha,
    # cd = 0.008 + 0.01 (cl - 0.4)^2 (AnalyticPolar defaults), so the fit must return those numbers.
    coeffs = qprop_airfoil_coefficients(AnalyticPolar(), 5e5)
    assert coeffs["CL0"] == pytest.approx(0.4, abs=1e-12)
    assert coeffs["CL_a"] == pytest.approx(0.9 * 2.0 * np.pi, rel=1e-12)
    assert coeffs["CD0"] == pytest.approx(0.008, rel=1e-9)
    assert coeffs["CLCD0"] == pytest.approx(0.4, abs=1e-6)
    assert coeffs["CD2u"] == pytest.approx(0.01, rel=1e-6)
    assert coeffs["CD2l"] == pytest.approx(0.01, rel=1e-6)
    assert coeffs["REexp"] == pytest.approx(0.0, abs=1e-12)
    assert coeffs["CLmin"] < 0.0 < coeffs["CLCD0"] < coeffs["CLmax"]


def test_invalid_geometry_and_files(tmp_path):
    with pytest.raises(ValueError, match="strictly increasing"):
        RotorGeometry(radii=[0.5, 0.4], chord=[0.1, 0.1], twist=[0.2, 0.1], radius=1.0, hub_radius=0.1, num_blades=2)
    with pytest.raises(ValueError, match="within hub and tip"):
        RotorGeometry(radii=[0.5, 1.4], chord=[0.1, 0.1], twist=[0.2, 0.1], radius=1.0, hub_radius=0.1, num_blades=2)
    with pytest.raises(FileNotFoundError):
        read_geometry(tmp_path / "missing.csv")
    (tmp_path / "bad.csv").write_text("# num_blades: 3\nr [m],chord [m],twist [deg]\n0.3,0.1,abc\n")
    with pytest.raises(ValueError, match="bad.csv:3"):
        read_geometry(tmp_path / "bad.csv")
    (tmp_path / "units.csv").write_text("# num_blades: 3\nr [ft],chord [m],twist [deg]\n0.3,0.1,1\n0.4,0.1,1\n")
    with pytest.raises(ValueError, match="unknown units 'ft'"):
        read_geometry(tmp_path / "units.csv")
    (tmp_path / "short.prop").write_text("name\n 2 ! Nblades\n")
    with pytest.raises(ValueError, match="too short"):
        read_geometry(tmp_path / "short.prop")
