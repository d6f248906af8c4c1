"""Section thickness ratio t/c as part of the airfoil description (NACA designations, files, spanwise sets)."""
import numpy as np
import pytest

from bild_mdo.airfoil import AnalyticPolar, CompressiblePolar, SpanwisePolar, get_polar, resolve_polar
from bild_mdo.airfoil.serialize import polar_from_dict, polar_to_dict
from bild_mdo.airfoil.text import FixedReynoldsPolar
from bild_mdo.airfoil.thickness import (DEFAULT_THICKNESS_RATIO, ThicknessWarning, naca_thickness_ratio,
                                        section_thickness_ratio, thickness_from_header)
from bild_mdo.io.airfoil import read_polar_file, write_polar_file


@pytest.mark.parametrize("name, expected", [
    # NACA 4-digit: the last two digits are the thickness in per cent of chord (Abbott & von Doenhoff, ch. 6);
    # 5-digit likewise (NACA 23012: 12 %).
    ("naca4412", 0.12), ("NACA 0012", 0.12), ("naca0012", 0.12), ("naca2415-neuralfoil", 0.15),
    ("naca23012", 0.12), ("naca4412@re=1e6", 0.12), ("clark-y", None), ("analytic", None), (None, None)])
def test_naca_designations(name, expected):
    assert naca_thickness_ratio(name) == expected


def test_builtins_carry_it():
    assert get_polar("naca4412").thickness_ratio == 0.12
    assert AnalyticPolar().thickness_ratio == 0.12


def test_wrapped_polars_have_their_base_thickness():
    base = AnalyticPolar()
    base.thickness_ratio = 0.15
    assert CompressiblePolar(base).thickness_ratio == 0.15
    assert FixedReynoldsPolar(base, 1e6).thickness_ratio == 0.15
    assert SpanwisePolar([base], [0.5]).thickness_ratio == 0.15


def test_explicit_value_is_checked():
    polar = AnalyticPolar()
    with pytest.raises(ValueError, match=r"t/c in \(0, 1\)"):
        polar.thickness_ratio = 1.5
    polar.thickness_ratio = None
    assert polar.thickness_ratio == 0.12          # back to the class's own value


def test_unknown_airfoil_gets_the_default_with_a_warning():
    class Mystery(AnalyticPolar):
        name = "mystery foil"
        _thickness_ratio = None

    with pytest.warns(ThicknessWarning, match="'mystery foil'.*0.12"):
        ratio, slope = section_thickness_ratio(Mystery(), np.array([0.3, 0.7]))
    np.testing.assert_array_equal(ratio, DEFAULT_THICKNESS_RATIO)
    np.testing.assert_array_equal(slope, 0.0)


def test_spanwise_blend_and_its_derivative():
    """The blend of the coefficients: t = (1 - s) t_0 + s t_1 with the quintic smooth step s (spanwise.py)."""
    root, tip = AnalyticPolar(), AnalyticPolar(cl0=0.3)
    root.thickness_ratio, tip.thickness_ratio = 0.2, 0.1
    polar = SpanwisePolar([root, tip], [0.2, 1.0])
    assert polar.thickness_ratio is None
    x = np.array([0.1, 0.4, 0.6, 0.9])
    ratio, slope = section_thickness_ratio(polar, x)
    t = np.clip((x - 0.2) / 0.8, 0.0, 1.0)
    s = t ** 3 * (10 - 15 * t + 6 * t ** 2)
    np.testing.assert_allclose(ratio, 0.2 - 0.1 * s, rtol=1e-14)
    np.testing.assert_allclose(ratio[2], 0.15, rtol=1e-14)             # midway: s = 1/2
    h = 1e-30
    complex_ratio, _ = section_thickness_ratio(polar, x + 1j * h)
    np.testing.assert_allclose(slope, complex_ratio.imag / h, rtol=1e-12)


def test_description_and_polar_file_carry_it(tmp_path):
    polar = AnalyticPolar(cd0=0.009)
    polar.thickness_ratio = 0.18
    description = polar_to_dict(polar)
    assert description["thickness_ratio"] == 0.18
    assert polar_from_dict(description).thickness_ratio == 0.18
    assert read_polar_file(write_polar_file(tmp_path / "foil.polar.json", polar)).thickness_ratio == 0.18
    # Built-ins are written by name: their name gives the thickness.
    assert polar_to_dict(get_polar("naca4412")) == {"type": "builtin", "name": "naca4412"}
    # No explicit value: nothing written (the files of before stay the same).
    assert "thickness_ratio" not in polar_to_dict(AnalyticPolar())


