"""Set-up of the BEM optimisation of paper Sec. 5.1: optimiser choice, bounds, loading a case."""
import numpy as np
import pytest

from bild_mdo.optimization.initial_design import CHORD_RATIO_BOUNDS
from bild_mdo.optimization.problem import OPTIMIZERS, build_optimization_problem, set_optimization_case
from tests.optimization.conftest import case_args


def test_input_errors():
    with pytest.raises(ValueError, match="optimizer must be one of"):
        build_optimization_problem(optimizer="cobyla")
    with pytest.raises(ValueError, match="takes bild_chord and bild_twist together"):
        build_optimization_problem(0.0, 800.0, 1.0, 0.2, 400.0, bild_chord=[0.1] * 30)
    with pytest.raises(ValueError, match="unknown airfoil 'no_such_airfoil'"):
        build_optimization_problem(polar="no_such_airfoil")
    prob = build_optimization_problem()
    with pytest.raises(ValueError, match="hub_radius < radius"):
        set_optimization_case(prob, 0.0, 800.0, 1.0, 1.2, 400.0, initial="linear")
    with pytest.raises(ValueError, match="v_axial must be >= 0"):
        set_optimization_case(prob, -1.0, 800.0, 1.0, 0.2, 400.0, initial="linear")


def test_snopt_without_pyoptsparse_says_what_to_do():
    assert OPTIMIZERS == ("slsqp", "ipopt", "snopt")
    try:
        import pyoptsparse  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError, match="use optimizer='slsqp' or 'ipopt'"):
            build_optimization_problem(optimizer="snopt")
    else:
        pytest.skip("pyOptSparse is installed")


def test_case_loads_bild_geometry_within_bounds(designs):
    case, bild = designs["cruise"]
    prob = build_optimization_problem(*case_args(case, bild), bild_chord=bild["chord"], bild_twist=bild["twist"])
    radius = case.inputs["radius"]
    # Per-station design values reproduce the BILD blade exactly (it lies inside the bounds).
    np.testing.assert_allclose(prob.get_val("chord_ratio_cp")[0], bild["chord"] / radius, rtol=1e-12)
    np.testing.assert_allclose(prob.get_val("twist_cp", units="rad")[0], bild["twist"], rtol=1e-12)
    assert np.all(prob.get_val("chord_ratio_cp") > CHORD_RATIO_BOUNDS[0])
    lower, upper = prob._bild_optimization["twist_bounds"]
    assert np.all(lower < bild["twist"]) and np.all(bild["twist"] < upper)
    assert prob.get_val("thrust_target")[0] == bild["thrust"]


def test_finite_difference_totals_approximate_the_exact_ones(designs):
    # Forward differences with OpenMDAO's default step 1e-6 have a truncation error O(h f''), so the
    # two gradients agree to about 1e-5 relative to their size, not to round-off.
    case, bild = designs["cruise"]
    of, wrt = ["energy_loss_ratio", "thrust_residual"], ["chord_ratio_cp", "twist_cp"]
    gradients = {}
    for approx in (None, "fd"):
        prob = build_optimization_problem(*case_args(case, bild), bild_chord=bild["chord"], bild_twist=bild["twist"],
                                          approx_totals=approx)
        prob.run_model()
        gradients[approx] = prob.compute_totals(of=of, wrt=wrt, return_format="array")
    scale = np.abs(gradients[None]).max()
    np.testing.assert_allclose(gradients["fd"], gradients[None], rtol=0.0, atol=1e-4 * scale)
    with pytest.raises(ValueError, match="approx_totals must be None"):
        build_optimization_problem(approx_totals="cs")
