"""BILDGroup(thrust_target=True): the reference chord solved for a required thrust, with exact totals."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.bild import BILDGroup
from bild_mdo.bild.feasibility import FeasibilityLedger
from bild_mdo.bild.thrust_target import ReferenceChordSolver, ThrustTargetComp
from bild_mdo.utils.testing import check_group_totals
from tests.bild.test_bild_group_airfoils import SPANWISE

NN = 24
POLAR = AnalyticPolar(reynolds_exponent=0.2)


def _designs(kind, n=NN, seed=0):
    """Random rotors (tip speeds 100-230 m/s) and the reference chords whose thrust is the target."""
    rng = np.random.default_rng(seed)
    radius = rng.uniform(0.3, 2.0, n)
    rpm = rng.uniform(100.0, 230.0, n) / radius * 60.0 / (2.0 * np.pi)
    advance_ratio = np.zeros(n) if kind == "hover" else rng.uniform(0.1, 0.8, n)
    inputs = dict(radius=radius, rpm=rpm, v_axial=advance_ratio * rpm / 60.0 * 2.0 * radius,
                  hub_radius_ratio=rng.uniform(0.1, 0.25, n), ref_radius_ratio=rng.uniform(0.4, 0.7, n),
                  altitude=rng.uniform(0.0, 3000.0, n))
    return inputs, rng.uniform(0.03, 0.15, n) * radius


def _run(inputs, thrust_target=None, ref_chord=None, polar=POLAR, **options):
    n = len(inputs["radius"])
    prob = om.Problem(BILDGroup(num_nodes=n, num_radial=12, polar=polar, thrust_target=thrust_target is not None,
                                **options), reports=False)
    prob.setup()
    for name, value in inputs.items():
        prob.set_val(name, value)
    prob.set_val("ref_chord" if thrust_target is None else "thrust_target",
                 ref_chord if thrust_target is None else thrust_target)
    prob.run_model()
    return prob


def test_thrust_target_recovers_the_reference_chord(kind):
    # T(c_ref) is monotone, so the chord that gives the thrust of a ref_chord design is that chord: the
    # thrust-target design is the same design, to the solver tolerance.
    inputs, chord = _designs(kind)
    direct = _run(inputs, ref_chord=chord)
    target = direct.get_val("thrust")
    solved = _run(inputs, thrust_target=target)
    np.testing.assert_allclose(solved.get_val("thrust"), target, rtol=1e-10)
    np.testing.assert_allclose(solved.get_val("ref_chord"), chord, rtol=1e-9)
    for name in ("torque", "chord", "twist"):
        np.testing.assert_allclose(solved.get_val(name), direct.get_val(name), rtol=1e-8, atol=1e-12)
    # A second solve starts from the converged chords and the secant slopes: one pass.
    solved.run_model()
    assert solved.model.thrust_target_balance._passes == 1


@pytest.mark.parametrize("kind, polar", [("hover", POLAR), ("cruise", SPANWISE)], ids=["hover", "cruise_spanwise"])
def test_totals_complex_step(kind, polar):
    # Implicit-function totals through the balance T/T* - 1 = 0; complex step runs the solver itself.
    inputs, chord = _designs(kind, n=3, seed=1)
    target = _run(inputs, ref_chord=chord, polar=polar).get_val("thrust")
    values = dict(inputs, thrust_target=target)
    check_group_totals(lambda: BILDGroup(num_nodes=3, num_radial=12, polar=polar, thrust_target=True),
                       of=["ref_chord", "torque", "power", "figure_of_merit", "chord", "twist"],
                       wrt=["thrust_target", "rpm", "radius", "v_axial", "ref_radius_ratio", "altitude"],
                       values=values, atol=1e-10, rtol=1e-6)


def test_unreachable_target_is_infeasible_and_the_others_converge():
    # The ideal loading has a largest thrust (the reference station overloads, Assumption 3); a target far
    # above it is reported for its node only.
    inputs, chord = _designs("cruise", n=3, seed=2)
    target = _run(inputs, ref_chord=chord).get_val("thrust") * np.array([1.0, 1e3, 1.0])
    prob = _run(inputs, thrust_target=target, on_infeasible="flag")
    np.testing.assert_array_equal(prob.get_val("feasible"), [1.0, 0.0, 1.0])
    np.testing.assert_allclose(prob.get_val("thrust")[[0, 2]], target[[0, 2]], rtol=1e-10)
    assert "thrust target not reached" in prob.model.feasibility.status()[1]
    with pytest.raises(om.AnalysisError, match=r"thrust target not reached: .* node\(s\) 1 "):
        _run(inputs, thrust_target=target)


def test_nonpositive_target_raises():
    inputs, _ = _designs("hover", n=3)
    with pytest.raises(om.AnalysisError, match="thrust_target must be positive and finite, got 0.0 at node 1"):
        _run(inputs, thrust_target=np.array([100.0, 0.0, 100.0]))


class _PiecewiseThrust(om.ExplicitComponent):
    """T = 1000 c [N/m] plus ``jump`` N where c > 0.1 m: a design whose thrust jumps at a branch switch."""

    def initialize(self):
        self.options.declare("jump", types=float)

    def setup(self):
        self.add_input("ref_chord", val=np.full(3, 0.05), units="m")
        self.add_output("dthrust_dr", val=np.ones((3, 1)), units="N/m")

    def compute(self, inputs, outputs):
        c = inputs["ref_chord"]
        # One station of width dr = 1 m (the balance's default): dT/dr in N/m is the thrust in N.
        outputs["dthrust_dr"] = (1000.0 * c + np.where(c > 0.1, self.options["jump"], 0.0))[:, None]


class _JumpGroup(om.Group):
    def initialize(self):
        self.options.declare("jump", types=float)

    def setup(self):
        self.feasibility = FeasibilityLedger(3)
        self.add_subsystem("thrust", _PiecewiseThrust(jump=self.options["jump"]), promotes=["*"])
        self.thrust_target_balance = self.add_subsystem(
            "balance", ThrustTargetComp(num_nodes=3, num_radial=1, feasibility=self.feasibility), promotes=["*"])
        self.nonlinear_solver = ReferenceChordSolver()


@pytest.mark.parametrize("jump, targets, reached", [
    # Up by 500 N at c = 0.1 m: 300 N lies in the gap 100 ... 600 N and has no reference chord.
    (500.0, [50.0, 300.0, 700.0], [True, False, True]),
    # Down by 50 N: 75 N is met twice (c = 0.075 m and 0.125 m); either is a solution.
    (-50.0, [40.0, 75.0, 200.0], [True, True, True]),
])
def test_a_jump_of_the_thrust_is_never_taken_for_a_solution(jump, targets, reached):
    prob = om.Problem(_JumpGroup(jump=jump), reports=False)
    prob.setup()
    prob.set_val("thrust_target", targets)
    prob.run_model()
    feasible = ~prob.model.feasibility.infeasible
    np.testing.assert_array_equal(feasible, reached)
    np.testing.assert_allclose(prob.get_val("dthrust_dr")[feasible, 0], np.array(targets)[feasible], rtol=1e-12)
    for status in prob.model.feasibility.status()[~feasible]:
        assert status.startswith("thrust target in a jump of the design")


@pytest.mark.parametrize("section_point, ideal_loading", [("reference", "paper"), ("local", "exact")])
def test_passes_rerun_only_the_loop_of_the_reference_chord(section_point, ideal_loading):
    # ReferenceChordSolver runs the subsystems upstream of ref_chord once, the loop (reference station ->
    # stations -> loads -> balance) once per pass, and what only depends on the loop (chord correction,
    # performance, Mach number, feasibility) once after the last pass, which is consistent: the performance's
    # thrust is the target, and the design is the one a run at the solved ref_chord gives.
    # The Reynolds-aware exact loading solves lambda, and its ref_chord is the chord of the stations at r_ref:
    # with r_ref on a station that is the station's chord, so the run at that ref_chord (whose reference state
    # is the ideal load of a station at r_ref, reference_solve's docstring) is the same design.
    from bild_mdo.airfoil import naca4412
    inputs, _ = _designs("cruise", n=3, seed=4)
    options = dict(polar=naca4412(), section_point=section_point, ideal_loading=ideal_loading,
                   on_infeasible="flag")
    if ideal_loading == "exact":
        radii = _run(inputs, ref_chord=0.1 * inputs["radius"], **options).get_val("radii")
        inputs = dict(inputs, ref_radius_ratio=radii[:, 6] / inputs["radius"])
    prob = _run(inputs, thrust_target=np.array([400.0, 900.0, 1500.0]), **options)
    model = prob.model
    passes = model.thrust_target_balance._passes
    assert passes >= 3
    counts = {sub.name: sub.iter_count for sub in model._subsystems_myproc}
    for name in ("atmosphere", "geometry", "stations", "rotational_speed"):
        assert counts[name] == 1, name
    for name in ("performance", "local_mach", "root_chord_correction", "feasibility_check"):
        assert counts[name] == 1, name
    assert counts["momentum_loads"] == counts["chord"] == counts["thrust_target_balance"] == passes
    assert (prob.get_val("feasible") > 0.5).all()
    np.testing.assert_allclose(prob.get_val("thrust"), [400.0, 900.0, 1500.0], rtol=1e-12)
    direct = _run(inputs, ref_chord=prob.get_val("ref_chord"), **options)
    # lambda -> chord at r_ref -> the reference state's lambda again: a second path to the same state, whose
    # Newton solve stops at 1e-13 in the angle.
    rtol = 1e-12 if ideal_loading == "paper" else 1e-10
    for name in ("thrust", "torque", "chord", "twist", "mach"):
        np.testing.assert_allclose(prob.get_val(name), direct.get_val(name), rtol=rtol, atol=1e-14)


class _LightThrust(om.ExplicitComponent):
    """T = 1000 c [N/m], and below c = 0.02 m a design too lightly loaded (a light check of the ledger fails),
    as where no station can be loaded: the thrust a solve sees there is a placeholder, not a trend."""

    def initialize(self):
        self.options.declare("feasibility")

    def setup(self):
        self.add_input("ref_chord", val=np.full(3, 0.05), units="m")
        self.add_output("dthrust_dr", val=np.ones((3, 1)), units="N/m")

    def compute(self, inputs, outputs):
        c = inputs["ref_chord"]
        light = c < 0.02
        self.options["feasibility"].record("light", light, "no station can be loaded: raise ref_chord", {},
                                           light=True)
        # The placeholder rises as c falls (a lower branch whose thrust does not follow c_ref).
        outputs["dthrust_dr"] = np.where(light, 5000.0, 1000.0 * c)[:, None]


class _LightGroup(om.Group):
    def setup(self):
        self.feasibility = FeasibilityLedger(3)
        self.add_subsystem("thrust", _LightThrust(feasibility=self.feasibility), promotes=["*"])
        self.thrust_target_balance = self.add_subsystem(
            "balance", ThrustTargetComp(num_nodes=3, num_radial=1, feasibility=self.feasibility), promotes=["*"])
        self.nonlinear_solver = ReferenceChordSolver()


def test_a_light_design_is_searched_above_and_a_parked_one_restarts():
    # A design too lightly loaded lies below the target (a larger chord helps), never above it: 5 N lies below
    # the smallest feasible thrust (20 N at c = 0.02 m) and is reported so, parked at a feasible chord above.
    prob = om.Problem(_LightGroup(), reports=False)
    prob.setup()
    prob.set_val("ref_chord", [0.015, 0.015, 0.3])  # the first pass of two designs is light
    prob.set_val("thrust_target", [5.0, 50.0, 300.0])
    prob.run_model()
    ledger = prob.model.feasibility
    np.testing.assert_array_equal(ledger.infeasible, [True, False, False])
    assert ledger.status()[0].startswith("thrust target not reached: below the smallest thrust")
    assert 0.02 <= prob.get_val("ref_chord")[0] < 0.02 * (1.0 + 1e-8)
    np.testing.assert_allclose(prob.get_val("dthrust_dr")[1:, 0], [50.0, 300.0], rtol=1e-12)
    # The next solve starts the parked design from the default chord, not from where it was parked: it
    # converges to the chord of a fresh model (T = 1000 c: 0.06 m), the others from their solution.
    prob.set_val("thrust_target", [60.0, 50.0, 300.0])
    prob.run_model()
    assert not np.any(ledger.infeasible)
    np.testing.assert_allclose(prob.get_val("ref_chord"), [0.06, 0.05, 0.3], rtol=1e-12)


def test_reynolds_aware_targets_in_sequence_on_one_model():
    # The paper's hover rotor (design_rotor's defaults) with the NACA 4412 surrogate and the Reynolds-aware exact
    # loading: below about 2.5 cm of reference chord no design is feasible (no station loaded, or a chord below
    # the lightest ideal load), and across c_ref ~0.0286 m the reference station changes sheet and the thrust
    # jumps from about 100 N to above 300 N.  Each target is met or reported with its reason, on one cached
    # model in turn, and a target after a failed one is met as by a fresh model (the parked chord is not reused).
    from bild_mdo import design_rotor
    from bild_mdo.bild.variants.reference_point.reference_airfoil import default_polar

    def design(thrust):
        return design_rotor(thrust=thrust, airfoil=default_polar(), section_point="local", ideal_loading="exact",
                            bem_analysis=False, on_infeasible="skip")

    fresh = design(400.0)
    for thrust, reason in ((1.0, "thrust target not reached: below the smallest thrust"),
                           (200.0, "thrust target in a jump of the design"), (400.0, None), (1.0, "thrust target not"),
                           (400.0, None)):
        result = design(thrust)
        if reason is None:
            assert result.status == "ok"
            np.testing.assert_allclose(result.thrust, thrust, rtol=1e-12)
            np.testing.assert_allclose(result.ref_chord, fresh.ref_chord, rtol=1e-9)
        else:
            assert result.status.startswith(reason)
