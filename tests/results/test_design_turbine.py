"""design_turbine: validation of the turbine BILD against the classical ideal rotors, and its BEM consistency."""
import warnings

import numpy as np
import openmdao.api as om
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.results.turbine_design import design_turbine
from tests.results.turbine_bem import analyze_turbine

# A polar without drag (to 1e-12: L/D = 4e11) and independent of the Reynolds number.
NO_DRAG = AnalyticPolar(cd0=1e-12)
GLAUERT = {0.5: 0.289, 1.0: 0.416, 1.5: 0.477, 2.0: 0.511, 2.5: 0.532, 5.0: 0.570, 7.5: 0.581, 10.0: 0.585}
IDEAL = dict(wind_speed=1.0, radius=1.0, hub_radius_ratio=1e-3, ref_radius_ratio=0.5, airfoil=NO_DRAG,
             loss_model="none", num_radial=400)


def glauert_power_coefficient(tip_speed_ratio, hub_radius_ratio=0.0):
    """Glauert's optimum rotor with wake rotation (Manwell et al., *Wind Energy Explained*, 2nd ed., Sec. 3.7.2;
    Burton et al., *Wind Energy Handbook*, Sec. 3.3): at each local speed ratio ``x``
    ``16 a**3 - 24 a**2 + a (9 - 3 x**2) - 1 + x**2 = 0`` (a in [1/4, 1/3]), ``a' = (1 - 3a)/(4a - 1)`` and
    ``C_P = 8/lambda**2 int a' (1 - a) x**3 dx`` from the hub's ``x`` to ``lambda``."""
    def integrand(x):
        a = brentq(lambda a: 16 * a ** 3 - 24 * a ** 2 + a * (9 - 3 * x * x) - 1 + x * x, 0.25 + 1e-12, 1.0 / 3.0,
                   xtol=1e-15)
        return (1 - 3 * a) / (4 * a - 1) * (1 - a) * x ** 3
    return 8.0 / tip_speed_ratio ** 2 * quad(integrand, hub_radius_ratio * tip_speed_ratio, tip_speed_ratio,
                                             epsabs=1e-13, limit=200)[0]


def test_glauert_optimum_rotor_with_wake_rotation():
    """Glauert's table (Manwell et al., Table 3.3; Burton et al., Table 3.1), no tip loss, no drag."""
    lam = np.array(list(GLAUERT))
    design = design_turbine(tip_speed_ratio=lam, **IDEAL)
    for value, tsr in zip(design.power_coefficient, lam):
        # Against the closed form integrated from the same hub: the midpoint rule over 400 annuli (1e-6).
        assert value == pytest.approx(glauert_power_coefficient(tsr, 1e-3), rel=1e-5)
        # Against the printed digits: within half a unit of the last digit; the 1e-5 allows for the table's
        # own rounding at lambda = 1, where the closed form is 0.415496 (printed 0.416: rounded from 0.4155).
        assert abs(value - GLAUERT[tsr]) <= 5e-4 + 1e-5
    # Glauert: a -> 1/3 at a high local speed ratio (the tip station at lambda >= 5).
    np.testing.assert_allclose(design.axial_induction[lam >= 5.0, -1], 1.0 / 3.0, atol=1e-3)


def test_betz_limit():
    """Betz (Burton et al., Sec. 3.2; Manwell et al., Sec. 3.3): C_P = 16/27, C_T = 8/9 at a = 1/3.

    Infinite blades (loss_model 'none'), no drag, and no wake rotation: the limit lambda -> inf of Glauert's
    rotor, here lambda = 100, where Glauert's closed form lies 2.3e-4 (relative) below 16/27.  The tolerance
    0.1 % (the issue's acceptance) holds that deficit; the design matches the closed form to 1e-5."""
    design = design_turbine(tip_speed_ratio=100.0, **IDEAL)
    assert design.power_coefficient == pytest.approx(16.0 / 27.0, rel=1e-3)
    assert design.power_coefficient == pytest.approx(glauert_power_coefficient(100.0, 1e-3), rel=1e-5)
    assert design.thrust_coefficient == pytest.approx(8.0 / 9.0, rel=1e-3)


