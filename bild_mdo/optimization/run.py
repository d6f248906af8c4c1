"""Running the BEM optimisation of paper Sec. 5.1: trim, scaling, the driver run and its result.

:func:`run_optimization` optimises the case loaded in a problem from
:func:`~bild_mdo.optimization.problem.build_optimization_problem`;
:func:`optimize_rotor` builds (or reuses) the problem, loads the case and runs
it, with optional restarts.  :func:`trim_to_thrust` makes a loaded design
feasible by collective pitch alone.
"""
from __future__ import annotations

import time

import numpy as np
import openmdao.api as om

from bild_mdo.optimization.initial_design import CHORD_RATIO_BOUNDS
from bild_mdo.optimization.batch_model import CASE_INPUTS, CaseSpec, ModelPool
from bild_mdo.optimization.lockstep import DEFAULT_BATCH_SIZE, TRIMMED_START_TOLERANCE, optimize_in_lockstep
from bild_mdo.optimization.problem import (build_optimization_problem, case_design_values, check_case,
                                           set_optimization_case)
from bild_mdo.optimization.result import (ANALYSIS_FAILED, RESULT_QUANTITIES, THRUST_TOLERANCE, OptimizationResult,
                                          count_invalid, invalid_flow_text, single_threaded_blas)
from bild_mdo.optimization.scaling import CHORD_RATIO_REF, TWIST_REF, hessian_scaling, response_gradients
from bild_mdo.optimization.turbine import THRUST_SIGN, turbine_metrics

_CASE_OPTIONS = ("initial", "bild_chord", "bild_twist", "reference_chord", "energy_loss_ref")


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
    bounds and runs the driver with single-threaded BLAS.  The first inflow
    solve of the run is cold (:func:`forget_inflow_history`), so the result
    depends only on the loaded case and design, never on what the problem
    solved before: a reused problem gives bit for bit what a fresh one
    gives.  A BEM solve that
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
    if meta["optimizer"] == "slsqp":
        return _slsqp(prob, restarts=0)
    return _run_driver(prob)


def _settings(meta, restarts):
    return {"scaling": meta["scaling"], "parameterization": meta["parameterization"], "order": meta["order"],
            "tol": meta["tol"], "maxiter": meta["maxiter"], "restarts": int(restarts),
            "num_radial": meta["num_radial"], "pitch_slope_sign": THRUST_SIGN[meta.get("rotor_type", "propeller")]}


def _slsqp(prob, restarts):
    """The case loaded in a single-case problem, through the lockstep engine with one case."""
    meta = prob._bild_optimization
    spec = CaseSpec(inputs={name: float(prob.get_val(name, units=units)[0]) for name, units in CASE_INPUTS},
                    chord_ratio_cp=prob.get_val("chord_ratio_cp")[0].copy(),
                    twist_cp=prob.get_val("twist_cp", units="rad")[0].copy(), twist_bounds=meta["twist_bounds"])
    with single_threaded_blas():
        return optimize_in_lockstep(ModelPool(meta, base=prob), [spec], _settings(meta, restarts))[0]


def forget_inflow_history(prob):
    """Make the next inflow solve of ``prob`` cold: forget the angles the warm start would begin from.

    With ``BEMOptimizationGroup(warm_start=True)`` (the default) each inflow
    solve starts from the previous solve's angles.  Warm and cold roots agree
    only to solver tolerance (``|R| <= 1e-13``), and an optimiser amplifies
    such differences: left in place, the angles of the previous case of a
    reused problem changed the next case's Ipopt run (one verification case
    took 866, 498 or 314 iterations, by what ran before it in its worker),
    so a sweep's numbers depended on how its cases were grouped into
    processes.  The SLSQP engine starts every case cold in the same way
    (:meth:`~bild_mdo.optimization.batch_model.BatchModel.evaluate`).

    Parameters
    ----------
    prob : om.Problem
        From :func:`~bild_mdo.optimization.problem.build_optimization_problem`.
    """
    inflow = prob.model.rotor.bem.inflow
    if inflow.options["warm_start"]:
        # InflowComp keeps its previous solve here (bild_mdo.bem.inflow, option warm_start); None is a cold solve.
        inflow._previous_phi = None


