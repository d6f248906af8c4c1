"""LocalReferenceComp: the reference station of the local-point variants, on the load-path table and in the gap.

Sources: complex step (partials), the definition of the reference point (the lowest minimum of cd/cl along
its own path of fixed load at Re_ref = rho W0 c_ref / mu, with the blade element carrying the momentum load),
and the Reynolds gap of the NACA 4412 surrogate next to the fold of its load-path table (Re ~2.1e5 to 2.2e5,
measured on the table: no sheet covers it there), where the state is solved on the polar instead.
"""
import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_check_partials

from bild_mdo.airfoil.load_path_table import load_path_table
from bild_mdo.bild.variants.reference_point.reference_airfoil import default_polar
from bild_mdo.bild.variants.local_point.gap import reference_reynolds
from bild_mdo.bild.variants.local_point.reference import LocalReferenceComp
from bild_mdo.bild.variants.local_point.reference_solve import ReferenceFlow, solve_reference, table_jets

#: Inputs of four designs; the chords put Re_ref at ~1.2e5, ~2.15e5 (the gap), ~5e5 and ~1.3e6.
INPUTS = dict(v_axial=[0.0, 10.0, 30.0, 0.0], v_theta_ref=[50.0, 60.0, 70.0, 80.0],
              ref_radius=[0.75, 0.7, 0.6, 0.9], radius=1.5, hub_radius=0.3, rho=1.1, mu=1.75e-5)


def _chords():
    w0 = np.hypot(INPUTS["v_axial"], INPUTS["v_theta_ref"])
    return np.array([1.2e5, 2.15e5, 5e5, 1.3e6]) * 1.75e-5 / (1.1 * w0)


def _problem(ideal_loading, chord_form):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("c", LocalReferenceComp(num_nodes=4, polar=default_polar(), chord_form=chord_form,
                                                     ideal_loading=ideal_loading), promotes=["*"])
    prob.setup(force_alloc_complex=True)
    for name, value in dict(INPUTS, ref_chord=_chords()).items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


@pytest.mark.parametrize("ideal_loading", ["paper", "exact"])
@pytest.mark.parametrize("chord_form", ["thrust", "torque"])
def test_reference_partials(ideal_loading, chord_form):
    prob = _problem(ideal_loading, chord_form)
    branch = prob.get_val("section_branch_ref")
    assert branch[1] == -1 and np.all(branch[[0, 2, 3]] >= 0)  # the gap and three table states
    assert_check_partials(prob.check_partials(method="cs", out_stream=None), atol=1e-8, rtol=1e-7)


@pytest.mark.parametrize("chord_form", ["thrust", "torque"])
def test_reference_state_is_a_minimum_at_re_ref(chord_form):
    # On the table the state has R2 = 0 (the element carries the momentum load) and ln Re = ln Re_ref, and it is
    # a minimum of cd/cl along its own path (kind (1 + tau s' / (1 + tau s)) > 0, load_path's docstring).
    table = load_path_table(default_polar())
    chords = _chords()
    ref = ReferenceFlow(*(np.broadcast_to(np.asarray(INPUTS[name], dtype=float), (4,)).copy()
                          for name in ("v_axial", "v_theta_ref", "ref_radius")), chords,
                        *(np.full(4, INPUTS[name]) for name in ("radius", "hub_radius", "rho", "mu")),
                        num_blades=3, loss_model="tip_hub", chord_form=chord_form)
    sol = solve_reference(table, default_polar(), ref)
    assert np.all(sol.ok) and np.array_equal(sol.on_table, [True, False, True, True])
    at = np.flatnonzero(sol.on_table)
    take = ref._replace(**{name: getattr(ref, name)[at] for name in ("v_axial", "v_theta", "r", "chord", "radius",
                                                                     "hub_radius", "rho", "mu")})
    (r2, r_ell), *_ = table_jets(table, take, sol.phi[at], sol.x0[at], sol.label[at])
    assert np.max(np.abs(r2.v)) < 1e-12 and np.max(np.abs(r_ell.v)) < 1e-12
    np.testing.assert_allclose(np.exp(table.curve(sol.x0[at], sol.label[at], ("ell",))["ell"].f),
                               reference_reynolds(take), rtol=1e-12)
    tau = -np.tan(sol.phi[at]) if chord_form == "thrust" else 1.0 / np.tan(sol.phi[at])
    s = table.curve(sol.x0[at], sol.label[at], ("s",))["s"]
    assert np.all(table.kind[sol.label[at]] * (1.0 + tau * s.f1 / (1.0 + tau * s.f)) > 0.0)


