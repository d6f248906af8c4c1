"""Polar file readers: round trips, XFOIL header parsing and every error path."""
import math
import re

import numpy as np
import pytest

from bild_mdo.airfoil.sources.polar_data import MIN_POINTS, PolarData, PolarFileError
from bild_mdo.airfoil.sources.readers import (
    available_builtin_polars,
    load_builtin_polars,
    read_polar_files,
    read_polar_table,
    read_xfoil_polar,
    write_polar_table,
)

# Header of a polar file written by XFOIL 6.99 (PACC), copied from a run of the
# Debian build; rows start on line 13.
XFOIL_699_HEADER = """\

       XFOIL         Version 6.99

 Calculated polar for: NACA 4412

 1 1 Reynolds number fixed          Mach number fixed

 xtrf =   1.000 (top)        1.000 (bottom)
 Mach =   0.000     Re =     1.000 e 6     Ncrit =   9.000  9.000

   alpha    CL        CD       CDp       CM     Top_Xtr  Bot_Xtr  Top_Itr  Bot_Itr
  ------ -------- --------- --------- -------- -------- -------- -------- --------
"""
XFOIL_FIRST_ROW_LINE = 13

# Older XFOIL (6.9x) writes seven columns and a single Ncrit.
XFOIL_OLD_HEADER = """\
       XFOIL         Version 6.96

 Calculated polar for: NACA 0012

 1 1 Reynolds number fixed          Mach number fixed

 xtrf =   1.000 (top)        1.000 (bottom)
 Mach =   0.100     Re =     0.050 e 6     Ncrit =   7.000

   alpha    CL        CD       CDp       CM     Top_Xtr  Bot_Xtr
  ------ -------- --------- --------- -------- -------- --------
"""


def _p(path):
    return re.escape(str(path))


def _rows(n=12):
    alpha = np.arange(n, dtype=float) - 2.0
    return alpha, 0.47 + 0.11 * alpha, 0.006 + 1e-4 * alpha ** 2


def _xfoil_text(header=XFOIL_699_HEADER, ncols=9, n=12, edit=None):
    alpha, cl, cd = _rows(n)
    lines = []
    for a, c, d in zip(alpha, cl, cd):
        extra = ["0.00100", "-0.1000", "0.5000", "1.0000", "30.0000", "160.0000"][:ncols - 3]
        lines.append(["%8.3f" % a, "%8.4f" % c, "%9.5f" % d] + extra)
    if edit:
        edit(lines)
    return header + "".join(" ".join(r) + "\n" for r in lines)


def _table_text(n=12, edit=None, header="alpha_deg cl cd", meta="# reynolds = 200000\n"):
    alpha, cl, cd = _rows(n)
    rows = [[repr(float(a)), repr(float(c)), repr(float(d))] for a, c, d in zip(alpha, cl, cd)]
    if edit:
        edit(rows)
    return meta + header + "\n" + "".join(" ".join(r) + "\n" for r in rows)


# ---------------------------------------------------------------- round trips

def test_table_round_trip_is_exact(tmp_path):
    rng = np.random.default_rng(4412)
    alpha = np.sort(rng.uniform(-10.0, 20.0, 25))
    data = PolarData(reynolds=123456.789, mach=0.05, alpha_deg=alpha, cl=rng.normal(size=25),
                     cd=rng.uniform(0.005, 0.2, 25), source="random test data", ncrit=7.5)
    path = tmp_path / "polar.txt"
    write_polar_table(path, data)
    back = read_polar_table(path)
    # write_polar_table uses repr(), the shortest exact float text, so values come back bit for bit.
    for field in ("alpha_deg", "cl", "cd"):
        np.testing.assert_array_equal(getattr(back, field), getattr(data, field))
    assert (back.reynolds, back.mach, back.ncrit, back.source) == (123456.789, 0.05, 7.5, "random test data")


def test_table_round_trip_without_ncrit(tmp_path):
    alpha, cl, cd = _rows()
    data = PolarData(reynolds=5e4, mach=0.0, alpha_deg=alpha, cl=cl, cd=cd, source="x")
    write_polar_table(tmp_path / "p.txt", data)
    back = read_polar_table(tmp_path / "p.txt", reynolds=5e4)
    assert back.ncrit is None and back.reynolds == 5e4
    np.testing.assert_array_equal(back.cd, data.cd)


