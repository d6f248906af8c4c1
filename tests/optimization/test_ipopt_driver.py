"""Tests of IpoptDriver (Ipopt through cyipopt) on problems with known optima."""
import sys
from importlib.metadata import entry_points

import numpy as np
import openmdao.api as om
import pytest
from numpy.testing import assert_allclose

from bild_mdo.optimization.ipopt_driver import MAX_QUASI_NEWTON_HISTORY, IpoptDriver

try:
    import cyipopt  # noqa: F401
    HAVE_CYIPOPT = True
except ImportError:
    HAVE_CYIPOPT = False

needs_cyipopt = pytest.mark.skipif(not HAVE_CYIPOPT, reason="cyipopt is not installed")

# ExecComp's own partial coloring gives up on these tiny components and says so; not our concern.
pytestmark = pytest.mark.filterwarnings("ignore:.*Coloring was deactivated")


# ---------------------------------------------------------------------------------------------
# Test models
# ---------------------------------------------------------------------------------------------

def hs071_problem(driver):
    """Hock-Schittkowski problem 71: min x1 x4 (x1 + x2 + x3) + x3
    s.t. x1 x2 x3 x4 >= 25, sum x_i^2 = 40, 1 <= x_i <= 5, from x0 = (1, 5, 5, 1)."""
    prob = om.Problem(reports=False)
    model = prob.model
    model.add_subsystem("objective", om.ExecComp("f = x[0]*x[3]*(x[0] + x[1] + x[2]) + x[2]",
                                                 x=np.ones(4)), promotes=["*"])
    model.add_subsystem("product", om.ExecComp("g_prod = x[0]*x[1]*x[2]*x[3]", x=np.ones(4)),
                        promotes=["*"])
    model.add_subsystem("squares", om.ExecComp("g_sq = x[0]**2 + x[1]**2 + x[2]**2 + x[3]**2",
                                               x=np.ones(4)), promotes=["*"])
    model.add_design_var("x", lower=1.0, upper=5.0)
    model.add_objective("f")
    model.add_constraint("g_prod", lower=25.0)
    model.add_constraint("g_sq", equals=40.0)
    prob.driver = driver
    prob.setup()
    prob.set_val("x", [1.0, 5.0, 5.0, 1.0])
    return prob


def paraboloid_problem(driver, scaled):
    """min (x-3)^2 + x y + (y+4)^2 - 3  s.t.  x + y >= 0,  x <= 6.5.

    Hand derivation (KKT): with both the constraint and the bound on x active,
    x* = 6.5, y* = -6.5, f* = 12.25 - 42.25 + 6.25 - 3 = -26.75; grad f = (0.5, 1.5)
    = 1.5 * (1, 1) - 1.0 * (1, 0), so both multipliers (1.5 and 1.0) are positive.
    """
    prob = om.Problem(reports=False)
    model = prob.model
    model.add_subsystem("parab", om.ExecComp(["f = (x - 3)**2 + x*y + (y + 4)**2 - 3",
                                              "c = x + y"]), promotes=["*"])
    if scaled:
        model.add_design_var("x", lower=-50.0, upper=6.5, ref=10.0, ref0=-2.0)
        model.add_design_var("y", lower=-50.0, upper=50.0, scaler=0.25, adder=3.0)
        model.add_objective("f", ref=20.0, ref0=-30.0)
        model.add_constraint("c", lower=0.0, ref=5.0, ref0=-1.0)
    else:
        model.add_design_var("x", lower=-50.0, upper=6.5)
        model.add_design_var("y", lower=-50.0, upper=50.0)
        model.add_objective("f")
        model.add_constraint("c", lower=0.0)
    prob.driver = driver
    prob.setup()
    return prob


def rosenbrock_problem(driver, scaled):
    """min (1 - x0)^2 + 100 (x1 - x0^2)^2 from (-1.2, 1); minimum f = 0 at (1, 1)."""
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("rosen", om.ExecComp("f = (1 - x[0])**2 + 100*(x[1] - x[0]**2)**2",
                                                  x=np.ones(2)), promotes=["*"])
    if scaled:
        prob.model.add_design_var("x", lower=-5.0, upper=5.0, ref=np.array([4.0, 2.0]),
                                  ref0=np.array([-1.0, 0.5]))
        prob.model.add_objective("f", ref=50.0)
    else:
        prob.model.add_design_var("x", lower=-5.0, upper=5.0)
        prob.model.add_objective("f")
    prob.driver = driver
    prob.setup()
    prob.set_val("x", [-1.2, 1.0])
    return prob


