"""A supersonic blade tip is flagged: ``TipMachWarning`` from ``analyze_rotor`` and ``design_rotor``.

Source of the numbers: the definition M_tip = sqrt(V_x^2 + (Omega R)^2) / a with the ISA sea-level speed of
sound a = 340.294 m/s (ICAO Standard Atmosphere, Doc 7488): in hover with R = 1 m, M_tip = 1 at
Omega = 340.294 rad/s, i.e. 3249.6 rpm.  1 % either side of it is sonic or not.
"""
import warnings

import numpy as np
import pytest

from bild_mdo import TipMachWarning, analyze_rotor, design_rotor
from bild_mdo.bem import station_radii

SONIC_RPM = 340.294 * 30.0 / np.pi          # hover, R = 1 m, sea level


def _tip_mach_warnings(function):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = function()
    return result, [str(w.message) for w in caught if issubclass(w.category, TipMachWarning)]


def _analyze(rpm, analytic_polar):
    radii = station_radii(1.0, 0.2, 12)
    return analyze_rotor(np.full(12, 0.1), np.full(12, 0.2), 1.0, 0.2, rpm, 0.0, 3, analytic_polar, radii=radii)


def test_analysis_past_a_sonic_tip_warns(analytic_polar):
    result, messages = _tip_mach_warnings(lambda: _analyze(1.01 * SONIC_RPM, analytic_polar))
    assert result.tip_mach == pytest.approx(1.01, rel=1e-4)
    assert len(messages) == 1 and "tip Mach number 1.01" in messages[0]


def test_analysis_below_a_sonic_tip_is_silent(analytic_polar):
    result, messages = _tip_mach_warnings(lambda: _analyze(0.99 * SONIC_RPM, analytic_polar))
    assert result.tip_mach == pytest.approx(0.99, rel=1e-4) and messages == []


def test_design_batch_names_the_supersonic_designs():
    rpm = np.array([0.5, 1.02, 0.9, 1.5]) * SONIC_RPM
    result, messages = _tip_mach_warnings(lambda: design_rotor(v_axial=0.0, rpm=rpm, radius=1.0, ref_chord=0.05))
    np.testing.assert_allclose(result.tip_mach, rpm / SONIC_RPM, rtol=1e-4)
    assert len(messages) == 1 and "design(s) [1, 3]" in messages[0]
