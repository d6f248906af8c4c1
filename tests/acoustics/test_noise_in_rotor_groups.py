"""The noise option of BILDGroup, BEMAnalysisGroup and MultipointRotorGroup: wiring and exact totals."""
import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials

from bild_mdo import BEMAnalysisGroup, BILDGroup, MultipointRotorGroup
from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.airfoil.spanwise import SpanwisePolar
from bild_mdo.utils.testing import assert_totals_match

# A hover and a climb design; observers below the rotor, in the disc plane side, and ahead of it.
OBSERVERS = np.array([[-15.0, 0.0, 4.0], [-8.0, 9.0, 0.0], [3.0, -10.0, 0.0]])
DESIGN = dict(v_axial=[0.0, 4.0], rpm=[900.0, 1000.0], radius=[1.4, 1.5], ref_chord=[0.12, 0.1])
pytestmark = pytest.mark.filterwarnings("ignore:(?s).*zero derivatives")


def _run(group, values, mode="fwd"):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("rotor", group, promotes=["*"])
    prob.setup(force_alloc_complex=True, mode=mode)
    for name, value in values.items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


def _spanwise():
    thick, thin = AnalyticPolar(), AnalyticPolar(cl0=0.35)
    thick.thickness_ratio, thin.thickness_ratio = 0.18, 0.1
    return SpanwisePolar([thick, thin], [0.2, 1.0])


def test_without_observers_the_groups_are_unchanged():
    """noise_observers=None (default) adds nothing: no subsystem, no noise variable."""
    for group in (BILDGroup(num_nodes=1, num_radial=4), BEMAnalysisGroup(num_nodes=1, num_radial=4,
                                                                       polar=AnalyticPolar())):
        prob = _run(group, {})
        names = {meta["prom_name"] for meta in prob.model.get_io_metadata().values()}
        assert not names & {"oaspl", "oaspl_dba", "observer_position", "thickness_ratio", "alpha_star_stations"}
        assert prob.model.rotor._get_subsystem("noise") is None


@pytest.mark.parametrize("mode", ["fwd", "rev"])
def test_bild_totals_into_oaspl_dba(mode):
    """d oaspl_dba / d (v_axial, rpm, radius, ref_chord) through the BILD chain, every pair against cs."""
    group = BILDGroup(num_nodes=2, num_radial=6, num_blades=2, noise_observers=OBSERVERS, noise_harmonics=4)
    prob = _run(group, DESIGN, mode)
    assert_no_approx_partials(prob.model)
    assert prob.get_val("oaspl_dba").shape == (2, 3)
    np.testing.assert_array_equal(prob.get_val("observer_position")[1], OBSERVERS)
    data = prob.check_totals(of=["oaspl_dba", "oaspl"], wrt=["v_axial", "rpm", "radius", "ref_chord"],
                             method="cs", out_stream=None)
    assert_totals_match(data, atol=1e-8, rtol=1e-7)


@pytest.mark.parametrize("mode", ["fwd", "rev"])
def test_bild_totals_with_a_blunt_trailing_edge(mode):
    """With the bluntness noise on (trailing_edge_thickness > 0, Psi of the option noise_trailing_edge_angle), the
    totals of oaspl_dba, also with respect to the thickness, every pair against cs; and the noise is louder."""
    group = BILDGroup(num_nodes=2, num_radial=6, num_blades=2, noise_observers=OBSERVERS, noise_harmonics=4,
                      noise_trailing_edge_angle=16.0, noise_azimuths=12)
    sharp_prob = _run(group, DESIGN, mode)
    assert sharp_prob.model.rotor.noise.broadband.options["num_azimuth"] == 12
    assert sharp_prob.model.rotor.noise.broadband.options["trailing_edge_angle"] == 16.0
    sharp = _run(BILDGroup(num_nodes=2, num_radial=6, num_blades=2, noise_observers=OBSERVERS, noise_harmonics=4,
                           noise_trailing_edge_angle=16.0), DESIGN, mode).get_val("oaspl")
    thickness = np.array([[1.2e-3] * 6, [0.4e-3] * 3 + [0.8e-3] * 3])
    prob = _run(BILDGroup(num_nodes=2, num_radial=6, num_blades=2, noise_observers=OBSERVERS, noise_harmonics=4,
                          noise_trailing_edge_angle=16.0), dict(DESIGN, trailing_edge_thickness=thickness), mode)
    assert np.all(prob.get_val("oaspl") > sharp)
    data = prob.check_totals(of=["oaspl_dba"], wrt=["v_axial", "rpm", "ref_chord", "trailing_edge_thickness"],
                             method="cs", out_stream=None)
    assert_totals_match(data, atol=1e-8, rtol=1e-7)


