"""A turbine design whose stations pass a = 0.4 says so: its loading has momentum theory's thrust there, while a
turbine BEM analysis applies Buhl's correction by default.

Sources: the design's own consistency (the loading is solved in the BEM model with momentum theory's thrust, so
an analysis with ``high_induction='none'`` gives back its power) and Buhl (2005), whose thrust exceeds momentum
theory's past a = 0.4 (``bild_mdo.bem.inflow_residual``), so the default analysis differs there.
"""
import numpy as np
import pytest

from bild_mdo import analyze_rotor, design_turbine
from bild_mdo.airfoil import AnalyticPolar

POLAR = AnalyticPolar(cd0=0.008)
CASE = dict(wind_speed=10.0, tip_speed_ratio=7.0, radius=40.0, num_radial=20, airfoil=POLAR)


def _analysis(design, high_induction):
    return analyze_rotor(design.chord, design.twist, 40.0, 40.0 * design.hub_radius_ratio, design.rpm, 10.0, 3,
                         POLAR, rotor_type="turbine", radii=design.radii, on_invalid="ignore",
                         high_induction=high_induction)


def test_heavily_loaded_design_notes_its_stations_past_critical_induction():
    best = design_turbine(**CASE)
    assert np.all(best.axial_induction < 0.4) and "past a = 0.4" not in best.summary()
    np.testing.assert_allclose(float(_analysis(best, None).power), best.power, rtol=1e-9)
    heavy = design_turbine(thrust=1.1 * best.thrust, **CASE)
    past = heavy.axial_induction > 0.4
    assert past.sum() >= 2
    summary = heavy.summary()
    assert f"{past.sum()} station(s) past a = 0.4" in summary
    assert all(f"{x:.3f}" in summary for x in heavy.radial_fractions[past])
    # Momentum theory's thrust gives the design back; Buhl's (the turbine default) does not.
    np.testing.assert_allclose(float(_analysis(heavy, "none").power), heavy.power, rtol=1e-9)
    assert abs(float(_analysis(heavy, None).power) / heavy.power - 1.0) > 1e-3
