"""Lockstep optimisation: many cases through one vectorised model, each with the result it gets alone.

Source of the expected numbers: each case's own solo optimisation (the same
SLSQP, scaling, bounds and tolerances on a single-case model).  The cases do
not interact in the batched model, so a case's trajectory, iteration count
and optimum must not depend on the other cases of its batch (the tolerances
are those of issue 11: energy loss to 1e-6 relative, thrust constraint to
1e-8).  Cases of the paper's sweep (Sec. 5.1, levels = 3): hover and forward
flight, small and large rotors, sea level and 3000 m.
"""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.bem.flow_states import PROPELLER
from bild_mdo.optimization.batch_model import BatchModel, CaseSpec, Evaluation
from bild_mdo.optimization.lockstep import TRIMMED_START_TOLERANCE, CaseRun
from bild_mdo.optimization.problem import build_optimization_problem, set_optimization_case
from bild_mdo.optimization.result import ANALYSIS_FAILED
from bild_mdo.optimization.run import optimize_rotor, trim_to_thrust
from bild_mdo.verification.case_functions import bild_batch
from bild_mdo.verification.cases import SweepSpec

# levels=3 case ids -> (J, R, altitude, c_ref): 19 = (0, 1.5 m, 0 m, 0.15 m) hover;
# 46 = (1.5, 1.5 m, 0 m, 0.15 m) cruise; 80 = (3, 1.5 m, 3000 m, 0.22 m) fast cruise at altitude;
# 4 = (0, 0.5 m, 1500 m, 0.15 m) small hovering rotor at altitude.
CASE_IDS = (19, 46, 80, 4)


@pytest.fixture(scope="module")
def sweep_cases():
    cases = SweepSpec(levels=3).cases(CASE_IDS)
    return cases, bild_batch(cases)


def _columns(cases, designs):
    keys = ("v_axial", "rpm", "radius", "hub_radius")
    return (*(np.array([c.inputs[k] for c in cases]) for k in keys), np.array([d["thrust"] for d in designs]),
            np.array([c.inputs["altitude"] for c in cases]))


def _geometry(designs):
    return {"bild_chord": np.array([d["chord"] for d in designs]),
            "bild_twist": np.array([d["twist"] for d in designs])}


@pytest.fixture(scope="module")
def solo(sweep_cases):
    cases, designs = sweep_cases
    prob = build_optimization_problem(optimizer="slsqp")
    out = []
    for args in zip(*_columns(cases, designs), designs):
        out.append(optimize_rotor(*(float(a) for a in args[:6]), problem=prob, restarts=1,
                                  bild_chord=args[6]["chord"], bild_twist=args[6]["twist"]))
    return out


def _assert_same(result, alone):
    assert result.converged and alone.converged, (result.status, alone.status)
    assert result.performance["energy_loss"] == pytest.approx(alone.performance["energy_loss"], rel=1e-6)
    assert abs(result.thrust_error - alone.thrust_error) <= 1e-8
    assert result.iterations == alone.iterations and result.status == alone.status
    np.testing.assert_allclose(result.chord, alone.chord, rtol=1e-5)


@pytest.mark.parametrize("batch_size", [4, 2])
def test_every_case_equals_its_solo_run(sweep_cases, solo, batch_size):
    cases, designs = sweep_cases
    # batch_size=2: two cases at a time, the next starting when one finishes.
    results = optimize_rotor(*_columns(cases, designs), optimizer="slsqp", restarts=1, batch_size=batch_size,
                             **_geometry(designs))
    assert isinstance(results, list) and len(results) == len(cases)
    for result, alone in zip(results, solo):
        _assert_same(result, alone)
        assert result.iterations > 0 and result.model_evaluations > result.iterations


def test_scalar_arguments_return_one_result(sweep_cases, solo):
    cases, designs = sweep_cases
    args = [float(column[0]) for column in _columns(cases, designs)]
    result = optimize_rotor(*args, optimizer="slsqp", restarts=1, bild_chord=designs[0]["chord"],
                            bild_twist=designs[0]["twist"])
    _assert_same(result, solo[0])


def test_broadcast_case_arguments(sweep_cases):
    cases, designs = sweep_cases
    # One operating point at two thrust targets: 2 cases from scalars and a length-2 array.
    v_axial, rpm, radius, hub_radius, thrust, altitude = (float(c[1]) for c in _columns(cases, designs))
    results = optimize_rotor(v_axial, rpm, radius, hub_radius, np.array([thrust, 0.9 * thrust]), altitude,
                             bild_chord=designs[1]["chord"], bild_twist=designs[1]["twist"])
    assert len(results) == 2 and all(r.converged for r in results)
    # The thrust constraint of each case holds (the optimiser's feasibility tolerance).
    assert results[0].performance["thrust"] == pytest.approx(thrust, rel=1e-6)
    assert results[1].performance["thrust"] == pytest.approx(0.9 * thrust, rel=1e-6)
    with pytest.raises(ValueError, match="bild_chord must have shape"):
        optimize_rotor(v_axial, rpm, radius, hub_radius, np.array([thrust, 0.9 * thrust]), altitude,
                       bild_chord=np.ones((3, 30)), bild_twist=designs[1]["twist"])


