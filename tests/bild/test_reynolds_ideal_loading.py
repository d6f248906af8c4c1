"""The Reynolds-aware exact ideal loading (section_point='local', ideal_loading='exact'): partials, invariants, optimum.

Sources of the asserted numbers: complex step and central differences of the residuals (exact derivatives),
the method's own definition (the per-annulus minimum of F (e - lambda t), checked by brute force on a grid;
a node's design does not depend on its batch), and the Reynolds-independent limit (kappa = 0: the exact
loading).  The invariants the local point shares with the paper's loading (chord(r_ref) = c_ref,
Re = rho W0 c / mu, the BEM analysis reproduces the design, totals by complex step, the thrust target) are
tested for both loadings in test_local_section_point_group.py.
"""
import warnings

import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_check_partials

from bild_mdo.airfoil.text import sweep_polar
from bild_mdo.bem.prandtl import prandtl_loss_jet
from bild_mdo.bild import BILDGroup
from bild_mdo.bild.annulus_stationarity import annulus, unloaded_angle
from bild_mdo.bild.local_section_point import solve_local_point
from bild_mdo.bild.reference_airfoil import default_polar
from bild_mdo.bild.reynolds_ideal_loading import INPUTS, STATES, Flow, load_reynolds_value, terms
from bild_mdo.bild import reynolds_ideal_loading_comp as comp_module
from bild_mdo.bild.reynolds_ideal_loading_comp import ReynoldsIdealLoadingComp, ReynoldsStationComp
from bild_mdo.bild.reynolds_ideal_loading_solve import solve_point

# Midpoints of 12 equal annuli from r/R = 0.2 put station 4 at r/R = 0.2 + 4.5 * 0.8/12 = 0.5 (hand derivation).
NR_REF = 12
REF_STATION = 4
OPERATING = {"hover": [0.0, 0.0, 0.0], "cruise": [10.0, 25.0, 40.0]}
FIELDS = ("r1", "r2", "r3", "n_tot", "d_tot", "objective", "eta2", "cl", "cd", "load_reynolds")


@pytest.fixture(autouse=True)
def _quiet():
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*Reynolds numbers outside the tabulated range")
        yield


def _flow(chord_form, **changes):
    values = dict(lam=np.array([8.0, 12.0, 15.0, 20.0]), v_axial=np.array([0.0, 10.0, 30.0, 0.0]),
                  v_theta=np.array([60.0, 110.0, 150.0, 190.0]), r=np.array([0.4, 0.7, 1.0, 1.3]),
                  radius=np.full(4, 1.5), hub_radius=np.full(4, 0.2), rho=np.full(4, 1.1), mu=np.full(4, 1.8e-5))
    values.update(changes)
    return Flow(**values, num_blades=3, loss_model="tip_hub", chord_form=chord_form)


STATE = {"phi": np.array([0.0, 10.0 / 110.0, 0.2, 0.0]) + 0.08, "alpha": np.full(4, 0.08),
         "re": np.array([1.5e5, 3e5, 6e5, 9e5])}


@pytest.mark.parametrize("chord_form", ["thrust", "torque"])
def test_residual_partials_with_respect_to_the_inputs_match_complex_step(chord_form):
    polar = default_polar()
    flow = _flow(chord_form)
    item = terms(polar, STATE["phi"], STATE["alpha"], STATE["re"], flow)
    step = 1e-30
    for name in INPUTS:
        perturbed = flow._replace(**{name: getattr(flow, name) + 1j * step})
        item_c = terms(polar, STATE["phi"], STATE["alpha"], STATE["re"], perturbed)
        for field in FIELDS:
            exact = np.broadcast_to(getattr(item, field).partial(name), (4,))
            np.testing.assert_allclose(exact, np.imag(getattr(item_c, field).v) / step, rtol=1e-9,
                                       atol=1e-12 * np.max(np.abs(getattr(item, field).v)), err_msg=f"{field}/{name}")