def _run_driver(prob):
    meta = prob._bild_optimization
    optimizer = meta["optimizer"]
    start = time.perf_counter()
    forget_inflow_history(prob)
    try:
        with single_threaded_blas():
            if meta["scaling"] == "hessian":
                refs = hessian_scaling(prob)
            else:
                refs = (CHORD_RATIO_REF, TWIST_REF)
            _apply_design_var_options(prob, *refs)
            prob.run_driver()
    except om.AnalysisError as exc:
        success, status, iterations = False, f"{ANALYSIS_FAILED}: {exc}", 0
    else:
        success, status, iterations = _driver_outcome(prob, optimizer)
    wall_time = time.perf_counter() - start
    thrust_error = float(prob.get_val("thrust_residual")[0])
    performance = {name: float(prob.get_val(name)[0]) for name in RESULT_QUANTITIES}
    converged = bool(success and abs(thrust_error) <= THRUST_TOLERANCE
                     and all(np.isfinite(v) for v in performance.values()))
    # As for the performance above: the model holds the last point the driver evaluated, the optimum it returns.
    flow_state = np.rint(np.real(prob.get_val("bem.flow_state")[0])).astype(int)
    invalid = count_invalid(flow_state)
    if invalid:
        status = f"{status}; {invalid_flow_text(flow_state)}"
    return OptimizationResult(
        converged=converged, status=status, iterations=iterations,
        model_evaluations=int(prob.driver.iter_count), wall_time=wall_time, setup_time=0.0,
        chord=prob.get_val("chord", units="m")[0].copy(), twist=prob.get_val("twist", units="rad")[0].copy(),
        performance=performance, thrust_error=thrust_error, optimizer=optimizer, flow_state=flow_state,
        invalid_stations=invalid)


def optimize_rotor(v_axial, rpm, radius, hub_radius, thrust_target, altitude=0.0, *, problem=None, restarts=0,
                   **options):
    """Optimise one rotor for minimum energy loss at the required thrust (paper Sec. 5.1).

    SLSQP runs through the lockstep engine (:mod:`bild_mdo.optimization.lockstep`)
    with one case; Ipopt and SNOPT on their OpenMDAO drivers.

    Parameters
    ----------
    v_axial, rpm, radius, hub_radius, thrust_target, altitude : float or array_like
        The case (m/s, rpm, m, m, N, m).  Arrays (broadcast against each
        other) optimise many cases together: see :func:`optimize_rotors`,
        which then returns a list of results, one per case.
    problem : om.Problem, optional
        A problem from :func:`~bild_mdo.optimization.problem.build_optimization_problem`
        to reuse: its optimiser, parameterisation and sizes are kept and only
        the case options (``initial``, ``bild_chord``, ``bild_twist``,
        ``reference_chord``, ``energy_loss_ref``) are read from ``options``.
        Reusing skips the set-up (0.05-0.2 s, several seconds for the
        first problem of a process, which builds the polar) and gives the
        same result, bit for bit, as a fresh problem, whatever it solved
        before (:func:`forget_inflow_history`).
    restarts : int
        How often to restart the optimiser from where it stopped when it
        reports failure (not after a failed BEM analysis): a restart
        recomputes the scaling and forgets the quasi-Newton Hessian, which
        clears stalls such as SLSQP's "Positive directional derivative for
        linesearch".  ``iterations``, ``model_evaluations`` and ``wall_time``
        add up over the attempts; ``status`` names the earlier failures.
        Independently of ``restarts``, an optimum worse than the initial
        design trimmed to the thrust (or a run that did not converge) is
        followed by one more run from that trimmed design, and the better
        converged result is kept (SLSQP:
        :class:`~bild_mdo.optimization.lockstep.CaseRun`; Ipopt and SNOPT:
        ``_from_trimmed_start`` here; ``status`` says so).
    **options
        Keyword options of :func:`~bild_mdo.optimization.problem.build_optimization_problem`.

    Returns
    -------
    OptimizationResult or list of OptimizationResult

    Examples
    --------
    >>> result = optimize_rotor(0.0, 800.0, 1.0, 0.2, 420.0, initial="linear")  # doctest: +SKIP
    >>> result.converged, result.performance["figure_of_merit"]  # doctest: +SKIP
    """
    case = (v_axial, rpm, radius, hub_radius, thrust_target, altitude)
    if any(np.ndim(value) > 0 for value in case):
        return optimize_rotors(*case, problem=problem, restarts=restarts, **options)
    start = time.perf_counter()
    if problem is None:
        prob = build_optimization_problem(v_axial, rpm, radius, hub_radius, thrust_target, altitude, **options)
        setup_time = time.perf_counter() - start
    else:
        _check_case_options(options)
        set_optimization_case(problem, v_axial, rpm, radius, hub_radius, thrust_target, altitude, **options)
        prob, setup_time = problem, 0.0
    if prob._bild_optimization["optimizer"] == "slsqp":
        result = _slsqp(prob, restarts)
        result.setup_time = setup_time
        return _signed(prob._bild_optimization, result, case)
    start_chord = prob.get_val("chord_ratio_cp")[0].copy()
    start_twist = prob.get_val("twist_cp", units="rad")[0].copy()
    result = run_optimization(prob)
    failures = []
    for _ in range(int(restarts)):
        if result.converged or result.status.startswith(ANALYSIS_FAILED):
            break
        failures.append(result.status)
        again = run_optimization(prob)
        again.iterations += result.iterations
        again.model_evaluations += result.model_evaluations
        again.wall_time += result.wall_time
        result = again
    if failures:
        result.status = f"{result.status} (after restarts from: {'; '.join(failures)})"
    if not result.status.startswith(ANALYSIS_FAILED):
        result = _from_trimmed_start(prob, result, start_chord, start_twist)
    result.setup_time = setup_time
    return _signed(prob._bild_optimization, result, case)


