"""Warm start of the BEM inflow solve: the same roots and flow states as the cold solve, in fewer passes.

The warm start (``warm_start=True``) may change how a root is found, never which root: the
reference of every assertion here is the cold solve of the same inputs (``warm_start=False``),
whose own correctness the other inflow tests establish.  Equality is to the solver tolerance
(``|R| <= 1e-13``, :data:`bild_mdo.bem.root_finding.RESIDUAL_TOL`); flow-state codes are equal
exactly.  Two solutions of |R| <= 1e-13 differ by up to 1e-13 / |dR/dphi|, about 1e-12 rad at
small slopes, so phi is compared with atol = 1e-10 rad (distinct roots lie 1e-3 rad or more apart).
"""
import atexit
import shutil
import tempfile
import warnings

import numpy as np
import openmdao.api as om
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.configuration import set_hypothesis_home_dir

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.bem.analyze import station_radii
from bild_mdo.bem.bem_group import BEMAnalysisGroup
from bild_mdo.bem.blade_element import denominator_function, inflow_angle_guess, residual_function
from bild_mdo.bem.inflow import InflowComp
from bild_mdo.bem.root_finding import solve_bracketed, solve_physical, warm_region_one
from bild_mdo.utils.testing import check_component_partials

# Hypothesis keeps its files in a temporary folder, never in the repository (as tests/fuzz/conftest.py).
_HOME = tempfile.mkdtemp(prefix="bild-mdo-hypothesis-")
atexit.register(shutil.rmtree, _HOME, ignore_errors=True)
set_hypothesis_home_dir(_HOME)

NN, NR, B = 3, 7, 3
POLAR = AnalyticPolar(reynolds_exponent=0.2)


def _rotors(seed, num_nodes, num_radial, pitch_deg):
    """Random propellers and lift rotors, hover and cruise; blade pitch = zero-induction angle + ``pitch_deg``."""
    rng = np.random.default_rng(seed)
    radius = rng.uniform(0.3, 2.0, num_nodes)
    hub = radius * rng.uniform(0.1, 0.25, num_nodes)
    rpm = rng.uniform(800.0, 6000.0, num_nodes)
    v_axial = rng.uniform(0.0, 70.0, num_nodes) * (rng.uniform(size=num_nodes) > 0.25)
    radii = station_radii(radius, hub, num_radial)
    x = (radii - hub[:, None]) / (radius - hub)[:, None]
    chord = radius[:, None] * rng.uniform(0.04, 0.16, (num_nodes, 1)) * (1.0 - rng.uniform(0.0, 0.6) * x)
    inflow = np.arctan(v_axial[:, None] / (rpm[:, None] * np.pi / 30.0 * radii))
    twist = inflow + np.radians(rng.uniform(*pitch_deg, (num_nodes, num_radial)))
    return dict(v_axial=v_axial, rpm=rpm, radius=radius, hub_radius=hub, radii=radii, chord=chord, twist=twist,
                rho=np.full(num_nodes, 1.2), mu=np.full(num_nodes, 1.8e-5))


def _flat(values, polar=POLAR):
    shape = values["radii"].shape
    kernels = {k: np.broadcast_to(np.reshape(v, (shape[0], -1)), shape).ravel() for k, v in values.items()}
    kernels.update(num_blades=B, polar=polar, loss_model="tip_hub")
    guess = inflow_angle_guess(kernels["v_axial"], kernels["rpm"], kernels["radii"], kernels["chord"],
                               kernels["twist"], B)
    return residual_function(**kernels), denominator_function(**kernels), kernels["v_axial"] > 0.0, guess


def _solve(values, solve_range, previous=None):
    residual, admissible, forward, guess = _flat(values)
    if solve_range == "physical":
        return solve_physical(residual, admissible, forward, initial_guess=guess, previous=previous)
    return solve_bracketed(residual, forward.size, initial_guess=guess, previous=previous), None


@settings(max_examples=40, deadline=None, database=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 2**32 - 1), jump_seed=st.integers(0, 2**32 - 1),
       step=st.floats(1e-6, 3e-2), solve_range=st.sampled_from(["physical", "full"]))
def test_warm_start_returns_the_cold_root_after_small_steps_and_large_jumps(seed, jump_seed, step, solve_range):
    # Blade pitch from 8 deg below to 25 deg above the zero-induction angle: windmilling, braking,
    # propeller and deep-stall stations, in hover and cruise.
    values = _rotors(seed, 4, 12, (-8.0, 25.0))
    cold, found = _solve(values, solve_range)
    previous = [cold,                                                      # an unchanged re-evaluation
                _solve(_rotors(jump_seed, 4, 12, (-8.0, 25.0)), solve_range)[0]]  # a large jump
    stepped = dict(values, twist=values["twist"] + step * np.random.default_rng(seed).standard_normal((4, 12)))
    cold_stepped, found_stepped = _solve(stepped, solve_range)
    for start in previous:
        warm, warm_found = _solve(values, solve_range, previous=start)
        np.testing.assert_allclose(warm, cold, rtol=1e-9, atol=1e-10)
        np.testing.assert_array_equal(warm_found, found)
    # An optimiser step: the perturbed twist, warm-started from the unperturbed roots.
    warm, warm_found = _solve(stepped, solve_range, previous=cold)
    np.testing.assert_allclose(warm, cold_stepped, rtol=1e-9, atol=1e-10)
    np.testing.assert_array_equal(warm_found, found_stepped)


