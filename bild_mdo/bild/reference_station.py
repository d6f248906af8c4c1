"""The one BEM solve of BILD: inflow angle at the reference station (Algorithm 1, step 2).

The reference station is one blade element (:mod:`bild_mdo.bem.blade_element`)
with ``C_l = C_l*`` and ``C_d = C_d*`` fixed: its options, inputs and loss-model
wiring are the BEM kernel's, and its inflow angle solves the same residual
with the same bracketed solver.
"""
from typing import NamedTuple

import numpy as np
import openmdao.api as om

from bild_mdo.bem.blade_element import add_section_inputs, declare_section_options
from bild_mdo.bem.inflow_residual import inflow_residual, inflow_residual_value, sign_of_sine
from bild_mdo.bem.prandtl import loss_inputs, loss_partials, prandtl_loss, prandtl_loss_and_dphi
from bild_mdo.bem.root_finding import BRACKET_EPS, MAX_ITER, RESIDUAL_TOL, opposite_signs, solve_bracketed
from bild_mdo.utils.newton import bracketed_newton, complex_step_update
from bild_mdo.utils.sparsity import node_wrt_node

#: Inputs of the reference-station section, shared by the solve and the induced velocities.
REFERENCE_INPUTS = ("v_axial", "v_theta_ref", "ref_radius", "ref_chord", "radius", "hub_radius",
                    "cl_star", "cd_star")


class ReferenceSection(NamedTuple):
    """Solidity and loss factor of the reference section, with the partials the chain rule needs."""

    sigma: np.ndarray
    dsigma_dref_chord: np.ndarray
    dsigma_dref_radius: np.ndarray
    loss: object


def reference_section(phi, inputs, num_blades, loss_model):
    """Local solidity ``sigma = B c_ref / (2 pi r_ref)`` and Prandtl loss at the reference station.

    Parameters
    ----------
    phi : ndarray
        Inflow angle at the reference station (rad), shape ``(nn,)``.
    inputs : mapping
        Values of :data:`REFERENCE_INPUTS`, shape ``(nn,)`` each.
    num_blades : int
        Number of blades B.
    loss_model : str
        Prandtl loss model, see :func:`bild_mdo.bem.prandtl.prandtl_loss`.

    Returns
    -------
    ReferenceSection
    """
    r_ref = inputs["ref_radius"]
    sigma = num_blades * inputs["ref_chord"] / (2.0 * np.pi * r_ref)
    loss = prandtl_loss(phi, r_ref, inputs["radius"], inputs["hub_radius"], num_blades, loss_model)
    return ReferenceSection(sigma, num_blades / (2.0 * np.pi * r_ref), -sigma / r_ref, loss)


def declare_reference_options(options):
    """Options of a reference-station component: the blade element's, without stations or polar."""
    declare_section_options(options, radial=False, polar=False)


def section_partials(d_dphi, d_dsigma, d_dF, d_dv_axial, d_dv_theta, d_dcl, d_dcd, section, loss_model):
    """Chain explicit partials of a reference-station quantity to the component inputs and phi.

    Returns
    -------
    dict
        ``{'phi': ..., input name: ...}``; the loss-factor partials appear only
        for the inputs the loss model depends on.
    """
    out = {
        "phi": d_dphi,
        "v_axial": d_dv_axial,
        "v_theta_ref": d_dv_theta,
        "ref_chord": d_dsigma * section.dsigma_dref_chord,
        "ref_radius": d_dsigma * section.dsigma_dref_radius,
        "cl_star": d_dcl,
        "cd_star": d_dcd,
    }
    for name, d_F in loss_partials(section.loss, loss_model, r="ref_radius").items():
        out[name] = out[name] + d_dF * d_F if name in out else d_dF * d_F
    return out


def section_wrt(loss_model):
    """The inputs a reference-station quantity depends on, for exact sparsity."""
    return ["v_axial", "v_theta_ref", "ref_chord", "ref_radius", "cl_star", "cd_star"] + list(loss_inputs(loss_model))


