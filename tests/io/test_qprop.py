"""QPROP propeller files: foreign files read with QPROP's meaning, hub and tip rows, the airfoil-model fit, and
the checks that keep a file from lying (station widths, format version, byte-order mark)."""
import numpy as np
import pytest

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.io.qprop import polar_from_qprop, qprop_airfoil_coefficients, read_qprop, write_qprop
from tests.io import FILE_RTOL

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
    geometry = read_qprop(path)
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
    path = write_qprop(tmp_path / "blade.prop", design)
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


def test_too_short_file(tmp_path):
    (tmp_path / "short.prop").write_text("name\n 2 ! Nblades\n")
    with pytest.raises(ValueError, match="too short"):
        read_qprop(tmp_path / "short.prop")


@pytest.mark.parametrize("line, replacement, message", [
    (" 0.50  5.8      ! CL0     CL_a", " 0.50  0      ! CL0     CL_a", ":5: CL_a must be a positive finite number"),
    (" -0.3  1.2      ! CLmin   CLmax", " 1.3  1.2", ":6: CLmin must be smaller than CLmax"),
    (" 70000   -0.7               !  REref  REexp", " 0 -0.7", ":9: REref must be a positive finite number"),
    (" 0.028  0.050  0.020  0.5   !  CD0    CD2u   CD2l   CLCD0", " nan 0.05 0.02 0.5", ":8: expected finite"),
    (" 2              ! Nblades  [ R ]", " 2.5", ":3: Nblades must be an integer >= 1, got 2.5"),
    (" 2              ! Nblades  [ R ]", " inf", ":3: expected finite numbers"),
    (" 3.0   0.9    20.0", " 3.0   0.9", ":16: expected a station row 'r c beta'"),
    (" 3.0   0.9    20.0", " 0.5   0.9    20.0", ": station radii must be strictly increasing"),
])
def test_damaged_qprop_files_give_one_line(tmp_path, line, replacement, message):
    assert line in FOREIGN_QPROP
    path = tmp_path / "damaged.prop"
    path.write_text(FOREIGN_QPROP.replace(line, replacement))
    with pytest.raises(ValueError) as info:
        read_qprop(path)
    assert str(info.value).startswith(f"{path}") and message in str(info.value)


def test_polar_from_qprop_checks_the_lift_slope():
    coefficients = dict(CL0=0.5, CL_a=0.0, CLmin=-0.3, CLmax=1.2, CD0=0.028, CD2u=0.05, CD2l=0.02, CLCD0=0.5,
                        REref=7e4, REexp=-0.7)
    with pytest.raises(ValueError, match="CL_a must be a positive finite number"):
        polar_from_qprop(coefficients)


def _station_rows(path):
    """Line numbers (0-based) of the station rows of a QPROP file."""
    lines = path.read_text().splitlines()
    content = [i for i, line in enumerate(lines) if line.strip() and not line.lstrip().startswith("#")]
    return lines, content[8:]


def test_qprop_file_carries_version_and_widths(tmp_path, design):
    text = write_qprop(tmp_path / "blade.prop", design).read_text()
    assert "# bild-mdo: format = 2\n" in text
    widths = next(line for line in text.splitlines() if line.startswith("# bild-mdo: dr [m] = ")).split("=")[1]
    # BILD's 9 equal annuli from 0.3 m to 1.5 m, one width per BILD station (not for the hub and tip rows).
    np.testing.assert_allclose(np.array(widths.split(), dtype=float), np.full(9, 1.2 / 9), rtol=FILE_RTOL)


def test_cut_qprop_file_is_refused(tmp_path, design):
    # Cut after the 5th BILD station: the reader takes the last row left for the tip row and keeps 4 stations.
    path = write_qprop(tmp_path / "blade.prop", design)
    lines, rows = _station_rows(path)
    path.write_text("\n".join(lines[:rows[5] + 1]) + "\n")
    with pytest.raises(ValueError, match=r"^\S*blade\.prop: 4 stations but 9 widths 'dr \[m\]': the file was cut or "
                                         r"edited; write it again from the design$"):
        read_qprop(path)


def test_format_1_qprop_file_is_read_and_checked(tmp_path, design, assert_same_geometry):
    path = write_qprop(tmp_path / "blade.prop", design)
    lines = [line.replace("format = 2", "format = 1") for line in path.read_text().splitlines()
             if not line.startswith("# bild-mdo: dr [m]")]
    path.write_text("\n".join(lines) + "\n")
    assert_same_geometry(read_qprop(path), design.geometry())
    # Without its tip row and the last BILD station (cut two rows), the reader drops the 8th station as the tip
    # row: 7 stations, the last at 0.3 + 6.5 * 0.133333 = 1.166667 m, 2.5 spacings from the tip (hand derivation).
    lines, rows = _station_rows(path)
    path.write_text("\n".join(lines[:rows[-3] + 1]) + "\n")
    with pytest.raises(ValueError, match=r"blade\.prop: the last station \(r = 1\.16667 m\) is 0\.333333 m from the "
                                         r"tip \(R = 1\.5 m\), .*; write the file again from the design "
                                         r"\(bild-mdo design --qprop\)$"):
        read_qprop(path)


def test_foreign_file_whose_stations_end_short_of_r_is_refused(tmp_path):
    # R = 8 in on the Nblades line, unscaled as in QPROP, and Rfac = 1: the last station (5 in) lies 3 in from R,
    # more than the 2 in to its neighbour.
    text = (FOREIGN_QPROP.replace(" 2              ! Nblades  [ R ]", " 2  8.0  ! Nblades  [ R ]")
            .replace(" 0.0254  0.0254   1.0  !  Rfac   Cfac   Bfac", " 1.0  1.0  1.0"))
    path = tmp_path / "short.prop"
    path.write_text(text)
    with pytest.raises(ValueError, match=r"short\.prop: the last station \(r = 5 m\) is 3 m from the tip \(R = 8 m\), "
                                         r"more than the 2 m to its neighbour: .*; add a station row at r = R, or "
                                         r"leave R out of the Nblades line"):
        read_qprop(path)


def test_newer_qprop_file_is_refused(tmp_path, design):
    path = write_qprop(tmp_path / "blade.prop", design)
    path.write_text(path.read_text().replace("format = 2", "format = 99"))
    with pytest.raises(ValueError, match=r"^\S*blade\.prop: format version 99 is newer than this bild-mdo reads"):
        read_qprop(path)


def test_byte_order_mark_is_read(tmp_path, design, assert_same_geometry):
    path = write_qprop(tmp_path / "blade.prop", design)
    path.write_bytes(b"\xef\xbb\xbf" + path.read_bytes())
    assert_same_geometry(read_qprop(path), design.geometry())