def test_bild_stations_see_the_design():
    """The noise group reads BILD's own outputs: alpha = alpha* at every station, BILD's loads and chord."""
    prob = _run(BILDGroup(num_nodes=2, num_radial=6, noise_observers=OBSERVERS), DESIGN)
    np.testing.assert_allclose(prob.get_val("alpha"), np.repeat(prob.get_val("alpha_star")[:, None], 6, 1))
    np.testing.assert_allclose(prob.get_val("rotor.noise.tonal.dthrust_dr"), prob.get_val("dthrust_dr"))
    np.testing.assert_allclose(prob.get_val("noise.thickness_ratio"), 0.12)   # built-in NACA 4412


def test_bild_spanwise_airfoils():
    """Spanwise airfoils: alpha* per station feeds the noise directly; t/c blends 0.18 -> 0.10 along r/R."""
    group = BILDGroup(num_nodes=2, num_radial=5, polar=_spanwise(), noise_observers=OBSERVERS[:2],
                      noise_harmonics=3)
    prob = _run(group, DESIGN)
    np.testing.assert_allclose(prob.get_val("alpha"), prob.get_val("alpha_star"))
    ratio = prob.get_val("noise.thickness_ratio")
    assert np.all(np.diff(ratio, axis=1) < 0) and np.all((ratio > 0.1) & (ratio < 0.18))
    data = prob.check_totals(of=["oaspl_dba"], wrt=["rpm", "radius"], method="cs", out_stream=None)
    assert_totals_match(data, atol=1e-8, rtol=1e-7)


def test_bem_totals_into_oaspl_dba():
    group = BEMAnalysisGroup(num_nodes=2, num_radial=5, polar=AnalyticPolar(), noise_observers=OBSERVERS,
                             noise_harmonics=3, noise_boundary_layer="untripped")
    prob = _run(group, dict(v_axial=[0.0, 3.0], rpm=[1200.0, 1300.0], radius=[1.0, 1.1]))
    assert_no_approx_partials(prob.model)
    data = prob.check_totals(of=["oaspl_dba"], wrt=["v_axial", "rpm", "radius", "chord", "twist"], method="cs",
                             out_stream=None)
    assert_totals_match(data, atol=1e-8, rtol=1e-7)


def test_multipoint_totals_into_oaspl_dba():
    """The blade designed at one condition, its noise at K = 2 analysis conditions, totals w.r.t. the design."""
    group = MultipointRotorGroup(num_nodes=2, num_radial=5, polar=AnalyticPolar(), noise_observers=OBSERVERS,
                                 noise_harmonics=3)
    prob = _run(group, dict(design_rpm=[900.0], v_axial=[0.0, 5.0], rpm=[900.0, 1000.0]), "rev")
    assert prob.get_val("oaspl_dba").shape == (2, 3)
    np.testing.assert_allclose(prob.get_val("noise.chord")[1], prob.get_val("chord")[0])
    assert prob.get_val("trailing_edge_thickness").shape == (2, 5)  # promoted, as in the other groups
    data = prob.check_totals(of=["oaspl_dba"], wrt=["design_rpm", "radius", "ref_chord", "rpm", "v_axial"],
                             method="cs", out_stream=None)
    assert_totals_match(data, atol=1e-8, rtol=1e-7)


def test_bad_observers_option():
    with pytest.raises(ValueError, match="shape"):
        BILDGroup(noise_observers=[[1.0, 2.0]])