@pytest.mark.parametrize("chord_form", ["thrust", "torque"])
def test_residual_partials_with_respect_to_the_states_match_central_differences(chord_form):
    # The polar's first derivatives are real under complex step, so the states are checked by central differences
    # (step 1e-6 relative; the surrogate is a spline whose third derivatives jump: measured agreement 2e-6, so
    # rtol 1e-5).
    polar = default_polar()
    flow = _flow(chord_form)
    item = terms(polar, STATE["phi"], STATE["alpha"], STATE["re"], flow)
    for name in STATES:
        h = 1e-6 * (STATE[name] if name == "re" else 1.0)
        up = terms(polar, **{"phi": STATE["phi"], "alpha": STATE["alpha"], "reynolds": STATE["re"],
                             **({name if name != "re" else "reynolds": STATE[name] + h})}, flow=flow)
        down = terms(polar, **{"phi": STATE["phi"], "alpha": STATE["alpha"], "reynolds": STATE["re"],
                               **({name if name != "re" else "reynolds": STATE[name] - h})}, flow=flow)
        for field in FIELDS:
            central = (getattr(up, field).v - getattr(down, field).v) / (2.0 * h)
            scale = np.max(np.abs(getattr(item, field).v)) / (np.max(STATE[name]) if name == "re" else 1.0)
            np.testing.assert_allclose(np.broadcast_to(getattr(item, field).partial(name), (4,)), central,
                                       rtol=1e-5, atol=1e-7 * scale, err_msg=f"{field}/{name}")


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip"])
@pytest.mark.parametrize("chord_form", ["thrust", "torque"])
def test_station_component_partials(chord_form, loss_model):
    nn, nr = 2, 5
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("c", ReynoldsStationComp(num_nodes=nn, num_radial=nr, polar=default_polar(),
                                                      chord_form=chord_form, loss_model=loss_model),
                             promotes=["*"])
    prob.setup(force_alloc_complex=True)
    r = np.linspace(0.35, 1.4, nr)
    for name, value in dict(ideal_loading_constant=[12.0, 15.0], v_axial=[0.0, 20.0], radius=1.5, hub_radius=0.3,
                            rho=1.1, mu=1.75e-5, radii=np.vstack([r, r]),
                            v_theta=np.vstack([80.0 * r, 90.0 * r])).items():
        prob.set_val(name, value)
    prob.run_model()
    assert np.all(prob.get_val("eta2") < 1.0)  # every station loaded: the partials are not trivially zero
    assert_check_partials(prob.check_partials(method="cs", out_stream=None), atol=1e-8, rtol=1e-7)


@pytest.mark.parametrize("chord_form", ["thrust", "torque"])
def test_reference_constant_partials(chord_form):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("c", ReynoldsIdealLoadingComp(num_nodes=3, polar=default_polar(), chord_form=chord_form),
                             promotes=["*"])
    prob.setup(force_alloc_complex=True)
    for name, value in dict(phi_ref=[0.12, 0.2, 0.45], alpha_star_ref=[0.05, 0.08, 0.1],
                            reynolds_ref=[2e5, 4e5, 8e5], v_axial=[0.0, 10.0, 30.0], v_theta_ref=[60.0, 70.0, 80.0],
                            ref_radius=[0.75, 0.7, 0.6], radius=1.5, hub_radius=0.3, rho=1.1, mu=1.75e-5).items():
        prob.set_val(name, value)
    prob.run_model()
    assert_check_partials(prob.check_partials(method="cs", out_stream=None), atol=1e-8, rtol=1e-7)


def _problem(kind, complex_step=False, mode="auto", num_radial=NR_REF, num_nodes=3, ideal_loading="exact",
             ref_chord=(0.1, 0.2, 0.3), **options):
    prob = om.Problem(BILDGroup(num_nodes=num_nodes, num_radial=num_radial, section_point="local",
                                ideal_loading=ideal_loading, **options), reports=False)
    prob.setup(mode=mode, force_alloc_complex=complex_step)
    values = dict(v_axial=OPERATING[kind], ref_chord=list(ref_chord), rpm=[800.0, 900.0, 1000.0],
                  altitude=[0.0, 1000.0, 2500.0])
    for name, value in values.items():
        prob.set_val(name, value[:num_nodes] if num_nodes < 3 else value)
    prob.run_model()
    return prob


def test_reynolds_independent_polar_gives_the_exact_loading(kind):
    # With no Re dependence s_Re = 0, so kappa = 0 and every station solves the exact loading at the max-L/D point.
    polar = sweep_polar("naca4412@re=1e6")
    aware = _problem(kind, polar=polar)
    reference = om.Problem(BILDGroup(num_nodes=3, num_radial=NR_REF, polar=polar, ideal_loading="exact"),
                           reports=False)
    reference.setup()
    for name, value in dict(v_axial=OPERATING[kind], ref_chord=[0.1, 0.2, 0.3], rpm=[800.0, 900.0, 1000.0],
                            altitude=[0.0, 1000.0, 2500.0]).items():
        reference.set_val(name, value)
    reference.run_model()
    for name in ("chord", "twist", "thrust", "torque", "energy_loss"):
        np.testing.assert_allclose(aware.get_val(name), reference.get_val(name), rtol=1e-9, atol=1e-12)


