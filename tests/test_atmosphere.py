"""ISA troposphere: table values, derivatives, component partials and range checks."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.atmosphere import AtmosphereComp, isa
from bild_mdo.utils.testing import check_component_partials


def test_sea_level_matches_isa_table():
    # ICAO Doc 7488 / ISO 2533 sea-level values: rho = 1.2250 kg/m^3, mu = 1.789e-5 Pa s,
    # a = 340.3 m/s, T = 288.15 K, p = 101325 Pa.
    s = isa(0.0)
    assert s.rho == pytest.approx(1.2250, abs=5e-5)
    assert s.mu == pytest.approx(1.789e-5, abs=5e-9)
    assert s.speed_of_sound == pytest.approx(340.3, abs=0.05)
    assert s.temperature == pytest.approx(288.15, abs=1e-12)
    assert s.pressure == pytest.approx(101325.0, abs=1e-9)


def test_3000_m_matches_isa_table():
    # ISA table at 3000 m: rho = 0.9093 kg/m^3, T = 268.66 K, p = 70121 Pa (4 significant digits;
    # the table is in geopotential altitude, which differs from geometric by 1.4 m here).
    s = isa(3000.0)
    assert s.rho == pytest.approx(0.9093, abs=1e-4)
    assert s.temperature == pytest.approx(268.66, abs=0.02)
    assert s.pressure == pytest.approx(70121.0, rel=5e-4)


def test_tropopause_temperature():
    # 11,000 m geometric is 10,981 m geopotential: T = 288.15 - 0.0065 * 10981.0 = 216.77 K (hand).
    assert isa(11000.0).temperature == pytest.approx(216.774, abs=1e-3)


def test_derivatives_match_complex_step():
    h = np.array([0.0, 1234.5, 6000.0, 11000.0])
    s = isa(h)
    step = 1e-30
    c = isa(h + 1j * step)
    for value, deriv in ((c.rho, s.drho_dh), (c.mu, s.dmu_dh), (c.speed_of_sound, s.dspeed_of_sound_dh),
                         (c.temperature, s.dtemperature_dh), (c.pressure, s.dpressure_dh)):
        np.testing.assert_allclose(np.imag(value) / step, deriv, rtol=1e-13)
    # Density falls with altitude (physical invariant).
    assert np.all(s.drho_dh < 0.0)


@pytest.mark.parametrize("altitude", [-1.0, 11000.5, np.nan])
def test_out_of_range_altitude_raises(altitude):
    with pytest.raises(ValueError, match="altitude"):
        isa(np.array([100.0, altitude]))


def test_component_partials_and_values():
    prob = check_component_partials(AtmosphereComp(num_nodes=3), {"altitude": [0.0, 3000.0, 9000.0]},
                                    atol=1e-12, rtol=1e-10)
    np.testing.assert_allclose(prob.get_val("rho")[:2], [1.2250, 0.9093], atol=1e-4)  # ISA table


@pytest.mark.parametrize("altitude", [-1.0, 12000.0, np.nan])
def test_component_rejects_out_of_range(altitude):
    # Inside a model the error is an AnalysisError (an optimiser backs off from it), not a ValueError;
    # the plain isa() keeps ValueError (test_out_of_range_altitude_raises).
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("atm", AtmosphereComp(num_nodes=2), promotes=["*"])
    prob.setup()
    prob.set_val("altitude", [0.0, altitude])
    with pytest.raises(om.AnalysisError, match="altitude must be within 0 ... 11000 m") as info:
        prob.run_model()
    assert not isinstance(info.value, ValueError)


def test_component_is_per_design():
    # The atmosphere depends on the altitude of a design only: it has no radial size option.
    assert "num_radial" not in AtmosphereComp().options


def test_values_without_derivatives_are_the_same():
    # A run without derivatives (AtmosphereComp.compute) evaluates the same formulas, and still checks the range.
    altitude = np.array([0.0, 1234.5, 11000.0])
    full, values = isa(altitude), isa(altitude, derivatives=False)
    for name in ("rho", "mu", "speed_of_sound", "temperature", "pressure"):
        np.testing.assert_array_equal(getattr(values, name), getattr(full, name))
    assert values.drho_dh is None
    with pytest.raises(ValueError, match="altitude"):
        isa(np.array([np.nan]), derivatives=False)
