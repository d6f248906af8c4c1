"""OpenMDAO driver that runs Ipopt through cyipopt, for installations without pyOptSparse.

Ipopt (Waechter & Biegler, Math. Program. 106(1), 2006) is an interior-point
method for large sparse nonlinear programs

    min f(x)  s.t.  g_L <= g(x) <= g_U,  x_L <= x <= x_U.

The driver hands Ipopt the problem in OpenMDAO's driver scaling (ref/ref0 or
scaler/adder applied to design variables, objective and constraints), the
constraint Jacobian in coordinate (COO) form with the sparsity OpenMDAO knows
(total coloring if declared, otherwise the variable blocks that the relevance
graph connects), and no Hessian: Ipopt builds a limited-memory quasi-Newton
approximation of it, here from as many past steps as there are design values
(up to :data:`MAX_QUASI_NEWTON_HISTORY`), where Ipopt keeps 6 by default.  The bounds, the Jacobian pattern and the callback
object cyipopt calls are built in :mod:`bild_mdo.optimization.ipopt_problem`.
Importing this module does not need cyipopt; making a driver does.
"""
import sys

import numpy as np
import openmdao.api as om
from openmdao.core.driver import Driver, RecordingDebugging

from bild_mdo.optimization.ipopt_problem import (IPOPT_STATUS_NAMES, SUCCESS_STATUSES, IpoptCallbacks,
                                                 constraint_bounds, design_var_bounds, import_cyipopt,
                                                 nonlinear_jacobian_pattern, voi_size)

#: Most past steps the quasi-Newton Hessian keeps (Ipopt ``limited_memory_max_history``): the default
#: is the number of design values up to this, i.e. full-memory BFGS for small problems.  Ipopt's own
#: default of 6 left the rotor optimisation (60 design values) hundreds of iterations longer: on the
#: hardest verification cases 570 -> 153 and 669 -> 553 iterations.
MAX_QUASI_NEWTON_HISTORY = 100


