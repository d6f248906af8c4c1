"""The registry of built-in airfoils and the one resolver of an ``airfoil`` argument."""
import functools
import importlib.util
import shutil

import numpy as np
import pytest

from bild_mdo.airfoil import (AnalyticPolar, TabulatedPolar, available_polars, builtin, get_polar, naca4412,
                              resolve_polar)
from bild_mdo.airfoil.generated import xfoil_polars
from bild_mdo.airfoil.sources import xfoil as xfoil_module
from bild_mdo.airfoil.sources.readers import load_builtin_polars, write_polar_table


def test_registry():
    assert available_polars() == ["analytic", "naca4412"]
    assert get_polar("NACA4412") is naca4412()          # cached, case-insensitive
    assert isinstance(get_polar("Analytic"), AnalyticPolar)
    with pytest.raises(ValueError, match="analytic, naca4412"):
        get_polar("clark-y")


def test_resolve_polar_returns_a_polar_object_unchanged():
    polar = AnalyticPolar(cl0=0.3)
    assert resolve_polar(polar) is polar


def test_resolve_polar_looks_up_built_in_names():
    # The shipped NACA 4412 data take precedence over generating the designation with XFOIL.
    assert resolve_polar(" NACA4412 ") is naca4412()
    assert isinstance(resolve_polar("analytic"), AnalyticPolar)


def test_resolve_polar_unknown_name_lists_the_choices():
    with pytest.raises(ValueError) as info:
        resolve_polar("clark-y")
    message = str(info.value)
    assert message.startswith("unknown airfoil 'clark-y'; available: analytic, naca4412, or a NACA 4- or 5-digit")
    assert "\n" not in message


@pytest.mark.parametrize("value", [None, 4412, 1.5, [], b"naca4412"])
def test_resolve_polar_rejects_other_types_naming_the_choices(value):
    with pytest.raises(ValueError, match=rf"built-in name \(analytic, naca4412\), .*; got {type(value).__name__}$"):
        resolve_polar(value)


@pytest.mark.parametrize("value, pattern", [
    ("naca 441", "only NACA 4- and 5-digit designations"),
    (["missing_re100000.txt"], "polar files not found: missing_re100000.txt"),
])
def test_resolve_polar_errors_are_one_line(value, pattern):
    with pytest.raises(ValueError, match=pattern) as info:
        resolve_polar(value)
    assert "\n" not in str(info.value)


@pytest.mark.skipif(importlib.util.find_spec("neuralfoil") is not None, reason="neuralfoil is installed")
def test_neuralfoil_without_the_extra_names_it():
    with pytest.raises(ValueError, match=r"^airfoil 'neuralfoil:naca2412' needs the optional package neuralfoil: "
                                         r"pip install 'bild-mdo\[neuralfoil\]'$"):
        resolve_polar("neuralfoil:naca2412")


def test_polar_files_folder_and_list(tmp_path):
    # The shipped NACA 4412 tables, copied: one file, a folder, a list and a comma-separated string.
    polars = [p for p in load_builtin_polars("naca4412") if p.reynolds in (5e5, 1e6)]
    for p in polars:
        write_polar_table(tmp_path / f"naca4412_re{int(p.reynolds)}.txt", p)
    files = sorted(tmp_path.iterdir())
    one = resolve_polar(str(files[0]))
    assert isinstance(one, TabulatedPolar) and one.reynolds.tolist() == [1e6] and one.name == "naca4412"
    folder = resolve_polar(tmp_path)
    assert folder.reynolds.tolist() == [5e5, 1e6] and folder.name == tmp_path.name.lower()
    assert resolve_polar(files) is resolve_polar(",".join(map(str, files))) is resolve_polar(files[::-1])


def test_coordinates_file_goes_to_xfoil(tmp_path, monkeypatch):
    # A Selig file is recognised as a shape (not a polar) and handed to the XFOIL generator.
    x = np.concatenate([np.linspace(1.0, 0.0, 20), np.linspace(0.0, 1.0, 20)[1:]])
    y = 0.6 * (0.2969 * np.sqrt(x) - 0.126 * x - 0.3516 * x**2 + 0.2843 * x**3 - 0.1015 * x**4)
    y[20:] *= -1
    path = tmp_path / "my_section.dat"
    path.write_text("MY SECTION\n" + "".join(f"{a:.6f} {b:.6f}\n" for a, b in zip(x, y)))
    calls = []

    def fake(spec):
        calls.append(spec)
        return [p for p in load_builtin_polars("naca4412") if p.reynolds in (5e5, 1e6)]

    monkeypatch.setattr(builtin, "xfoil_polars", fake)
    polar = resolve_polar(path)
    assert calls == [str(path)] and polar.name == "my_section"


@pytest.mark.skipif(shutil.which("xfoil") is None or shutil.which("xvfb-run") is None,
                    reason="XFOIL (apt-get install xfoil xvfb) is not installed")
def test_naca_designation_runs_xfoil_once_then_reads_the_cache(monkeypatch):
    # Fewer Reynolds numbers and angles than the defaults keep the test at a few seconds.
    monkeypatch.setattr(builtin, "xfoil_polars", functools.partial(
        xfoil_polars, reynolds=(5e5, 1e6), alpha_deg=np.arange(-8.0, 16.01, 1.0)))
    monkeypatch.setattr(builtin, "_RESOLVED", {})
    polar = resolve_polar("NACA 0012")
    assert polar.name == "naca0012" and polar.reynolds.tolist() == [5e5, 1e6]
    # A symmetric section: no lift at zero incidence, odd lift curve, thin-airfoil slope
    # 2 pi per rad reduced by the boundary layer (XFOIL: about 0.11 per deg at Re = 1e6).
    alpha = np.radians([-4.0, 0.0, 4.0])
    cl = polar.evaluate(alpha, 1e6).cl
    assert abs(cl[1]) < 0.01 and cl[2] == pytest.approx(-cl[0], abs=0.01)
    assert cl[2] / 4.0 == pytest.approx(0.11, rel=0.1)
    assert resolve_polar("naca0012") is polar

    # A new process: nothing in memory, XFOIL must not run again.
    monkeypatch.setattr(builtin, "_RESOLVED", {})

    def no_xfoil(*args, **kwargs):
        raise AssertionError("XFOIL ran although its polars are cached")

    monkeypatch.setattr(xfoil_module, "run_xfoil", no_xfoil)
    again = resolve_polar("naca0012")
    assert again is not polar
    np.testing.assert_array_equal(again.evaluate(alpha, 7e5).cd, polar.evaluate(alpha, 7e5).cd)


def test_naca_designation_without_xfoil_is_one_clear_line(tmp_path, monkeypatch):
    monkeypatch.setenv("PATH", str(tmp_path))
    monkeypatch.setattr(builtin, "_RESOLVED", {})
    with pytest.raises(ValueError, match=r"^airfoil 'naca2412': the XFOIL runner needs the programs 'xfoil' and "
                                         r"'xvfb-run' on PATH; .* apt-get install xfoil xvfb$"):
        resolve_polar("naca2412")
