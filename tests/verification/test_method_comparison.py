"""BILD (three variants), MIL and the BEM optimum at the same thrust: invariants on three forward-flight cases.

Sources of the asserted numbers:

* the comparison's definition: every design is trimmed to one thrust, the optimum's (trim tolerance 1e-10);
* the optimisation problem (paper Problem 1, Sec. 5.1): the optimum meets BILD's thrust to
  ``THRUST_TOLERANCE``, and it is a local minimum of the same BEM model within the optimiser's bounds, so no
  design inside those bounds trimmed to its thrust has less energy loss beyond the optimality check's
  tolerance (``optimality.DEFAULT_TOLERANCE``; the optimum is the lowest of the runs from the BILD variants' designs);
* BILDGroup's ``thrust_target`` option: the design's thrust equals the target to 1e-12 relative;
* Rankine-Froude actuator-disk momentum theory: at thrust T no rotor of radius R exceeds the ideal
  propulsive efficiency ``2 / (1 + sqrt(1 + T_c))``, ``T_c = 2 T / (rho V^2 pi R^2)``; profile drag only
  adds loss at the same thrust (Adkins & Liebeck 1994, Eqs. for T_c and P_c with ``eps = C_d/C_l``).
"""
import numpy as np
import pytest

from bild_mdo.atmosphere import isa
from bild_mdo.mil import design_mil
from bild_mdo.optimization.initial_design import CHORD_RATIO_BOUNDS, TWIST_LIMITS
from bild_mdo.optimization.result import THRUST_TOLERANCE
from bild_mdo.verification.cases import SweepSpec
from bild_mdo.verification.method_comparison import METHODS, compare_methods, forward_flight_cases
from bild_mdo.verification.method_designs import column
from bild_mdo.verification.optimality import DEFAULT_TOLERANCE

# 12 stations keep the three optimisations short; J = 1.5 and 3, R = 1 and 1.5 m, altitudes 1500 and 3000 m.
SPEC = SweepSpec(levels=3, num_radial=12)
CASE_IDS = (40, 53, 67)


def rankine_froude_efficiency(thrust, v_axial, rho, radius):
    """Ideal propulsive efficiency of an actuator disk (hand derivation from momentum and energy)."""
    t_c = 2.0 * thrust / (rho * v_axial**2 * np.pi * radius**2)
    return 2.0 / (1.0 + np.sqrt(1.0 + t_c))


@pytest.fixture(scope="module")
def comparison():
    return compare_methods(SPEC.cases(CASE_IDS), repeats=0)  # no timing: nothing here is about time


def test_forward_flight_cases_of_levels_3():
    cases = forward_flight_cases(SweepSpec(levels=3))
    # 3 levels of J (0, 1.5, 3), two of them > 0, times 3**3 for R, altitude and c_ref.
    assert len(cases) == 54
    assert min(case.inputs["advance_ratio"] for case in cases) == 1.5


def test_hover_is_refused_before_any_design():
    with pytest.raises(ValueError, match="forward flight"):
        compare_methods(SweepSpec(levels=3).cases([0]))


def test_every_design_and_every_trim_exists(comparison):
    assert comparison.methods == list(METHODS)
    for method in METHODS:
        assert comparison.designs[method].converged.all(), (method, comparison.notes)
        assert np.isfinite(comparison.energy_excess[method]).all(), (method, comparison.notes)


def test_trimmed_designs_meet_the_common_thrust(comparison):
    for method in comparison.methods:
        done = np.isfinite(comparison.thrust_residual[method])
        assert np.all(np.abs(comparison.thrust_residual[method][done]) <= 1e-8), method


