"""Running the BEM optimisation of paper Sec. 5.1: trim, scaling, the driver run and its result.

:func:`run_optimization` optimises the case loaded in a problem from
:func:`~bild_mdo.optimization.problem.build_optimization_problem`;
:func:`optimize_rotor` builds (or reuses) the problem, loads the case and runs
it, with optional restarts.  :func:`trim_to_thrust` makes a loaded design
feasible by collective pitch alone.
"""
from __future__ import annotations

import contextlib
import dataclasses
import time

import numpy as np
import openmdao.api as om

from bild_mdo.bem.flow_states import FLOW_STATE_NAMES, INVALID_STATES
from bild_mdo.bem.metrics import PERFORMANCE_OUTPUTS
from bild_mdo.optimization.initial_design import CHORD_RATIO_BOUNDS
from bild_mdo.optimization.problem import build_optimization_problem, set_optimization_case
from bild_mdo.optimization.scaling import CHORD_RATIO_REF, TWIST_REF, hessian_scaling, response_gradients

#: Relative thrust-constraint violation above which a run counts as not converged.
THRUST_TOLERANCE = 1.0e-6

#: Performance quantities reported by :func:`run_optimization`.
RESULT_QUANTITIES = tuple(PERFORMANCE_OUTPUTS)

_ANALYSIS_FAILED = "BEM analysis failed at a trial point"
_CASE_OPTIONS = ("initial", "bild_chord", "bild_twist", "reference_chord", "energy_loss_ref")
_BLAS_THREADS = []


def single_threaded_blas():
    """Context limiting BLAS to one thread, when threadpoolctl is installed.

    SciPy's SLSQP calls BLAS on small dense matrices; OpenBLAS's extra threads
    then busy-wait and double the CPU time of every optimisation, which slows
    a sweep that already runs one process per core.

    Returns
    -------
    contextlib.AbstractContextManager
    """
    if not _BLAS_THREADS:
        try:
            from threadpoolctl import ThreadpoolController
        except ImportError:
            _BLAS_THREADS.append(None)
        else:
            _BLAS_THREADS.append(ThreadpoolController())
    controller = _BLAS_THREADS[0]
    if controller is None:
        return contextlib.nullcontext()
    return controller.limit(limits=1, user_api="blas")


def trim_to_thrust(prob, tol=1.0e-12, max_iter=20):
    """Shift the loaded design's twist uniformly until the BEM thrust equals the target (collective pitch).

    Makes a design feasible without the optimiser, e.g. to evaluate the BILD
    geometry in the BEM model at exactly ``T*``: the energy loss of that
    design is an upper bound that the optimum must not exceed.  Newton's
    method on the pitch offset with the exact ``dT/dtwist``.

    Parameters
    ----------
    prob : om.Problem
        From :func:`~bild_mdo.optimization.problem.build_optimization_problem`,
        with a case loaded; its twist design values are updated in place and
        the model is left run.
    tol : float
        Tolerance on ``|T/T* - 1|``.
    max_iter : int
        Newton iterations.

    Returns
    -------
    float
        The pitch offset (rad).

    Raises
    ------
    om.AnalysisError
        If the thrust target cannot be met within ``max_iter`` iterations.
    """
    x_c = prob.get_val("chord_ratio_cp")[0].copy()
    x_t = prob.get_val("twist_cp", units="rad")[0].copy()
    offset = 0.0
    for _ in range(max_iter):
        _, g_t = response_gradients(prob, x_c, x_t + offset)
        residual = float(prob.get_val("thrust_residual")[0])
        if abs(residual) <= tol:
            return offset
        # A uniform offset moves every twist design value, stations or B-spline control points alike.
        offset -= residual / float(np.sum(g_t[x_c.size:]))
    raise om.AnalysisError(f"trim_to_thrust: |T/T* - 1| = {abs(residual):.3e} after {max_iter} Newton steps")


def _apply_design_var_options(prob, ref_chord, ref_twist):
    lower, upper = prob._bild_optimization["twist_bounds"]
    prob.model.set_design_var_options("chord_ratio_cp", ref=ref_chord, lower=CHORD_RATIO_BOUNDS[0],
                                      upper=CHORD_RATIO_BOUNDS[1])
    prob.model.set_design_var_options("twist_cp", ref=ref_twist, lower=lower, upper=upper)
    # The driver copies design-variable metadata in final_setup.
    prob.final_setup()


