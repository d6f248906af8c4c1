"""The science of the verification sweep: batched BILD and the per-case BEM optimisation (paper Sec. 5.1).

Plug these into :func:`~bild_mdo.verification.runner.run_sweep`::

    run_sweep(spec, db_path, bild_batch, optimize_case, workers=2)

:func:`bild_batch` designs every case with one vectorised :class:`~bild_mdo.bild.BILDGroup`
run; :func:`optimize_case` solves the same energy-loss minimisation with the
full BEM model and a gradient-based optimiser, warm-started from the BILD
geometry, with BILD's thrust as the equality constraint (as in the paper).
:func:`optimize_cases` optimises a chunk of cases in lockstep (one vectorised
BEM model for all of them, :mod:`bild_mdo.optimization.lockstep`), each with
the result :func:`optimize_case` gives it alone; ``bild-mdo verify`` uses it.
All are module-level functions, so they pickle to worker processes.
"""
from __future__ import annotations

import time

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.text import sweep_polar
from bild_mdo.bem.metrics import VERIFIED_METRICS
from bild_mdo.bild.problem import bild_problem
from bild_mdo.optimization.problem import DEFAULT_MAXITER, DEFAULT_TOL, build_optimization_problem, make_driver
from bild_mdo.optimization.run import optimize_rotor, optimize_rotors
from bild_mdo.utils.batches import isolate_failures

from .cases import START_KINDS, CaseSetupError, bild_setting
from .starts import combine_starts

#: Inputs that must be equal for cases to share one batched BILD model.
_MODEL_KEYS = ("num_radial", "num_blades", "airfoil")

# Problems already set up in this process, by configuration: setting one up costs more than a
# warm-started optimisation, and every case of a sweep has the same configuration.  A reused problem keeps no
# state from its previous case (bild_mdo.optimization.run.forget_inflow_history), so a case's row does not depend
# on the worker or the chunk it ran in.
_PROBLEMS = {}


def _group_cases(cases, section_points):
    """Indices of ``cases`` by BILD model: the :data:`_MODEL_KEYS`, the ideal loading and the section point (last)."""
    groups = {}
    for index, case in enumerate(cases):
        key = tuple(case.inputs[k] for k in _MODEL_KEYS) + (_ideal_loading(case), section_points[index])
        groups.setdefault(key, []).append(index)
    return groups


def _set_bild_inputs(prob, cases):
    def column(key):
        return np.array([float(case.inputs[key]) for case in cases])

    radius = column("radius")
    prob.set_val("v_axial", column("v_axial"), units="m/s")
    prob.set_val("rpm", column("rpm"), units="rpm")
    prob.set_val("radius", radius, units="m")
    prob.set_val("hub_radius_ratio", column("hub_radius") / radius)
    prob.set_val("ref_radius_ratio", column("reference_radius") / radius)
    prob.set_val("ref_chord", column("reference_chord"), units="m")
    prob.set_val("altitude", column("altitude"), units="m")


def require_optimizer(optimizer):
    """Raise ImportError (with the install hint) unless ``optimizer`` can run here.

    Makes the optimiser's OpenMDAO driver once, which imports its package
    (cyipopt for 'ipopt', pyOptSparse for 'snopt'); costs milliseconds, so a
    sweep checks it before any case runs.

    Parameters
    ----------
    optimizer : {'slsqp', 'ipopt', 'snopt'}
    """
    make_driver(optimizer, DEFAULT_TOL[optimizer], DEFAULT_MAXITER[optimizer])


