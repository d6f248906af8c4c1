"""The compiled partials of the load-path model (partials_kernel) against the jets of load_path_model.

Both local-point variants: the Reynolds-aware exact loading (states phi, x0) and the paper's loading with the
local point (state x0, phi the quartic's), and the reference station on the table.

Source: the jets (:class:`~bild_mdo.utils.jet.Jet`, forward-mode derivatives of the same model, themselves
checked against complex step in test_local_stations and test_local_reference) and
:func:`~bild_mdo.bem.prandtl.prandtl_loss_jet` for Prandtl's factor.  The compiled model is a second,
independent writing of the derivatives, so agreement to round-off checks both.
"""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.airfoil.load_path_table import load_path_table
from bild_mdo.bem.prandtl import prandtl_loss_jet
from bild_mdo.bild.variants.local_paper.solve import LOADED as PAPER_LOADED
from bild_mdo.bild.variants.local_paper.solve import paper_jets
from bild_mdo.bild.variants.local_paper.solve import solve_stations as solve_paper
from bild_mdo.bild.variants.local_point.kernels import LOSS_CODES
from bild_mdo.bild.variants.local_point.load_path_model import INPUTS, section_jets, station_jets, take
from bild_mdo.bild.variants.local_point.partials_kernel import state_totals
from bild_mdo.bild.variants.local_point.prandtl_kernels import prandtl_partials_one
from bild_mdo.bild.variants.local_point.reference_solve import ReferenceFlow, solve_reference, table_jets
from bild_mdo.bild.variants.local_point.station import OUTPUTS
from bild_mdo.bild.variants.reference_point.reference_airfoil import default_polar
from bild_mdo.bild.variants.reynolds_exact.solve import LOADED, solve_stations
from bild_mdo.utils.jet import eliminate, jacobian
from tests.bild.variants.test_local_stations import _flow

_PRANDTL_FIELDS = ("F", "dF_dphi", "d2F_dphi2", "dF_dr", "d2F_dphi_dr", "dF_dradius", "d2F_dphi_dradius",
                   "dF_dhub_radius", "d2F_dphi_dhub_radius")


def _relative_error(value, reference):
    """Largest error relative to the largest magnitude of the reference along the first axis (per partial)."""
    scale = np.maximum(np.max(np.abs(reference), axis=0, keepdims=True), 1e-300)
    return np.max(np.abs(value - reference) / scale)


@pytest.mark.parametrize("loss_model", ["none", "tip", "tip_hub"])
def test_prandtl_partials_are_those_of_the_jet(loss_model):
    # Angles from 0.02 to 1.4 rad and radii over the whole span: every form of the factor (series, acos, atan).
    phi = np.linspace(0.02, 1.4, 37)
    r = np.linspace(0.31, 1.499, 37)[::-1]
    jet = prandtl_loss_jet(phi, r, 1.5, 0.3, 3, loss_model)
    compiled = np.array([prandtl_partials_one(np.sin(p), np.cos(p), x, 1.5, 0.3, 3, LOSS_CODES[loss_model])
                         for p, x in zip(phi, r)])
    reference = np.column_stack([np.broadcast_to(getattr(jet, name), phi.shape) for name in _PRANDTL_FIELDS])
    assert _relative_error(compiled, reference) < 1e-12


@pytest.mark.parametrize("loss_model", ["none", "tip", "tip_hub"])
@pytest.mark.parametrize("chord_form", ["thrust", "torque"])
def test_station_totals_are_those_of_the_jets(chord_form, loss_model):
    table = load_path_table(default_polar())
    flow = _flow(60, chord_form, loss_model)
    sol = solve_stations(table, flow)
    at = np.flatnonzero(sol.status == LOADED)
    assert at.size > 40
    sub = take(flow, at)
    states, label = (sol.phi[at], sol.x0[at]), sol.label[at]
    # The jets' elimination, as LocalStationComp._linear does it.
    jets = station_jets(table, sub, *states, label)
    residuals, names = (jets.r1, jets.r2), ("phi", "x0")
    outputs = {"eta2": jets.eta2, "alpha_star": jets.alpha, "cl_star": jets.cl, "cd_star": jets.cd,
               "reynolds": jets.reynolds, "load_reynolds": jets.load_reynolds}
    sens = -np.linalg.solve(jacobian(residuals, names, at.size), jacobian(residuals, INPUTS, at.size))
    reference = eliminate((outputs[name] for name in OUTPUTS), names, INPUTS, sens, at.size)
    points = np.column_stack([*states, *(getattr(sub, name) for name in INPUTS), np.ones(at.size)])
    compiled = state_totals(table, points, label, sub.num_blades, chord_form == "torque", loss_model, ("r1", "r2"),
                            INPUTS, OUTPUTS)
    assert np.all(np.isfinite(compiled))
    assert _relative_error(compiled, reference) < 1e-10


