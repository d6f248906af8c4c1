import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.airfoil.compressibility import CompressiblePolar
from bild_mdo.airfoil.spanwise import SpanwisePolar
from bild_mdo.bild.variants.reference_point.reference_airfoil import ReferenceAirfoilComp
from bild_mdo.utils.testing import check_component_partials
from tests.bild.conftest import NN, NR, state

# cd0 scales as Re**-0.2 (turbulent skin friction), so the max-L/D point moves with Re.
RE_DEPENDENT = AnalyticPolar(reynolds_exponent=0.2)


def test_partials_reynolds_dependent_polar(kind):
    check_component_partials(ReferenceAirfoilComp(num_nodes=NN, polar=RE_DEPENDENT), state(kind))


def test_partials_builtin_naca4412(kind):
    # Default polar (None): the NACA 4412 surrogate; Re_ref here is inside its table (4e5 ... 1.5e6).
    prob = check_component_partials(ReferenceAirfoilComp(num_nodes=NN), state(kind))
    ratio = prob.get_val("cl_star") / prob.get_val("cd_star")
    # A cambered airfoil at Re ~ 1e6 reaches L/D of order 100 at alpha* of a few degrees.
    assert np.all((ratio > 60) & (ratio < 200))
    assert np.all((np.degrees(prob.get_val("alpha_star")) > 2) & (np.degrees(prob.get_val("alpha_star")) < 10))


def test_reynolds_number_and_closed_form(kind):
    values = state(kind)
    prob = check_component_partials(ReferenceAirfoilComp(num_nodes=NN, polar=RE_DEPENDENT), values)
    # Re_ref = rho W0 c_ref / mu with W0 = sqrt(V_x**2 + (Omega r_ref)**2) (speed without induction).
    w0 = np.hypot(values["v_axial"], values["v_theta_ref"])
    reynolds = values["rho"] * w0 * values["ref_chord"] / values["mu"]
    np.testing.assert_allclose(prob.get_val("reynolds_ref"), reynolds, rtol=1e-14)
    # AnalyticPolar's closed form of the max-L/D point (k cl*^2 = k cl_cd_min^2 + cd0 f(Re)).
    alpha, cl, cd = RE_DEPENDENT.max_lift_to_drag_closed_form(reynolds)
    np.testing.assert_allclose(prob.get_val("alpha_star"), alpha, rtol=1e-10)
    np.testing.assert_allclose(prob.get_val("cl_star"), cl, rtol=1e-10)
    np.testing.assert_allclose(prob.get_val("cd_star"), cd, rtol=1e-10)


def test_nonpositive_chord_raises():
    values = state("hover")
    values["ref_chord"] = np.array([0.1, 0.0, 0.1])
    with pytest.raises(om.AnalysisError, match="ref_chord must be positive"):
        check_component_partials(ReferenceAirfoilComp(num_nodes=NN, polar=RE_DEPENDENT), values)


@pytest.mark.parametrize("name", ["v_axial", "v_theta_ref", "ref_chord", "rho", "mu"])
def test_nonfinite_reynolds_inputs_raise_naming_the_input(name):
    # Re_ref = rho W0 c_ref / mu: a NaN or inf in any factor must be reported by name, not passed to the polar.
    values = state("cruise")
    values[name] = values[name].copy()
    values[name][2] = np.nan if name != "mu" else np.inf
    with pytest.raises(om.AnalysisError, match=rf"{name} must be finite for the reference Reynolds number, "
                                               r"got .* at node 2"):
        check_component_partials(ReferenceAirfoilComp(num_nodes=NN, polar=RE_DEPENDENT), values)


@pytest.mark.parametrize("name", ["rho", "mu"])
def test_nonpositive_air_properties_raise(name):
    values = state("cruise")
    values[name] = values[name].copy()
    values[name][0] = 0.0
    with pytest.raises(om.AnalysisError, match=f"{name} must be positive"):
        check_component_partials(ReferenceAirfoilComp(num_nodes=NN, polar=RE_DEPENDENT), values)