def _table(analytic=AnalyticPolar()):
    """A polar table file's text (alpha_deg, cl, cd at Re = 1e6) made from the analytic polar, -12 ... 20 deg."""
    alpha = np.arange(-12.0, 20.5, 1.0)
    values = analytic.evaluate(np.radians(alpha), 1e6)
    rows = "\n".join(f"{a:6.1f} {cl:.6f} {cd:.6f}" for a, cl, cd in zip(alpha, values.cl, values.cd))
    return "# reynolds = 1000000\nalpha_deg cl cd\n" + rows + "\n"


def test_polar_table_header_gives_it(tmp_path):
    """A '# thickness_ratio = 0.15' comment line of a polar table file; without it, the file's name decides."""
    path = tmp_path / "myfoil_re1000000.txt"
    path.write_text("# thickness_ratio = 0.15\n" + _table())
    assert thickness_from_header(path) == 0.15
    assert resolve_polar(str(path)).thickness_ratio == 0.15
    named = tmp_path / "naca2415_re1000000.txt"
    named.write_text(_table(AnalyticPolar(cl0=0.3)))
    assert thickness_from_header(named) is None
    assert resolve_polar(str(named)).thickness_ratio == 0.15
    bad = tmp_path / "bad_re1000000.txt"
    bad.write_text("# thickness_ratio = thick\n" + _table())
    with pytest.raises(ValueError, match="thickness_ratio"):
        thickness_from_header(bad)


def _naca_4digit(thickness, camber=0.0, position=0.4, points=81):
    """Selig coordinates of a NACA 4-digit section (Abbott & von Doenhoff, Sec. 6.4), thickness normal to the
    camber line."""
    beta = np.linspace(0.0, np.pi, points)
    x = 0.5 * (1.0 - np.cos(beta))
    half = 5.0 * thickness * (0.2969 * np.sqrt(x) - 0.126 * x - 0.3516 * x**2 + 0.2843 * x**3 - 0.1015 * x**4)
    front = x < position
    yc = np.where(front, camber / position**2 * (2 * position * x - x**2),
                  camber / (1 - position) ** 2 * (1 - 2 * position + 2 * position * x - x**2))
    slope = np.arctan(np.where(front, 2 * camber / position**2 * (position - x),
                               2 * camber / (1 - position) ** 2 * (position - x)))
    upper = np.column_stack([x - half * np.sin(slope), yc + half * np.cos(slope)])
    lower = np.column_stack([x + half * np.sin(slope), yc - half * np.cos(slope)])
    return np.vstack([upper[::-1], lower[1:]])


@pytest.mark.parametrize("thickness, camber", [(0.12, 0.0), (0.15, 0.0), (0.12, 0.04)])
def test_thickness_of_a_coordinates_file(thickness, camber):
    # The NACA 4-digit half-thickness polynomial peaks at x = 0.3 with 5 t (0.2969 sqrt(0.3) - ...) = 0.50015 t
    # (a hand evaluation), so the section is t thick there, to 3e-4 t; with 4 % camber the thickness normal to
    # the chord differs from the one normal to the camber line by less than 0.2 % of t.
    from bild_mdo.airfoil.thickness import coordinates_thickness_ratio
    assert coordinates_thickness_ratio(_naca_4digit(thickness, camber)) == pytest.approx(thickness, rel=2e-3)


def test_coordinates_file_polar_carries_its_thickness(tmp_path, monkeypatch):
    from bild_mdo.airfoil import builtin
    from bild_mdo.airfoil.sources.readers import load_builtin_polars
    path = tmp_path / "thick_section.dat"
    path.write_text("THICK SECTION\n" + "".join(f"{a:.6f} {b:.6f}\n" for a, b in _naca_4digit(0.18)))
    monkeypatch.setattr(builtin, "xfoil_polars",
                        lambda spec: [p for p in load_builtin_polars("naca4412") if p.reynolds in (5e5, 1e6)])
    assert resolve_polar(path).thickness_ratio == pytest.approx(0.18, rel=2e-3)


def test_crossing_surfaces_are_refused():
    from bild_mdo.airfoil.thickness import coordinates_thickness_ratio
    xy = _naca_4digit(0.12)
    xy[:, 1] *= -1.0  # lower above upper
    with pytest.raises(ValueError, match="upper surface must lie above the lower one"):
        coordinates_thickness_ratio(xy, "flipped.dat")