def wilson_lissaman_walker(tip_speed_ratio, num_blades, lift_to_drag):
    """Maximum C_P with drag and finite blade number (Wilson, Lissaman & Walker 1976; Manwell et al., Sec. 3.10)::

        C_P = 16/27 lambda / (lambda + (1.32 + ((lambda - 8)/20)**2) / B**(2/3))
              - 0.57 lambda**2 / (L/D (lambda + 1/(2B)))

    for 4 <= lambda <= 20, 25 <= L/D <= inf and B = 1, 2, 3."""
    lam, b = tip_speed_ratio, num_blades
    return (16.0 / 27.0 * lam / (lam + (1.32 + ((lam - 8.0) / 20.0) ** 2) / b ** (2.0 / 3.0))
            - 0.57 * lam ** 2 / (lift_to_drag * (lam + 1.0 / (2.0 * b))))


def frozen_loss_power_coefficient(tip_speed_ratio, num_blades, count=2000):
    """Glauert's optimum rotor with Prandtl's ``F`` on both momentum terms (``dT ~ a F (1 - a)``, ``dQ ~ a' F
    (1 - a)``, the convention of this BEM, CCBlade and AeroDyn) and ``F`` held fixed in each annulus: ``F``
    multiplies the annulus' power ``a' (1 - a)`` as a constant, so the best ``a`` is Glauert's and
    ``C_P = 8/lambda**2 int F a' (1 - a) x**3 dx`` with ``F`` at Glauert's inflow angle ``tan(phi) = (1 - a) /
    (x (1 + a'))`` (hand derivation; midpoint rule over ``count`` annuli from the axis to the tip)."""
    lam = tip_speed_ratio
    frac = (np.arange(count) + 0.5) / count
    x = lam * frac
    a = np.array([brentq(lambda a: 16 * a ** 3 - 24 * a ** 2 + a * (9 - 3 * xi * xi) - 1 + xi * xi, 0.25 + 1e-12,
                         1.0 / 3.0, xtol=1e-15) for xi in x])
    a_t = (1 - 3 * a) / (4 * a - 1)
    phi = np.arctan2(1 - a, x * (1 + a_t))
    f = 2 / np.pi * np.arccos(np.exp(-0.5 * num_blades * (1 - frac) / (frac * np.sin(phi))))
    return 8.0 / lam ** 2 * np.sum(f * a_t * (1 - a) * x ** 3) * (lam / count)


@pytest.mark.parametrize("num_blades", [1, 3])
def test_tip_loss_design_beats_the_frozen_loss_optimum(num_blades):
    """With tip loss and no drag the design is the optimum of its BEM model with ``F`` free in the loading, so
    it lies above the classical estimate that holds ``F`` fixed per annulus (frozen_loss_power_coefficient),
    and close to it (the loading's dF/dphi terms move little power).  Measured: 0.0006 ... 0.0034 above it
    over lambda = 4 ... 15 for one and three blades."""
    lam = np.array([4.0, 8.0, 15.0])
    design = design_turbine(wind_speed=1.0, tip_speed_ratio=lam, radius=1.0, hub_radius_ratio=1e-3,
                            ref_radius_ratio=0.5, num_blades=num_blades, airfoil=NO_DRAG, loss_model="tip",
                            num_radial=200)
    frozen = np.array([frozen_loss_power_coefficient(value, num_blades) for value in lam])
    assert np.all(design.power_coefficient > frozen)
    assert np.all(design.power_coefficient - frozen < 0.005)


#: Bound of the agreement asserted here, absolute in C_P.  NOT the correlation's own stated accuracy: the source
#: (Wilson, Lissaman & Walker 1976, quoted by Manwell et al., Sec. 3.10) was not at hand to check that figure, so
#: this is the measured agreement rounded up, and the point stays open in issue 27 (CHANGELOG, docs page).  The
#: correlation fits another placement of the tip loss (dT ~ a F (1 - a F)): the per-annulus optimum of that form
#: lies within 1.5 % of it for B = 1 ... 3, lambda = 4 ... 15, the same computation in this BEM's form (a F (1 - a))
#: 0.2-14 % below it (most for B = 1 at lambda = 4) (docs/user-guide/turbines.md).
WLW_ACCURACY = 0.035