def test_reference_state_does_not_depend_on_the_batch():
    prob = _problem("exact", "thrust")
    for node in range(4):
        alone = om.Problem(reports=False)
        alone.model.add_subsystem("c", LocalReferenceComp(num_nodes=1, polar=default_polar(), ideal_loading="exact"),
                                  promotes=["*"])
        alone.setup()
        for name, value in dict(INPUTS, ref_chord=_chords()).items():
            alone.set_val(name, np.broadcast_to(np.asarray(value, dtype=float), (4,))[node])
        alone.run_model()
        for name in ("phi_ref", "alpha_star_ref", "cl_star_ref", "cd_star_ref", "ideal_loading_constant"):
            np.testing.assert_array_equal(alone.get_val(name)[0], prob.get_val(name)[node])


def test_a_chord_below_the_lightest_ideal_load_is_infeasible():
    # The definition of the reference point (reference_solve's docstring): a station placed at r_ref, solved at
    # the reference's own lambda, takes the reference state.  On the paper's hover rotor (the BILDGroup defaults)
    # with the NACA 4412 surrogate, reference chords of 1-2.5 cm put the reference state where lambda falls as
    # the chord grows or where loading the annulus saves less than leaving it unloaded (Phi >= 0): the station
    # at r_ref then takes a load ten times heavier (phi ~0.48 against ~0.05 rad), so the design is not the one
    # c_ref names.  Those, and only those, are infeasible with the lightest-load reason.
    from bild_mdo.bild import BILDGroup
    from bild_mdo.bild.variants.local_point.reference import LIGHTEST_LOAD
    from bild_mdo.bild.variants.local_point.reference_solve import station_flow
    from bild_mdo.bild.variants.reynolds_exact.solve import solve_stations

    chords = np.geomspace(0.01, 0.5, 40)
    prob = om.Problem(BILDGroup(num_nodes=chords.size, num_radial=8, polar=default_polar(), section_point="local",
                                ideal_loading="exact", on_infeasible="flag"), reports=False)
    prob.setup()
    prob.set_val("ref_chord", chords)
    prob.run_model()
    comp = prob.model.reference_point
    solution = comp._cache["solution"]
    at_r_ref = solve_stations(comp.table, station_flow(comp._flow(comp._inputs))._replace(
        lam=prob.get_val("ideal_loading_constant")))
    light = prob.model.feasibility.status() == LIGHTEST_LOAD
    assert 5 <= np.sum(light) and np.all(chords[light] < 0.025) and np.all(prob.get_val("feasible")[chords > 0.025])
    assert np.all(np.abs(at_r_ref.phi[light] - solution.phi[light]) > 0.1)
    # The two criteria agree where the station takes the reference's sheet: the same state, to round-off.
    same = ~light & (at_r_ref.label == solution.label) & solution.on_table
    assert np.sum(same) >= 20
    np.testing.assert_allclose(at_r_ref.phi[same], solution.phi[same], rtol=0.0, atol=1e-10)
    assert np.all(prob.model.feasibility.light[light])


@pytest.mark.parametrize("ideal_loading", ["exact", "paper"])
@pytest.mark.parametrize("ref_chord", [0.0047, 0.009])
def test_a_blade_without_ref_chord_at_r_ref_is_named(ref_chord, ideal_loading):
    """Invariant of both local-point variants: a station placed at r_ref takes the reference state, so the blade
    has ref_chord there.  With 12 stations from 0.2 R a station sits at r_ref = R/2, where a consistent design's
    chord is ref_chord to round-off (test_consistent_designs_have_ref_chord_at_r_ref).  A small two-blade hover
    rotor (R = 0.3 m, 6000 rpm) at these chords has a reference state (Re_ref 3e4-6e4) on another sheet than the
    state a station at r_ref takes at that lambda (with the exact loading: of lower F (e - lambda t)): its blade
    has another chord there (measured 0.38 and 0.0195 m exact, 0.043 and 0.019 m paper loading), and the result
    says so (a warning, the notes; station_branch_ref with the exact loading)."""
    from bild_mdo import design_rotor
    from bild_mdo.results.design import ReferenceChordWarning

    with pytest.warns(ReferenceChordWarning, match="has not ref_chord at r_ref"):
        design = design_rotor(radius=0.3, rpm=6000, v_axial=0.0, num_blades=2, ref_chord=ref_chord, num_radial=12,
                              section_point="local", ideal_loading=ideal_loading, bem_analysis=False)
    assert design.radii[4] == pytest.approx(design.ref_radius, rel=1e-12)
    assert abs(design.chord[4] / ref_chord - 1.0) > 0.5
    if ideal_loading == "exact":
        assert design.values["station_branch_ref"] != design.values["section_branch_ref"]
    assert "ref_chord is not the blade's chord at r_ref" in design.summary()


