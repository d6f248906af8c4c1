"""SLSQP optimisations of many cases in lockstep, through one vectorised model evaluation per step.

Every case runs its own, unmodified ``scipy.optimize.minimize(method='SLSQP')``
in its own thread.  Its objective, constraint and gradient callbacks post a
request (design values, gradients wanted) and block; when every live case
has posted its next request (or finished), the coordinator, in the calling
thread, evaluates all of them at once in one batch model
(:class:`~bild_mdo.optimization.batch_model.ModelPool`): one ``run_model``
and one ``compute_totals`` of the summed responses, two reverse solves for
the whole batch.  Each case thus keeps its own optimiser state, scaling,
bounds, iteration count and stopping test; the batch only shares the cost
of the model.  At most ``batch_size`` cases run at a time; a finished
case's row goes to the next case waiting, and when none waits the batch
shrinks (model sizes are powers of two); a case whose analysis raises gets its own error and the
others go on (the batch is bisected, :func:`~bild_mdo.utils.batches.isolate_failures`).

A single case takes the same path (:class:`CaseRun` with the same model
rows) without threads, and asks for gradients only when SLSQP does; in
lockstep every evaluation also computes the gradients (speculatively:
SLSQP asks for them at almost every point it evaluates, and a step whose
batch needs gradients for some case costs the same for all).  The values
of a case do not depend on the other rows of its batch, so its trajectory,
iterations and optimum are those of the case alone.

Measured (2-core machine shared with other jobs, CPU times): one model
evaluation with gradients costs 14 ms for one case alone and 58 ms for 64
cases (0.9 ms per case, 15x less); 11 vs 27 ms without gradients.  In a
lockstep run of 16 cases under a profiler, 93 % of the wall time was the
batched model evaluation, so the coordinator, the thread hand-offs and the
16 SLSQP iterations themselves took 7 %.

Why threads over SciPy's public API and not SciPy's private
reverse-communication loop (``scipy.optimize._slsqplib.slsqp``, which
``_minimize_slsqp`` drives): those 7 % bound what the private loop could
save (it still runs SLSQP's own steps), against tying the package to a
SciPy internal that changed in SciPy 1.16.  Per case the outcome is the
same either way: the cases share nothing but the model evaluation.

With the inflow warm start (``BEMOptimizationGroup(warm_start=True)``)
each case starts from the angles of its own previous evaluation, whatever
row of the batch it had (:meth:`~bild_mdo.optimization.batch_model.BatchModel.evaluate`),
so its answers stay those of the case alone.
"""
from __future__ import annotations

import queue
import threading
import time

import numpy as np
import openmdao.api as om
from scipy.optimize import minimize

from bild_mdo.optimization.batch_model import Evaluation
from bild_mdo.optimization.initial_design import CHORD_RATIO_BOUNDS
from bild_mdo.optimization.result import (ANALYSIS_FAILED, RESULT_QUANTITIES, THRUST_TOLERANCE, OptimizationResult,
                                          count_invalid, invalid_flow_text)
from bild_mdo.optimization.scaling import (CHORD_RATIO_REF, TWIST_REF, hessian_diagonal_from_gradients,
                                           references_from_diagonal)

#: Cases optimised at the same time by default (see the module docstring).
DEFAULT_BATCH_SIZE = 64

# Design points remembered per case: SLSQP asks for values and gradients at its last few points only.
_CACHE_POINTS = 8

#: Relative margin of the first-order estimate of the trimmed initial design's objective
#: (:meth:`CaseRun._worse_than_trimmed_start`): an optimum less than this below the estimate (or above
#: it) has the start trimmed to compare exactly.
_TRIM_ESTIMATE_MARGIN = 1.0e-3
#: An optimum worse than the trimmed initial design by more than this (relative) is restarted from it;
#: the tolerance of the verification's optimality check (:mod:`bild_mdo.verification.optimality`).
TRIMMED_START_TOLERANCE = 1.0e-4


class _Stopped(Exception):
    """Ends a case thread whose lockstep run was abandoned (another case raised)."""


