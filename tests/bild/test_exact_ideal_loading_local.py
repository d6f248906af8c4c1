"""BILDGroup(ideal_loading='exact', section_point='local'): each station's own section point in the exact condition."""
import warnings

import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials

from bild_mdo.airfoil.text import sweep_polar
from bild_mdo.bem.analyze import analyze_rotor
from bild_mdo.bild import BILDGroup
from bild_mdo.bild.annulus_stationarity import stationarity
from bild_mdo.bild.reference_airfoil import default_polar
from bild_mdo.results.design import design_rotor
from bild_mdo.utils.testing import assert_totals_match

NR_REF, REF_STATION = 12, 4  # r/R = 0.2 + 4.5 * 0.8/12 = 0.5 (hand derivation)
OPERATING = {"hover": [0.0, 0.0, 0.0], "cruise": [10.0, 25.0, 40.0]}


@pytest.fixture(autouse=True)
def _quiet():
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*Reynolds numbers outside the tabulated range")
        yield


def _problem(kind, section_point="local", complex_step=False, mode="auto", num_radial=NR_REF, **options):
    prob = om.Problem(BILDGroup(num_nodes=3, num_radial=num_radial, section_point=section_point,
                                ideal_loading="exact", **options), reports=False)
    prob.setup(mode=mode, force_alloc_complex=complex_step)
    for name, value in dict(v_axial=OPERATING[kind], ref_chord=[0.1, 0.2, 0.3], rpm=[800.0, 900.0, 1000.0],
                            altitude=[0.0, 1000.0, 2500.0]).items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


def test_chord_at_reference_radius_and_equal_marginal_cost(kind):
    # The reference station's own point and lambda = G(phi_ref) give a station at r_ref the chord c_ref; every
    # station's (F e)'/(F t)' with its own cd/cl equals lambda.
    prob = _problem(kind)
    np.testing.assert_allclose(prob.get_val("chord")[:, REF_STATION], [0.1, 0.2, 0.3], rtol=1e-9)
    ratio = prob.get_val("cd_star") / prob.get_val("cl_star")
    terms = stationarity(prob.get_val("phi"), prob.get_val("v_axial")[:, None], prob.get_val("v_theta"), ratio,
                         prob.get_val("radii"), prob.get_val("radius")[:, None], prob.get_val("hub_radius")[:, None],
                         3, "tip_hub")
    lam = np.broadcast_to(prob.get_val("ideal_loading_constant")[:, None], ratio.shape)
    np.testing.assert_allclose(terms.N / terms.D, lam, rtol=1e-8)


def test_bem_analysis_reproduces_the_design(kind):
    polar = default_polar()
    prob = _problem(kind)
    result = analyze_rotor(prob.get_val("chord"), prob.get_val("twist"), prob.get_val("radius"),
                           prob.get_val("hub_radius"), prob.get_val("rpm"), prob.get_val("v_axial"), 3, polar,
                           altitude=prob.get_val("altitude"))
    np.testing.assert_allclose(result.thrust, prob.get_val("thrust"), rtol=1e-6)
    np.testing.assert_allclose(result.torque, prob.get_val("torque"), rtol=1e-6)


def test_reynolds_independent_polar_gives_the_reference_design(kind):
    polar = sweep_polar("naca4412@re=1e6")
    local = _problem(kind, polar=polar)
    reference = _problem(kind, section_point="reference", polar=polar)
    for name in ("chord", "twist", "thrust", "energy_loss"):
        np.testing.assert_allclose(local.get_val(name), reference.get_val(name), rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("mode", ["fwd", "rev"])
def test_totals_complex_step(kind, mode):
    prob = _problem(kind, complex_step=True, mode=mode, num_radial=5)
    data = prob.check_totals(of=["thrust", "torque", "energy_loss", "chord", "twist"],
                             wrt=["v_axial", "rpm", "radius", "ref_chord", "ref_radius_ratio", "altitude"],
                             method="cs", out_stream=None)
    assert_totals_match(data, atol=1e-10, rtol=1e-6)
    assert_no_approx_partials(prob.model, method="cs")


def test_inboard_station_that_cannot_be_loaded_gets_zero_chord():
    # At J = 1.5 with the Reynolds-dependent polar the hub station's own point (low Re) costs more energy per
    # thrust at zero load than lambda: the optimum with chord >= 0 leaves it unloaded (the paper's loading
    # would load it; here it is neither infeasible nor windmilling).  BEM of the blade reproduces the loads.
    polar = default_polar()
    design = design_rotor(advance_ratio=1.5, ideal_loading="exact", section_point="local", num_radial=30,
                          airfoil=polar)
    chord = np.ravel(design.chord)
    assert chord[0] == 0.0 and np.all(chord[1:] > 0.0)
    assert np.ravel(design.values["eta2"])[0] == 1.0
    result = analyze_rotor(np.maximum(chord, 1e-9), np.ravel(design.twist), design.radius, 0.2 * design.radius,
                           design.rpm, design.v_axial, 3, polar)
    assert float(np.ravel(result.thrust)[0]) == pytest.approx(design.thrust, rel=1e-6)