# A thick root section (more zero-lift drag, less camber) blending into the default section by r/R = 0.8.
ROOT = AnalyticPolar(cl0=0.25, cd0=0.012, k=0.012, cl_cd_min=0.3, reynolds_exponent=0.15)
TIP = RE_DEPENDENT
SPANWISE = SpanwisePolar([ROOT, TIP], [0.3, 0.8])
# Karman-Tsien moves alpha* with Mach number (Prandtl-Glauert would only scale cl*).
COMPRESSIBLE = CompressiblePolar(RE_DEPENDENT, correction="karman-tsien")


def _with_speed_of_sound(kind, a=(340.3, 320.0, 300.0)):
    values = state(kind)
    values["speed_of_sound"] = np.array(a)
    return values


@pytest.mark.parametrize("polar", [RE_DEPENDENT, COMPRESSIBLE, SPANWISE,
                                   SpanwisePolar([CompressiblePolar(ROOT), COMPRESSIBLE], [0.3, 0.8])],
                         ids=["uniform", "mach", "spanwise", "spanwise_mach"])
def test_partials_mach_and_spanwise(kind, polar):
    check_component_partials(ReferenceAirfoilComp(num_nodes=NN, num_radial=NR, polar=polar), _with_speed_of_sound(kind))


def test_mach_number_is_reference_speed_without_induction_over_speed_of_sound(kind):
    values = _with_speed_of_sound(kind)
    prob = check_component_partials(ReferenceAirfoilComp(num_nodes=NN, polar=COMPRESSIBLE), values)
    mach = np.hypot(values["v_axial"], values["v_theta_ref"]) / values["speed_of_sound"]
    np.testing.assert_allclose(prob.get_val("mach_ref"), mach, rtol=1e-14)
    point = COMPRESSIBLE.max_lift_to_drag(prob.get_val("reynolds_ref"), mach=mach)
    np.testing.assert_array_equal(prob.get_val("alpha_star"), point.alpha)
    np.testing.assert_array_equal(prob.get_val("cl_star"), point.cl)
    # The same section without compressibility: at M_ref ~ 0.1-0.2 Karman-Tsien raises cl* by a few percent.
    incompressible = RE_DEPENDENT.max_lift_to_drag(prob.get_val("reynolds_ref"))
    assert np.all(prob.get_val("cl_star") > incompressible.cl)


def test_spanwise_point_per_station_and_at_reference_radius(kind):
    values = _with_speed_of_sound(kind)
    prob = check_component_partials(ReferenceAirfoilComp(num_nodes=NN, num_radial=NR, polar=SPANWISE), values)
    reynolds = prob.get_val("reynolds_ref")
    assert prob.get_val("cl_star").shape == (NN, NR)
    stations = SPANWISE.max_lift_to_drag(reynolds[:, None], radial_fraction=values["radii"] / values["radius"][:, None])
    np.testing.assert_allclose(prob.get_val("alpha_star"), stations.alpha, rtol=1e-13)
    np.testing.assert_allclose(prob.get_val("cd_star"), stations.cd, rtol=1e-13)
    ref = SPANWISE.max_lift_to_drag(reynolds, radial_fraction=values["ref_radius_ratio"])
    np.testing.assert_allclose(prob.get_val("cl_star_ref"), ref.cl, rtol=1e-13)
    # Root and tip stations take their own airfoils' closed-form points (AnalyticPolar, Reynolds only).
    fraction = values["radii"] / values["radius"][:, None]
    for polar, at in ((ROOT, fraction <= 0.3), (TIP, fraction >= 0.8)):
        alpha, cl, cd = polar.max_lift_to_drag_closed_form(np.broadcast_to(reynolds[:, None], (NN, NR)))
        assert np.any(at)
        np.testing.assert_allclose(prob.get_val("cl_star")[at], cl[at], rtol=1e-10)