@dataclasses.dataclass
class OptimizationResult:
    """Outcome of :func:`run_optimization` and :func:`optimize_rotor`.

    Attributes
    ----------
    converged : bool
        The optimiser reports success and ``|T/T* - 1| <= THRUST_TOLERANCE``.
    status : str
        The optimiser's exit message.
    iterations : int
        Major iterations of the optimiser.
    model_evaluations : int
        Model evaluations by the driver (OpenMDAO ``iter_count``).
    wall_time : float
        Time of the scaling step and the driver run (s), without set-up.
    setup_time : float
        Time to build and set up the problem (s); 0 when a problem was reused.
    chord, twist : ndarray, shape (nr,)
        Optimal geometry at the stations (m, rad).
    performance : dict
        Per-design BEM outputs at the optimum (float), one per entry of
        :data:`bild_mdo.bem.metrics.METRICS`: ``thrust`` (N), ``torque``
        (N m), ``power`` (W), ``efficiency``, ``energy_loss`` (W), ...
    thrust_error : float
        ``T/T* - 1`` at the optimum.
    optimizer : str
        Optimiser name.
    flow_state : ndarray of int, shape (nr,)
        Flow-state code of every station at the optimum (:mod:`bild_mdo.bem.flow_states`).
    invalid_stations : int
        Stations of the optimum in a flow state the momentum model does not
        represent (:data:`~bild_mdo.bem.flow_states.INVALID_STATES`).  The
        optimisation ignores such states at its trial points; a converged
        optimum with ``invalid_stations > 0`` is reported (``status`` says so)
        but not trusted by :attr:`flow_valid`.
    """

    converged: bool
    status: str
    iterations: int
    model_evaluations: int
    wall_time: float
    setup_time: float
    chord: np.ndarray
    twist: np.ndarray
    performance: dict
    thrust_error: float
    optimizer: str
    flow_state: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0, dtype=int))
    invalid_stations: int = 0

    @property
    def flow_valid(self):
        """True when every station of the optimum is in a valid flow state."""
        return self.invalid_stations == 0


def _driver_outcome(prob, optimizer):
    driver = prob.driver
    if optimizer == "slsqp":
        res = getattr(driver, "_scipy_optimize_result", None)
        if res is None:
            return False, "SLSQP returned no result", 0
        return bool(res.success), str(res.message), int(getattr(res, "nit", 0))
    if optimizer == "ipopt":
        return (not driver.fail, f"{driver.ipopt_status_name}: {driver.ipopt_message}",
                int(driver.ipopt_iterations))
    inform = getattr(getattr(driver, "pyopt_solution", None), "optInform", None) or {}
    return not driver.fail, str(inform.get("text", "SNOPT finished")), int(driver.iter_count)


def run_optimization(prob):
    """Run the optimisation of the case loaded in ``prob`` and collect the result.

    Scales the design variables (``scaling='hessian'``), applies the case's
    bounds and runs the driver with single-threaded BLAS.  A BEM solve that
    fails at a trial point (``om.AnalysisError``, which SLSQP cannot back off
    from) ends the run as not converged; the error is in ``status``.

    Parameters
    ----------
    prob : om.Problem
        From :func:`~bild_mdo.optimization.problem.build_optimization_problem`, with a case loaded.

    Returns
    -------
    OptimizationResult
        ``setup_time`` is 0.
    """
    meta = prob._bild_optimization
    optimizer = meta["optimizer"]
    start = time.perf_counter()
    try:
        with single_threaded_blas():
            if meta["scaling"] == "hessian":
                refs = hessian_scaling(prob)
            else:
                refs = (CHORD_RATIO_REF, TWIST_REF)
            _apply_design_var_options(prob, *refs)
            prob.run_driver()
    except om.AnalysisError as exc:
        success, status, iterations = False, f"{_ANALYSIS_FAILED}: {exc}", 0
    else:
        success, status, iterations = _driver_outcome(prob, optimizer)
    wall_time = time.perf_counter() - start
    thrust_error = float(prob.get_val("thrust_residual")[0])
    performance = {name: float(prob.get_val(name)[0]) for name in RESULT_QUANTITIES}
    converged = bool(success and abs(thrust_error) <= THRUST_TOLERANCE
                     and all(np.isfinite(v) for v in performance.values()))
    # As for the performance above: the model holds the last point the driver evaluated, the optimum it returns.
    flow_state = np.rint(np.real(prob.get_val("bem.flow_state")[0])).astype(int)
    invalid = int(np.isin(flow_state, INVALID_STATES).sum())
    if invalid:
        status = f"{status}; {invalid_flow_text(flow_state)}"
    return OptimizationResult(
        converged=converged, status=status, iterations=iterations,
        model_evaluations=int(prob.driver.iter_count), wall_time=wall_time, setup_time=0.0,
        chord=prob.get_val("chord", units="m")[0].copy(), twist=prob.get_val("twist", units="rad")[0].copy(),
        performance=performance, thrust_error=thrust_error, optimizer=optimizer, flow_state=flow_state,
        invalid_stations=invalid)


