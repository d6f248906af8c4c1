"""The registry of built-in airfoils and the one resolver of an ``airfoil`` argument."""
import pytest

from bild_mdo.airfoil import AnalyticPolar, available_polars, get_polar, naca4412, resolve_polar


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
    assert resolve_polar(" NACA4412 ") is naca4412()
    assert isinstance(resolve_polar("analytic"), AnalyticPolar)


def test_resolve_polar_unknown_name_lists_the_choices():
    with pytest.raises(ValueError) as info:
        resolve_polar("naca0012")
    message = str(info.value)
    assert message.startswith("unknown airfoil 'naca0012'; available: analytic, naca4412")
    assert "\n" not in message


@pytest.mark.parametrize("value", [None, 4412, 1.5, ["naca4412"], b"naca4412"])
def test_resolve_polar_rejects_other_types_naming_the_choices(value):
    expected = (r"built-in name \(analytic, naca4412\) or a bild_mdo.airfoil.Polar object, "
                rf"got {type(value).__name__}$")
    with pytest.raises(ValueError, match=expected):
        resolve_polar(value)