def test_every_station_is_the_lowest_minimum_of_its_annulus():
    # The definition: at the design's lambda each loaded station minimises F (e - lambda t) over phi with its
    # own section point.  Brute force: 300 angles per station, each with the lowest cd/cl of its path made
    # self-consistent in Q by ten fixed-point passes; no grid point may beat the design (to the grid's
    # resolution, 1e-5 relative).  Hover at 3000 m with a small chord: sections at Re 1e4-1e5, where the
    # NACA 4412 has two nearly equal minima of cd/cl along the path.
    polar = default_polar()
    prob = om.Problem(BILDGroup(num_nodes=1, num_radial=10, section_point="local", ideal_loading="exact"),
                      reports=False)
    prob.setup()
    for name, value in dict(v_axial=0.0, radius=0.5, rpm=800.0, altitude=3000.0, ref_chord=0.08).items():
        prob.set_val(name, value)
    prob.run_model()
    lam = prob.get_val("ideal_loading_constant")[0]
    n = 10
    flow = Flow(lam=np.full(n, lam), v_axial=np.zeros(n), v_theta=prob.get_val("v_theta")[0],
                r=prob.get_val("radii")[0], radius=np.full(n, 0.5), hub_radius=np.full(n, 0.1),
                rho=np.full(n, prob.get_val("rho")[0]), mu=np.full(n, prob.get_val("mu")[0]), num_blades=3,
                loss_model="tip_hub", chord_form="thrust")
    design = terms(polar, prob.get_val("phi")[0], prob.get_val("alpha_star")[0],
                   np.maximum(prob.get_val("reynolds")[0], 1.0), flow)
    loaded = prob.get_val("eta2")[0] < 1.0
    design_objective = np.where(loaded, design.objective.v, 0.0)
    k = 300
    phi = np.linspace(0.002, 0.5, k)
    grid = flow._replace(**{name: np.repeat(getattr(flow, name), k) for name in Flow._fields[:8]})
    phi_all = np.tile(phi, n)
    ratio = np.full(phi_all.shape, 0.02)
    for _ in range(10):
        load = load_reynolds_value(phi_all, ratio, grid)
        usable = np.isfinite(load) & (load > 1e3)
        point = solve_local_point(polar, phi_all[usable], load[usable])
        ratio[usable] = point.cd / point.cl
    ring = annulus(phi_all, grid.v_axial, grid.v_theta, ratio)
    f = prandtl_loss_jet(phi_all, grid.r, grid.radius, grid.hub_radius, 3, "tip_hub").F
    objective = np.where(usable, f * (ring.e - lam * ring.t), np.inf).reshape(n, k)
    best = np.minimum(objective.min(axis=1), 0.0)
    assert np.all(design_objective <= best + 1e-5 * np.abs(best))
    assert np.sum(loaded) >= 8


def test_design_does_not_depend_on_the_batch(kind):
    # A feasible node's outputs do not depend on the other nodes (each station is solved on its own).
    batch = _problem(kind)
    for node in range(3):
        alone = om.Problem(BILDGroup(num_nodes=1, num_radial=NR_REF, section_point="local", ideal_loading="exact"),
                           reports=False)
        alone.setup()
        for name, value in dict(v_axial=OPERATING[kind], ref_chord=[0.1, 0.2, 0.3], rpm=[800.0, 900.0, 1000.0],
                                altitude=[0.0, 1000.0, 2500.0]).items():
            alone.set_val(name, value[node])
        alone.run_model()
        for name in ("chord", "twist"):
            np.testing.assert_allclose(alone.get_val(name)[0], batch.get_val(name)[node], rtol=1e-10, atol=1e-14)


