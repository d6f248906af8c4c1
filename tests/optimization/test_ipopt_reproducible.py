"""Ipopt optimisations are reproducible: the same case gives the same numbers, bit for bit, whatever ran before.

The inflow warm start (``BEMOptimizationGroup(warm_start=True)``) keeps the
angles of a problem's last solve; left from the previous case, they changed
the next case's Ipopt run (``bild-mdo verify --optimizer ipopt`` rows then
depended on which worker and chunk a case ran in).  Every driver run now
starts cold (:func:`~bild_mdo.optimization.run.forget_inflow_history`).
"""
import numpy as np
import pytest

from bild_mdo.optimization.problem import build_optimization_problem
from bild_mdo.optimization.run import forget_inflow_history, optimize_rotor

try:
    import cyipopt  # noqa: F401
    HAVE_CYIPOPT = True
except ImportError:
    HAVE_CYIPOPT = False

pytestmark = pytest.mark.skipif(not HAVE_CYIPOPT, reason="cyipopt is not installed")

# Small, fast configuration: 12 stations, 40 Ipopt iterations at most (converged or not, a run must repeat).
OPTIONS = dict(optimizer="ipopt", num_radial=12, maxiter=40)
# (v_axial, rpm, radius, hub_radius, thrust_target, altitude): a hover and a cruise rotor.
HOVER = (0.0, 800.0, 1.0, 0.2, 420.0, 0.0)
CRUISE = (20.0, 800.0, 1.2, 0.24, 300.0, 1000.0)


def _fingerprint(result):
    """Everything a sweep stores of a result, as exact values."""
    return (result.chord.tobytes(), result.twist.tobytes(), tuple(sorted(result.performance.items())),
            result.thrust_error, result.converged, result.status, result.iterations, result.model_evaluations,
            result.flow_state.tobytes())


def _optimize(case, prob):
    return optimize_rotor(*case, problem=prob, initial="linear")


def test_a_case_alone_again_and_after_another_case_is_bitwise_the_same():
    alone = _fingerprint(_optimize(CRUISE, build_optimization_problem(**OPTIONS)))

    reused = build_optimization_problem(**OPTIONS)
    other = _optimize(HOVER, reused)
    after_other = _fingerprint(_optimize(CRUISE, reused))
    again = _fingerprint(_optimize(CRUISE, reused))

    assert other.iterations > 0
    assert after_other == alone
    assert again == alone


def test_forget_inflow_history_makes_the_next_solve_cold():
    prob = build_optimization_problem(*HOVER, **OPTIONS)
    prob.run_model()
    cold = prob.get_val("bem.phi").copy()
    inflow = prob.model.rotor.bem.inflow
    assert inflow._previous_phi is not None
    forget_inflow_history(prob)
    assert inflow._previous_phi is None
    prob.run_model()
    np.testing.assert_array_equal(prob.get_val("bem.phi"), cold)