class ReferenceStationComp(om.ImplicitComponent):
    """Inflow angle ``phi_ref`` of the reference station, the one BEM solve of BILD.

    The blade element at ``r_ref`` has the prescribed chord ``c_ref`` and works
    at the maximum-L/D point, so ``C_l = C_l*`` and ``C_d = C_d*`` are fixed
    (not read from the polar at the solved angle of attack).  The state solves
    the BEM residual, Eq. (9) generalised by Prandtl's loss factor::

        R(phi) = (V_x/V_theta)(sigma C_theta + 4 F sin cos) + sigma C_x - 4 F sin**2 = 0

    with ``sigma = B c_ref / (2 pi r_ref)``, ``C_x, C_theta`` from Eq. (7) and
    ``F = F(phi, r_ref)``.  The solve reuses the package's bracketed BEM solver
    (:func:`bild_mdo.bem.root_finding.solve_bracketed`); under complex step one
    complex Newton update after the real solve
    (:func:`~bild_mdo.utils.newton.complex_step_update`) carries the exact derivative.
    The state Jacobian is diagonal, so ``solve_linear`` divides elementwise.

    Options
    -------
    num_nodes, num_blades, loss_model
        Those of :func:`~bild_mdo.bem.blade_element.declare_section_options`
        (no stations, no polar).

    Inputs
    ------
    v_axial[nn] (m/s), v_theta_ref[nn] (m/s)
        Axial free-stream velocity, ``Omega r_ref``.
    ref_radius[nn] (m), ref_chord[nn] (m)
        Reference station radius and chord.
    radius[nn] (m), hub_radius[nn] (m)
        Tip and hub radii (Prandtl loss factor).
    cl_star[nn] (-), cd_star[nn] (-)
        Lift and drag coefficients at the maximum lift-to-drag ratio.

    Outputs
    -------
    phi_ref[nn] (rad)
        Inflow angle at the reference station.
    """

    def initialize(self):
        declare_reference_options(self.options)

    def setup(self):
        nn = self.options["num_nodes"]
        add_section_inputs(self, REFERENCE_INPUTS)
        self.add_output("phi_ref", val=np.full(nn, 0.1), units="rad",
                        desc="inflow angle at the reference station")
        self._dR_dphi = np.ones(nn)

    def setup_partials(self):
        rows, cols = node_wrt_node(self.options["num_nodes"])
        self.declare_partials("phi_ref", ["phi_ref"] + section_wrt(self.options["loss_model"]),
                              rows=rows, cols=cols)

    def _residual(self, phi, inputs):
        """Residual and all its partials (real part), at inflow angle ``phi``."""
        b, model = self.options["num_blades"], self.options["loss_model"]
        section = reference_section(phi, inputs, b, model)
        res = inflow_residual(phi, inputs["v_axial"], inputs["v_theta_ref"], section.sigma,
                              inputs["cl_star"], inputs["cd_star"], section.loss.F)
        partials = section_partials(res.dR_dphi, res.dR_dsigma, res.dR_dF, res.dR_dv_axial,
                                    res.dR_dv_theta, res.dR_dcl, res.dR_dcd, section, model)
        return res.residual, partials

    def _residual_value(self, phi, inputs):
        b, model = self.options["num_blades"], self.options["loss_model"]
        section = reference_section(phi, inputs, b, model)
        return inflow_residual_value(phi, inputs["v_axial"], inputs["v_theta_ref"], section.sigma,
                                     inputs["cl_star"], inputs["cd_star"], section.loss.F)

    def apply_nonlinear(self, inputs, outputs, residuals):
        residuals["phi_ref"] = self._residual_value(outputs["phi_ref"], inputs)

    def solve_nonlinear(self, inputs, outputs):
        nn = self.options["num_nodes"]
        real = {name: np.real(inputs[name]) for name in REFERENCE_INPUTS}
        if np.any(real["v_theta_ref"] <= 0.0):
            raise om.AnalysisError(f"{self.msginfo}: the reference station needs a positive rotor speed")
        if np.any(real["v_axial"] < 0.0):
            raise om.AnalysisError(f"{self.msginfo}: BILD designs need v_axial >= 0 (Assumption 4)")

        phi = self._solve_region_one(real)
        if phi is None:
            def residual(phi, idx):
                sub = {name: value[idx] for name, value in real.items()}
                value, partials = self._residual(phi, sub)
                return value, partials["phi"]

            phi = solve_bracketed(residual, nn, describe=lambda i: f"reference station of design/node {i}")
        if np.iscomplexobj(outputs["phi_ref"]):
            _, partials = self._residual(phi, real)
            phi = complex_step_update(phi, self._residual_value(phi, inputs), partials["phi"])
        outputs["phi_ref"] = phi

    def _solve_region_one(self, real):
        """The root in ``[eps, pi/2]`` from an explicit estimate, or None where the bracketed search is needed.

        The bracketed search (:func:`~bild_mdo.bem.root_finding.solve_bracketed`) takes region 1,
        ``[eps, pi/2]``, wherever its end points have opposite signs.  With ``C_l*, C_d*`` fixed the
        residual has one root there (one sign change on a 4001-point grid at each of 20,000 random
        reference stations: ``V_x/V_theta <= 2``, ``sigma <= 0.9``, ``L/D`` 5 ... 200, Prandtl tip and
        hub losses), so only the start differs: the small-angle root of the residual without loss
        and drag, ``4 phi**2 - lam (sigma C_l + 4) phi - sigma C_l = 0`` (``lam = V_x / V_theta``),
        instead of the false-position point; the iteration evaluates only ``R`` and ``dR/dphi``
        (the other partials once, in ``linearize``).  Returns None (the bracketed search then
        solves every node) if a node needs another region or its root is not a simple crossing
        in the direction of the end-point signs.
        """
        b, model = self.options["num_blades"], self.options["loss_model"]
        v_x, v_t, cl, cd = real["v_axial"], real["v_theta_ref"], real["cl_star"], real["cd_star"]
        sigma = b * real["ref_chord"] / (2.0 * np.pi * real["ref_radius"])
        lam = v_x / v_t
        geometry = (real["ref_radius"], real["radius"], real["hub_radius"])
        n = v_x.size

        def residual(phi, idx):
            r_ref, radius, hub = (x[idx] for x in geometry)
            loss, dloss = prandtl_loss_and_dphi(phi, r_ref, radius, hub, b, model)
            s, c = np.sin(phi), np.cos(phi)
            sgn = sign_of_sine(phi)
            abs_s = sgn * s
            lam_i, sig_i, cl_i, cd_i = lam[idx], sigma[idx], cl[idx], cd[idx]
            c_x, c_theta = cl_i * c - cd_i * s, cl_i * s + cd_i * c
            value = lam_i * (sig_i * c_theta + 4.0 * loss * abs_s * c) + sig_i * c_x - 4.0 * loss * s * abs_s
            slope = (lam_i * (sig_i * c_x + 4.0 * loss * sgn * np.cos(2.0 * phi)) - sig_i * c_theta
                     - 4.0 * loss * sgn * np.sin(2.0 * phi) + 4.0 * abs_s * (lam_i * c - s) * dloss)
            return value, slope

        lo, hi = BRACKET_EPS, 0.5 * np.pi
        bsig = lam * (sigma * cl + 4.0)
        estimate = np.clip((bsig + np.sqrt(bsig * bsig + 16.0 * sigma * cl)) / 8.0, 2.0 * lo, 0.5 * hi)
        index = np.arange(n)
        with np.errstate(all="ignore"):
            values, slopes = residual(np.concatenate([np.full(n, lo), np.full(n, hi), estimate]),
                                      np.concatenate([index, index, index]))
        r_lo, r_hi, r_0 = values[:n], values[n:2 * n], values[2 * n:]
        if not (np.all(np.isfinite(values)) and np.all(opposite_signs(r_lo, r_hi))):
            return None
        # The first Newton pass, from the estimate, inside the bracket it narrows.
        same = np.sign(r_0) == np.sign(r_lo)
        lo_1 = np.where(same, estimate, lo)
        hi_1 = np.where(same, hi, estimate)
        with np.errstate(all="ignore"):
            x_1 = estimate - r_0 / slopes[2 * n:]
        result = bracketed_newton(residual, lo_1, hi_1, np.where(same, r_0, r_lo), x_1, atol=RESIDUAL_TOL,
                                  max_iter=MAX_ITER, quadratic_stop=True)
        # A simple root whose slope has the sign of R(pi/2) - R(eps): with one root in the region that is
        # the bracketed search's root; anything else goes to that search.
        if not (np.all(result.converged) and np.all(result.slope * (r_hi - r_lo) > 0.0)):
            return None
        return result.x

    def linearize(self, inputs, outputs, jacobian):
        _, partials = self._residual(np.real(outputs["phi_ref"]),
                                     {name: np.real(inputs[name]) for name in REFERENCE_INPUTS})
        for name, value in partials.items():
            jacobian["phi_ref", "phi_ref" if name == "phi" else name] = value
        self._dR_dphi = partials["phi"]

    def solve_linear(self, d_outputs, d_residuals, mode):
        if mode == "fwd":
            d_outputs["phi_ref"] = d_residuals["phi_ref"] / self._dR_dphi
        else:
            d_residuals["phi_ref"] = d_outputs["phi_ref"] / self._dR_dphi