def test_a_failing_analysis_fails_its_case_alone(sweep_cases, solo, monkeypatch):
    cases, designs = sweep_cases
    columns = _columns(cases, designs)
    bad_thrust = float(columns[4][1])
    evaluate = BatchModel.evaluate

    def failing(self, specs, x_chord, x_twist, gradients, previous_phi=None):
        # A stand-in for a BEM solve that raises for one case (the cruise case) at every trial point.
        if any(spec.inputs["thrust_target"] == bad_thrust for spec in specs):
            raise om.AnalysisError("stand-in analysis failure")
        return evaluate(self, specs, x_chord, x_twist, gradients, previous_phi)

    monkeypatch.setattr(BatchModel, "evaluate", failing)
    results = optimize_rotor(*columns, optimizer="slsqp", restarts=1, **_geometry(designs))
    assert not results[1].converged and results[1].status.startswith(ANALYSIS_FAILED)
    assert "stand-in analysis failure" in results[1].status
    for k in (0, 2, 3):
        _assert_same(results[k], solo[k])


# levels=3 cases 0 = (J 0, R 0.5 m, 0 m, c_ref 0.08 m) and 8 = (0, 0.5 m, 3000 m, 0.22 m): small hovering rotors
# whose root stations are in deep stall, where the BEM inflow angle can jump between roots
# (bild_mdo.optimization.lockstep.CaseRun, "Worse than the start").
STALLED_ROOT_CASE_IDS = (0, 8)


def test_stalled_root_cases_keep_solo_results_and_beat_trimmed_bild():
    cases = SweepSpec(levels=3).cases(STALLED_ROOT_CASE_IDS)
    designs = bild_batch(cases)
    prob = build_optimization_problem(optimizer="slsqp")
    alone, trimmed = [], []
    for args, bild in zip(zip(*_columns(cases, designs)), designs):
        args = [float(a) for a in args]
        alone.append(optimize_rotor(*args, problem=prob, restarts=1, bild_chord=bild["chord"],
                                    bild_twist=bild["twist"]))
        # BILD's own design trimmed to T* by collective pitch: a feasible design, so an upper bound on the optimum.
        set_optimization_case(prob, *args, bild_chord=bild["chord"], bild_twist=bild["twist"])
        trim_to_thrust(prob)
        trimmed.append(float(prob.get_val("energy_loss")[0]))
    results = optimize_rotor(*_columns(cases, designs), optimizer="slsqp", restarts=1, **_geometry(designs))
    for result, solo_result, bound in zip(results, alone, trimmed):
        _assert_same(result, solo_result)
        # The tolerance of the verification's optimality check (bild_mdo.verification.optimality).
        assert result.performance["energy_loss"] <= bound * (1.0 + TRIMMED_START_TOLERANCE), result.status


def _jump_model(x_chord, x_twist, gradients, previous_phi):
    """Stand-in model with a jump: E = c^2 + t^2 + (1 if c > 0.4), constraint c + t - 1 = 0 (one station)."""
    c, t = float(x_chord[0]), float(x_twist[0])
    energy = c**2 + t**2 + (1.0 if c > 0.4 else 0.0)
    return Evaluation(energy, c + t - 1.0, {"energy_loss": energy}, x_chord.copy(), x_twist.copy(),
                      np.full(1, PROPELLER), np.array([2.0 * c, 2.0 * t]), np.array([1.0, 1.0]), np.zeros(1))


def test_an_optimum_worse_than_the_trimmed_start_is_restarted_from_it():
    # Hand derivation: from (c, t) = (0.3, 0.5) SLSQP heads for the smooth optimum (0.5, 0.5), past the jump,
    # E = 1.5.  The start trimmed by t alone is (0.3, 0.7), E = 0.58; from there the best feasible design
    # below the jump is the limit c -> 0.4, t = 0.6: E = 0.16 + 0.36 = 0.52.
    spec = CaseSpec({}, np.array([0.3]), np.array([0.5]), (np.array([0.0]), np.array([1.5])))
    settings = {"scaling": "hessian", "parameterization": "stations", "order": 4, "tol": 1e-8, "maxiter": 100,
                "restarts": 0, "num_radial": 1}
    result = CaseRun(spec, _jump_model, settings, speculate=False).solve()
    assert result.converged and "restarted from the initial design trimmed to the thrust" in result.status
    assert result.performance["energy_loss"] == pytest.approx(0.52, abs=1e-6)
    assert result.thrust_error == pytest.approx(0.0, abs=1e-8)
