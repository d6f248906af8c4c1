"""The exact ideal loading (ideal_loading='exact'): component partials, group totals and the invariants."""
import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.bem.analyze import analyze_rotor
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bild import BILDGroup
from bild_mdo.bild.annulus_stationarity import stationarity
from bild_mdo.bild.variants.paper.eta2 import Eta2Comp
from bild_mdo.bild.variants.exact.exact_eta2 import ExactEta2Comp
from bild_mdo.bild.variants.exact.exact_ideal_loading import ExactIdealLoadingComp
from bild_mdo.utils.testing import check_component_partials, check_group_totals
from tests.bild.conftest import NN, NR, state

NR_REF, REF_STATION = 12, 4  # r/R = 0.2 + 4.5 * 0.8/12 = 0.5 (hand derivation)
OPERATING = {"hover": [0.0, 0.0, 0.0], "cruise": [10.0, 25.0, 40.0]}


def _reference_values(kind):
    s = state(kind)
    # Reference inflow angles of moderately loaded reference stations (between phi0 and the maximum thrust).
    phi0 = np.arctan2(s["v_axial"], s["v_theta_ref"])
    return dict(phi_ref=phi0 + np.array([0.06, 0.08, 0.05]), **{name: s[name] for name in (
        "v_axial", "v_theta_ref", "ref_radius", "radius", "hub_radius", "cl_star", "cd_star")})


def _station_values(kind, lam=(12.0, 15.0, 18.0)):
    s = state(kind)
    return dict(ideal_loading_constant=np.array(lam), **{name: s[name] for name in (
        "v_axial", "v_theta", "radii", "radius", "hub_radius", "cl_star", "cd_star")})


@pytest.mark.parametrize("loss_model", LOSS_MODELS)
def test_ideal_loading_partials(kind, loss_model):
    prob = check_component_partials(ExactIdealLoadingComp(num_nodes=NN, loss_model=loss_model),
                                    _reference_values(kind))
    assert np.all(prob.get_val("ideal_loading_constant") > 0.0)


@pytest.mark.parametrize("loss_model", LOSS_MODELS)
def test_eta2_partials(kind, loss_model):
    prob = check_component_partials(ExactEta2Comp(num_nodes=NN, num_radial=NR, loss_model=loss_model),
                                    _station_values(kind))
    eta2 = prob.get_val("eta2")
    assert np.all((eta2 > 0.5) & (eta2 < 1.0))


def test_eta2_partials_per_station_airfoil_point(kind):
    values = _station_values(kind)
    values["cl_star"] = np.linspace(0.9, 1.2, NN * NR).reshape(NN, NR)
    values["cd_star"] = np.linspace(0.009, 0.014, NN * NR).reshape(NN, NR)
    check_component_partials(ExactEta2Comp(num_nodes=NN, num_radial=NR, varies_along_span=True), values)


def test_unloaded_stations_have_eta2_one_and_zero_partials(kind):
    # A station whose lightest load costs more energy per thrust than lambda (G(phi0) > lambda; in hover
    # G(0+) = V_theta C_d*/C_l*) carries no load; node 0's lambda = 0.05 m/s unloads every station.
    values = _station_values(kind, lam=(0.05, 15.0, 18.0))
    prob = check_component_partials(ExactEta2Comp(num_nodes=NN, num_radial=NR), values)
    np.testing.assert_array_equal(prob.get_val("eta2")[0], 1.0)


def test_reference_station_that_produces_no_thrust_is_refused():
    values = _reference_values("cruise")
    values["phi_ref"] = np.arctan2(values["v_axial"], values["v_theta_ref"]) - 0.01
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("c", ExactIdealLoadingComp(num_nodes=NN), promotes=["*"])
    prob.setup()
    for name, value in values.items():
        prob.set_val(name, value)
    with pytest.raises(om.AnalysisError, match="must produce thrust"):
        prob.run_model()


def _problem(kind, num_radial=NR_REF, polar=None, values=None, **options):
    prob = om.Problem(BILDGroup(num_nodes=3, num_radial=num_radial, polar=polar, ideal_loading="exact", **options),
                      reports=False)
    prob.setup()
    settings = dict(v_axial=OPERATING[kind], ref_chord=[0.1, 0.2, 0.3], rpm=[800.0, 900.0, 1000.0],
                    altitude=[0.0, 1000.0, 2500.0], **(values or {}))
    for name, value in settings.items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


