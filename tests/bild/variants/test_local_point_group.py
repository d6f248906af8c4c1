"""BILDGroup(section_point='local'), both loadings: the invariants of the method, exact totals, the reference limit.

Sources: the method's invariants (chord(r_ref) = c_ref; Re = rho W0 c / mu at every station; a BEM analysis of
the blade returns the design's loads; a design does not depend on its batch), complex step (totals), and the
Reynolds-independent limit (a polar frozen at one Reynolds number gives the reference-point design).
"""
import warnings

import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials

from bild_mdo.airfoil.text import sweep_polar
from bild_mdo.bem.analyze import analyze_rotor
from bild_mdo.bild import BILDGroup
from bild_mdo.bild.variants.reference_point.reference_airfoil import default_polar
from bild_mdo.bild.variants.local_paper import station as paper_station
from bild_mdo.bild.variants.reynolds_exact import station as reynolds_station
from bild_mdo.utils.testing import assert_totals_match

# Midpoints of 12 equal annuli from r/R = 0.2 put station 4 at r/R = 0.2 + 4.5 * 0.8/12 = 0.5 (hand derivation).
NR_REF = 12
REF_STATION = 4
OPERATING = {"hover": [0.0, 0.0, 0.0], "cruise": [10.0, 25.0, 40.0]}


@pytest.fixture(autouse=True)
def _quiet():
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=".*Reynolds numbers outside the tabulated range")
        yield


def _problem(kind, section_point="local", complex_step=False, mode="auto", num_radial=NR_REF,
             ref_chord=(0.1, 0.2, 0.3), **options):
    prob = om.Problem(BILDGroup(num_nodes=3, num_radial=num_radial, section_point=section_point, **options),
                      reports=False)
    prob.setup(mode=mode, force_alloc_complex=complex_step)
    for name, value in dict(v_axial=OPERATING[kind], ref_chord=list(ref_chord), rpm=[800.0, 900.0, 1000.0],
                            altitude=[0.0, 1000.0, 2500.0]).items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


LOADINGS = pytest.mark.parametrize("ideal_loading", ["paper", "exact"])


@LOADINGS
@pytest.mark.parametrize("chord_form", ["thrust", "torque"])
def test_chord_at_reference_radius_is_reference_chord(kind, chord_form, ideal_loading):
    # Invariant (issue 12): the reference station's point minimises cd/cl on the path through its own load
    # with c_ref, so a station at r_ref gets the same load, the same point and the chord c_ref (with the
    # Reynolds-aware exact loading: lambda makes the reference state's own residuals vanish).
    prob = _problem(kind, chord_form=chord_form, ideal_loading=ideal_loading)
    np.testing.assert_allclose(prob.get_val("radii")[:, REF_STATION] / prob.get_val("radius"), 0.5, rtol=1e-14)
    np.testing.assert_allclose(prob.get_val("chord")[:, REF_STATION], [0.1, 0.2, 0.3], rtol=1e-9)
    np.testing.assert_allclose(prob.get_val("alpha_star")[:, REF_STATION], prob.get_val("alpha_star_ref"),
                               atol=1e-10)


@LOADINGS
def test_stations_run_at_their_own_reynolds_number(kind, ideal_loading):
    # Re = rho W0 c / mu at every station (the BEM convention), with the chord that carries the ideal load.
    prob = _problem(kind, ideal_loading=ideal_loading)
    w0 = np.hypot(prob.get_val("v_axial")[:, None], prob.get_val("v_theta"))
    reynolds = prob.get_val("rho")[:, None] * w0 * prob.get_val("chord") / prob.get_val("mu")[:, None]
    np.testing.assert_allclose(prob.get_val("reynolds"), reynolds, rtol=1e-9)


@LOADINGS
def test_bem_analysis_reproduces_the_local_design(kind, ideal_loading):
    # The blade elements of the local design run at their own (alpha, Re) point of the same polar, with
    # Re = rho W0 c / mu as in the BEM analysis, and Eq. (25) holds, so BEM must return BILD's loads.  The
    # accuracy is that of the two solves (BEM inflow angle, the loops' Newton tolerance), not of the polar
    # model: the polar is evaluated at the same points by both.
    polar = default_polar()
    prob = _problem(kind, ideal_loading=ideal_loading)
    result = analyze_rotor(prob.get_val("chord"), prob.get_val("twist"), prob.get_val("radius"),
                           prob.get_val("hub_radius"), prob.get_val("rpm"), prob.get_val("v_axial"), 3, polar,
                           altitude=prob.get_val("altitude"))
    np.testing.assert_allclose(result.thrust, prob.get_val("thrust"), rtol=1e-6)
    np.testing.assert_allclose(result.torque, prob.get_val("torque"), rtol=1e-6)
    np.testing.assert_allclose(result.phi, prob.get_val("phi"), atol=1e-8)


@LOADINGS
def test_reynolds_independent_polar_gives_the_reference_design(kind, ideal_loading):
    # Invariant: with no Re dependence the fixed-load optimum of every station is the max-L/D point (and the
    # Reynolds feedback kappa vanishes: the exact loading at the max-L/D point).
    polar = sweep_polar("naca4412@re=1e6")
    local = _problem(kind, polar=polar, ideal_loading=ideal_loading)
    reference = _problem(kind, section_point="reference", polar=polar, ideal_loading=ideal_loading)
    for name in ("chord", "twist", "thrust", "torque", "energy_loss"):
        np.testing.assert_allclose(local.get_val(name), reference.get_val(name), rtol=1e-9, atol=1e-12)