def invalid_flow_text(flow_state):
    """One phrase on the stations of a design in an invalid flow state, e.g. ``'2 of 30 stations ... (4: ...)'``.

    Parameters
    ----------
    flow_state : array_like of int, shape (nr,)
        Flow-state codes of :mod:`bild_mdo.bem.flow_states`.

    Returns
    -------
    str
    """
    flow_state = np.asarray(flow_state, dtype=int)
    bad = np.flatnonzero(np.isin(flow_state, INVALID_STATES))
    names = sorted({FLOW_STATE_NAMES[int(code)] for code in flow_state[bad]})
    return (f"{bad.size} of {flow_state.size} stations in an invalid BEM flow state at the optimum "
            f"({', '.join(names)}; stations {bad.tolist()})")


def optimize_rotor(v_axial, rpm, radius, hub_radius, thrust_target, altitude=0.0, *, problem=None, restarts=0,
                   **options):
    """Optimise one rotor for minimum energy loss at the required thrust (paper Sec. 5.1).

    Parameters
    ----------
    v_axial, rpm, radius, hub_radius, thrust_target, altitude : float
        The case (m/s, rpm, m, m, N, m).
    problem : om.Problem, optional
        A problem from :func:`~bild_mdo.optimization.problem.build_optimization_problem`
        to reuse: its optimiser, parameterisation and sizes are kept and only
        the case options (``initial``, ``bild_chord``, ``bild_twist``,
        ``reference_chord``, ``energy_loss_ref``) are read from ``options``.
        Reusing skips the set-up (0.05-0.2 s, several seconds for the
        first problem of a process, which builds the polar).
    restarts : int
        How often to restart the optimiser from where it stopped when it
        reports failure (not after a failed BEM analysis): a restart
        recomputes the scaling and forgets the quasi-Newton Hessian, which
        clears stalls such as SLSQP's "Positive directional derivative for
        linesearch".  ``iterations``, ``model_evaluations`` and ``wall_time``
        add up over the attempts; ``status`` names the earlier failures.
    **options
        Keyword options of :func:`~bild_mdo.optimization.problem.build_optimization_problem`.

    Returns
    -------
    OptimizationResult

    Examples
    --------
    >>> result = optimize_rotor(0.0, 800.0, 1.0, 0.2, 420.0, initial="linear")  # doctest: +SKIP
    >>> result.converged, result.performance["figure_of_merit"]  # doctest: +SKIP
    """
    start = time.perf_counter()
    if problem is None:
        prob = build_optimization_problem(v_axial, rpm, radius, hub_radius, thrust_target, altitude, **options)
        setup_time = time.perf_counter() - start
    else:
        unknown = set(options) - set(_CASE_OPTIONS)
        if unknown:
            raise ValueError(f"with problem=..., only the case options {_CASE_OPTIONS} can be given; "
                             f"got {sorted(unknown)}")
        set_optimization_case(problem, v_axial, rpm, radius, hub_radius, thrust_target, altitude, **options)
        prob, setup_time = problem, 0.0
    result = run_optimization(prob)
    failures = []
    for _ in range(int(restarts)):
        if result.converged or result.status.startswith(_ANALYSIS_FAILED):
            break
        failures.append(result.status)
        again = run_optimization(prob)
        again.iterations += result.iterations
        again.model_evaluations += result.model_evaluations
        again.wall_time += result.wall_time
        result = again
    if failures:
        result.status = f"{result.status} (after restarts from: {'; '.join(failures)})"
    result.setup_time = setup_time
    return result
