"""MIL design checked against closed forms derived by hand from Adkins & Liebeck's design relations.

Source of the relations: C. N. Adkins and R. H. Liebeck, "Design of optimum propellers", J. Propulsion and
Power 10(5), 1994 (A&L): with ``a_t = lambda (1 + zeta/2)`` the flow angle is ``tan(phi) = a_t/xi`` (Betz's
rigid helicoidal wake), ``G = F (xi/lambda) cos(phi) sin(phi)``, and the design integrands are::

    I1' = 4 xi G (1 - eps tan(phi))            I2' = lambda (I1'/(2 xi)) (1 + eps/tan(phi)) sin(phi) cos(phi)
    J1' = 4 xi G (1 + eps/tan(phi))            J2' = (J1'/2) (1 - eps tan(phi)) cos^2(phi)
    T_c = I1 zeta - I2 zeta^2                  P_c = J1 zeta + J2 zeta^2

No published MIL design case with its numbers (A&L's example propeller, Larrabee's SAE 790585 example, an
XROTOR/QMIL documented run) could be reached from this workplace, so the checks below are hand derivations
from these relations, each exact (no fitted or regression number):

1. Without drag (eps = 0), for any blade number, loss factor, speed ratio and stations:
   ``J2' + (1 + zeta/2) I2' = 2 G cos(phi) (xi cos(phi) + xi tan(phi) sin(phi)) = 2 xi G = I1'/2`` and
   ``J1' = I1'``, so ``P_c = (1 + zeta/2) T_c``: the design's efficiency is ``1/(1 + zeta/2)``, the
   Rankine-Froude efficiency of a disk whose slipstream gains the displacement velocity ``v' = zeta V``.
2. With infinitely many blades (F = 1) the integrands are rational in ``xi`` with ``s = xi^2 + a_t^2``::

       I1' = (4 a_t/lambda)(xi^3 - eps a_t xi^2)/s      J1' = (4 a_t/lambda)(xi^3 + (eps/a_t) xi^4)/s
       I2' = 2 a_t^2 ((1 - eps^2) xi^3 + (eps/a_t) xi^4 - eps a_t xi^2)/s^2
       J2' = (2 a_t/lambda)((1 - eps^2) xi^5 + (eps/a_t) xi^6 - eps a_t xi^4)/s^2

   and integrate in closed form (:func:`_closed_form_integrals`); ``lambda -> 0`` gives back the
   Rankine-Froude relations of ``test_mil_group.test_rankine_froude_limit``.
3. Betz's condition as A&L use it: the wake is a rigid helicoid, ``r tan(phi) = (V + v'/2)/Omega`` at every
   station, and every section works at the design angle of attack, ``twist = phi + alpha*``.
"""
import numpy as np
import openmdao.api as om
import pytest
from scipy.optimize import brentq

from bild_mdo.atmosphere import isa
from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.mil import MILGroup, design_mil
from bild_mdo.mil.kernel import LOSS_FORMS

# Prandtl's exponent f = (B/2)(1 - xi)/sin(phi_t) exceeds the package's clip (100) at every Gauss station
# below, and QMIL's root factor sqrt(1 + (4 lambda_w/(pi B xi))**2) is 1 + O(1e-18): F = 1 to round-off, the
# B -> infinity limit.
_INFINITE_BLADES = 10**9


@pytest.mark.parametrize("loss_form", LOSS_FORMS)
@pytest.mark.parametrize("num_blades", [2, 3, 6])
def test_inviscid_efficiency_is_froude_at_displacement_velocity(loss_form, num_blades):
    # Hand derivation 1: exact for every design, so to round-off (light to heavy loading, hub or none).
    kwargs = dict(v_axial=[20.0, 49.17, 70.0], rpm=[2600.0, 2400.0, 1800.0], radius=0.875,
                  hub_radius=[0.0, 0.1, 0.2], cl_star=0.7, cd_star=0.0, alpha_star=0.05, num_blades=num_blades,
                  loss_form=loss_form, num_radial=17)
    by_thrust = design_mil([200.0, 900.0, 2500.0], **kwargs)
    by_power = design_mil(power=[4e3, 5e4, 1.5e5], **kwargs)
    for design in (by_thrust, by_power):
        assert np.all(design.zeta > 0.1)  # loading high enough for the identity to be more than 1 - O(zeta^2)
        np.testing.assert_allclose(design.efficiency * (1.0 + 0.5 * design.zeta), 1.0, rtol=1e-13)


def _closed_form_integrals(speed_ratio, zeta, hub_ratio, eps):
    """``(I1, I2, J1, J2)`` for F = 1 over ``hub_ratio <= xi <= 1`` (hand derivation 2)."""
    a = speed_ratio * (1.0 + 0.5 * zeta)

    def antiderivatives(x):
        s, arc = x * x + a * a, np.arctan(x / a)
        over_s = {2: x - a * arc, 3: 0.5 * (x * x - a * a * np.log(s)), 4: x ** 3 / 3.0 - a * a * x + a ** 3 * arc}
        n0 = x / (2.0 * a * a * s) + arc / (2.0 * a ** 3)  # integral of 1/s^2
        n2 = arc / (2.0 * a) - x / (2.0 * s)
        over_s2 = {2: n2, 3: 0.5 * (np.log(s) + a * a / s), 4: x - 1.5 * a * arc + a * a * x / (2.0 * s),
                   5: 0.5 * (x * x - 2.0 * a * a * np.log(s) - a ** 4 / s),
                   # xi^6 = (xi^2 - 2 a^2) s^2 + 3 a^4 xi^2 + 2 a^6
                   6: x ** 3 / 3.0 - 2.0 * a * a * x + 3.0 * a ** 4 * n2 + 2.0 * a ** 6 * n0}
        i1 = 4.0 * a / speed_ratio * (over_s[3] - eps * a * over_s[2])
        i2 = 2.0 * a * a * ((1.0 - eps ** 2) * over_s2[3] + eps / a * over_s2[4] - eps * a * over_s2[2])
        j1 = 4.0 * a / speed_ratio * (over_s[3] + eps / a * over_s[4])
        j2 = 2.0 * a / speed_ratio * ((1.0 - eps ** 2) * over_s2[5] + eps / a * over_s2[6] - eps * a * over_s2[4])
        return np.array([i1, i2, j1, j2])

    return antiderivatives(1.0) - antiderivatives(hub_ratio)


