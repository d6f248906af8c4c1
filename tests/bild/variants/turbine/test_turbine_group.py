"""TurbineBILDGroup: totals on every (of, wrt) pair against complex step, and the family's invariants."""
import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.bild.turbine_group import TurbineBILDGroup
from bild_mdo.utils.testing import assert_totals_match

NN, NR = 2, 7
BASE = dict(v_axial=[8.0, 7.0], rpm=[200.0, 160.0], radius=[3.0, 3.5], hub_radius_ratio=[0.1, 0.15],
            ref_radius_ratio=[0.7, 0.6], altitude=[0.0, 800.0])
MEMBER = {"multiplier": dict(power_thrust_multiplier=[0.0, 1.5], section_chord=[0.2, 0.25]),
          "ref_chord": dict(ref_chord=[0.08, 0.1]),
          "thrust": dict(thrust_target=[700.0, 600.0], section_chord=[0.2, 0.25])}
OF = ["power", "thrust", "power_coefficient", "thrust_coefficient", "tip_speed_ratio", "chord", "twist", "phi_ref"]


def _problem(design_for, mode="fwd", polar=None):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("turbine", TurbineBILDGroup(num_nodes=NN, num_radial=NR, design_for=design_for,
                                                         polar=polar), promotes=["*"])
    prob.setup(force_alloc_complex=True, mode=mode)
    for name, value in {**BASE, **MEMBER[design_for]}.items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


@pytest.mark.parametrize("mode", ["fwd", "rev"])
@pytest.mark.parametrize("design_for", ["multiplier", "ref_chord", "thrust"])
def test_totals(design_for, mode):
    prob = _problem(design_for, mode)
    other = "power_thrust_multiplier" if design_for != "multiplier" else "ref_chord"
    wrt = list(BASE) + list(MEMBER[design_for])
    data = prob.check_totals(of=OF + [other], wrt=wrt, method="cs", out_stream=None)
    assert_totals_match(data, atol=1e-9, rtol=1e-6)
    assert_no_approx_partials(prob.model, method="cs")
    assert_no_approx_partials(prob.model, method="fd")


def test_members_agree():
    """The three parameterisations name one family: the same mu, c_ref and thrust give the same blade
    (a polar independent of the Reynolds number, so that the section points agree)."""
    polar = AnalyticPolar()
    by_mu = _problem("multiplier", polar=polar)
    MEMBER["ref_chord"] = dict(ref_chord=by_mu.get_val("ref_chord"))
    by_chord = _problem("ref_chord", polar=polar)
    MEMBER["thrust"] = dict(thrust_target=by_mu.get_val("thrust"), section_chord=[0.2, 0.25])
    by_thrust = _problem("thrust", polar=polar)
    for prob in (by_chord, by_thrust):
        np.testing.assert_allclose(prob.get_val("power_thrust_multiplier"), [0.0, 1.5], atol=1e-8)
        np.testing.assert_allclose(prob.get_val("chord"), by_mu.get_val("chord"), rtol=1e-8)
        np.testing.assert_allclose(prob.get_val("power"), by_mu.get_val("power"), rtol=1e-10)
    assert np.all(by_mu.get_val("axial_induction") < 0.4)
    MEMBER["ref_chord"] = dict(ref_chord=[0.08, 0.1])
    MEMBER["thrust"] = dict(thrust_target=[700.0, 600.0], section_chord=[0.2, 0.25])


def test_thrust_out_of_reach_names_the_remedy():
    MEMBER["thrust"] = dict(thrust_target=[1e6, 600.0], section_chord=[0.2, 0.25])
    try:
        with pytest.raises(om.AnalysisError, match="above the largest thrust of the windmill state"):
            _problem("thrust")
    finally:
        MEMBER["thrust"] = dict(thrust_target=[700.0, 600.0], section_chord=[0.2, 0.25])
