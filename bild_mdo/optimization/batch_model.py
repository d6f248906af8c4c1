"""Many optimisation cases evaluated in one vectorised BEM model: one row per case.

:class:`ModelPool` holds set-up problems of one configuration (stations,
blades, polar, parameterisation) at sizes 1, 2, 4, ... and evaluates any
list of cases at their design values in the smallest that fits, padding
the spare rows with copies of the first case.  A gradient request costs one
``compute_totals`` of the sums over the rows of the objective and the thrust
constraint (:class:`~bild_mdo.optimization.responses.ResponseSumsComp`): two
reverse linear solves for the whole batch, since the cases do not interact.
A batch that raises is split (:func:`~bild_mdo.utils.batches.isolate_failures`)
so that only the failing cases get the error.
"""
from __future__ import annotations

import dataclasses
import itertools
import time

import numpy as np
import openmdao.api as om

from bild_mdo.bem.metrics import PERFORMANCE_OUTPUTS
from bild_mdo.optimization.bem_optimization_group import BEMOptimizationGroup
from bild_mdo.optimization.responses import ResponseSumsComp
from bild_mdo.utils.batches import isolate_failures

#: Per-case inputs of the optimisation model and their units.
CASE_INPUTS = (("v_axial", "m/s"), ("rpm", "rpm"), ("radius", "m"), ("hub_radius", "m"), ("altitude", "m"),
               ("thrust_target", "N"), ("energy_loss_ref", "W"))

#: Errors of one case's analysis that must not fail the other cases of its batch.
CASE_ERRORS = (om.AnalysisError, ValueError, ArithmeticError)

_RESPONSES = ("energy_loss_ratio", "thrust_residual")
# Identifies a CaseSpec for as long as the process runs (an id() can be reused).
_SERIALS = itertools.count()
_DESIGN_VARIABLES = ("chord_ratio_cp", "twist_cp")


@dataclasses.dataclass
class CaseSpec:
    """One case of a lockstep optimisation: operating point, initial design values and bounds.

    Attributes
    ----------
    inputs : dict
        Name -> float for every entry of :data:`CASE_INPUTS` (model units listed there).
    chord_ratio_cp, twist_cp : ndarray, shape (ncp,)
        Initial design values (c/R, rad), within the bounds.
    twist_bounds : tuple of ndarray
        Lower and upper twist bounds of the design values (rad).
    """

    inputs: dict
    chord_ratio_cp: np.ndarray
    twist_cp: np.ndarray
    twist_bounds: tuple
    serial: int = dataclasses.field(default_factory=lambda: next(_SERIALS), repr=False, compare=False)


@dataclasses.dataclass
class Evaluation:
    """The model's answer for one case at one design.

    Attributes
    ----------
    energy_loss_ratio, thrust_residual : float
        Objective ``E/E_ref`` and constraint ``T/T* - 1``.
    performance : dict
        Name -> float for every entry of :data:`~bild_mdo.bem.metrics.PERFORMANCE_OUTPUTS`.
    chord, twist : ndarray, shape (nr,)
        Geometry at the stations (m, rad).
    flow_state : ndarray of int, shape (nr,)
        Flow-state codes of the stations.
    grad_energy, grad_thrust : ndarray, shape (2 ncp,) or None
        Gradients of the two responses in model units (chord entries, then
        twist entries); None when not requested.
    phi : ndarray, shape (nr,) or None
        Inflow angles (rad): the warm start of the case's next evaluation.
    """

    energy_loss_ratio: float
    thrust_residual: float
    performance: dict
    chord: np.ndarray
    twist: np.ndarray
    flow_state: np.ndarray
    grad_energy: np.ndarray = None
    grad_thrust: np.ndarray = None
    phi: np.ndarray = None


def build_batch_problem(num_nodes, meta):
    """A set-up problem of ``num_nodes`` cases with the configuration of ``meta`` and the response sums.

    Parameters
    ----------
    num_nodes : int
        Cases (rows).
    meta : dict
        ``prob._bild_optimization`` of a problem from
        :func:`~bild_mdo.optimization.problem.build_optimization_problem`.

    Returns
    -------
    om.Problem
        No driver; set up in reverse mode.
    """
    prob = om.Problem(reports=False)
    group = BEMOptimizationGroup(num_nodes=num_nodes, num_radial=meta["num_radial"], num_blades=meta["num_blades"],
                                 polar=meta["polar"], loss_model=meta["loss_model"],
                                 parameterization=meta["parameterization"], num_cp=meta["num_cp"], order=meta["order"])
    prob.model.add_subsystem("rotor", group, promotes=["*"])
    prob.model.add_subsystem("sums", ResponseSumsComp(num_nodes=num_nodes), promotes=["*"])
    if meta.get("approx_totals") is not None:
        prob.model.approx_totals(method=meta["approx_totals"])
    prob.setup(mode="rev")
    prob.final_setup()
    return prob