TARGET = np.array([0.0, 0.5, 2.0, 3.0, 4.0])


class TargetDistance(om.ExplicitComponent):
    """f = sum((x - TARGET)^2)."""

    def setup(self):
        self.add_input("x", np.ones(5), desc="design vector")
        self.add_output("f", 0.0, desc="squared distance to TARGET")
        self.declare_partials("f", "x")

    def compute(self, inputs, outputs):
        outputs["f"] = np.sum((inputs["x"] - TARGET) ** 2)

    def compute_partials(self, inputs, partials):
        partials["f", "x"] = 2.0 * (inputs["x"] - TARGET)


class BandConstraints(om.ExplicitComponent):
    """g_i = x_i^2 + x_{i+1}^2 (banded Jacobian) and s = sum(x) (linear)."""

    def setup(self):
        self.add_input("x", np.ones(5), desc="design vector")
        self.add_output("g", np.ones(4), desc="sums of squares of neighbours")
        self.add_output("s", 0.0, desc="sum of the design vector")
        i = np.arange(4)
        self.declare_partials("g", "x", rows=np.r_[i, i], cols=np.r_[i, i + 1])
        self.declare_partials("s", "x", val=np.ones((1, 5)))

    def compute(self, inputs, outputs):
        x = inputs["x"]
        outputs["g"] = x[:-1] ** 2 + x[1:] ** 2
        outputs["s"] = np.sum(x)

    def compute_partials(self, inputs, partials):
        x = inputs["x"]
        partials["g", "x"] = np.r_[2.0 * x[:-1], 2.0 * x[1:]]


def vector_problem(driver, coloring=False, scaled=False):
    """min |x - TARGET|^2  s.t.  1 <= x_i^2 + x_{i+1}^2 <= 10 (i = 0..3), sum x = 8 (linear),
    0 <= x <= 3.5.  At the optimum g_0 sits on its lower and g_3 on its upper bound."""
    prob = om.Problem(reports=False)
    model = prob.model
    model.add_subsystem("objective", TargetDistance(), promotes=["*"])
    model.add_subsystem("band", BandConstraints(), promotes=["*"])
    if scaled:
        model.add_design_var("x", lower=0.0, upper=3.5, ref=2.0, ref0=-1.0)
        model.add_objective("f", ref=10.0)
        model.add_constraint("g", lower=1.0, upper=10.0, ref=4.0)
        model.add_constraint("s", equals=8.0, linear=True, ref=3.0, ref0=1.0)
    else:
        model.add_design_var("x", lower=0.0, upper=3.5)
        model.add_objective("f")
        model.add_constraint("g", lower=1.0, upper=10.0)
        model.add_constraint("s", equals=8.0, linear=True)
    prob.driver = driver
    if coloring:
        prob.driver.declare_coloring(show_summary=False)
    prob.setup()
    prob.set_val("x", np.ones(5))
    return prob


class FragileQuadratic(om.ExplicitComponent):
    """f = 0.8 (x - 1)^2 that raises AnalysisError for x > x_fail, and records every x it sees."""

    def initialize(self):
        self.options.declare("x_fail", default=np.inf, types=float, desc="model fails above this x")
        self.options.declare("error", default=om.AnalysisError, desc="exception class to raise",
                             recordable=False)
        self.seen = []
        self.failures = 0

    def setup(self):
        self.add_input("x", 0.0, desc="design variable")
        self.add_output("f", 0.0, desc="objective")
        self.declare_partials("f", "x")

    def compute(self, inputs, outputs):
        x = inputs["x"][0]
        self.seen.append(x)
        if x > self.options["x_fail"]:
            self.failures += 1
            raise self.options["error"](f"model undefined at x = {x} > {self.options['x_fail']}")
        outputs["f"] = 0.8 * (x - 1.0) ** 2

    def compute_partials(self, inputs, partials):
        partials["f", "x"] = 1.6 * (inputs["x"][0] - 1.0)


def fragile_problem(**comp_options):
    prob = om.Problem(reports=False)
    comp = prob.model.add_subsystem("quad", FragileQuadratic(**comp_options), promotes=["*"])
    prob.model.add_design_var("x", lower=-5.0, upper=5.0)
    prob.model.add_objective("f")
    prob.driver = IpoptDriver(disp=False)
    prob.setup()
    prob.set_val("x", -3.0)
    return prob, comp


# ---------------------------------------------------------------------------------------------
# Tests
# ---------------------------------------------------------------------------------------------