def test_xfoil_round_trip_through_table(tmp_path):
    (tmp_path / "xf.pol").write_text(_xfoil_text())
    data = read_xfoil_polar(tmp_path / "xf.pol")
    write_polar_table(tmp_path / "t.txt", data)
    back = read_polar_table(tmp_path / "t.txt")
    np.testing.assert_array_equal(back.cl, data.cl)
    assert back.reynolds == data.reynolds == 1e6


def test_write_rejects_non_polardata(tmp_path):
    with pytest.raises(TypeError, match="PolarData"):
        write_polar_table(tmp_path / "x.txt", {"alpha_deg": [0.0]})


# ------------------------------------------------------------ XFOIL header

def test_xfoil_699_header_and_columns(tmp_path):
    path = tmp_path / "naca4412.pol"
    path.write_text(_xfoil_text())
    data = read_xfoil_polar(path)
    alpha, cl, cd = _rows()
    # "Re =     1.000 e 6" is XFOIL's way of writing 1.0e6 (mantissa, space, e, exponent).
    assert data.reynolds == 1.0e6
    assert data.mach == 0.0 and data.ncrit == 9.0
    np.testing.assert_allclose(data.alpha_deg, alpha, atol=5e-4)
    np.testing.assert_allclose(data.cl, cl, atol=5e-5)
    np.testing.assert_allclose(data.cd, cd, atol=5e-6)
    assert data.source == "naca4412.pol"


def test_xfoil_old_seven_column_file(tmp_path):
    path = tmp_path / "old.pol"
    path.write_text(_xfoil_text(XFOIL_OLD_HEADER, ncols=7))
    data = read_xfoil_polar(path)
    # "0.050 e 6" = 5.0e4; Mach and Ncrit straight from the header line.
    assert math.isclose(data.reynolds, 5.0e4, rel_tol=1e-12)
    assert data.mach == 0.1 and data.ncrit == 7.0


def test_xfoil_variable_re_polar_rejected(tmp_path):
    path = tmp_path / "t2.pol"
    path.write_text(_xfoil_text(XFOIL_699_HEADER.replace("1 1 Reynolds number fixed",
                                                         "2 2 Reynolds number ~ 1/sqrt(CL)")))
    with pytest.raises(PolarFileError, match="fixed-Re"):
        read_xfoil_polar(path)


# ------------------------------------------------------------- plain tables

def test_csv_any_column_order_extra_columns_comments(tmp_path):
    path = tmp_path / "p.csv"
    alpha, cl, cd = _rows()
    body = "".join(f"{float(d)!r}, 0.5, {float(a)!r}, {float(c)!r}  # row comment\n"
                   for a, c, d in zip(alpha, cl, cd))
    path.write_text("# measured somewhere\n\ncd, cm, alpha_deg, cl\n" + body)
    data = read_polar_table(path, reynolds=3e5, mach=0.1)
    np.testing.assert_array_equal(data.alpha_deg, alpha)
    np.testing.assert_array_equal(data.cl, cl)
    np.testing.assert_array_equal(data.cd, cd)
    assert (data.reynolds, data.mach, data.source) == (3e5, 0.1, "p.csv")


def test_table_reynolds_argument_must_match_file(tmp_path):
    path = tmp_path / "p.txt"
    path.write_text(_table_text())
    assert read_polar_table(path, reynolds=2e5).reynolds == 2e5
    with pytest.raises(PolarFileError, match=rf"{_p(path)}:1: file says reynolds = 200000"):
        read_polar_table(path, reynolds=1e6)


def test_table_without_reynolds_needs_argument(tmp_path):
    path = tmp_path / "p.txt"
    path.write_text(_table_text(meta=""))
    with pytest.raises(PolarFileError, match=rf"{_p(path)}: no Reynolds number: pass reynolds="):
        read_polar_table(path)


# --------------------------------------------------------------- error paths
# Each message must start with "<file>:<line>:" (or name the file and the
# lines involved) so the user can go straight to the problem.

def _bad_number(rows):
    rows[3][1] = "0.5x"


def _short_row(rows):
    rows[4] = rows[4][:-1]


def _swap(rows):
    rows[5][0], rows[6][0] = rows[6][0], rows[5][0]


def _zero_cd(rows):
    rows[7][2] = "0.0"


def _nan_cl(rows):
    rows[2][1] = "nan"