def test_optimum_meets_bild_thrust_and_its_trim_is_round_off(comparison):
    bild_thrust = comparison.designs["bild_reference"].extra["thrust"]
    np.testing.assert_array_less(np.abs(comparison.thrust / bild_thrust - 1.0), THRUST_TOLERANCE)
    # The optimisation's BEM model and the trim's BEM analysis are the same model: nothing to trim.
    np.testing.assert_array_less(np.abs(comparison.pitch_offset["optimum"]), 1e-9)
    np.testing.assert_allclose(comparison.energy_excess["optimum"], 0.0, atol=1e-12)


@pytest.mark.parametrize("method", ["bild_local", "bild_local_exact"])
def test_local_bild_is_designed_for_the_reference_thrust(comparison, method):
    np.testing.assert_allclose(comparison.designs[method].extra["thrust"],
                               comparison.designs["bild_reference"].extra["thrust"], rtol=1e-12)


def test_unknown_variant_is_refused():
    with pytest.raises(ValueError, match="variants must include 'bild_reference'"):
        compare_methods(SPEC.cases(CASE_IDS[:1]), variants=("bild_reference", "bild_exact"), repeats=0)


def test_no_design_inside_the_bounds_beats_the_optimum(comparison):
    # The optimum is a minimum within the optimiser's bounds only (at J = 3 BILD's local point can put
    # the root twist above 90 deg, outside them); these three cases have every design inside.
    radius = column(comparison.cases, "radius")[:, None]
    for method in comparison.methods:
        # As trimmed: a zero chord (an unloaded annulus) is held at the lower chord bound.
        twist = comparison.twist_trimmed[method]
        chord_ratio = np.maximum(comparison.designs[method].chord / radius, CHORD_RATIO_BOUNDS[0])
        inside = (np.all((twist >= TWIST_LIMITS[0]) & (twist <= TWIST_LIMITS[1]), axis=1)
                  & np.all((chord_ratio >= CHORD_RATIO_BOUNDS[0]) & (chord_ratio <= CHORD_RATIO_BOUNDS[1]), axis=1))
        excess = comparison.energy_excess[method]
        assert inside[np.isfinite(excess)].all(), method
        assert np.all(excess[np.isfinite(excess)] >= -DEFAULT_TOLERANCE), (method, excess)


def test_rankine_froude_bounds_every_design_at_the_common_thrust(comparison):
    v_axial, radius = column(comparison.cases, "v_axial"), column(comparison.cases, "radius")
    rho = np.asarray(isa(column(comparison.cases, "altitude")).rho)
    ideal = rankine_froude_efficiency(comparison.thrust, v_axial, rho, radius)
    for method in METHODS:
        if method in comparison.efficiency:
            eta = comparison.efficiency[method]
            assert np.all(eta[np.isfinite(eta)] < ideal), method


def test_drag_free_mil_lies_between_rankine_froude_and_mil_with_drag(comparison):
    bild = comparison.designs["bild_reference"]
    mil = comparison.designs["mil"]
    v_axial, radius = column(comparison.cases, "v_axial"), column(comparison.cases, "radius")
    kwargs = dict(v_axial=v_axial, rpm=column(comparison.cases, "rpm"), radius=radius,
                  hub_radius=column(comparison.cases, "hub_radius"), altitude=column(comparison.cases, "altitude"),
                  alpha_star=bild.extra["alpha_star"], cl_star=bild.extra["cl_star"], num_blades=SPEC.num_blades,
                  num_radial=SPEC.num_radial)
    drag_free = design_mil(bild.extra["thrust"], cd_star=0.0, **kwargs)
    np.testing.assert_allclose(drag_free.thrust, bild.extra["thrust"], rtol=1e-10)
    np.testing.assert_allclose(mil.extra["design_thrust"], bild.extra["thrust"], rtol=1e-10)
    rho = np.asarray(isa(column(comparison.cases, "altitude")).rho)
    ideal = rankine_froude_efficiency(bild.extra["thrust"], v_axial, rho, radius)
    assert np.all(drag_free.efficiency < ideal)
    assert np.all(mil.extra["efficiency"] < drag_free.efficiency)