def _signed(meta, result, case):
    """A turbine's result with the turbine's metrics as its ``performance`` (:func:`turbine_metrics`)."""
    if meta.get("rotor_type") == "turbine":  # NaN metrics of a failed run stay NaN, turbine-signed
        v_axial, rpm, radius, _, _, altitude = (float(value) for value in case)
        result.performance = turbine_metrics(result.performance, v_axial, rpm, radius, altitude)
    return result


def _from_trimmed_start(prob, result, start_chord, start_twist):
    """Ipopt/SNOPT: a result worse than the start trimmed to the thrust gets one more run from there.

    The driver counterpart of the SLSQP engine's rule
    (:class:`~bild_mdo.optimization.lockstep.CaseRun`): a converged optimum whose
    energy loss exceeds that of the initial design trimmed to ``T*`` by collective
    pitch (:func:`trim_to_thrust`) by more than
    :data:`~bild_mdo.optimization.lockstep.TRIMMED_START_TOLERANCE`, or a run
    that did not converge, is followed by one run from the trimmed design; the
    better converged result is kept and ``status`` says so.  Without it, Ipopt on
    levels 3 of the verification left 1 of 81 cases at its iteration limit and 2
    above BILD's trimmed design (+0.90 %, +0.74 %); with it, 81 of 81 converged,
    at most one above, by 0.03 % (one run each).  The model is left at the returned design.
    """
    optimum_chord = prob.get_val("chord_ratio_cp")[0].copy()
    optimum_twist = prob.get_val("twist_cp", units="rad")[0].copy()

    def keep_first():
        prob.set_val("chord_ratio_cp", optimum_chord)
        prob.set_val("twist_cp", optimum_twist, units="rad")
        prob.run_model()
        return result

    prob.set_val("chord_ratio_cp", start_chord)
    prob.set_val("twist_cp", start_twist, units="rad")
    try:
        trim_to_thrust(prob)
    except om.AnalysisError:
        bound = None
    else:
        bound = float(prob.get_val("energy_loss")[0])
    energy = result.performance["energy_loss"]
    if bound is None or (result.converged and energy <= bound * (1.0 + TRIMMED_START_TOLERANCE)):
        return keep_first()
    label = (f"{100.0 * (energy / bound - 1.0):.2f} % worse than the trimmed start" if result.converged
             else f"not converged: {result.status}")
    again = run_optimization(prob)
    again.iterations += result.iterations
    again.model_evaluations += result.model_evaluations
    again.wall_time += result.wall_time
    if again.converged and (not result.converged or again.performance["energy_loss"] < energy):
        again.status = f"{again.status} (restarted from the initial design trimmed to the thrust; first run {label})"
        return again
    result.iterations, result.model_evaluations, result.wall_time = (again.iterations, again.model_evaluations,
                                                                     again.wall_time)
    result.status = f"{result.status} ({label}; a restart from the trimmed start did no better)"
    return keep_first()


def _check_case_options(options):
    unknown = set(options) - set(_CASE_OPTIONS)
    if unknown:
        raise ValueError(f"with problem=..., only the case options {_CASE_OPTIONS} can be given; got {sorted(unknown)}")


def _per_case(value, count, shape, name):
    """``value`` for each of ``count`` cases: one for all, or one per case (first axis)."""
    if value is None or isinstance(value, str):
        return [value] * count
    array = np.asarray(value, dtype=float)
    if array.shape == shape:
        return [array] * count
    if array.shape == (count,) + shape:
        return list(array)
    raise ValueError(f"{name} must have shape {shape} (all cases) or {(count,) + shape} (one per case), "
                     f"got {array.shape}")