@pytest.mark.parametrize("chord_form", ["thrust", "torque"])
def test_reference_totals_are_those_of_the_jets(chord_form):
    # Reference states on the table at Re_ref 1e5 ... 1.5e6 (the gap near 2.15e5 has its own jets).
    n = 24
    v_axial, v_theta = np.where(np.arange(n) % 3 == 0, 0.0, np.linspace(5.0, 40.0, n)), np.linspace(45.0, 90.0, n)
    rho, mu = np.full(n, 1.1), np.full(n, 1.75e-5)
    chord = np.geomspace(1e5, 1.5e6, n) * mu / (rho * np.hypot(v_axial, v_theta))
    ref = ReferenceFlow(v_axial, v_theta, np.linspace(0.5, 1.0, n), chord, np.full(n, 1.5), np.full(n, 0.3), rho,
                        mu, num_blades=3, loss_model="tip_hub", chord_form=chord_form)
    table = load_path_table(default_polar())
    sol = solve_reference(table, default_polar(), ref)
    at = np.flatnonzero(sol.on_table & sol.ok)
    assert at.size > 18
    sub = ReferenceFlow(*(field[at] for field in ref[:8]), *ref[8:])
    residuals, (n_tot, d_tot), alpha, cl, cd, load = table_jets(table, sub, sol.phi[at], sol.x0[at], sol.label[at])
    keys = ["v_axial", "v_theta", "r", "chord", "radius", "hub_radius", "rho", "mu"]
    sens = -np.linalg.solve(jacobian(residuals, ("phi", "x0"), at.size), jacobian(residuals, keys, at.size))
    reference = eliminate([alpha, cl, cd, load, n_tot / d_tot], ("phi", "x0"), keys, sens, at.size)
    points = np.column_stack([sol.phi[at], sol.x0[at], np.zeros(at.size), sub.v_axial, sub.v_theta, sub.r,
                              sub.radius, sub.hub_radius, sub.rho, sub.mu, sub.chord])
    compiled = state_totals(table, points, sol.label[at], 3, chord_form == "torque", "tip_hub", ("r2", "r_ell"), keys,
                            ("alpha_star", "cl_star", "cd_star", "load_reynolds", "lambda_ratio"))
    assert _relative_error(compiled, reference) < 1e-10


@pytest.mark.parametrize("loss_model", ["tip", "tip_hub"])
@pytest.mark.parametrize("chord_form", ["thrust", "torque"])
def test_paper_loading_station_totals_are_those_of_the_jets(chord_form, loss_model):
    # The local point with the paper's loading: one state x0, phi and eta2 from the quartic (27) at s(x0).
    table = load_path_table(default_polar())
    flow = _flow(60, chord_form, loss_model)
    sol = solve_paper(table, flow)
    at = np.flatnonzero(sol.status == PAPER_LOADED)
    assert at.size > 30
    sub, x0, label = take(flow, at), sol.x0[at], sol.label[at]
    jets = paper_jets(table, sub, x0, label)
    alpha, cl, cd, reynolds, load = section_jets(table, label, jets.x0, jets.s, jets.ring.tau)
    outputs = {"eta2": jets.eta2, "alpha_star": alpha, "cl_star": cl, "cd_star": cd, "reynolds": reynolds,
               "load_reynolds": jets.ring.p * load}
    sens = -np.linalg.solve(jacobian((jets.r,), ("x0",), at.size), jacobian((jets.r,), INPUTS, at.size))
    reference = eliminate((outputs[name] for name in OUTPUTS), ("x0",), INPUTS, sens, at.size)
    points = np.column_stack([np.zeros(at.size), x0, *(getattr(sub, name) for name in INPUTS), np.ones(at.size)])
    compiled = state_totals(table, points, label, sub.num_blades, chord_form == "torque", loss_model, ("r2",), INPUTS,
                            OUTPUTS, paper=True)
    assert np.all(np.isfinite(compiled))
    assert _relative_error(compiled, reference) < 1e-10


def test_partials_that_are_not_finite_raise():
    # A state off its sheet (x0 beyond the sheet's cover) has no partials: one clear error, not silent NaN; a
    # station the caller replaces (required False) is let through.
    table = load_path_table(default_polar())
    flow = _flow(20)
    sol = solve_stations(table, flow)
    at = np.flatnonzero(sol.status == LOADED)[:3]
    sub = take(flow, at)
    points = np.column_stack([sol.phi[at], sol.x0[at], *(getattr(sub, name) for name in INPUTS), np.ones(at.size)])
    points[1, 1] = table.x_last + 10.0
    args = (table, points, sol.label[at], sub.num_blades, False, "tip_hub", ("r1", "r2"), INPUTS, OUTPUTS)
    with pytest.raises(om.AnalysisError, match="not finite .1 of 3 stations"):
        state_totals(*args)
    totals = state_totals(*args, required=np.array([True, False, True]))
    assert np.all(np.isfinite(totals[[0, 2]])) and not np.all(np.isfinite(totals[1]))
