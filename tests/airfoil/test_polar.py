"""The Polar interface: optional Mach number and station arguments leave the two-argument polar unchanged."""
import numpy as np
import pytest

from bild_mdo.airfoil import (AnalyticPolar, MachPolarSecondDerivatives, MachPolarValues, PolarSecondDerivatives,
                              PolarValues, StationPolarValues, TabulatedPolar)
from bild_mdo.airfoil.sources.polar_data import PolarData


@pytest.fixture
def polar():
    return AnalyticPolar(reynolds_exponent=0.2)


def test_result_types_follow_the_arguments(polar):
    assert type(polar.evaluate(0.1, 1e6)) is PolarValues
    assert type(polar.evaluate(0.1, 1e6, mach=0.3)) is MachPolarValues
    assert type(polar.evaluate(0.1, 1e6, radial_fraction=0.5)) is StationPolarValues
    assert type(polar.second_derivatives(0.1, 1e6)) is PolarSecondDerivatives
    assert type(polar.second_derivatives(0.1, 1e6, mach=0.3)) is MachPolarSecondDerivatives


def test_a_polar_without_mach_data_ignores_the_mach_number(polar):
    alpha = np.radians(np.linspace(-180, 180, 72)).reshape(8, 9)
    reynolds = np.geomspace(1e5, 3e6, 9)
    plain = polar.evaluate(alpha, reynolds)
    with_mach = polar.evaluate(alpha, reynolds, mach=0.6)
    for got, want in zip(with_mach[:6], plain):
        np.testing.assert_array_equal(got, want)
    assert with_mach.dcl_dmach.shape == (8, 9) and not with_mach.dcl_dmach.any()
    # Complex Mach (OpenMDAO's complex step) carries a zero derivative.
    assert not np.imag(polar.evaluate(alpha, reynolds, mach=0.6 + 1e-30j).cl).any()
    second = polar.second_derivatives(alpha, reynolds, mach=0.6)
    for got, want in zip(second[:4], polar.second_derivatives(alpha, reynolds)):
        np.testing.assert_array_equal(got, want)


def test_complex_inputs_carry_every_first_derivative(polar):
    h = 1e-30
    v = polar.evaluate(0.1, 5e5, mach=0.3, radial_fraction=0.4)
    c = polar.evaluate(0.1 + 2j * h, 5e5 + 3j * h, mach=0.3 + 5j * h, radial_fraction=0.4 + 7j * h)
    assert np.imag(c.cl) / h == pytest.approx(2 * v.dcl_dalpha + 3 * v.dcl_dre, rel=1e-14)
    assert np.imag(c.cd) / h == pytest.approx(2 * v.dcd_dalpha + 3 * v.dcd_dre, rel=1e-14)


@pytest.mark.parametrize("mach", [-0.1, np.nan, np.inf])
def test_invalid_mach_numbers(polar, mach):
    with pytest.raises(ValueError, match="Mach number must be finite and >= 0"):
        polar.evaluate(0.1, 1e6, mach=mach)


def test_max_lift_to_drag_with_mach_and_station_on_a_uniform_polar(polar):
    plain = polar.max_lift_to_drag([2e5, 1e6])
    full = polar.max_lift_to_drag([2e5, 1e6], mach=0.4, radial_fraction=[0.3, 0.9])
    np.testing.assert_array_equal(full.alpha, plain.alpha)
    np.testing.assert_array_equal(full.dcl_dre, plain.dcl_dre)
    assert not (full.dalpha_dmach.any() or full.dcl_dradial_fraction.any())


def test_tabulated_polar_refuses_mixed_mach_numbers():
    alpha = np.arange(-10.0, 15.0)
    tables = [PolarData(1e6, m, alpha, 0.1 * alpha, 0.01 + 1e-4 * alpha**2, source=f"M={m}") for m in (0.0, 0.5)]
    with pytest.raises(ValueError, match=r"several Mach numbers \[0.0, 0.5\]; use .*MachTabulatedPolar"):
        TabulatedPolar(tables)