def optimize_rotors(v_axial, rpm, radius, hub_radius, thrust_target, altitude=0.0, *, problem=None, restarts=0,
                    batch_size=DEFAULT_BATCH_SIZE, **options):
    """Optimise many rotors in lockstep: :func:`optimize_rotor` with arrays for the case arguments.

    The case arguments broadcast against each other (numpy rules) to ``n``
    cases, taken in C order.  With SLSQP every case runs its own optimiser,
    and all share one vectorised model evaluation per step
    (:mod:`bild_mdo.optimization.lockstep`): each case gets the result it gets
    alone, for a fraction of the time.  Ipopt and SNOPT optimise the cases
    one after the other on their drivers.

    Parameters
    ----------
    v_axial, rpm, radius, hub_radius, thrust_target, altitude : array_like
        The cases (m/s, rpm, m, m, N, m).
    problem : om.Problem, optional
        A problem from :func:`~bild_mdo.optimization.problem.build_optimization_problem`
        whose configuration to use; only the case options may be given then.
    restarts : int
        See :func:`optimize_rotor`.
    batch_size : int
        Cases optimised at the same time (SLSQP); when one finishes, the next starts.
    **options
        As for :func:`optimize_rotor`; ``bild_chord`` and ``bild_twist`` of
        shape ``(num_radial,)`` (all cases) or ``(n, num_radial)``,
        ``reference_chord`` and ``energy_loss_ref`` scalar or ``(n,)``.

    Returns
    -------
    list of OptimizationResult
        One per case, in order.  For SLSQP ``wall_time`` is each case's share
        of the lockstep run, and ``setup_time`` its share of the set-up.
    """
    columns = [np.ravel(c) for c in np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in
                                                            (v_axial, rpm, radius, hub_radius, thrust_target,
                                                             altitude)))]
    count = columns[0].size
    case_options = {key: options.pop(key) for key in _CASE_OPTIONS if key in options}
    start = time.perf_counter()
    if problem is None:
        problem = _configuration(options)
    else:
        _check_case_options(options)
    setup_time = time.perf_counter() - start
    meta = problem._bild_optimization
    nr = meta["num_radial"]
    per_case = {"initial": [case_options.get("initial", "bild")] * count}
    for key, shape in (("bild_chord", (nr,)), ("bild_twist", (nr,)), ("reference_chord", ()),
                       ("energy_loss_ref", ())):
        per_case[key] = _per_case(case_options.get(key), count, shape, key)
    if meta["optimizer"] != "slsqp":
        return [optimize_rotor(*(float(c[k]) for c in columns), problem=problem, restarts=restarts,
                               **{key: values[k] for key, values in per_case.items()}) for k in range(count)]
    specs = []
    for k in range(count):
        case = [float(c[k]) for c in columns]
        check_case(*case)
        values = case_design_values(meta, *case, **{key: vals[k] for key, vals in per_case.items()})
        inputs = dict(zip(("v_axial", "rpm", "radius", "hub_radius", "thrust_target", "altitude"), case),
                      energy_loss_ref=values["energy_loss_ref"])
        inputs["thrust_target"] *= THRUST_SIGN[meta.get("rotor_type", "propeller")]
        specs.append(CaseSpec(inputs, values["chord_ratio_cp"], values["twist_cp"], values["twist_bounds"]))
    with single_threaded_blas():
        results = optimize_in_lockstep(_pool(meta), specs, _settings(meta, restarts), batch_size)
    for k, result in enumerate(results):
        result.setup_time += setup_time / count
        results[k] = _signed(meta, result, [c[k] for c in columns])
    return results


# Set-up problems and batch models by configuration, reused by later calls in this process.
_CONFIGURATIONS = {}
_POOLS = {}


def _configuration(options):
    key = repr(sorted((k, id(v) if not isinstance(v, (str, int, float, type(None))) else v)
                      for k, v in options.items()))
    prob = _CONFIGURATIONS.get(key)
    if prob is None:
        prob = _CONFIGURATIONS[key] = build_optimization_problem(**options)
    return prob


def _pool(meta):
    key = tuple(meta[k] if k != "polar" else id(meta[k]) for k in
                ("num_radial", "num_blades", "polar", "loss_model", "parameterization", "num_cp", "order",
                 "approx_totals"))
    pool = _POOLS.get(key)
    if pool is None:
        pool = _POOLS[key] = ModelPool(meta)
    return pool