class CaseRun:
    """One case's SLSQP optimisation, with restarts, against an evaluation function.

    Worse than the start.  At a blade station in deep stall the BEM
    residual can have three roots; where two of them merge, the solved
    inflow angle jumps (levels-10 case 0, J = 0, R = 0.5 m: the root
    station's phi jumps from 23.8 to 21.1 deg for a twist change of 5e-6
    rad, and T/T* by 4.5e-4), so the objective and the thrust are
    discontinuous there.  SLSQP's line search then keeps cutting its steps
    back at such a jump, and the run can end far from the best design near
    its start: levels-10 case 1049 ended 8.4 % worse than its initial
    (BILD) design trimmed to the thrust by collective pitch.  So a converged
    optimum is compared with that trimmed start: first by a first-order
    estimate from the start's gradients (no model evaluation), and only if
    that flags it, by trimming the start (Newton steps on a uniform twist
    offset); an optimum worse than the trimmed start by more than
    :data:`TRIMMED_START_TOLERANCE` is followed by one more SLSQP run from
    the trimmed start, and the better converged optimum is kept (``status``
    says so).  A case whose runs all fail to converge (iteration limit, line
    search) gets the same last run from the trimmed start, whose result is
    kept if it converges.  The check uses only the case's own evaluations, so lockstep
    and solo runs still agree.

    Parameters
    ----------
    spec : CaseSpec
        The case (:class:`~bild_mdo.optimization.batch_model.CaseSpec`).
    evaluate : callable
        ``evaluate(x_chord, x_twist, gradients, previous_phi) -> Evaluation``
        for this case (raises the case's analysis error); ``previous_phi`` is
        the inflow angle of the case's previous evaluation (NaN: none).
    settings : dict
        ``scaling``, ``parameterization``, ``order``, ``tol``, ``maxiter``, ``restarts``, ``num_radial``.
    speculate : bool
        Ask for the gradients at every evaluation (lockstep) or only when SLSQP does (alone).
    """

    def __init__(self, spec, evaluate, settings, speculate):
        self.spec, self.settings, self.speculate = spec, settings, speculate
        self._evaluate = evaluate
        self._cache = {}
        self.evaluations = 0
        self.last = None
        # The first evaluation: the initial design (with its gradients when the scaling asked for them).
        self._start = None

    def point(self, x_chord, x_twist, gradients):
        """The case's Evaluation at these design values (model units), from the cache when there."""
        key = x_chord.tobytes() + x_twist.tobytes()
        found = self._cache.get(key)
        if found is None or (gradients and found.grad_energy is None):
            # Model evaluations at new points (a gradient at a point evaluated before is not one).
            self.evaluations += found is None
            previous = self.last.phi if self.last is not None else np.full(self.settings["num_radial"], np.nan)
            found = self._evaluate(x_chord, x_twist, gradients or self.speculate, previous)
            if len(self._cache) >= _CACHE_POINTS:
                self._cache.pop(next(iter(self._cache)))
            self._cache[key] = self.last = found
            if self._start is None:
                self._start = found
        return found

    def _gradients(self, x_chord, x_twist):
        found = self.point(x_chord, x_twist, True)
        return found.grad_energy, found.grad_thrust

    def _references(self, x_chord, x_twist):
        n = x_chord.size
        if self.settings["scaling"] != "hessian":
            return np.concatenate([np.full(n, CHORD_RATIO_REF), np.full(n, TWIST_REF)])
        diag, _ = hessian_diagonal_from_gradients(self._gradients, x_chord, x_twist,
                                                  self.settings["parameterization"], self.settings["order"])
        return np.concatenate(references_from_diagonal(diag))

    def _slsqp(self, x_chord, x_twist):
        n = x_chord.size
        ref = self._references(x_chord, x_twist)
        lower = np.concatenate([np.full(n, CHORD_RATIO_BOUNDS[0]), self.spec.twist_bounds[0]]) / ref
        upper = np.concatenate([np.full(n, CHORD_RATIO_BOUNDS[1]), self.spec.twist_bounds[1]]) / ref

        def at(scaled, gradients):
            x = scaled * ref
            return self.point(x[:n], x[n:], gradients)

        constraint = {"type": "eq", "fun": lambda s: at(s, False).thrust_residual,
                      "jac": lambda s: at(s, True).grad_thrust * ref}
        res = minimize(lambda s: at(s, False).energy_loss_ratio, np.concatenate([x_chord, x_twist]) / ref,
                       method="SLSQP", jac=lambda s: at(s, True).grad_energy * ref,
                       bounds=list(zip(lower, upper)), constraints=[constraint], tol=self.settings["tol"],
                       options={"maxiter": self.settings["maxiter"], "disp": False})
        x = res.x * ref
        return res, x[:n], x[n:]

    def _attempt(self, x_chord, x_twist):
        """One SLSQP run: success, status, iterations and the design values it ends at."""
        res, x_chord, x_twist = self._slsqp(x_chord, x_twist)
        return bool(res.success), str(res.message), int(res.nit), x_chord, x_twist

    def solve(self):
        """Optimise; ``wall_time`` and ``setup_time`` of the result are left to the caller.

        Returns
        -------
        OptimizationResult
        """
        x_chord, x_twist = self.spec.chord_ratio_cp.copy(), self.spec.twist_cp.copy()
        iterations, failures, success, final = 0, [], False, None
        for attempt in range(int(self.settings["restarts"]) + 1):
            try:
                success, status, spent, x_chord, x_twist = self._attempt(x_chord, x_twist)
                final = self.point(x_chord, x_twist, False)
            except om.AnalysisError as exc:
                success, status = False, f"{ANALYSIS_FAILED}: {exc}"
                break
            iterations += spent
            if count_invalid(final.flow_state):
                status = f"{status}; {invalid_flow_text(final.flow_state)}"
            if _converged(success, final) or attempt == int(self.settings["restarts"]):
                break
            failures.append(status)
        if failures:
            status = f"{status} (after restarts from: {'; '.join(failures)})"
        if final is not None and not _converged(success, final):
            # Every run failed (iteration limit, line search): the stalled-root cases of issue 11 are
            # chaotic in their start, so the trimmed start is a genuinely different last try.
            success, status, iterations, final = self._from_trimmed_start(success, status, iterations, final,
                                                                          failed=True)
        elif final is not None and self._worse_than_trimmed_start(final):
            success, status, iterations, final = self._from_trimmed_start(success, status, iterations, final)
        return self._result(success, status, iterations, final)

    def _from_trimmed_start(self, success, status, iterations, final, failed=False):
        """One more SLSQP run from the trimmed start if ``final`` is worse than it (or ``failed``); the better."""
        trimmed = self._trimmed_start()
        if trimmed is None:
            return success, status, iterations, final
        bound = trimmed[2].energy_loss_ratio
        if not failed and final.energy_loss_ratio <= bound * (1.0 + TRIMMED_START_TOLERANCE):
            return success, status, iterations, final
        worse = f"{100.0 * (final.energy_loss_ratio / bound - 1.0):.2f} %"
        label = "no run converged" if failed else f"{worse} worse than the trimmed start"
        try:
            again, again_status, spent, x_chord, x_twist = self._attempt(trimmed[0], trimmed[1])
            other = self.point(x_chord, x_twist, False)
        except om.AnalysisError as exc:
            return success, f"{status} ({label}; a restart from the trimmed start failed: {exc})", \
                iterations, final
        iterations += spent
        if _converged(again, other) and (failed or other.energy_loss_ratio < final.energy_loss_ratio):
            if count_invalid(other.flow_state):
                again_status = f"{again_status}; {invalid_flow_text(other.flow_state)}"
            why = f"the earlier runs ended: {status}" if failed else f"the first optimum was {worse} worse than it"
            return again, (f"{again_status} (restarted from the initial design trimmed to the thrust: "
                           f"{why})"), iterations, other
        return success, f"{status} ({label}; a restart from the trimmed start did no better)", \
            iterations, final

    def _worse_than_trimmed_start(self, final):
        """First-order test: is ``final`` worse than the initial design trimmed to the thrust by collective pitch?"""
        start = self._start
        if start is None or start.grad_energy is None:
            return True
        n = self.spec.chord_ratio_cp.size
        slope = float(np.sum(start.grad_thrust[n:]))
        if not slope * self.settings.get("pitch_slope_sign", 1.0) > 0.0:
            return True
        estimate = start.energy_loss_ratio - float(np.sum(start.grad_energy[n:])) / slope * start.thrust_residual
        return final.energy_loss_ratio > estimate * (1.0 - _TRIM_ESTIMATE_MARGIN)

    def _trimmed_start(self, steps=8):
        """The initial design trimmed to ``T = T*`` by a uniform twist offset (Newton); None if that fails."""
        x_chord, x_twist = self.spec.chord_ratio_cp.copy(), self.spec.twist_cp.copy()
        lower, upper = self.spec.twist_bounds
        for _ in range(steps):
            try:
                found = self.point(x_chord, x_twist, True)
            except om.AnalysisError:
                return None
            if abs(found.thrust_residual) <= THRUST_TOLERANCE:
                return x_chord, x_twist, found
            slope = float(np.sum(found.grad_thrust[x_chord.size:]))
            # A turbine's thrust falls with pitch (pitch_slope_sign -1); against that, the start is stalled.
            if not slope * self.settings.get("pitch_slope_sign", 1.0) > 0.0:
                return None
            x_twist = np.clip(x_twist - found.thrust_residual / slope, lower, upper)
        return None

    def _result(self, success, status, iterations, final):
        # The optimum SLSQP returns; after a failed analysis, the last design that could be analysed.
        final = final or self.last or _failed_evaluation(self.settings["num_radial"])
        invalid = count_invalid(final.flow_state)
        return OptimizationResult(
            converged=_converged(success, final), status=status, iterations=iterations,
            model_evaluations=self.evaluations, wall_time=0.0, setup_time=0.0, chord=final.chord.copy(),
            twist=final.twist.copy(), performance=dict(final.performance), thrust_error=final.thrust_residual,
            optimizer="slsqp", flow_state=final.flow_state.copy(), invalid_stations=invalid)


