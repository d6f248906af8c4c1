"""The full-BEM turbine optimisation (``rotor_type='turbine'``): the most power at a thrust."""
import numpy as np
import pytest

from bild_mdo import design_turbine
from bild_mdo.airfoil.text import sweep_polar
from bild_mdo.bem.analyze import analyze_rotor
from bild_mdo.optimization.problem import build_optimization_problem
from bild_mdo.optimization.result import THRUST_TOLERANCE
from bild_mdo.optimization.run import optimize_rotor
from bild_mdo.optimization.turbine import ideal_turbine_energy_loss, turbine_twist_bounds

WIND, RADIUS, HUB, RHO = 8.0, 4.0, 0.4, 1.225  # sea-level ISA density
FROZEN = sweep_polar("naca4412@re=1e6")  # the NACA 4412 table frozen at Re 1e6


def _bild(thrust_coefficient=0.6):
    thrust = thrust_coefficient * 0.5 * RHO * np.pi * RADIUS**2 * WIND**2
    design = design_turbine(wind_speed=WIND, tip_speed_ratio=7.0, radius=RADIUS, hub_radius_ratio=HUB / RADIUS,
                            num_radial=12, airfoil=FROZEN, thrust=thrust)
    return thrust, design


def test_cold_start_reaches_the_turbine_bild_blade():
    # With a Reynolds-frozen polar the turbine BILD blade is the BEM optimum (the annulus stationarity of
    # E - mu T with Prandtl's F, bild_mdo.bild.variants.turbine); a cold start must end at it.
    thrust, design = _bild()
    rpm = float(design.rpm)
    result = optimize_rotor(WIND, rpm, RADIUS, HUB, thrust, 0.0, rotor_type="turbine", initial="linear",
                            num_radial=12, polar=FROZEN)
    assert result.converged, result.status
    perf = result.performance
    assert perf["thrust"] == pytest.approx(thrust, rel=THRUST_TOLERANCE)
    assert perf["power"] == pytest.approx(float(design.power), rel=1e-6)
    assert np.linalg.norm(result.chord - np.ravel(design.chord)) / np.linalg.norm(np.ravel(design.chord)) < 2e-3
    assert np.linalg.norm(result.twist - np.ravel(design.twist)) / np.linalg.norm(np.ravel(design.twist)) < 2e-3
    # Definitions: C_P = P / (rho A V^3 / 2), E = V T - P, lambda = Omega R / V.
    assert perf["power_coefficient"] == pytest.approx(perf["power"] / (0.5 * RHO * np.pi * RADIUS**2 * WIND**3),
                                                      rel=1e-4)  # ISA sea level 1.225 to 5 digits
    assert perf["energy_loss"] == pytest.approx(WIND * perf["thrust"] - perf["power"], rel=1e-9)
    assert perf["tip_speed_ratio"] == pytest.approx(7.0, rel=1e-12)
    # The optimum's blade analysed on its own by the turbine BEM (rotor_type='turbine') gives the same power.
    check = analyze_rotor(result.chord, result.twist, RADIUS, HUB, rpm, WIND, 3, FROZEN, rotor_type="turbine")
    assert float(check.power) == pytest.approx(perf["power"], rel=1e-8)


def test_actuator_disc_reference_and_twist_bounds():
    # Momentum theory: T = 2 rho A V^2 a (1 - a) and E = V T - P = T a V; at a = 1/3 (Betz), C_T = 8/9.
    area = np.pi * (RADIUS**2 - HUB**2)
    thrust = 2.0 * RHO * area * WIND**2 * (1.0 / 3.0) * (2.0 / 3.0)
    assert ideal_turbine_energy_loss(thrust, WIND, RADIUS, HUB, RHO) == pytest.approx(thrust * WIND / 3.0, rel=1e-12)
    # The bounds hold the BILD twist (below the inflow angle without induction, negative toward a fast tip).
    _, design = _bild()
    fractions = (np.ravel(design.radii) - HUB) / (RADIUS - HUB)
    lower, upper = turbine_twist_bounds(WIND, float(design.rpm), RADIUS, HUB, fractions)
    assert np.all(lower < np.ravel(design.twist)) and np.all(np.ravel(design.twist) < upper)


def test_rotor_type_is_checked():
    with pytest.raises(ValueError, match="rotor_type must be one of"):
        build_optimization_problem(rotor_type="windmill")