class BatchModel:
    """One set-up problem and the evaluation of up to ``size`` cases on it, one per row.

    Parameters
    ----------
    prob : om.Problem
        From :func:`build_batch_problem`, or (size 1) from
        :func:`~bild_mdo.optimization.problem.build_optimization_problem`.
    """

    def __init__(self, prob):
        self.prob = prob
        self.size = int(prob.model.rotor.options["num_nodes"])
        self._state = None
        inflow = prob.model.rotor.bem.inflow
        # The warm start is per case, not per row: a row's previous solve may be another case's.
        self._inflow = inflow if inflow.options["warm_start"] else None
        summed = getattr(prob.model, "sums", None) is not None
        self._of = [f"{r}_sum" for r in _RESPONSES] if summed else list(_RESPONSES)
        if self.size > 1 and not summed:
            raise ValueError("a batch problem of several cases needs the response sums (build_batch_problem)")

    def evaluate(self, specs, x_chord, x_twist, gradients, previous_phi=None):
        """Run the model for ``specs`` at design values ``x_chord``, ``x_twist`` (rows), optionally with gradients.

        Parameters
        ----------
        specs : list of CaseSpec
            At most ``size``.
        x_chord, x_twist : ndarray, shape (len(specs), ncp)
            Design values (model units).
        gradients : bool
            Whether to compute the gradients too.
        previous_phi : ndarray, shape (len(specs), nr), optional
            Each case's inflow angles at its previous evaluation, the warm
            start of its inflow solve (NaN rows: a cold solve).  With the same
            previous angles a case gets the same answer in any batch.

        Returns
        -------
        list of Evaluation
        """
        count, prob = len(specs), self.prob
        pad = np.concatenate([np.arange(count), np.zeros(self.size - count, dtype=int)])
        x_chord, x_twist = np.asarray(x_chord)[pad], np.asarray(x_twist)[pad]
        state = (tuple(specs[i].serial for i in pad), x_chord.tobytes(), x_twist.tobytes())
        # A gradient at the point just evaluated (what SLSQP asks for next) needs no second model run.
        if state != self._state:
            self._state = None
            for name, units in CASE_INPUTS:
                prob.set_val(name, np.array([specs[i].inputs[name] for i in pad]), units=units)
            prob.set_val("chord_ratio_cp", x_chord)
            prob.set_val("twist_cp", x_twist, units="rad")
            if self._inflow is not None:
                nr = prob.model.rotor.options["num_radial"]
                previous = np.full((count, nr), np.nan) if previous_phi is None else np.asarray(previous_phi)
                # InflowComp keeps its previous solve here (bild_mdo.bem.inflow, option warm_start).
                self._inflow._previous_phi = previous[pad].ravel().copy()
            prob.run_model()
            self._state = state
        objective = prob.get_val("energy_loss_ratio")
        residual = prob.get_val("thrust_residual")
        performance = {name: prob.get_val(name) for name in PERFORMANCE_OUTPUTS}
        chord, twist = prob.get_val("chord", units="m"), prob.get_val("twist", units="rad")
        flow_state = np.rint(np.real(prob.get_val("bem.flow_state"))).astype(int)
        phi = np.real(prob.get_val("bem.phi", units="rad"))
        grads = [None] * 2
        if gradients:
            jac = prob.compute_totals(of=self._of, wrt=list(_DESIGN_VARIABLES), return_format="array",
                                      driver_scaling=False)
            half = jac.shape[1] // 2
            grads = [np.concatenate([row[:half].reshape(self.size, -1), row[half:].reshape(self.size, -1)], axis=1)
                     for row in jac]
        return [Evaluation(float(objective[k]), float(residual[k]), {n: float(v[k]) for n, v in performance.items()},
                           chord[k].copy(), twist[k].copy(), flow_state[k].copy(),
                           None if grads[0] is None else grads[0][k].copy(),
                           None if grads[1] is None else grads[1][k].copy(), phi[k].copy())
                for k in range(count)]


class ModelPool:
    """Batch models of one configuration at sizes 1, 2, 4, ..., set up on first use.

    Parameters
    ----------
    meta : dict
        ``prob._bild_optimization`` of the configuration.
    base : om.Problem, optional
        A single-case problem of this configuration to use as the size-1 model.
    """

    def __init__(self, meta, base=None):
        self.meta = meta
        self._models = {} if base is None else {1: BatchModel(base)}
        self.setup_time = 0.0

    def model(self, count):
        """The smallest model of at least ``count`` rows (a power of two)."""
        size = 1 << max(0, int(count) - 1).bit_length()
        model = self._models.get(size)
        if model is None:
            start = time.perf_counter()
            model = self._models[size] = BatchModel(build_batch_problem(size, self.meta))
            self.setup_time += time.perf_counter() - start
        return model

    def evaluate(self, specs, x_chord, x_twist, gradients, previous_phi):
        """Evaluate every case; a case whose analysis raises gets its exception instead of an Evaluation.

        Parameters
        ----------
        specs, x_chord, x_twist, gradients, previous_phi
            See :meth:`BatchModel.evaluate`; any number of cases (``previous_phi`` required).

        Returns
        -------
        list of Evaluation or Exception
        """
        x_chord, x_twist, previous_phi = np.asarray(x_chord), np.asarray(x_twist), np.asarray(previous_phi)

        def run(part):
            return self.model(part.size).evaluate([specs[i] for i in part], x_chord[part], x_twist[part], gradients,
                                                  previous_phi[part])

        successes, failures = isolate_failures(run, np.arange(len(specs)), CASE_ERRORS)
        out = [None] * len(specs)
        for part, evaluations in successes:
            for i, evaluation in zip(part, evaluations):
                out[i] = evaluation
        for i, exc in failures:
            out[i] = exc
        return out
