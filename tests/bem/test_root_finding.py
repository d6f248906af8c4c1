"""Guaranteed-bracket inflow solve (Ning 2014 search order) and the complex-step Newton update."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.bem.root_finding import find_brackets, solve_bracketed, solve_physical
from bild_mdo.utils.newton import complex_step_update


def _shifted_sine(roots):
    """R(phi) = sin(phi - root): one root per station at ``root`` (mod pi), derivative cos."""
    calls = []

    def residual(phi, idx):
        calls.append(np.array(idx))
        return np.sin(phi - roots[idx]), np.cos(phi - roots[idx])
    return residual, calls


def test_finds_roots_in_all_three_regions():
    # Roots in region 1 (0, pi/2), region 2 [-pi/4, 0) and region 3 (pi/2, pi).  sin(phi - a) also
    # vanishes at a - pi, which for the region-3 roots (a < 3 pi/4) lies below -pi/4, outside region 2.
    roots = np.array([0.3, 1.2, 1e-3, -0.5, -0.05, 2.0, 2.3, np.pi / 2 - 1e-9])
    residual, calls = _shifted_sine(roots)
    phi = solve_bracketed(residual, roots.size)
    np.testing.assert_allclose(phi, roots, atol=1e-14)
    # Only stations still iterating are evaluated, so the index sets shrink.
    assert calls[-1].size < roots.size


def test_region_one_takes_precedence():
    # R = -sin(2 phi - 0.6) has roots at 0.3 (region 1) and 0.3 + pi/2 (region 3); Ning's order
    # must return the region-1 root.
    def residual(phi, idx):
        return -np.sin(2 * phi - 0.6), -2 * np.cos(2 * phi - 0.6)
    phi = solve_bracketed(residual, 3)
    np.testing.assert_allclose(phi, 0.3, atol=1e-14)


def test_brackets_follow_ning_order():
    roots = np.array([0.4, -0.3, 2.2])
    residual, _ = _shifted_sine(roots)
    lo, hi, r_lo, r_hi = find_brackets(residual, roots.size)
    np.testing.assert_allclose(lo, [1e-6, -np.pi / 4, np.pi / 2])
    np.testing.assert_allclose(hi, [np.pi / 2, -1e-6, np.pi - 1e-6])
    assert np.all(r_lo * r_hi <= 0.0)


def test_converges_to_round_off_on_steep_and_flat_residuals():
    # Residual scales from 1e-6 to 1e6 with a cubic root (flat: Newton slows, bisection rescues).
    scale = np.array([1e-6, 1.0, 1e6, 1.0])
    power = np.array([1, 1, 1, 3])
    root = 0.7

    def residual(phi, idx):
        d = phi - root
        return scale[idx] * d ** power[idx], scale[idx] * power[idx] * d ** (power[idx] - 1)
    phi = solve_bracketed(residual, 4)
    np.testing.assert_allclose(phi[:3], root, atol=1e-15)
    assert abs(phi[3] - root) ** 3 <= 1e-13  # converged on |R| <= 1e-13 (RESIDUAL_TOL)


def test_no_bracket_raises_analysis_error_naming_station():
    def residual(phi, idx):
        value = np.where(idx == 5, 1.0 + phi**2, np.sin(phi - 0.3))
        return value, np.where(idx == 5, 2 * phi, np.cos(phi - 0.3))
    with pytest.raises(om.AnalysisError, match=r"design/node 1, station 2"):
        solve_bracketed(residual, 6, shape=(2, 3))


def test_non_finite_residual_raises():
    def residual(phi, idx):
        return np.where(idx == 1, np.nan, np.sin(phi - 0.3)), np.cos(phi - 0.3)
    with pytest.raises(om.AnalysisError, match="not finite"):
        solve_bracketed(residual, 3)


def test_complex_step_update_carries_exact_derivative():
    # R(phi; x) = phi^3 + phi - x: dphi/dx = 1 / (3 phi^2 + 1) (implicit function theorem).
    x = np.array([0.5, 2.0, 10.0])
    phi = solve_bracketed(lambda p, i: (p**3 + p - x[i], 3 * p**2 + 1), 3)
    h = 1e-30
    phi_c = complex_step_update(phi, phi**3 + phi - (x + 1j * h), 3 * phi**2 + 1)
    np.testing.assert_allclose(np.real(phi_c), phi, rtol=0, atol=1e-15)
    np.testing.assert_allclose(np.imag(phi_c) / h, 1.0 / (3 * phi**2 + 1), rtol=1e-14)


def test_non_convergence_raises_analysis_error_naming_station():
    # Station 0: R = phi - 0.7, solved by the first Newton step.  Station 1: a cubic root,
    # R = (phi - 0.7)**3, which needs more than two safeguarded Newton steps from [1e-6, pi/2].
    def residual(phi, idx):
        cubic = idx == 1
        d = phi - 0.7
        return np.where(cubic, d**3, d), np.where(cubic, 3 * d**2, 1.0)
    with pytest.raises(om.AnalysisError, match=r"did not converge in 2 iterations at design/node 0, station 1"):
        solve_bracketed(residual, 2, shape=(1, 2), max_iter=2)


def test_physical_solve_order_and_admissibility():
    # R = sin(phi - root): roots at root and root - pi.  Station 0: Q1 root 0.3.  Station 1: root -0.5
    # (Q2) and -0.5 + pi = 2.64 (Q3): Q2 comes first.  Station 2: the same, but W < 0 where phi < 0
    # (admissible rejects it), so forward flight takes Q3.  Station 3: as 2 in hover (no Q3): none.
    roots = np.array([0.3, -0.5, -0.5, -0.5])
    residual, _ = _shifted_sine(roots)
    reject_negative = np.array([False, False, True, True])

    def admissible(phi, idx):
        return ~(reject_negative[idx] & (phi < 0))

    phi, found = solve_physical(residual, admissible, forward=np.array([True, True, True, False]))
    np.testing.assert_array_equal(found, [True, True, True, False])
    np.testing.assert_allclose(phi[:3], [0.3, -0.5, np.pi - 0.5], atol=1e-14)
    assert np.isnan(phi[3])


def test_physical_solve_takes_low_induction_branch_of_two_q1_roots():
    # R = (phi - 0.1)(phi - 0.9) > 0 at both ends of Q1: an even number of roots there.  In forward
    # flight the largest (0.9, smaller induction) is taken; in hover the first admissible sign change.
    def residual(phi, idx):
        return (phi - 0.1) * (phi - 0.9), 2 * phi - 1.0

    phi, found = solve_physical(residual, lambda p, i: np.ones(p.shape, dtype=bool), np.array([True, False]))
    assert np.all(found)
    np.testing.assert_allclose(phi, [0.9, 0.1], atol=1e-14)