@pytest.mark.parametrize("ideal_loading", ["exact", "paper"])
@pytest.mark.parametrize("radius, v_axial", [(1.0, 20.0), (1.5, 0.0)])
def test_consistent_designs_have_ref_chord_at_r_ref(radius, v_axial, ideal_loading, recwarn):
    """The same invariant where it holds (the paper's sweep: 800 rpm, three blades, c_ref 0.15 m): the chord of the
    station at r_ref is ref_chord to 1e-12, the sheets agree, and nothing is flagged."""
    from bild_mdo import design_rotor
    from bild_mdo.results.design import ReferenceChordWarning

    design = design_rotor(radius=radius, rpm=800, v_axial=v_axial, num_blades=3, ref_chord=0.15, num_radial=12,
                          section_point="local", ideal_loading=ideal_loading, bem_analysis=False)
    assert design.chord[4] == pytest.approx(0.15, rel=1e-12)
    if ideal_loading == "exact":
        assert design.values["station_branch_ref"] == design.values["section_branch_ref"]
    assert not [w for w in recwarn if issubclass(w.category, ReferenceChordWarning)]
    assert "ref_chord is not" not in design.summary()


def _small_rotor_reference(ref_chord):
    """LocalReferenceComp (exact loading) of the small two-blade hover rotor (R 0.3 m, 6000 rpm, r_ref = R/2,
    sea-level air) at these reference chords."""
    from bild_mdo.atmosphere import isa

    air = isa(0.0, derivatives=False)
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("c", LocalReferenceComp(num_nodes=len(ref_chord), num_blades=2, polar=default_polar(),
                                                     ideal_loading="exact"), promotes=["*"])
    prob.setup(force_alloc_complex=True)
    for name, value in dict(v_axial=0.0, v_theta_ref=6000.0 * np.pi / 30.0 * 0.15, ref_radius=0.15, radius=0.3,
                            hub_radius=0.06, rho=air.rho, mu=air.mu, ref_chord=ref_chord).items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


# In hover the reference state's partials w.r.t. v_axial vanish (they grow as v_axial: 2.2e-8 rad per m/s at
# 1e-3 m/s, 2.2e-5 at 1 m/s, measured), so OpenMDAO's zero-derivative warning is expected here.
@pytest.mark.filterwarnings("ignore:(?s).*has zero derivatives")
def test_the_reference_state_is_the_one_a_station_at_r_ref_takes():
    """Invariant: a station at r_ref takes the reference state at its lambda.  On the small hover rotor at
    c_ref 0.0254 m the state of least cd/cl with that chord is not one (a station at r_ref takes another sheet at
    its lambda, and a chord of 0.044 m); the next state with c_ref, on another sheet, is, so the reference takes it
    and the blade has ref_chord at r_ref (a station sits there with 12 stations).  At 0.02 m the state of least
    cd/cl is already the station's; partials by complex step on both."""
    from bild_mdo import design_rotor

    prob = _small_rotor_reference([0.0254, 0.02])
    comp = prob.model.c
    first = solve_reference(comp.table, default_polar(), comp._flow(comp._inputs))
    branch, station = prob.get_val("section_branch_ref"), prob.get_val("station_branch_ref")
    assert first.label[0] != branch[0] and branch[0] == station[0]
    assert first.label[1] == branch[1] == station[1]
    assert_check_partials(prob.check_partials(method="cs", out_stream=None), atol=1e-8, rtol=1e-7)
    design = design_rotor(radius=0.3, rpm=6000, v_axial=0.0, num_blades=2, ref_chord=0.0254, num_radial=12,
                          section_point="local", ideal_loading="exact", bem_analysis=False)
    assert design.radii[4] == pytest.approx(design.ref_radius, rel=1e-12)
    assert design.chord[4] == pytest.approx(0.0254, rel=1e-12)
    assert design.values["section_branch_ref"] == branch[0]