# plain table: line 1 is "# reynolds", line 2 the header, row i on line i + 3
@pytest.mark.parametrize("edit, line, pattern", [
    (_bad_number, 6, r"malformed number '0\.5x' in column 'cl'"),
    (_short_row, 7, r"2 columns, expected 3"),
    (_swap, 9, r"alpha must be strictly increasing; alpha = 3 follows alpha = 4 on line 8"),
    (_zero_cd, 10, r"cd = 0\.0 must be > 0"),
    (_nan_cl, 5, r"cl is nan"),
])
def test_table_errors_name_file_and_line(tmp_path, edit, line, pattern):
    path = tmp_path / "bad.txt"
    path.write_text(_table_text(edit=edit))
    with pytest.raises(PolarFileError, match=rf"{_p(path)}:{line}: {pattern}"):
        read_polar_table(path)


def _xf_bad_number(rows):
    rows[3][1] = "0.5x"


def _xf_short_row(rows):
    rows[4] = rows[4][:-1]


def _xf_swap(rows):
    rows[5][0], rows[6][0] = rows[6][0], rows[5][0]


def _xf_zero_cd(rows):
    rows[7][2] = "0.00000"


def _xf_nan(rows):
    rows[2][2] = "NaN"


@pytest.mark.parametrize("edit, row, pattern", [
    (_xf_bad_number, 3, r"malformed number '0\.5x' in column 'cl'"),
    (_xf_short_row, 4, r"8 columns, expected 9"),
    (_xf_swap, 6, r"alpha must be strictly increasing; alpha = 3 follows alpha = 4 on line 18"),
    (_xf_zero_cd, 7, r"cd = 0\.0 must be > 0"),
    (_xf_nan, 2, r"cd is nan"),
])
def test_xfoil_errors_name_file_and_line(tmp_path, edit, row, pattern):
    path = tmp_path / "bad.pol"
    path.write_text(_xfoil_text(edit=edit))
    with pytest.raises(PolarFileError, match=rf"{_p(path)}:{XFOIL_FIRST_ROW_LINE + row}: {pattern}"):
        read_xfoil_polar(path)


def test_too_few_points_names_file_and_lines(tmp_path):
    table = tmp_path / "few.txt"
    table.write_text(_table_text(n=MIN_POINTS - 1))
    with pytest.raises(PolarFileError, match=rf"{_p(table)}: only 9 data rows \(lines 3-11\); at least 10"):
        read_polar_table(table)
    pol = tmp_path / "few.pol"
    pol.write_text(_xfoil_text(n=MIN_POINTS - 1))
    with pytest.raises(PolarFileError, match=rf"{_p(pol)}: only 9 data rows \(lines 13-21\)"):
        read_xfoil_polar(pol)


def test_table_missing_header(tmp_path):
    path = tmp_path / "nohead.txt"
    path.write_text(_table_text(header="0.0 0.1 0.01", meta="# just numbers\n"))
    with pytest.raises(PolarFileError, match=rf"{_p(path)}:2: missing header: the first row holds numbers"):
        read_polar_table(path, reynolds=1e5)
    path.write_text(_table_text(header="angle cl cd"))
    with pytest.raises(PolarFileError, match=rf"{_p(path)}:2: missing header: .*missing \['alpha_deg'\]"):
        read_polar_table(path)
    path.write_text("# only comments\n\n")
    with pytest.raises(PolarFileError, match=rf"{_p(path)}:2: missing header: no line naming the columns"):
        read_polar_table(path, reynolds=1e5)


def test_xfoil_missing_header(tmp_path):
    path = tmp_path / "nore.pol"
    path.write_text(_xfoil_text(header="   alpha    CL        CD\n  ------ -------- ---------\n", ncols=3))
    with pytest.raises(PolarFileError, match=rf"{_p(path)}:1: missing header: no 'Re = ...' line"):
        read_xfoil_polar(path)
    no_dashes = "".join(line + "\n" for line in XFOIL_699_HEADER.splitlines() if "------" not in line)
    path.write_text(_xfoil_text(header=no_dashes))
    with pytest.raises(PolarFileError, match=rf"{_p(path)}:\d+: missing header: expected a column line"):
        read_xfoil_polar(path)


def test_table_malformed_metadata(tmp_path):
    path = tmp_path / "meta.txt"
    path.write_text(_table_text(meta="# reynolds = lots\n"))
    with pytest.raises(PolarFileError, match=rf"{_p(path)}:1: malformed number 'lots' for reynolds"):
        read_polar_table(path)