def test_group_totals(kind):
    values = dict(v_axial=OPERATING[kind], ref_chord=[0.1, 0.2, 0.3], rpm=[800.0, 900.0, 1000.0],
                  altitude=[0.0, 1000.0, 2500.0])
    check_group_totals(lambda: BILDGroup(num_nodes=3, num_radial=NR_REF, ideal_loading="exact"),
                       of=["thrust", "torque", "energy_loss", "figure_of_merit", "chord", "twist"],
                       wrt=["v_axial", "rpm", "radius", "ref_chord", "ref_radius_ratio", "hub_radius_ratio",
                            "altitude"], values=values, atol=1e-10, rtol=1e-6)


def test_group_totals_thrust_target():
    values = dict(v_axial=[0.0, 10.0, 25.0], thrust_target=[800.0, 1200.0, 1500.0], rpm=[800.0, 900.0, 1000.0])
    check_group_totals(lambda: BILDGroup(num_nodes=3, num_radial=NR_REF, ideal_loading="exact", thrust_target=True),
                       of=["ref_chord", "energy_loss", "chord", "twist"], wrt=["v_axial", "rpm", "thrust_target"],
                       values=values, atol=1e-10, rtol=1e-6)


def test_default_is_the_paper_method():
    prob = om.Problem(BILDGroup(num_nodes=2, num_radial=5), reports=False)
    prob.setup()
    assert prob.model.options["ideal_loading"] == "paper"
    assert isinstance(prob.model.eta2, Eta2Comp)
    exact = _problem("hover", num_radial=5)
    assert isinstance(exact.model.eta2, ExactEta2Comp)
    assert_no_approx_partials(exact.model, method="cs")
    assert_no_approx_partials(exact.model, method="fd")


@pytest.mark.parametrize("num_radial, station", [(NR_REF, REF_STATION), (20, 7)])
def test_chord_at_reference_radius_is_reference_chord(kind, num_radial, station):
    # Invariant of Alg. 1 kept by the exact loading: lambda = G(phi_ref), and G is monotone on the loaded
    # branch, so the station at r_ref has phi = phi_ref and the chord c_ref of the BEM solve there.
    prob = _problem(kind, num_radial=num_radial)
    np.testing.assert_allclose(prob.get_val("radii")[:, station] / prob.get_val("radius"), 0.5, rtol=1e-14)
    np.testing.assert_allclose(prob.get_val("phi")[:, station], prob.get_val("phi_ref"), rtol=1e-10)
    np.testing.assert_allclose(prob.get_val("chord")[:, station], [0.1, 0.2, 0.3], rtol=1e-9)


def test_every_station_has_the_same_marginal_energy_per_thrust(kind):
    # The defining property: (F e)'/(F t)' at each station's phi (its own BEM curve at alpha*) equals lambda.
    prob = _problem(kind)
    cl, cd = prob.get_val("cl_star")[:, None], prob.get_val("cd_star")[:, None]
    v_theta = prob.get_val("v_theta")
    terms = stationarity(prob.get_val("phi"), prob.get_val("v_axial")[:, None], v_theta, cd / cl,
                         prob.get_val("radii"), prob.get_val("radius")[:, None], prob.get_val("hub_radius")[:, None],
                         3, "tip_hub")
    lam = prob.get_val("ideal_loading_constant")[:, None]
    np.testing.assert_allclose(terms.N / terms.D, np.broadcast_to(lam, v_theta.shape), rtol=1e-9)


def test_bem_analysis_reproduces_the_design(kind):
    # With a Reynolds-independent polar every blade element of the design works at alpha*, so BEM returns the
    # design's own loads (the same invariant as the paper's chain).
    polar = AnalyticPolar()
    prob = _problem(kind, polar=polar)
    result = analyze_rotor(prob.get_val("chord"), prob.get_val("twist"), prob.get_val("radius"),
                           prob.get_val("hub_radius"), prob.get_val("rpm"), prob.get_val("v_axial"), 3, polar,
                           altitude=prob.get_val("altitude"))
    np.testing.assert_allclose(result.thrust, prob.get_val("thrust"), rtol=1e-6)
    np.testing.assert_allclose(result.torque, prob.get_val("torque"), rtol=1e-6)