def bild_batch(cases):
    """BILD designs of many cases in one vectorised run (``num_nodes = len(cases)``).

    Cases that differ in the number of stations, blades, airfoil, ideal
    loading or section point are run as separate batches (one per
    combination; the sweep has one).  Each case is designed at its
    ``section_point`` with its ``ideal_loading``; a case with
    ``starts >= 2`` is also designed at the other section point (same ideal
    loading), the optimiser's second start.  When a
    batch fails (one infeasible design fails the whole vectorised model), it
    is split in halves until every failing case is alone, so each failed case
    gets its own reason and the other cases their designs.

    Parameters
    ----------
    cases : list of Case
        Sweep cases (:class:`~bild_mdo.verification.cases.Case`).

    Returns
    -------
    list of dict
        One per case, in order, with the keys of
        :data:`~bild_mdo.verification.store.RESULT_KEYS` (``energy_loss`` in
        W, ``chord`` in m and ``twist`` in rad at the stations) and
        ``thrust`` (N), the thrust target of the optimisation; with
        ``starts >= 2``, ``other_chord`` and ``other_twist`` (the other
        section point's design, None where it failed) and ``run_time``
        (this section point's share of the batch).  Otherwise ``run_time``
        is left to the runner (batch wall time divided by the number of
        cases).  A case whose design fails is marked not converged with the
        error text.
    """
    results = [None] * len(cases)
    points = [getattr(case, "section_point", "reference") for case in cases]
    start = time.perf_counter()
    for key, indices in _group_cases(cases, points).items():
        _bild_group(cases, indices, results, key[-1], key[-2])
    second = [i for i, case in enumerate(cases) if getattr(case, "starts", 1) >= 2 and results[i]["converged"]]
    if second:
        # BILD's run time is its own design's; the other point's design is a start of the optimiser.
        share = (time.perf_counter() - start) / len(cases)
        for row in results:
            row["run_time"] = share
        others = [_other_point(points[i]) for i in second]
        alternatives = [None] * len(cases)
        for key, members in _group_cases([cases[i] for i in second], others).items():
            _bild_group(cases, [second[m] for m in members], alternatives, key[-1], key[-2])
        for i in second:
            usable = alternatives[i]["converged"]
            results[i].update(other_chord=alternatives[i]["chord"] if usable else None,
                              other_twist=alternatives[i]["twist"] if usable else None)
    return results


def _ideal_loading(case):
    return getattr(case, "ideal_loading", "paper")


def _other_point(section_point):
    return "local" if section_point == "reference" else "reference"


class _SetupFailure(Exception):
    """A BILD model that cannot be set up: not a failure of a case, so never isolated by bisection."""


def _bild_group(cases, indices, results, section_point="reference", ideal_loading="paper"):
    """BILD for ``cases[i]`` for i in ``indices`` in one run, isolating the failing cases by bisection."""
    num_radial, num_blades, airfoil = (cases[indices[0]].inputs[k] for k in _MODEL_KEYS)

    def run(part):
        batch = [cases[i] for i in part]
        try:
            prob = bild_problem(len(batch), int(num_radial), int(num_blades), sweep_polar(airfoil),
                                section_point=section_point, ideal_loading=ideal_loading)
        except (ValueError, TypeError) as exc:
            raise _SetupFailure(exc) from exc
        _set_bild_inputs(prob, batch)
        prob.run_model()
        # Copies: the cached problem is reused (and overwritten) by the next run of the same size.
        return ({name: prob.get_val(name).copy() for name in VERIFIED_METRICS + ("thrust",)},
                prob.get_val("chord", units="m").copy(), prob.get_val("twist", units="rad").copy())

    try:
        successes, failures = isolate_failures(run, indices, (om.AnalysisError, ValueError, ArithmeticError))
    except _SetupFailure as exc:
        raise CaseSetupError(f"the BILD model ({bild_setting(section_point, ideal_loading)}) cannot be set up for "
                             f"{num_blades} blades, {num_radial} stations and airfoil {airfoil!r}: {exc.__cause__}"
                             ) from exc.__cause__
    for i, exc in failures:
        results[i] = {"converged": False, "error": f"BILD failed: {' '.join(str(exc).split())}"}
    for part, (values, chord, twist) in successes:
        for k, i in enumerate(part):
            row = {name: float(values[name][k]) for name in VERIFIED_METRICS}
            finite = all(np.isfinite(v) for v in row.values()) and np.all(np.isfinite(chord[k]))
            row.update(chord=chord[k].copy(), twist=twist[k].copy(), thrust=float(values["thrust"][k]),
                       converged=bool(finite))
            if not finite:
                row["error"] = "BILD returned non-finite values"
            results[i] = row


def time_single_bild_design(case, repeats=20):
    """Wall time of one BILD design (``num_nodes = 1``), model run only, best of ``repeats``.

    Parameters
    ----------
    case : Case
        A sweep case.
    repeats : int
        Number of timed runs.

    Returns
    -------
    float
        Seconds per ``run_model`` of a set-up single-design problem.
    """
    inputs = case.inputs
    prob = bild_problem(1, int(inputs["num_radial"]), int(inputs["num_blades"]), sweep_polar(inputs["airfoil"]),
                        section_point=getattr(case, "section_point", "reference"), ideal_loading=_ideal_loading(case))
    _set_bild_inputs(prob, [case])
    prob.run_model()
    best = np.inf
    for _ in range(repeats):
        start = time.perf_counter()
        prob.run_model()
        best = min(best, time.perf_counter() - start)
    return best