def test_missing_file():
    with pytest.raises(PolarFileError, match="no such polar file"):
        read_polar_table("/nonexistent/polar.txt", reynolds=1e5)


# ---------------------------------------------------------- built-in loader

def test_builtin_loader_names():
    assert "naca4412" in available_builtin_polars()
    # Case, spaces and dashes in the name are ignored.
    assert [p.reynolds for p in load_builtin_polars("NACA 4412")] == \
        [p.reynolds for p in load_builtin_polars("naca-4412")]
    with pytest.raises(ValueError, match=r"no built-in polars named 'naca0012'; available: .*naca4412"):
        load_builtin_polars("naca0012")


# Usual spellings of the three columns (alpha, cl, cd), with an extra column and the comma or space separator.
@pytest.mark.parametrize("header, order", [
    ("alpha,cl,cd", "acd"), ("Alpha CL CD", "acd"), ("AoA,CL,CD,Cm", "acdx"), ("alpha_deg cd cl", "adc"),
    ("ALPHA Cl Cd Cdp", "acdx"), ("aoa(deg) c_l c_d", "acd"),
])
def test_table_column_spellings(tmp_path, header, order):
    rows = [(-4.0 + i, 0.1 * i, 0.01 + 0.001 * i) for i in range(12)]
    sep = "," if "," in header else " "
    lines = [header] + [sep.join(str({"a": a, "c": cl, "d": cd, "x": 0.0}[k]) for k in order) for a, cl, cd in rows]
    path = tmp_path / "spelled_re250000.txt"
    path.write_text("\n".join(lines) + "\n")
    data = read_polar_table(path)
    assert data.reynolds == 250000.0          # from the file name
    np.testing.assert_array_equal(data.alpha_deg, [r[0] for r in rows])
    np.testing.assert_array_equal(data.cl, [r[1] for r in rows])
    np.testing.assert_array_equal(data.cd, [r[2] for r in rows])


AIRFOILTOOLS = """Xfoil polar. Reynolds number fixed. Mach number fixed
Polar key,xf-naca2412-il-200000
Airfoil,naca2412-il
Reynolds number,200000
Ncrit,9
Mach,0
Max Cl/Cd,76.1
Max Cl/Cd alpha,6.25
Url,http://airfoiltools.com/polar/csv?polar=xf-naca2412-il-200000
,
Alpha,Cl,Cd,Cdp,Cm,Top_Xtr,Bot_Xtr
"""


def test_airfoiltools_csv_with_its_preamble(tmp_path):
    rows = [f"{-5 + i:.3f},{0.2 + 0.1 * i:.4f},{0.01 + 0.0005 * i:.5f},0.004,-0.05,0.6,1.0" for i in range(12)]
    path = tmp_path / "xf-naca2412-il-200000.csv"
    path.write_text(AIRFOILTOOLS + "\n".join(rows) + "\n")
    data = read_polar_table(path)
    assert (data.reynolds, data.mach, data.ncrit) == (200000.0, 0.0, 9.0)
    assert data.alpha_deg[0] == -5.0 and data.cd[-1] == pytest.approx(0.0155)
    # Errors after the preamble still name the file and the line (row 5 is line 16).
    rows[4] = "-1.000,0.6x00,0.01200,0.004,-0.05,0.6,1.0"
    path.write_text(AIRFOILTOOLS + "\n".join(rows) + "\n")
    with pytest.raises(PolarFileError, match=rf"{_p(path)}:16: malformed number '0\.6x00' in column 'cl'"):
        read_polar_table(path)


def test_read_polar_files_reads_a_folder_of_both_formats(tmp_path):
    (tmp_path / "a.pol").write_text(_xfoil_text())
    (tmp_path / "b_re50000.txt").write_text(_table_text(meta=""))
    (tmp_path / "notes.md").write_text("not a polar")
    polars = read_polar_files(tmp_path)
    assert sorted(p.reynolds for p in polars) == sorted([read_xfoil_polar(tmp_path / "a.pol").reynolds, 5e4])
    (tmp_path / "c.txt").write_text(_table_text(meta="# reynolds = 50000\n"))
    with pytest.raises(PolarFileError, match=r"c\.txt: Re = 50000, Mach = 0 again \(also in .*b_re50000\.txt\)"):
        read_polar_files(tmp_path)
    (tmp_path / "empty").mkdir()
    with pytest.raises(PolarFileError, match="empty: no polar files"):
        read_polar_files(tmp_path / "empty")