@pytest.mark.parametrize("num_blades", [1, 2, 3])
@pytest.mark.parametrize("cd0", [1e-12, 0.008, 0.02])
def test_wilson_lissaman_walker(num_blades, cd0):
    """Tip loss (Prandtl, inside the loading) and drag: the correlation within WLW_ACCURACY (see there).

    Measured: |difference| <= 0.033 for B = 2, 3 over lambda = 4 ... 20 and L/D = 47 ... inf; for B = 1 the
    design lies up to 0.057 below the correlation at lambda = 4 and within 0.035 from lambda = 10 on
    (not met below: see the docs page, docs/user-guide/turbines.md)."""
    polar = AnalyticPolar(cd0=cd0)
    point = polar.max_lift_to_drag(1e6)
    lift_to_drag = float(point.cl / point.cd)
    assert lift_to_drag >= 25.0
    lam = np.array([4.0, 6.0, 8.0, 10.0, 12.0, 15.0, 20.0])
    design = design_turbine(wind_speed=1.0, tip_speed_ratio=lam, radius=1.0, hub_radius_ratio=1e-3,
                            ref_radius_ratio=0.5, num_blades=num_blades, airfoil=polar, loss_model="tip",
                            num_radial=100)
    deviation = design.power_coefficient - wilson_lissaman_walker(lam, num_blades, lift_to_drag)
    inside = lam >= (10.0 if num_blades == 1 else 4.0)
    assert np.all(np.abs(deviation[inside]) <= WLW_ACCURACY)


@pytest.mark.parametrize("member", [dict(), dict(thrust=1.2e5), dict(ref_chord=1.0)])
def test_bem_analysis_reproduces_the_design(member):
    """The BEM analysis of the designed blade (windmill inflow, mirrored section, tests/results/turbine_bem.py)
    gives the design's power and thrust: to 1e-10 with a Reynolds-independent polar; with the NACA 4412 the
    stations' own Reynolds numbers (the design takes the reference station's, Assumption 2) move them 0.2 %."""
    common = dict(wind_speed=10.0, tip_speed_ratio=7.0, radius=40.0, num_radial=20)
    design = design_turbine(airfoil=AnalyticPolar(), loss_model="tip_hub", **common, **member)
    power, thrust, state = analyze_turbine(design)
    assert power == pytest.approx(design.power, rel=1e-10)
    assert thrust == pytest.approx(design.thrust, rel=1e-10)
    assert np.all(state == 3)  # every station in the windmill state (bild_mdo.bem.flow_states.WINDMILL)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # Reynolds numbers above the built-in table
        design = design_turbine(**common, **member)
        power, thrust, _ = analyze_turbine(design)
    assert power == pytest.approx(design.power, rel=3e-3)
    assert thrust == pytest.approx(design.thrust, rel=3e-3)


def test_members_and_invariants():
    """Thrust below the maximum-power thrust costs power; the thrust member meets its thrust."""
    common = dict(wind_speed=10.0, tip_speed_ratio=7.0, radius=40.0, num_radial=20, airfoil=AnalyticPolar())
    best = design_turbine(**common)
    limited = design_turbine(thrust=0.8 * best.thrust, **common)
    assert limited.thrust == pytest.approx(0.8 * best.thrust, rel=1e-12)
    assert limited.power < best.power and limited.power_thrust_multiplier > 0.0
    by_chord = design_turbine(ref_chord=best.ref_chord, **common)
    assert by_chord.power == pytest.approx(best.power, rel=1e-10)
    assert abs(by_chord.power_thrust_multiplier) < 1e-8
    assert best.power_coefficient == pytest.approx(best.power / (0.5 * best.rho * np.pi * 40.0 ** 2 * 10.0 ** 3))
    assert "power coefficient C_P" in best.summary()


def test_validation_messages():
    with pytest.raises(ValueError, match="tip_speed_ratio or rpm"):
        design_turbine(tip_speed_ratio=7.0, rpm=15.0)
    with pytest.raises(ValueError, match="wind_speed"):
        design_turbine(wind_speed=-1.0)
    with pytest.raises(om.AnalysisError, match="reduce ref_chord"):
        design_turbine(ref_chord=50.0, airfoil=AnalyticPolar(), num_radial=10)