def _converged(success, final):
    return bool(success and abs(final.thrust_residual) <= THRUST_TOLERANCE
                and all(np.isfinite(v) for v in final.performance.values()))


def _failed_evaluation(nr):
    nan = np.full(nr, np.nan)
    return Evaluation(np.nan, np.nan, {name: np.nan for name in RESULT_QUANTITIES}, nan, nan.copy(),
                      np.zeros(nr, dtype=int), phi=nan.copy())


def optimize_in_lockstep(pool, specs, settings, batch_size=DEFAULT_BATCH_SIZE):
    """Optimise every case with SLSQP; all cases share one batched model evaluation per step.

    Parameters
    ----------
    pool : ModelPool
        Batch models of the cases' configuration (:class:`~bild_mdo.optimization.batch_model.ModelPool`).
    specs : list of CaseSpec
        The cases.
    settings : dict
        See :class:`CaseRun`.
    batch_size : int
        Cases optimised at the same time; when one finishes, the next starts.

    Returns
    -------
    list of OptimizationResult
        In the order of ``specs``; ``wall_time`` is the wall time of the whole
        run divided by the number of cases, ``setup_time`` the same share of
        the batch models set up on the way.
    """
    start, setup_before = time.perf_counter(), pool.setup_time
    if len(specs) == 1:
        spec = specs[0]

        def evaluate(x_chord, x_twist, gradients, previous_phi):
            answer = pool.evaluate([spec], x_chord[None, :], x_twist[None, :], gradients, previous_phi[None, :])[0]
            if isinstance(answer, Exception):
                raise answer
            return answer

        results = [CaseRun(spec, evaluate, settings, speculate=False).solve()]
    else:
        results = _coordinate(pool, specs, settings, max(1, int(batch_size)))
    wall, setup = time.perf_counter() - start, pool.setup_time - setup_before
    for result in results:
        result.wall_time = (wall - setup) / len(specs)
        result.setup_time = setup / len(specs)
    return results