@needs_cyipopt
def test_hs071_reaches_published_optimum():
    prob = hs071_problem(IpoptDriver(disp=False))
    result = prob.run_driver()

    # Hock & Schittkowski, "Test Examples for Nonlinear Programming Codes" (1981), problem 71.
    assert_allclose(prob.get_val("f"), 17.0140173, rtol=1e-7)
    assert_allclose(prob.get_val("x"), [1.0, 4.7429994, 3.8211503, 1.3794082], atol=1e-6)
    # Constraint values at the optimum: product active at 25, sum of squares equal to 40.
    assert_allclose(prob.get_val("g_prod"), 25.0, rtol=1e-7)
    assert_allclose(prob.get_val("g_sq"), 40.0, rtol=1e-7)

    driver = prob.driver
    assert result.success
    assert driver.fail is False
    assert driver.ipopt_status == 0
    assert driver.ipopt_status_name == "Solve_Succeeded"
    assert "success" in driver.ipopt_message.lower()
    assert driver.ipopt_iterations > 0
    assert result.ipopt_status == 0 and result.ipopt_iterations == driver.ipopt_iterations
    assert result.model_evals == driver.iter_count and result.deriv_evals > 0


@needs_cyipopt
def test_run_returns_failure_flag_like_other_drivers():
    # OpenMDAO 3.45: Driver.run() returns the failure flag (bool), run_driver() a DriverResult.
    prob = hs071_problem(IpoptDriver(disp=False))
    prob.final_setup()
    fail = prob.driver.run()
    assert fail is False


@needs_cyipopt
@pytest.mark.parametrize("scaled", [False, True], ids=["unscaled", "ref_scaled"])
def test_paraboloid_with_scaling_reaches_hand_derived_optimum(scaled):
    prob = paraboloid_problem(IpoptDriver(disp=False), scaled)
    result = prob.run_driver()
    assert result.success
    # Hand derivation in paraboloid_problem's docstring.
    assert_allclose(prob.get_val("x"), 6.5, atol=1e-6)
    assert_allclose(prob.get_val("y"), -6.5, atol=1e-6)
    assert_allclose(prob.get_val("f"), -26.75, atol=1e-6)
    if scaled:
        # Ipopt works in driver scaling: x_driver = (x - ref0) / (ref - ref0) = 8.5 / 12.
        assert_allclose(prob.driver.ipopt_info["x"][0], 8.5 / 12.0, atol=1e-7)
        # The hand-derived multipliers in driver scaling: a multiplier scales with
        # (ref - ref0) of its variable or constraint over (ref - ref0) of the objective,
        # mu_x = 1.0 * 12 / 50 and lambda_c = 1.5 * 6 / 50.
        assert_allclose(prob.driver.ipopt_info["mult_x_U"][0], 1.0 * 12.0 / 50.0, rtol=1e-5)
        assert_allclose(abs(prob.driver.ipopt_info["mult_g"][0]), 1.5 * 6.0 / 50.0, rtol=1e-5)
    else:
        assert_allclose(prob.driver.ipopt_info["mult_x_U"][0], 1.0, rtol=1e-5)
        assert_allclose(abs(prob.driver.ipopt_info["mult_g"][0]), 1.5, rtol=1e-5)


@needs_cyipopt
def test_rosenbrock_scaled_matches_unscaled():
    optima = []
    for scaled in (False, True):
        prob = rosenbrock_problem(IpoptDriver(disp=False), scaled)
        assert prob.run_driver().success
        optima.append(prob.get_val("x").copy())
        # Analytic minimum of the Rosenbrock function.
        assert_allclose(prob.get_val("x"), [1.0, 1.0], atol=1e-6)
        assert prob.get_val("f")[0] < 1e-12
    assert_allclose(optima[0], optima[1], atol=1e-6)


@pytest.fixture
def slsqp_vector_optimum():
    prob = vector_problem(om.ScipyOptimizeDriver(optimizer="SLSQP", tol=1e-12, disp=False))
    assert prob.run_driver().success
    return prob.get_val("x").copy(), prob.get_val("f").copy()


@needs_cyipopt
@pytest.mark.parametrize("coloring, scaled", [(False, False), (True, False), (True, True)],
                         ids=["dense", "colored", "colored_scaled"])
