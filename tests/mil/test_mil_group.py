"""MILGroup and design_mil: Adkins & Liebeck (1994) checked against the limits and claims of their method.

Published checks (sources named at each test):
* Rankine-Froude actuator-disk theory (Glauert, "Airplane propellers", in Durand, Aerodynamic Theory, 1935;
  A&L's relations reduce to it for lambda -> 0, no drag, F -> 1): T_c = (2 zeta + zeta^2)(1 - xi_0^2),
  eta = 1 / (1 + zeta/2).
* A&L's abstract: their procedure "brings into exact agreement the procedure for design and analysis" -- an
  independent BEM analysis (bild_mdo.bem.analyze_rotor) of the designed blade at its airfoil point reproduces
  the design's thrust and power.
* A&L give a thrust-specified and a power-specified form of the same design.
"""
import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.atmosphere import isa
from bild_mdo.bem.analyze import analyze_rotor
from bild_mdo.mil import MILGroup, design_mil
from bild_mdo.mil.kernel import LOSS_FORMS
from bild_mdo.utils.testing import check_group_totals

CASE = dict(v_axial=49.17, rpm=2400.0, radius=0.875, hub_radius=0.1, num_blades=2)


def test_rankine_froude_limit():
    # lambda = 0.25/(1047 * 1) ~ 2.4e-4, no drag: F = 1 (tip station: exp(-f) ~ 1e-12), cos(phi) = 1 - O(lambda^2).
    t_c, hub_ratio = 3.0, 0.2
    rho = 1.225
    thrust = t_c * 0.5 * rho * 0.25 ** 2 * np.pi
    design = design_mil(thrust, v_axial=0.25, rpm=10000.0, radius=1.0, hub_radius=hub_ratio, cl_star=0.8,
                        cd_star=0.0, alpha_star=0.05, num_blades=2, num_radial=40)
    zeta = np.sqrt(1.0 + t_c / (1.0 - hub_ratio ** 2)) - 1.0
    np.testing.assert_allclose(design.zeta, zeta, rtol=1e-6)
    np.testing.assert_allclose(design.efficiency, 1.0 / (1.0 + 0.5 * zeta), rtol=1e-6)


def test_design_and_bem_analysis_agree():
    # Reynolds-independent polar; the MIL design at its max-L/D point is analysed by the package's BEM with the
    # same (local-angle, tip-only) Prandtl factor: thrust and power agree to the BEM solver's tolerance.
    polar = AnalyticPolar()
    alpha, cl, cd = (float(v) for v in polar.max_lift_to_drag_closed_form(1e6))
    design = design_mil([600.0, 1200.0], **CASE, cl_star=cl, cd_star=cd, alpha_star=alpha, loss_form="local",
                        num_radial=30)
    sea_level = isa(0.0)  # the design's atmosphere (design_mil's default altitude)
    rho, mu = sea_level.rho, sea_level.mu
    width = (CASE["radius"] - CASE["hub_radius"]) / 30
    bem = analyze_rotor(design.chord, design.twist, CASE["radius"], CASE["hub_radius"], CASE["rpm"],
                        CASE["v_axial"], CASE["num_blades"], polar, loss_model="tip", radii=design.radii,
                        dr=np.full_like(design.radii, width), rho=rho, mu=mu)
    np.testing.assert_allclose(bem.thrust, [600.0, 1200.0], rtol=1e-10)
    np.testing.assert_allclose(bem.power, design.power, rtol=1e-10)
    # ... and the blade works at the design's airfoil point everywhere.
    np.testing.assert_allclose(bem.lift_coefficient, cl, rtol=1e-9)


def test_thrust_and_power_forms_agree():
    kwargs = dict(**CASE, cl_star=0.7, cd_star=0.012, alpha_star=0.06)
    by_thrust = design_mil(900.0, **kwargs)
    by_power = design_mil(power=by_thrust.power, **kwargs)
    np.testing.assert_allclose(by_power.thrust, 900.0, rtol=1e-10)
    np.testing.assert_allclose(by_power.chord, by_thrust.chord, rtol=1e-9)
    np.testing.assert_allclose(by_power.twist, by_thrust.twist, rtol=1e-10)


def test_batch_equals_single_designs():
    kwargs = dict(v_axial=[30.0, 49.17, 70.0], rpm=[2000.0, 2400.0, 2700.0], radius=0.875, hub_radius=0.1,
                  cl_star=0.7, cd_star=0.01, alpha_star=0.05, num_blades=3)
    batch = design_mil([500.0, 900.0, 700.0], **kwargs)
    single = design_mil(700.0, **{**kwargs, "v_axial": 70.0, "rpm": 2700.0})
    np.testing.assert_allclose(batch.chord[2], single.chord[0], rtol=1e-12)
    assert batch.chord.shape == (3, 20)
    # Drag lowers the efficiency below the inviscid design's; both below Froude's ideal 1/(1 + zeta/2).
    assert np.all(batch.efficiency < 1.0 / (1.0 + 0.5 * batch.zeta))


def test_hover_and_bad_targets_are_rejected():
    kwargs = dict(rpm=2400.0, radius=0.875, hub_radius=0.1, cl_star=0.7, cd_star=0.01, alpha_star=0.05)
    with pytest.raises(ValueError, match="v_axial must be a positive finite number.*forward flight"):
        design_mil(900.0, v_axial=0.0, **kwargs)
    with pytest.raises(ValueError, match="exactly one of thrust and power"):
        design_mil(900.0, v_axial=40.0, power=5e4, **kwargs)
    with pytest.raises(ValueError, match="thrust must be a positive"):
        design_mil(-1.0, v_axial=40.0, **kwargs)


@pytest.mark.parametrize("loss_form", LOSS_FORMS)
@pytest.mark.parametrize("design_for", ["thrust", "power"])
def test_group_totals(design_for, loss_form):
    target = f"design_{design_for}"
    values = dict(v_axial=[40.0, 60.0], rpm=[2200.0, 2600.0], radius=[0.8, 0.9], hub_radius=[0.1, 0.12],
                  altitude=[0.0, 1500.0], cl_star=[0.7, 0.9], cd_star=[0.01, 0.015], alpha_star=[0.05, 0.07])
    values[target] = [700.0, 1100.0] if design_for == "thrust" else [3e4, 6e4]
    check_group_totals(lambda: MILGroup(num_nodes=2, num_radial=4, num_blades=3, design_for=design_for,
                                        loss_form=loss_form),
                       of=["chord", "twist", "zeta", "thrust", "power", "torque", "efficiency"],
                       wrt=["v_axial", "rpm", "radius", "hub_radius", "altitude", target, "cl_star", "cd_star",
                            "alpha_star"], values=values, atol=1e-7, rtol=1e-7)


def test_no_approximated_partials():
    prob = om.Problem(MILGroup(num_nodes=2, num_radial=3), reports=False)
    prob.setup()
    assert_no_approx_partials(prob.model, include_self=True, recurse=True)