def _case_thread(index, spec, settings, inbox):
    """Start the thread of one case; returns its reply queue."""
    replies = queue.SimpleQueue()

    def evaluate(x_chord, x_twist, gradients, previous_phi):
        inbox.put((index, "evaluate", (x_chord, x_twist, gradients, previous_phi)))
        answer = replies.get()
        if answer is _Stopped:
            raise _Stopped
        if isinstance(answer, Exception):
            raise answer
        return answer

    def body():
        try:
            result = CaseRun(spec, evaluate, settings, speculate=True).solve()
        except _Stopped:
            return
        except BaseException as exc:  # reported to the coordinator, which raises it in the calling thread
            inbox.put((index, "error", exc))
            return
        inbox.put((index, "done", result))

    threading.Thread(target=body, name=f"bild-lockstep-case-{index}", daemon=True).start()
    return replies


def _coordinate(pool, specs, settings, batch_size):
    inbox = queue.SimpleQueue()
    results = [None] * len(specs)
    waiting = list(range(len(specs)))[::-1]
    live, slots = {}, []
    try:
        while waiting or live:
            # A finished case's place goes to the next case, so the batch stays full until the last cases.
            while waiting and len(live) < batch_size:
                index = waiting.pop()
                live[index] = _case_thread(index, specs[index], settings, inbox)
            pending = {}
            while len(pending) < len(live):
                index, kind, payload = inbox.get()
                if kind == "evaluate":
                    pending[index] = payload
                    continue
                del live[index]
                if kind == "error":
                    raise payload
                results[index] = payload
            if not pending:
                continue
            slots = _assign_rows(slots, pending)
            rows = [index if index in pending else min(pending) for index in slots]
            answers = pool.evaluate([specs[i] for i in rows], *(np.array([pending[i][k] for i in rows]) for k in (0, 1)),
                                    any(p[2] for p in pending.values()), np.array([pending[i][3] for i in rows]))
            for index, answer in zip(rows, answers):
                if index in live and index in pending:
                    live[index].put(answer)
                    del pending[index]
    finally:
        for replies in live.values():
            replies.put(_Stopped)
    return results


def _assign_rows(slots, pending):
    """Rows of the batch model per case: a case keeps its row (its warm start) until the batch halves."""
    slots = [index if index in pending else None for index in slots]
    if 2 * len(pending) <= len(slots):
        slots = [index for index in slots if index is not None]
    placed = set(slots)
    for index in sorted(pending):
        if index not in placed:
            if None in slots:
                slots[slots.index(None)] = index
            else:
                slots.append(index)
    return slots