class IpoptDriver(Driver):
    """OpenMDAO driver for the Ipopt interior-point optimizer (via cyipopt).

    Supports one scalar objective, equality and (double-sided) inequality
    constraints, linear constraints (Jacobian computed once), vector design
    variables with bounds, OpenMDAO's driver scaling and total-derivative
    coloring (``declare_coloring``).  Ipopt runs with
    ``hessian_approximation='limited-memory'`` and, unless ``opt_settings``
    says otherwise, ``limited_memory_max_history`` equal to the number of
    design values (at most :data:`MAX_QUASI_NEWTON_HISTORY`).

    An ``om.AnalysisError`` raised by the model at a trial point is reported to
    Ipopt as a failed evaluation, so Ipopt cuts the step and tries again.  One
    raised while computing derivatives stops Ipopt (status -13,
    Invalid_Number_Detected), and one at the starting point propagates.  Any
    other exception is re-raised by ``run_driver`` once Ipopt has stopped.

    Parameters
    ----------
    **kwargs : dict
        Driver options, e.g. ``IpoptDriver(maxiter=200, tol=1e-8)``.

    Options
    -------
    maxiter : int
        Maximum number of Ipopt iterations (Ipopt ``max_iter``).
    tol : float
        Ipopt's relative convergence tolerance on the scaled NLP error (``tol``).
    print_level : int
        Ipopt console verbosity, 0 (silent) to 12 (``print_level``).
    disp : bool
        Print a one-line summary of the outcome after the run.

    Attributes
    ----------
    opt_settings : dict
        Ipopt options by name (``{'mu_strategy': 'adaptive', 'max_iter': 500}``),
        passed to Ipopt verbatim after the driver options, so they take
        precedence.  Numeric Ipopt options must be given as ``float`` and
        integer ones as ``int``.
    fail : bool
        True if the most recent run did not converge.
    ipopt_status : int or None
        Ipopt's return status of the most recent run (0 solved, 1 solved to the
        acceptable level, 2 infeasible, -1 iteration limit, ...).
    ipopt_status_name : str
        Name of that status (``'Solve_Succeeded'``, ...).
    ipopt_message : str
        Ipopt's explanation of that status.
    ipopt_iterations : int
        Number of Ipopt iterations of the most recent run (``iter_count`` is the
        number of model evaluations, as in the other OpenMDAO drivers).
    ipopt_info : dict or None
        cyipopt's result dictionary: ``x``, ``g`` and ``obj_val`` in driver
        scaling, multipliers ``mult_g``, ``mult_x_L``, ``mult_x_U``, ``status``,
        ``status_msg``.

    After ``prob.run_driver()``, ``prob.driver.result`` (an OpenMDAO
    ``DriverResult``) carries ``success`` and the same ``ipopt_status``,
    ``ipopt_status_name``, ``ipopt_message`` and ``ipopt_iterations``.
    """

    def __init__(self, **kwargs):
        self._cyipopt = import_cyipopt()
        super().__init__(**kwargs)

        self.supports["optimization"] = True
        self.supports["inequality_constraints"] = True
        self.supports["equality_constraints"] = True
        self.supports["two_sided_constraints"] = True
        self.supports["linear_constraints"] = True
        self.supports["simultaneous_derivatives"] = True
        self.supports["gradients"] = True
        self.supports["multiple_objectives"] = False
        self.supports["active_set"] = False
        self.supports["integer_design_vars"] = False
        self.supports["distributed_design_vars"] = False
        self.supports._read_only = True

        self.opt_settings = {}
        self._total_jac_format = "array"
        self._reset_run_state()
        self.fail = False

    def _declare_options(self):
        self.options.declare("maxiter", default=1000, types=int, lower=0,
                             desc="Maximum number of Ipopt iterations (Ipopt option max_iter).")
        self.options.declare("tol", default=1.0e-8, types=float, lower=0.0,
                             desc="Ipopt convergence tolerance on the scaled NLP error "
                                  "(Ipopt option tol).")
        self.options.declare("print_level", default=0, types=int, lower=0, upper=12,
                             desc="Ipopt console output level, 0 (silent) to 12 "
                                  "(Ipopt option print_level).")
        self.options.declare("disp", default=True, types=bool,
                             desc="Print a short summary of the optimization outcome after the run.")

    def _get_name(self):
        return "IpoptDriver"

    def _reset_run_state(self):
        """Forget the outcome and the evaluation caches of the previous run."""
        self.fail = True
        self.ipopt_status = None
        self.ipopt_status_name = "NOT_RUN"
        self.ipopt_message = ""
        self.ipopt_iterations = 0
        self.ipopt_info = None
        # Model evaluation cache: the design point the model holds, its responses and their Jacobian.
        self._x_model = self._f_cache = self._g_cache = self._x_jac = self._jac_cache = None
        self._eval_failed = False
        # Constraint Jacobian layout (COO), set at the start of a run.
        self._lin_jac_vals = self._jac_rows = self._jac_cols = self._nl_jac_rows = self._nl_jac_cols = None
        self._nl_responses, self._nl_names, self._lin_names = [], [], []

    def _setup_driver(self, problem):
        super()._setup_driver(problem)
        if len(self._objs) > 1:
            raise RuntimeError(f"{self.msginfo} supports a single objective, "
                               f"got {list(self._objs)}.")
        for name, meta in self._objs.items():
            if meta["size"] != 1:
                raise RuntimeError(f"{self.msginfo}: objective '{name}' must be a scalar, "
                                   f"it has size {meta['size']}.")

    def run(self):
        """Optimize the model with Ipopt.

        Returns
        -------
        bool
            Failure flag (OpenMDAO's driver convention): True if Ipopt did not
            converge, False on success.  ``prob.run_driver()`` turns it into
            ``DriverResult.success``.
        """
        self.result.reset()
        problem = self._problem()
        model = problem.model
        self.iter_count = 0
        self._total_jac = None
        self._total_jac_linear = None
        self._reset_run_state()

        self._ipopt_settings(0)  # checks the settings before the first model run
        self._check_for_missing_objective()
        self._check_for_invalid_desvar_values()

        with RecordingDebugging(self._get_name(), self.iter_count, self):
            with model._relevance.nonlinear_active("iter"):
                self._run_solve_nonlinear()
            self.iter_count += 1

        desvar_vals = self.get_design_var_values()
        x0 = np.concatenate([np.atleast_1d(desvar_vals[name]).ravel() for name in self._designvars])
        if x0.size == 0:
            raise RuntimeError(f"{self.msginfo}: the problem has no design variables.")
        # Rows of the nonlinear total Jacobian in the order OpenMDAO's coloring uses.
        self._nl_responses = self._get_ordered_nl_responses()
        self._nl_names = [name for name in self._nl_responses if name in self._cons]
        self._lin_names = [name for name, meta in self._cons.items() if meta["linear"]]
        self._x_model = x0.copy()
        self._cache_responses()
        settings = self._ipopt_settings(x0.size)

        x_lower, x_upper = design_var_bounds(self)
        # Nonlinear constraints first, then linear ones, as in the Jacobian.
        g_lower, g_upper = constraint_bounds(self, self._nl_names + self._lin_names)

        if self._lin_names:
            # Linear constraints have a constant Jacobian: one total-derivative solve for the run.
            lin_jac = self._compute_totals(of=self._lin_names, wrt=list(self._designvars),
                                           return_format="array")
        else:
            lin_jac = np.zeros((0, x0.size))

        coloring = problem.get_total_coloring(self._coloring_info, run_model=False)
        self._build_jacobian_structure(coloring, lin_jac)

        cyipopt = self._cyipopt
        nlp = cyipopt.Problem(n=x0.size, m=g_lower.size, problem_obj=IpoptCallbacks(self),
                              lb=x_lower, ub=x_upper, cl=g_lower, cu=g_upper)
        for key, value in settings.items():
            nlp.add_option(key, value)

        self._exc_info = None
        try:
            x_opt, info = nlp.solve(x0)
        finally:
            nlp.close()
        if self._exc_info is not None:
            self._reraise()

        # Leave the model at Ipopt's answer even if its last trial point was elsewhere.
        if self._x_model is None or not np.array_equal(x_opt, self._x_model) or self._eval_failed:
            self._run_at(x_opt)

        status = int(info["status"])
        message = info["status_msg"]
        self.ipopt_info = info
        self.ipopt_status = status
        self.ipopt_status_name = IPOPT_STATUS_NAMES.get(status, "Unknown_Status")
        self.ipopt_message = message.decode() if isinstance(message, bytes) else str(message)
        self.fail = status not in SUCCESS_STATUSES

        if self.options["disp"] and problem.comm.rank == 0:
            outcome = "FAILED" if self.fail else "Complete"
            print(f"Optimization {outcome} (Ipopt status {status}, {self.ipopt_status_name}, "
                  f"{self.ipopt_iterations} iterations, {self.iter_count} model evaluations)")
            if self.fail:
                print(self.ipopt_message)
            print("-" * 35)

        return self.fail

    def _update_result(self, result):
        result.ipopt_status = self.ipopt_status
        result.ipopt_status_name = self.ipopt_status_name
        result.ipopt_message = self.ipopt_message
        result.ipopt_iterations = self.ipopt_iterations

    def _ipopt_settings(self, num_design_values):
        settings = {
            "max_iter": int(self.options["maxiter"]),
            "tol": float(self.options["tol"]),
            "print_level": int(self.options["print_level"]),
            "sb": "yes",
            "hessian_approximation": "limited-memory",
            "limited_memory_max_history": int(min(max(num_design_values, 6), MAX_QUASI_NEWTON_HISTORY)),
        }
        settings.update(self.opt_settings)
        if settings["hessian_approximation"] != "limited-memory":
            raise ValueError(f"{self.msginfo} provides no exact Hessian; opt_settings"
                             "['hessian_approximation'] must be 'limited-memory', got "
                             f"{settings['hessian_approximation']!r}.")
        return settings

    def _build_jacobian_structure(self, coloring, lin_jac):
        """COO pattern of dg/dx: rows of nonlinear constraints, then rows of linear ones."""
        self._nl_jac_rows, self._nl_jac_cols = nonlinear_jacobian_pattern(self, self._nl_names, coloring)
        lin_r, lin_c = np.nonzero(lin_jac)
        self._lin_jac_vals = lin_jac[lin_r, lin_c]
        row_offset = sum(voi_size(self._cons[name]) for name in self._nl_names)
        self._jac_rows = np.concatenate([self._nl_jac_rows, lin_r + row_offset])
        self._jac_cols = np.concatenate([self._nl_jac_cols, lin_c])

    def _cache_responses(self):
        obj = next(iter(self.get_objective_values().values()))
        self._f_cache = float(np.asarray(obj).ravel()[0])
        cons = self.get_constraint_values()
        self._g_cache = np.concatenate(
            [np.zeros(0)] + [np.asarray(cons[name], dtype=float).ravel()
                             for name in self._nl_names + self._lin_names])

    def _run_at(self, x):
        """Run the model at driver-scaled design point ``x``; return False on an AnalysisError."""
        model = self._problem().model
        dv_vec = self._vectors["design_var"]
        dv_vec.set_data(x, driver_scaling=True)
        self._set_design_vars(driver_scaling=True)

        failed = False
        with RecordingDebugging(self._get_name(), self.iter_count, self):
            self.iter_count += 1
            try:
                with model._relevance.nonlinear_active("iter"):
                    self._run_solve_nonlinear()
            except om.AnalysisError:
                model._clear_iprint()
                failed = True
            except Exception:
                # cyipopt re-raises this after Ipopt stops; until then no more model runs.
                self._exc_info = sys.exc_info()
                raise

        self._x_model = np.array(x, dtype=float)
        self._eval_failed = failed
        if not failed:
            self._cache_responses()
        return not failed

    def _evaluate(self, x):
        """Make sure the model holds ``x``; raise Ipopt's evaluation error if it failed there."""
        if self._exc_info is not None:
            raise self._cyipopt.CyIpoptEvaluationError()
        if self._x_model is None or not np.array_equal(x, self._x_model):
            self._run_at(x)
        if self._eval_failed:
            raise self._cyipopt.CyIpoptEvaluationError()

    def _objective(self, x):
        self._evaluate(x)
        return self._f_cache

    def _constraints(self, x):
        self._evaluate(x)
        return self._g_cache.copy()

    def _total_jacobian(self, x):
        self._evaluate(x)
        if self._x_jac is None or not np.array_equal(x, self._x_jac):
            try:
                self._jac_cache = self._compute_totals(of=self._nl_responses,
                                                       wrt=list(self._designvars),
                                                       return_format="array")
            except om.AnalysisError:
                self._problem().model._clear_iprint()
                raise self._cyipopt.CyIpoptEvaluationError() from None
            except Exception:
                self._exc_info = sys.exc_info()
                raise
            self._x_jac = np.array(x, dtype=float)
        return self._jac_cache

    def _gradient(self, x):
        return self._total_jacobian(x)[0].copy()

    def _jacobian(self, x):
        jac = self._total_jacobian(x)
        nl_vals = jac[1:][self._nl_jac_rows, self._nl_jac_cols]
        return np.concatenate([nl_vals, self._lin_jac_vals])

    def _jacobian_structure(self):
        return self._jac_rows, self._jac_cols

    def _intermediate(self, iter_count):
        self.ipopt_iterations = int(iter_count)