def _configuration(inputs):
    """What one optimisation problem serves: stations, blades, airfoil and rotor type (a turbine case says so)."""
    return (int(inputs["num_radial"]), int(inputs["num_blades"]), inputs["airfoil"],
            inputs.get("rotor_type", "propeller"))


def _cached_problem(inputs, optimizer, parameterization, tol):
    num_radial, num_blades, airfoil, rotor_type = _configuration(inputs)
    key = (optimizer, parameterization, tol, num_radial, num_blades, airfoil, rotor_type)
    prob = _PROBLEMS.get(key)
    if prob is None:
        prob = build_optimization_problem(optimizer=optimizer, parameterization=parameterization, tol=tol,
                                          num_radial=num_radial, num_blades=num_blades, polar=sweep_polar(airfoil),
                                          rotor_type=rotor_type)
        _PROBLEMS[key] = prob
    return prob


def optimize_case(case, bild_result, optimizer=None, initial="bild", parameterization="stations", tol=None,
                  restarts=1):
    """BEM optimisation of one sweep case with BILD's thrust as the constraint (paper Sec. 5.1).

    Parameters
    ----------
    case : Case
        The sweep case.
    bild_result : dict
        This case's entry of :func:`bild_batch` (``thrust``, ``chord``, ``twist``).
    optimizer : {'slsqp', 'ipopt', 'snopt'}, optional
        Default ``case.optimizer``.
    initial : {'bild', 'linear'}
        Warm start from the BILD geometry or the linear cold start.
    parameterization : {'stations', 'bspline'}
        Design variables per station (paper) or B-spline control points.
    tol : float, optional
        Optimiser tolerance (default of :func:`~bild_mdo.optimization.problem.build_optimization_problem`).
    restarts : int
        Restarts from where a failed run stopped (see
        :func:`~bild_mdo.optimization.run.optimize_rotor`).

    Returns
    -------
    dict
        The keys of :data:`~bild_mdo.verification.store.RESULT_KEYS` at the
        optimum, ``converged``, ``status`` and ``iterations``; with
        ``case.starts > 1`` the best of the starts (:func:`optimize_cases`).

    Raises
    ------
    ImportError
        If the optimiser's package is missing.
    CaseSetupError
        If the optimisation problem cannot be set up; the runner does not
        store such a case, so a rerun retries it.  The run time
        is left to the runner (wall time of this call, including the one-off
        problem set-up of a worker's first case).
    """
    if getattr(case, "starts", 1) > 1:
        result = optimize_cases([(case, bild_result)], optimizer, initial, parameterization, tol, restarts)[0]
        if isinstance(result, Exception):
            raise result
        return result
    inputs = case.inputs
    optimizer = case.optimizer if optimizer is None else optimizer
    try:
        prob = _cached_problem(inputs, optimizer, parameterization, tol)
    except ImportError:
        raise
    except Exception as exc:  # any failure to build the model is a set-up error, not a result of this case
        raise CaseSetupError(f"the BEM optimisation problem cannot be set up: {type(exc).__name__}: {exc}") from exc
    result = optimize_rotor(inputs["v_axial"], inputs["rpm"], inputs["radius"], inputs["hub_radius"],
                            bild_result["thrust"], inputs["altitude"], problem=prob, restarts=restarts, initial=initial,
                            bild_chord=bild_result.get("chord"), bild_twist=bild_result.get("twist"),
                            reference_chord=inputs["reference_chord"])
    return optimum_row(result)


def optimum_row(result):
    """The store's quantities of one optimisation result (:data:`~bild_mdo.bem.metrics.VERIFIED_METRICS`, the
    geometry, convergence, status, iterations)."""
    row = {name: result.performance[name] for name in VERIFIED_METRICS}
    row.update(chord=result.chord, twist=result.twist, converged=result.converged, status=result.status,
               iterations=result.iterations)
    return row