def test_closed_form_reduces_to_rankine_froude():
    # The hand-derived integrals themselves: lambda -> 0 gives Rankine-Froude,
    # T_c = (2 zeta + zeta^2)(1 - xi_0^2) and P_c = (1 + zeta/2) T_c.
    zeta, hub_ratio = 0.4, 0.2
    i1, i2, j1, j2 = _closed_form_integrals(1e-7, zeta, hub_ratio, 0.0)
    froude = (2.0 * zeta + zeta ** 2) * (1.0 - hub_ratio ** 2)
    np.testing.assert_allclose(i1 * zeta - i2 * zeta ** 2, froude, rtol=1e-10)
    np.testing.assert_allclose(j1 * zeta + j2 * zeta ** 2, (1.0 + 0.5 * zeta) * froude, rtol=1e-10)


@pytest.mark.parametrize("loss_form", LOSS_FORMS)
@pytest.mark.parametrize("eps", [0.0, 0.02])
def test_infinite_blade_design_matches_closed_form(loss_form, eps):
    # Hand derivation 2 at heavy loading with swirl (lambda = 0.35, T_c = 1): the zeta solve, the thrust and
    # power integrals and the viscous terms against the exact integrals.  Gauss-Legendre stations (user
    # stations of MILGroup) integrate the smooth integrands to round-off, so the tolerance is the solver's.
    speed_ratio, hub_ratio, t_c, cl = 0.35, 0.25, 1.0, 0.8
    radius, rpm = 1.0, 1500.0
    v_axial = speed_ratio * rpm * RPM_TO_RAD_PER_S * radius
    rho = isa(0.0).rho

    def thrust_residual(zeta):
        i1, i2, _, _ = _closed_form_integrals(speed_ratio, zeta, hub_ratio, eps)
        return i1 * zeta - i2 * zeta ** 2 - t_c

    zeta = brentq(thrust_residual, 0.0, 1.0, xtol=1e-15, rtol=1e-15)  # T_c(1) > 1: the smaller root, A&L's branch
    _, _, j1, j2 = _closed_form_integrals(speed_ratio, zeta, hub_ratio, eps)
    p_c = j1 * zeta + j2 * zeta ** 2

    nodes, weights = np.polynomial.legendre.leggauss(32)
    prob = om.Problem(MILGroup(num_nodes=1, num_radial=32, num_blades=_INFINITE_BLADES, loss_form=loss_form,
                               radial_fractions=hub_ratio + 0.5 * (1.0 - hub_ratio) * (nodes + 1.0),
                               width_fractions=0.5 * (1.0 - hub_ratio) * weights), reports=False)
    prob.setup()
    for name, value in dict(v_axial=v_axial, rpm=rpm, radius=radius, hub_radius=hub_ratio * radius, altitude=0.0,
                            design_thrust=t_c * 0.5 * rho * v_axial ** 2 * np.pi * radius ** 2, cl_star=cl,
                            cd_star=eps * cl).items():
        prob.set_val(name, value)
    prob.run_model()

    np.testing.assert_allclose(prob.get_val("loss_factor"), 1.0, rtol=1e-15)
    np.testing.assert_allclose(prob.get_val("zeta"), zeta, rtol=1e-12)
    np.testing.assert_allclose(prob.get_val("efficiency"), t_c / p_c, rtol=1e-12)
    np.testing.assert_allclose(prob.get_val("power", units="W"), p_c * 0.5 * rho * v_axial ** 3 * np.pi * radius ** 2,
                               rtol=1e-12)
    # The swirl terms matter here: the Rankine-Froude (lambda -> 0) zeta of the same T_c is a third lower.
    assert zeta > 1.3 * (np.sqrt(1.0 + t_c / (1.0 - hub_ratio ** 2)) - 1.0)


def test_wake_is_a_rigid_helicoid():
    # Hand derivation 3 (Betz's condition): holds with drag and with Prandtl's F at any blade number.
    v_axial, rpm, alpha = np.array([35.0, 60.0]), np.array([2200.0, 2600.0]), 0.06
    design = design_mil([700.0, 1500.0], v_axial=v_axial, rpm=rpm, radius=0.9, hub_radius=0.12, cl_star=0.75,
                        cd_star=0.011, alpha_star=alpha, num_blades=3, num_radial=13)
    omega = (rpm * RPM_TO_RAD_PER_S)[:, None]
    pitch = (v_axial[:, None] * (1.0 + 0.5 * design.zeta[:, None])) / omega
    np.testing.assert_allclose(design.radii * np.tan(design.phi), np.broadcast_to(pitch, design.phi.shape), rtol=1e-13)
    np.testing.assert_allclose(design.twist, design.phi + alpha, rtol=1e-14)