def _three_roots(phi, idx):
    # R = -(phi - 0.3)(phi - 0.7)(phi - 1.1): R(eps) > 0 > R(pi/2), three simple roots in region 1.
    return -(phi - 0.3) * (phi - 0.7) * (phi - 1.1), -(3.0 * phi**2 - 4.2 * phi + 1.25)


@pytest.mark.parametrize("cold_start", [0.2, 0.5, 0.9, 1.3])
def test_three_roots_in_region_one_warm_start_keeps_the_cold_root(cold_start):
    # Cold starts left of, between and right of the roots; previous roots all over region 1.  Where
    # the samples show more than one root (a slope of the wrong sign, a point on the wrong side) the
    # station is solved cold, so every returned root is the cold solve's.
    previous = np.linspace(0.05, 1.5, 30)
    guess = np.full(previous.size, cold_start)
    cold = solve_bracketed(_three_roots, previous.size, initial_guess=guess)
    _, accepted = warm_region_one(_three_roots, previous, initial_guess=guess)
    assert not np.any(accepted[np.abs(previous - 0.7) < 0.2])      # near the middle root: never
    warm = solve_bracketed(_three_roots, previous.size, initial_guess=guess, previous=previous)
    np.testing.assert_allclose(warm, cold, atol=1e-12)


def test_region_one_without_sign_change_goes_to_the_cold_search():
    # R = sin(phi + 0.5): no sign change in [eps, pi/2] (root -0.5 in region 2): never accepted, cold root kept.
    def residual(phi, idx):
        return np.sin(phi + 0.5), np.cos(phi + 0.5)
    phi, accepted = warm_region_one(residual, np.array([0.3, 1.0]))
    assert not np.any(accepted) and np.all(np.isnan(phi))
    np.testing.assert_allclose(solve_bracketed(residual, 2, previous=np.array([0.3, 1.0])), -0.5, atol=1e-14)


def _component_values():
    values = _rotors(3, NN, NR, (2.0, 12.0))
    return {k: v for k, v in values.items()}


@pytest.mark.parametrize("solve_range", ["physical", "full"])
def test_component_partials_by_complex_step_with_warm_start(solve_range):
    comp = InflowComp(num_nodes=NN, num_radial=NR, num_blades=B, polar=POLAR, solve_range=solve_range,
                      warm_start=True)
    prob = check_component_partials(comp, _component_values(), atol=1e-9, rtol=1e-9)
    # The check ran the solve again (complex step) from the first solve's phi: still converged.
    prob.model.run_apply_nonlinear()
    assert np.max(np.abs(prob.model._residuals.asarray())) < 1e-12


def _group(warm_start, nn=NN, nr=NR):
    prob = om.Problem(BEMAnalysisGroup(num_nodes=nn, num_radial=nr, num_blades=B, polar=POLAR,
                                       warm_start=warm_start, on_invalid="ignore"), reports=False)
    prob.setup(check=False)
    return prob


def test_group_warm_start_matches_cold_over_an_optimiser_like_sequence():
    # A sequence of twist and rpm changes (small steps, then a jump), applied to a cold and a warm group.
    values = _rotors(7, NN, NR, (0.0, 14.0))
    cold, warm = _group(False), _group(True)
    rng = np.random.default_rng(11)
    twist, rpm = values["twist"].copy(), values["rpm"].copy()
    for k in range(6):
        if k == 4:
            twist, rpm = twist + np.radians(8.0), 0.6 * rpm      # a large jump
        else:
            twist = twist + 2e-3 * rng.standard_normal(twist.shape)
        for prob in (cold, warm):
            for name in ("v_axial", "radius", "hub_radius", "chord"):
                prob.set_val(name, values[name])
            prob.set_val("twist", twist)
            prob.set_val("rpm", rpm)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", UserWarning)
                prob.run_model()
        np.testing.assert_allclose(warm.get_val("phi"), cold.get_val("phi"), rtol=1e-9, atol=1e-10)
        np.testing.assert_array_equal(warm.get_val("flow_state"), cold.get_val("flow_state"))
        np.testing.assert_allclose(warm.get_val("thrust"), cold.get_val("thrust"), rtol=1e-10)