def optimize_cases(payloads, optimizer=None, initial="bild", parameterization="stations", tol=None, restarts=1):
    """BEM optimisations of a chunk of sweep cases in lockstep: :func:`optimize_case` for many cases at once.

    Cases of one configuration (optimiser, stations, blades, airfoil) share
    one lockstep run (:func:`~bild_mdo.optimization.run.optimize_rotors`);
    every case gets the result it gets alone.  A case with ``starts > 1``
    is optimised again from each further start of
    :data:`~bild_mdo.verification.cases.START_KINDS` (the other section
    point's BILD design, the linear cold start; one lockstep run per start),
    and its row is the best of them with the spread between them
    (:func:`~bild_mdo.verification.starts.combine_starts`).

    Parameters
    ----------
    payloads : list of (Case, dict)
        Each case with its entry of :func:`bild_batch`.
    optimizer, initial, parameterization, tol, restarts
        See :func:`optimize_case`.

    Returns
    -------
    list of dict or Exception
        Per case, in order: the row of :func:`optimize_case`, or the exception
        that case raised (a :class:`CaseSetupError` when its problem cannot
        be set up).  ``run_time`` is left to the caller.

    Raises
    ------
    ImportError
        If the optimiser's package is missing.
    """
    first = optimize_start(payloads, optimizer, initial, parameterization, tol, restarts)
    runs = [first]
    for number, kind in enumerate(START_KINDS[1:], start=2):
        chosen = [k for k, (case, bild) in enumerate(payloads) if getattr(case, "starts", 1) >= number
                  and (kind != "other_bild" or bild.get("other_chord") is not None)]
        run = [None] * len(payloads)
        if chosen:
            part = [(payloads[k][0], dict(payloads[k][1], chord=payloads[k][1]["other_chord"],
                                          twist=payloads[k][1]["other_twist"]) if kind == "other_bild"
                     else payloads[k][1]) for k in chosen]
            for k, result in zip(chosen, optimize_start(part, optimizer, "linear" if kind == "linear" else "bild",
                                                         parameterization, tol, restarts)):
                run[k] = result
        runs.append(run)
    return [combine_starts([run[k] for run in runs]) if getattr(case, "starts", 1) > 1 else first[k]
            for k, (case, _bild) in enumerate(payloads)]


def optimize_start(payloads, optimizer, initial, parameterization="stations", tol=None, restarts=1):
    """One start (``initial`` 'bild' or 'linear') of every case: a lockstep run per configuration; per case the row
    of :func:`optimum_row` or the exception it raised (:func:`optimize_cases`, and the turbine sweep's)."""
    out = [None] * len(payloads)
    groups = {}
    for k, (case, _bild) in enumerate(payloads):
        chosen = case.optimizer if optimizer is None else optimizer
        groups.setdefault((chosen,) + _configuration(case.inputs), []).append(k)
    for (chosen, *_), members in groups.items():
        try:
            prob = _cached_problem(payloads[members[0]][0].inputs, chosen, parameterization, tol)
        except ImportError:
            raise
        except Exception as exc:  # any failure to build the model is a set-up error, not a result of the cases
            error = CaseSetupError(f"the BEM optimisation problem cannot be set up: {type(exc).__name__}: {exc}")
            for k in members:
                out[k] = error
            continue
        _optimize_group(prob, [payloads[k] for k in members], members, out, initial, restarts)
    return out


def _optimize_group(prob, payloads, members, out, initial, restarts):
    columns = {key: np.array([case.inputs[key] for case, _ in payloads], dtype=float)
               for key in ("v_axial", "rpm", "radius", "hub_radius", "altitude")}
    # A turbine case has no reference chord (its cold start takes Betz-Schmitz's chord).
    chords = [case.inputs.get("reference_chord") for case, _ in payloads]
    columns["reference_chord"] = None if any(c is None for c in chords) else np.array(chords, dtype=float)
    thrust = np.array([bild["thrust"] for _, bild in payloads], dtype=float)
    geometry = {}
    if initial == "bild":
        geometry = {key: np.array([bild[key] for _, bild in payloads], dtype=float) for key in ("chord", "twist")}
    try:
        results = optimize_rotors(columns["v_axial"], columns["rpm"], columns["radius"], columns["hub_radius"],
                                  thrust, columns["altitude"], problem=prob, restarts=restarts, initial=initial,
                                  bild_chord=geometry.get("chord"), bild_twist=geometry.get("twist"),
                                  reference_chord=columns["reference_chord"])
    except ValueError:
        if len(payloads) == 1:
            raise
        # A case the optimisation rejects (inconsistent inputs): every case alone, so only that one fails.
        for k, payload in zip(members, payloads):
            try:
                _optimize_group(prob, [payload], [k], out, initial, restarts)
            except Exception as exc:  # the case's own error, reported in its row
                out[k] = exc
        return
    for k, result in zip(members, results):
        out[k] = optimum_row(result)