@LOADINGS
@pytest.mark.parametrize("mode", ["fwd", "rev"])
def test_totals_complex_step(kind, mode, ideal_loading):
    prob = _problem(kind, complex_step=True, mode=mode, num_radial=5, ideal_loading=ideal_loading)
    data = prob.check_totals(of=["thrust", "torque", "energy_loss", "chord", "twist"],
                             wrt=["v_axial", "rpm", "radius", "ref_chord", "ref_radius_ratio", "altitude"],
                             method="cs", out_stream=None)
    # Every partial is exact (the section points' use the polar's exact d2/dRe2), so the totals agree with complex
    # step to the loops' convergence: rtol 1e-11 at atol 1e-13 measured in both modes and both states.
    assert_totals_match(data, atol=1e-12, rtol=1e-9)
    assert_no_approx_partials(prob.model, method="cs")
    assert_no_approx_partials(prob.model, method="fd")


@LOADINGS
def test_thrust_target_local_design(ideal_loading):
    prob = om.Problem(BILDGroup(num_nodes=2, num_radial=8, section_point="local", thrust_target=True,
                                ideal_loading=ideal_loading), reports=False)
    prob.setup()
    prob.set_val("v_axial", [0.0, 15.0])
    prob.set_val("thrust_target", [900.0, 700.0])
    prob.run_model()
    # The Reynolds-aware exact loading solves lambda and reports the stations' chord at r_ref as ref_chord: with
    # r_ref on a station (the fourth) that is the station's chord, whose design is the same (the reference state
    # is a station's ideal load at r_ref, reference_solve's docstring).
    ratio = prob.get_val("radii")[:, 3] / prob.get_val("radius") if ideal_loading == "exact" else np.full(2, 0.5)
    prob.set_val("ref_radius_ratio", ratio)
    prob.run_model()
    # The solve's tolerance is 1e-12 in ln T (ThrustTargetComp): met as tightly as with the paper's BILD.
    np.testing.assert_allclose(prob.get_val("thrust"), [900.0, 700.0], rtol=2e-12)
    # The thrust-target design is the design at the chord it found.
    chord = prob.get_val("ref_chord")
    direct = om.Problem(BILDGroup(num_nodes=2, num_radial=8, section_point="local", ideal_loading=ideal_loading),
                        reports=False)
    direct.setup()
    direct.set_val("v_axial", [0.0, 15.0])
    direct.set_val("ref_radius_ratio", ratio)
    direct.set_val("ref_chord", chord)
    direct.run_model()
    np.testing.assert_allclose(direct.get_val("chord"), prob.get_val("chord"), rtol=1e-9, atol=1e-14)


@LOADINGS
def test_design_does_not_depend_on_the_batch(kind, ideal_loading):
    # A node's outputs do not depend on the other nodes (each station is solved on its own), bit for bit.
    batch = _problem(kind, ideal_loading=ideal_loading)
    values = dict(v_axial=OPERATING[kind], ref_chord=[0.1, 0.2, 0.3], rpm=[800.0, 900.0, 1000.0],
                  altitude=[0.0, 1000.0, 2500.0])
    for node in range(3):
        alone = om.Problem(BILDGroup(num_nodes=1, num_radial=NR_REF, section_point="local",
                                     ideal_loading=ideal_loading), reports=False)
        alone.setup()
        for name, value in values.items():
            alone.set_val(name, value[node])
        alone.run_model()
        for name in ("chord", "twist", "section_branch"):
            np.testing.assert_array_equal(alone.get_val(name)[0], batch.get_val(name)[node])


@pytest.mark.parametrize("ideal_loading, module", [("exact", reynolds_station), ("paper", paper_station)])
def test_a_rerun_solves_only_the_designs_whose_inputs_changed(kind, ideal_loading, module, monkeypatch):
    # A design whose inputs did not change keeps its stations' states: after changing node 1's ref_chord only
    # node 1's stations are solved, and the outputs equal a fresh problem's at the new inputs.
    prob = _problem(kind, ideal_loading=ideal_loading)
    solved = []
    real_solve = module.solve_stations
    monkeypatch.setattr(module, "solve_stations", lambda table, flow, **kw: solved.append(flow.r.size)
                        or real_solve(table, flow, **kw))
    prob.set_val("ref_chord", [0.1, 0.25, 0.3])
    prob.run_model()
    assert solved == [NR_REF]
    monkeypatch.undo()
    fresh = _problem(kind, ideal_loading=ideal_loading, ref_chord=[0.1, 0.25, 0.3])
    for name in ("chord", "twist", "thrust", "torque"):
        np.testing.assert_allclose(prob.get_val(name), fresh.get_val(name), rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("value", ["Local", "max_ld", None, 1])
def test_invalid_section_point_is_one_line(value):
    with pytest.raises(ValueError, match="section_point must be 'reference' or 'local'"):
        BILDGroup(section_point=value)


def test_mach_or_spanwise_polar_is_refused():
    prob = om.Problem(BILDGroup(num_nodes=1, num_radial=4, section_point="local",
                                polar=sweep_polar("0.2:naca4412;1:naca4415")), reports=False)
    with pytest.raises(ValueError, match="varies with the Reynolds number only"):
        prob.setup()
