"""BladeElementLoadsComp: partials, and blade-element loads equal to momentum loads at the solved phi."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.bem.analyze import station_radii
from bild_mdo.bem.inflow import InflowComp
from bild_mdo.bem.loads import BladeElementLoadsComp
from bild_mdo.utils.testing import check_component_partials

NN, NR, B = 3, 7, 3
# In hover V_x = 0 makes d(W0)/d(V_x) = V_x/W0 vanish, so OpenMDAO reports declared-but-zero partials.
pytestmark = pytest.mark.filterwarnings("ignore:(?s).*zero derivatives")


def _problem(polar, blade, loss_model="tip_hub", all_hover=False):
    """Inflow solve feeding the loads, so the loads are evaluated at the converged phi."""
    prob = om.Problem(reports=False)
    kw = dict(num_nodes=NN, num_radial=NR, num_blades=B, polar=polar, loss_model=loss_model)
    prob.model.add_subsystem("inflow", InflowComp(**kw), promotes=["*"])
    prob.model.add_subsystem("loads", BladeElementLoadsComp(**kw), promotes=["*"])
    prob.setup(force_alloc_complex=True)
    for name in ("rpm", "radius", "hub_radius", "chord", "twist"):
        prob.set_val(name, blade[name])
    prob.set_val("v_axial", 0.0 * blade["v_axial"] if all_hover else blade["v_axial"])
    prob.set_val("radii", station_radii(blade["radius"], blade["hub_radius"], NR))
    prob.set_val("rho", [1.225, 1.1, 0.95])
    prob.set_val("mu", [1.79e-5, 1.75e-5, 1.7e-5])
    prob.run_model()
    return prob


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip", "none"])
@pytest.mark.parametrize("all_hover", [False, True], ids=["hover+cruise", "hover"])
def test_partials(smooth_polar, make_blade, loss_model, all_hover):
    # At the converged phi of the inflow solve, where the loads are used.
    solved = _problem(smooth_polar, make_blade(NN, NR), loss_model, all_hover)
    comp = BladeElementLoadsComp(num_nodes=NN, num_radial=NR, num_blades=B, polar=smooth_polar,
                                 loss_model=loss_model)
    names = ("phi", "v_axial", "rpm", "radius", "hub_radius", "radii", "chord", "twist", "rho", "mu")
    check_component_partials(comp, {name: solved.get_val(name) for name in names}, atol=1e-9, rtol=1e-9)


@pytest.mark.parametrize("loss_model", ["tip_hub", "none"])
def test_momentum_equals_blade_element_at_converged_phi(analytic_polar, make_blade, loss_model):
    """Physical invariant of BEM (paper Table 1 with the Prandtl factor F):
    4 pi rho u_axial (u_axial - V_x) r F = dT/dr and 2 pi rho u_axial u_theta r^2 F = dQ/dr at R(phi) = 0."""
    prob = _problem(analytic_polar, make_blade(NN, NR, seed=1), loss_model)
    g = prob.get_val
    rho, vx = g("rho")[:, None], g("v_axial")[:, None]
    r, F, ux, ut = g("radii"), g("loss_factor"), g("u_axial"), g("u_theta")
    np.testing.assert_allclose(4 * np.pi * rho * ux * (ux - vx) * r * F, g("dthrust_dr"), rtol=1e-10)
    np.testing.assert_allclose(2 * np.pi * rho * ux * ut * r**2 * F, g("dtorque_dr"), rtol=1e-10)
    # Inflow triangle (paper Fig. 1b): W sin(phi) = u_axial, W cos(phi) = V_theta - u_theta/2.
    v_theta = g("rpm")[:, None] * np.pi / 30 * r
    np.testing.assert_allclose(g("inflow_speed") * np.sin(g("phi")), ux, rtol=1e-11)
    np.testing.assert_allclose(g("inflow_speed") * np.cos(g("phi")), v_theta - ut / 2, rtol=1e-11)
    # Hover: momentum theory needs u_axial > V_x for positive thrust (paper Assumption 3).
    assert np.all(ux > vx) and np.all(g("dthrust_dr") > 0)


def test_reynolds_uses_speed_without_induction(analytic_polar, make_blade):
    # Documented choice (as in CCBlade): Re = rho W0 c / mu with W0 = sqrt(V_x^2 + V_theta^2).
    prob = _problem(analytic_polar, make_blade(NN, NR))
    g = prob.get_val
    w0 = np.hypot(g("v_axial")[:, None], g("rpm")[:, None] * np.pi / 30 * g("radii"))
    np.testing.assert_allclose(g("reynolds"), g("rho")[:, None] * w0 * g("chord") / g("mu")[:, None],
                               rtol=1e-14)
    np.testing.assert_allclose(g("alpha"), g("twist") - g("phi"), rtol=1e-14)