def test_a_rerun_resolves_only_the_designs_whose_inputs_changed(kind, monkeypatch):
    # Each station is solved on its own given lambda, so a design whose inputs did not change keeps its states:
    # after changing node 1's ref_chord, only node 1's stations are solved (the other nodes' lambda moves by
    # round-off, from the reference station's solve), and every output equals a fresh problem's at the new
    # inputs, as a node alone equals it in its batch.
    prob = _problem(kind)
    solved = []
    real_solve = comp_module.solve_stations
    monkeypatch.setattr(comp_module, "solve_stations", lambda polar, flow: solved.append(flow.r.size)
                        or real_solve(polar, flow))
    prob.set_val("ref_chord", [0.1, 0.25, 0.3])
    prob.run_model()
    assert solved == [NR_REF]
    monkeypatch.undo()
    fresh = _problem(kind, ref_chord=(0.1, 0.25, 0.3))
    for name in ("chord", "twist", "thrust", "torque"):
        np.testing.assert_allclose(prob.get_val(name), fresh.get_val(name), rtol=1e-10, atol=1e-14)


def test_a_trial_angle_at_zero_load_fails_quietly():
    # At the unloaded inflow angle the annulus carries no load (hand derivation: t = q = 0 there), so the load
    # Reynolds number's logarithmic derivatives divide by zero.  The inner solve reports failure (the bracketed
    # solve then treats the angle as a failed evaluation) without a floating-point warning reaching the user.
    flow = _flow("thrust")
    with np.errstate(all="raise"):
        _, _, ok = solve_point(default_polar(), unloaded_angle(flow.v_axial, flow.v_theta), STATE["alpha"],
                               STATE["re"], flow)
    assert not ok.any()


def _station_problem(lam):
    r = np.linspace(0.35, 1.4, 5)
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("c", ReynoldsStationComp(num_nodes=2, num_radial=5, polar=default_polar()),
                             promotes=["*"])
    prob.setup()
    for name, value in dict(ideal_loading_constant=lam, v_axial=[0.0, 20.0], radius=1.5, hub_radius=0.3, rho=1.1,
                            mu=1.75e-5, radii=np.vstack([r, r]), v_theta=np.vstack([80.0 * r, 90.0 * r])).items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


def test_inputs_moved_by_round_off_keep_the_states_corrected_by_newton(monkeypatch):
    # Inputs within 1e-12 (relative) of the last call's: no station is solved again; the kept states take one
    # Newton step on the residuals, so they solve them at the new inputs as a fresh solve does, to round-off
    # (O(1e-24) from the step; measured: 1.4e-14 relative in alpha_star, against 5.6e-14 without the step).
    lam = np.array([12.0, 15.0])
    prob = _station_problem(lam)
    solved = []
    real_solve = comp_module.solve_stations
    monkeypatch.setattr(comp_module, "solve_stations", lambda polar, flow: solved.append(flow.r.size)
                        or real_solve(polar, flow))
    moved = lam * (1.0 + 5e-13)
    prob.set_val("ideal_loading_constant", moved)
    prob.run_model()
    assert solved == []
    monkeypatch.undo()
    fresh = _station_problem(moved)
    for name in ("eta2", "alpha_star", "reynolds", "load_reynolds"):
        np.testing.assert_allclose(prob.get_val(name), fresh.get_val(name), rtol=3e-14)


def test_a_grid_angle_without_a_local_point_leaves_the_other_stations_alone(monkeypatch):
    # solve_local_point raises for a whole batch when one path has no minimum; the grid isolates such an
    # element (utils.batches.isolate_failures) and solves every station as before.  Stand-in: the first grid
    # angle of station 0 "has no minimum".
    import bild_mdo.bild.reynolds_ideal_loading_solve as solve

    polar = default_polar()
    flow = _flow("thrust")
    before = solve.solve_stations(polar, flow)
    real = solve.solve_local_point
    first_angle = solve.unloaded_angle(flow.v_axial[0], flow.v_theta[0]) + solve.GRID_FRACTIONS[0] * (
        solve.overloaded_angle(flow.v_axial[0], flow.v_theta[0], 0.02) - solve.unloaded_angle(flow.v_axial[0],
                                                                                              flow.v_theta[0]))

    raised = []

    def no_minimum_at_one_angle(polar_, phi, *args, **kwargs):
        if np.any(np.isclose(phi, first_angle, rtol=0.0, atol=1e-15)):
            raised.append(phi.size)
            raise ValueError("local section point: no interior minimum (stand-in)")
        return real(polar_, phi, *args, **kwargs)

    monkeypatch.setattr(solve, "solve_local_point", no_minimum_at_one_angle)
    after = solve.solve_stations(polar, flow)
    assert raised and raised[-1] == 1  # bisected down to the one element
    assert np.all(before.status == 0) and np.all(after.status == 0)
    for field in ("phi", "alpha", "reynolds"):
        np.testing.assert_array_equal(getattr(after, field)[1:], getattr(before, field)[1:])
