"""bild_problem: the set-up BILD model, cached by configuration."""
import numpy as np
import pytest

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.bild.problem import bild_problem, clear_model_cache


def test_same_configuration_reuses_the_problem():
    clear_model_cache()
    first = bild_problem(num_nodes=2, num_radial=6)
    # Built-in names are case-insensitive and resolve to one polar object, so the cache is hit.
    assert bild_problem(num_nodes=2, num_radial=6, airfoil=" NACA4412") is first
    assert bild_problem(num_nodes=2, num_radial=7) is not first
    clear_model_cache()
    assert bild_problem(num_nodes=2, num_radial=6) is not first


def test_problem_runs_with_a_polar_object():
    prob = bild_problem(num_nodes=1, num_radial=8, airfoil=AnalyticPolar())
    prob.set_val("v_axial", 10.0)
    prob.run_model()
    # Thrust is positive for a loaded forward-flight design (paper Assumption 3).
    assert np.all(prob.get_val("thrust") > 0.0)


@pytest.mark.parametrize("change, match", [
    (dict(airfoil="clarky"), "unknown airfoil"),
    (dict(airfoil=3), "airfoil must be"),
    (dict(num_nodes=0), "num_nodes must be an integer"),
    (dict(num_radial=True), "num_radial must be an integer"),
])
def test_invalid_arguments(change, match):
    with pytest.raises(ValueError, match=match):
        bild_problem(**change)


def test_thrust_target_problem_is_its_own_configuration():
    # The ref_chord-input model and the thrust-target model are different problems in the cache.
    polar = AnalyticPolar()
    direct = bild_problem(num_nodes=1, num_radial=8, airfoil=polar)
    solved = bild_problem(num_nodes=1, num_radial=8, airfoil=polar, thrust_target=True)
    assert solved is not direct
    direct.set_val("ref_chord", 0.12)
    direct.run_model()
    solved.set_val("thrust_target", direct.get_val("thrust"))
    solved.run_model()
    np.testing.assert_allclose(solved.get_val("ref_chord"), 0.12, rtol=1e-10)


def test_section_point_is_its_own_configuration():
    clear_model_cache()
    reference = bild_problem(num_nodes=1, num_radial=6)
    local = bild_problem(num_nodes=1, num_radial=6, section_point="local")
    assert local is not reference
    assert local.model.options["section_point"] == "local"
    assert bild_problem(num_nodes=1, num_radial=6, section_point="local") is local