def test_vector_problem_agrees_with_slsqp(slsqp_vector_optimum, coloring, scaled):
    prob = vector_problem(IpoptDriver(disp=False), coloring=coloring, scaled=scaled)
    assert prob.run_driver().success
    x_ref, f_ref = slsqp_vector_optimum
    # Reference: ScipyOptimizeDriver(SLSQP, tol=1e-12) on the same problem.
    assert_allclose(prob.get_val("x"), x_ref, atol=2e-7)
    assert_allclose(prob.get_val("f"), f_ref, rtol=1e-7)
    # Both sides of the double-sided constraint are used, and the linear equality holds.
    g = prob.get_val("g")
    assert_allclose([g[0], g[3]], [1.0, 10.0], atol=1e-6)
    assert_allclose(prob.get_val("s"), 8.0, atol=1e-8)

    driver = prob.driver
    n_linear = 5  # the dense row ds/dx
    if coloring:
        # Banded dg/dx: 2 entries in each of the 4 rows.
        assert driver._jac_rows.size == 8 + n_linear
    else:
        assert driver._jac_rows.size == 4 * 5 + n_linear
    assert driver._jac_rows.size == driver._jac_cols.size


@needs_cyipopt
def test_unlinked_constraint_blocks_left_out_of_the_jacobian():
    """Without coloring, only (constraint, design variable) blocks that the model connects are
    passed to Ipopt.  min a0^2 + a1^2 + b0^2 + b1^2 + b2^2  s.t.  c_a = 2 a >= 2,
    c_b = b0 + b1 + b2 >= 3: optimum a = (1, 1), b = (1, 1, 1), f = 5 (hand derivation:
    every bound is active, by symmetry the b's are equal)."""
    prob = om.Problem(reports=False)
    model = prob.model
    model.add_subsystem("obj", om.ExecComp("f = a[0]**2 + a[1]**2 + b[0]**2 + b[1]**2 + b[2]**2",
                                           a=np.zeros(2), b=np.zeros(3)), promotes=["*"])
    model.add_subsystem("ca", om.ExecComp("c_a = 2*a", a=np.zeros(2), c_a=np.zeros(2),
                                          has_diag_partials=True), promotes=["*"])
    model.add_subsystem("cb", om.ExecComp("c_b = b[0] + b[1] + b[2]", b=np.zeros(3)),
                        promotes=["*"])
    model.add_design_var("a", lower=-10.0, upper=10.0)
    model.add_design_var("b", lower=-10.0, upper=10.0)
    model.add_objective("f")
    model.add_constraint("c_a", lower=2.0)
    model.add_constraint("c_b", lower=3.0)
    prob.driver = IpoptDriver(disp=False)
    prob.setup()
    assert prob.run_driver().success

    assert_allclose(prob.get_val("a"), [1.0, 1.0], atol=1e-6)
    assert_allclose(prob.get_val("b"), [1.0, 1.0, 1.0], atol=1e-6)
    assert_allclose(prob.get_val("f"), 5.0, atol=1e-6)
    # dc_a/da (2x2) + dc_b/db (1x3); the dc_a/db and dc_b/da blocks (9 entries) are left out.
    assert prob.driver._jac_rows.size == 4 + 3


@needs_cyipopt
def test_recorder_records_driver_iterations(tmp_path):
    prob = paraboloid_problem(IpoptDriver(disp=False), scaled=True)
    case_file = tmp_path / "ipopt_cases.sql"
    prob.driver.add_recorder(om.SqliteRecorder(str(case_file)))
    prob.driver.recording_options["record_desvars"] = True
    prob.driver.recording_options["record_objectives"] = True
    prob.setup()
    assert prob.run_driver().success
    prob.cleanup()

    reader = om.CaseReader(str(case_file))
    cases = reader.list_cases("driver", out_stream=None)
    # One case per model evaluation, the same count the driver reports.
    assert len(cases) == prob.driver.iter_count > 2
    last = reader.get_case(cases[-1])
    # The last recorded case is the optimum (hand derivation in paraboloid_problem).
    assert_allclose(last.get_design_vars(scaled=False)["x"], 6.5, atol=1e-6)
    assert_allclose(last.get_objectives(scaled=False)["f"], -26.75, atol=1e-6)


@needs_cyipopt
def test_analysis_error_makes_ipopt_cut_the_step():
    # Without the failure, Ipopt's first trial point from x0 = -3 is x ~ 2.09 (quasi-Newton step
    # with an identity initial Hessian); the model refuses x > 1.5, so that trial fails.
    prob, comp = fragile_problem(x_fail=1.5)
    result = prob.run_driver()

    assert comp.seen[1] > 1.5, "the first trial point must enter the failing region"
    assert comp.failures >= 1
    assert result.success
    # Minimum of 0.8 (x - 1)^2, inside the valid region.
    assert_allclose(prob.get_val("x"), 1.0, atol=1e-6)
    assert comp.seen[-1] <= 1.5  # the model is left at a valid point


@needs_cyipopt
def test_other_exceptions_are_not_swallowed():
    prob, comp = fragile_problem(x_fail=1.5, error=ValueError)
    with pytest.raises(ValueError, match="model undefined"):
        prob.run_driver()
    assert comp.failures == 1


@needs_cyipopt
def test_infeasible_problem_reports_failure():
    # x, y in [0, 1] give x^2 + y^2 <= 2 < 3: no feasible point exists.
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("c", om.ExecComp(["f = x + y", "g = x**2 + y**2"]), promotes=["*"])
    prob.model.add_design_var("x", lower=0.0, upper=1.0)
    prob.model.add_design_var("y", lower=0.0, upper=1.0)
    prob.model.add_objective("f")
    prob.model.add_constraint("g", lower=3.0)
    prob.driver = IpoptDriver(disp=False)
    prob.setup()
    prob.set_val("x", 0.5)
    prob.set_val("y", 0.5)
    result = prob.run_driver()

    assert not result.success
    assert result.exit_status == "FAIL"
    assert prob.driver.fail is True
    assert prob.driver.ipopt_status == 2
    assert prob.driver.ipopt_status_name == "Infeasible_Problem_Detected"
    assert result.ipopt_status == 2
    assert "infeasib" in prob.driver.ipopt_message.lower()


@needs_cyipopt
def test_iteration_limit_from_options_and_opt_settings():
    prob = rosenbrock_problem(IpoptDriver(disp=False, maxiter=3), scaled=False)
    result = prob.run_driver()
    # Rosenbrock from (-1.2, 1) needs tens of iterations, so 3 is a hard stop.
    assert not result.success
    assert prob.driver.ipopt_status == -1  # Maximum_Iterations_Exceeded
    assert prob.driver.ipopt_iterations == 3

    # opt_settings go to Ipopt verbatim and override the driver options.
    prob.driver.opt_settings["max_iter"] = 5
    prob.set_val("x", [-1.2, 1.0])
    prob.run_driver()
    assert prob.driver.ipopt_status == -1
    assert prob.driver.ipopt_iterations == 5


@needs_cyipopt
def test_quasi_newton_history_defaults_to_the_number_of_design_values():
    # Full-memory BFGS for small problems: as many past steps as design values (the rotor's 60),
    # never fewer than Ipopt's own default of 6, at most MAX_QUASI_NEWTON_HISTORY; opt_settings win.
    driver = IpoptDriver(disp=False)
    assert driver._ipopt_settings(60)["limited_memory_max_history"] == 60
    assert driver._ipopt_settings(2)["limited_memory_max_history"] == 6
    assert driver._ipopt_settings(10_000)["limited_memory_max_history"] == MAX_QUASI_NEWTON_HISTORY
    driver.opt_settings["limited_memory_max_history"] = 12
    assert driver._ipopt_settings(60)["limited_memory_max_history"] == 12


@needs_cyipopt
def test_exact_hessian_is_rejected():
    prob = rosenbrock_problem(IpoptDriver(disp=False), scaled=False)
    prob.driver.opt_settings["hessian_approximation"] = "exact"
    with pytest.raises(ValueError, match="limited-memory"):
        prob.run_driver()


@needs_cyipopt
def test_vector_objective_is_rejected():
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("c", om.ExecComp("f = 2*x", x=np.ones(2), f=np.ones(2)),
                             promotes=["*"])
    prob.model.add_design_var("x")
    prob.model.add_objective("f")
    prob.driver = IpoptDriver()
    with pytest.raises(RuntimeError, match="must be a scalar"):
        prob.setup()
        prob.final_setup()


def test_missing_cyipopt_raises_install_recipe(monkeypatch):
    # A None entry in sys.modules makes "import cyipopt" raise ImportError.
    monkeypatch.setitem(sys.modules, "cyipopt", None)
    with pytest.raises(ImportError) as excinfo:
        IpoptDriver()
    message = str(excinfo.value)
    assert "apt-get install coinor-libipopt-dev liblapack-dev libblas-dev pkg-config" in message
    assert "pip install 'bild-mdo[ipopt]'" in message


def test_registered_as_openmdao_driver_entry_point():
    eps = {ep.name: ep for ep in entry_points(group="openmdao_driver")}
    assert "ipoptdriver" in eps
    assert eps["ipoptdriver"].load() is IpoptDriver
