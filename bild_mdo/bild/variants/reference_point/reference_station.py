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
from bild_mdo.bem.inflow_residual import inflow_residual, inflow_residual_value
from bild_mdo.bem.prandtl import (EXPONENT_MAX, EXPONENT_MIN, SIN_PHI_FLOOR, loss_inputs, loss_partials,
                                  prandtl_loss)
from bild_mdo.bem.root_finding import BRACKET_EPS, opposite_signs, solve_bracketed
from bild_mdo.utils.newton import complex_step_update
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


class ReferenceLoss(NamedTuple):
    """Real Prandtl factor of the reference station and its partials (:func:`reference_loss`).

    ``F`` and ``dF_dphi`` always; the radius partials only when asked for (else None).
    ``sin, cos, sign`` are ``sin phi``, ``cos phi`` and ``sgn(sin phi)`` (+1 at 0, as
    :func:`~bild_mdo.bem.inflow_residual.sign_of_sine`).
    """

    F: np.ndarray
    dF_dphi: np.ndarray
    dF_dref_radius: object
    dF_dradius: object
    dF_dhub_radius: object
    sin: np.ndarray
    cos: np.ndarray
    sign: np.ndarray


def _acos_factor(f):
    """``F = 2/pi acos(exp(-f))`` and ``dF/df``, ``f`` clipped as :func:`bild_mdo.bem.prandtl.acos_factor` does."""
    clipped = np.minimum(np.maximum(f, EXPONENT_MIN), EXPONENT_MAX)
    inside = (f > EXPONENT_MIN) & (f < EXPONENT_MAX)
    return _TWO_OVER_PI * np.arccos(np.exp(-clipped)), inside * (_TWO_OVER_PI / np.sqrt(np.expm1(2.0 * clipped)))


def reference_loss(phi, r_ref, radius, hub_radius, num_blades, loss_model, radii=True):
    """:func:`~bild_mdo.bem.prandtl.prandtl_loss` at the reference station, real, in a few array operations.

    The same factor, clips, floor and partials (``f = k / |sin phi|`` with ``k = B (R - r) / (2 r)``
    and ``k = B (r - r_hub) / (2 r_hub)``), without broadcasting, complex support or per-factor
    calls: the reference station evaluates it on ``(nn,)`` arrays (or NumPy scalars for one
    design) several times per run.  Inputs must be real; ``radii=False`` skips the radius partials.

    Returns
    -------
    ReferenceLoss
    """
    s, c = np.sin(phi), np.cos(phi)
    sgn = 1.0 - 2.0 * (s < 0.0)
    abs_s = np.maximum(sgn * s, SIN_PHI_FLOOR)
    if loss_model == "none":
        one = np.ones_like(s)
        zero = 0.0 * s
        return ReferenceLoss(one, zero, zero, zero, zero, s, c, sgn)
    # d ln f / d phi (zero where |sin| is floored).
    dlog = (sgn * s >= SIN_PHI_FLOOR) * (-sgn * c / abs_s)
    half_b = 0.5 * num_blades
    g_tip = half_b / (r_ref * abs_s)
    f_tip = g_tip * (radius - r_ref)
    F_tip, a_tip = _acos_factor(f_tip)
    if loss_model == "tip":
        dF_dphi = a_tip * f_tip * dlog
        if not radii:
            return ReferenceLoss(F_tip, dF_dphi, None, None, None, s, c, sgn)
        return ReferenceLoss(F_tip, dF_dphi, -a_tip * (g_tip + f_tip / r_ref), a_tip * g_tip, 0.0 * s,
                             s, c, sgn)
    g_hub = half_b / (hub_radius * abs_s)
    f_hub = g_hub * (r_ref - hub_radius)
    F_hub, a_hub = _acos_factor(f_hub)
    # Each factor's dF/df times the other factor.
    a_tip, a_hub = a_tip * F_hub, a_hub * F_tip
    dF_dphi = (a_tip * f_tip + a_hub * f_hub) * dlog
    if not radii:
        return ReferenceLoss(F_tip * F_hub, dF_dphi, None, None, None, s, c, sgn)
    return ReferenceLoss(F_tip * F_hub, dF_dphi, a_hub * g_hub - a_tip * (g_tip + f_tip / r_ref), a_tip * g_tip,
                         -a_hub * (g_hub + f_hub / hub_radius), s, c, sgn)


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
        real = {name: np.real(inputs[name]) for name in REFERENCE_INPUTS}
        if (real["v_theta_ref"] <= 0.0).any():
            raise om.AnalysisError(f"{self.msginfo}: the reference station needs a positive rotor speed")
        if (real["v_axial"] < 0.0).any():
            raise om.AnalysisError(f"{self.msginfo}: BILD designs need v_axial >= 0 (Assumption 4)")
        if self.options["loss_model"] == "tip_hub" and (real["hub_radius"] <= 0.0).any():
            # The same rule as bild_mdo.bem.prandtl.prandtl_loss (the lean loss factor here does not check).
            raise ValueError("hub_radius must be positive for loss_model='tip_hub' "
                             "(use loss_model='tip' for a rotor without hub)")

        phi, ok = self._solve_region_one(real)
        if not ok.all():
            todo = np.flatnonzero(~ok)
            sub = {name: value[todo] for name, value in real.items()}

            def residual(phi, idx):
                value, partials = self._residual(phi, {name: x[idx] for name, x in sub.items()})
                return value, partials["phi"]

            phi[todo] = solve_bracketed(residual, todo.size,
                                        describe=lambda i: f"reference station of design/node {todo[i]}")
        if np.iscomplexobj(outputs["phi_ref"]):
            _, partials = self._residual(phi, real)
            phi = complex_step_update(phi, self._residual_value(phi, inputs), partials["phi"])
        outputs["phi_ref"] = phi

    def _solve_region_one(self, real):
        """The root in ``[eps, pi/2]`` by Newton's method from a closed-form start, and where it is that root.

        The bracketed search (:func:`~bild_mdo.bem.root_finding.solve_bracketed`) takes region 1,
        ``[eps, pi/2]``, wherever its end points have opposite signs.  With ``C_l*, C_d*`` fixed the
        residual has one root there (one sign change on a 4001-point grid at each of 20,000 random
        reference stations: ``V_x/V_theta <= 2``, ``sigma <= 0.9``, ``L/D`` 5 ... 200, Prandtl tip and
        hub losses), so only the start differs.  With the geometric angle ``phi_g = atan(V_x/V_theta)``
        and ``phi = phi_g + delta`` the residual is ``R cos(phi_g) = sigma (C_l cos(delta) - C_d
        sin(delta)) - 4 F sin(phi) sin(delta)``; with the load ``q = sigma (C_l cos(delta) - C_d
        sin(delta)) / (4 F)`` held fixed its root is closed, ``sin(delta) sin(phi_g + delta) = q``, i.e.
        ``cos(phi_g + 2 delta) = cos(phi_g) - 2 q``.  The start takes it with ``q = sigma C_l / 4``,
        then once more with ``q`` at that angle (within 6e-4 rad of the root over the paper's
        sweep), so that 2-3 Newton passes of the residual and its phi slope alone converge
        (the other partials once, in ``linearize``).  A node is accepted where the end points have
        opposite signs, the iteration converged inside the region and the root is simple in the
        direction of the end-point signs (with one root in the region, the bracketed search's root);
        the others (``ok`` False) go to that search.  One design runs on NumPy scalars: the same
        operations, without the cost of one-element arrays.

        Returns
        -------
        phi, ok : ndarray
            Shape ``(nn,)``.
        """
        b, model = self.options["num_blades"], self.options["loss_model"]
        scalar = self.options["num_nodes"] == 1
        v = {name: (x[0] if scalar else x) for name, x in real.items()}
        lam = v["v_axial"] / v["v_theta_ref"]
        sigma = b * v["ref_chord"] / (2.0 * np.pi * v["ref_radius"])
        cl, cd = v["cl_star"], v["cd_star"]
        geometry = (v["ref_radius"], v["radius"], v["hub_radius"], b, model)

        def residual(phi):
            loss = reference_loss(phi, *geometry, radii=False)
            s, c, F = loss.sin, loss.cos, loss.F
            c_x, c_theta = cl * c - cd * s, cl * s + cd * c
            # Region 1: |sin phi| = sin phi (an iterate outside it is rejected below).
            value = lam * (sigma * c_theta + 4.0 * F * s * c) + sigma * c_x - 4.0 * F * s * s
            slope = (lam * (sigma * c_x + 4.0 * F * (c * c - s * s)) - sigma * c_theta - 8.0 * F * s * c
                     + 4.0 * s * (lam * c - s) * loss.dF_dphi)
            return value, slope, F

        geometric = np.arctan(lam)
        cos_geometric = np.cos(geometric)

        def closed_form(quarter_load):
            """``phi_g + delta`` with ``cos(phi_g + 2 delta) = cos(phi_g) - 2 quarter_load``."""
            return 0.5 * (geometric + np.arccos(np.minimum(np.maximum(cos_geometric - 2.0 * quarter_load, -1.0),
                                                           1.0)))

        lo, hi = BRACKET_EPS, 0.5 * np.pi
        with np.errstate(all="ignore"):
            start = closed_form(0.25 * sigma * cl)
            values, _, loss = residual(np.stack(np.broadcast_arrays(lo, hi, start)))
            r_lo, r_hi = values[0], values[1]
            delta = start - geometric
            phi = closed_form(0.25 * sigma * (cl * np.cos(delta) - cd * np.sin(delta)) / loss[2])
            # Each node stops on its own (and keeps its root): a node's result does not depend on the batch.
            previous, slope, converged = None, 0.0 * lam, lam < -np.inf
            for _ in range(_MAX_PASSES):
                value, new_slope, _ = residual(phi)
                step = value / new_slope
                size = np.abs(step)
                # Converged: a correction below 1e-12 rad, or quadratic convergence whose applied
                # correction leaves a predicted error below half an ulp (errors O(1e-24) rad).
                stop = size <= _STEP_TOL
                if previous is not None:
                    stop = stop | (size ** 3 <= _QUADRATIC_TOL * np.abs(phi) * previous ** 2)
                if converged.any():
                    phi = np.where(converged, phi, phi - step)
                    slope = np.where(converged, slope, new_slope)
                else:
                    phi, slope = phi - step, new_slope
                converged = converged | stop
                if converged.all():
                    break
                previous = size
            ok = (converged & np.isfinite(phi) & (phi >= lo) & (phi <= hi) & opposite_signs(r_lo, r_hi)
                  & (slope * (r_hi - r_lo) > 0.0))
        return np.atleast_1d(np.asarray(phi, dtype=float)).copy(), np.atleast_1d(ok)

    def _lean_partials(self, phi, real):
        """All partials of the residual at a real ``phi`` (those of ``_residual``, in fewer operations)."""
        b, model = self.options["num_blades"], self.options["loss_model"]
        # One design: NumPy scalars (the same operations, without the cost of one-element arrays).
        scalar = self.options["num_nodes"] == 1
        v = {name: (x[0] if scalar else x) for name, x in real.items()}
        r_ref, v_x, v_t = v["ref_radius"], v["v_axial"], v["v_theta_ref"]
        cl, cd = v["cl_star"], v["cd_star"]
        with np.errstate(all="ignore"):
            loss = reference_loss(phi[0] if scalar else phi, r_ref, v["radius"], v["hub_radius"], b, model)
            s, c, sgn, F = loss.sin, loss.cos, loss.sign, loss.F
            sigma = b * v["ref_chord"] / (2.0 * np.pi * r_ref)
            lam = v_x / v_t
            c_x, c_theta = cl * c - cd * s, cl * s + cd * c
            bracket = sigma * c_theta + 4.0 * F * sgn * s * c
            dR_dF = 4.0 * sgn * s * (lam * c - s)
            dR_dsigma = lam * c_theta + c_x
            partials = {
                "phi": (lam * (sigma * c_x + 4.0 * F * sgn * (c * c - s * s)) - sigma * c_theta
                        - 8.0 * F * sgn * s * c + dR_dF * loss.dF_dphi),
                "v_axial": bracket / v_t,
                "v_theta_ref": -lam * bracket / v_t,
                "ref_chord": dR_dsigma * b / (2.0 * np.pi * r_ref),
                "ref_radius": -dR_dsigma * sigma / r_ref + dR_dF * loss.dF_dref_radius,
                "cl_star": sigma * (lam * s + c),
                "cd_star": sigma * (lam * c - s),
            }
            for name in loss_inputs(model):
                partials[name] = dR_dF * getattr(loss, f"dF_d{name}")
            finite = np.isfinite(sum(partials.values())).all()
        # Beyond the floating-point range: the general path (its overflow guards and error message).
        return partials if finite else self._residual(phi, real)[1]

    def linearize(self, inputs, outputs, jacobian):
        partials = self._lean_partials(np.real(outputs["phi_ref"]),
                                       {name: np.real(inputs[name]) for name in REFERENCE_INPUTS})
        for name, value in partials.items():
            jacobian["phi_ref", "phi_ref" if name == "phi" else name] = value
        self._dR_dphi = partials["phi"]

    def solve_linear(self, d_outputs, d_residuals, mode):
        if mode == "fwd":
            d_outputs["phi_ref"] = d_residuals["phi_ref"] / self._dR_dphi
        else:
            d_residuals["phi_ref"] = d_outputs["phi_ref"] / self._dR_dphi


_TWO_OVER_PI = 2.0 / np.pi
#: Newton passes of the reference-station solve before a node goes to the bracketed search.
_MAX_PASSES = 8
#: A Newton correction (rad) below which the reference-station solve has converged (it is applied).
_STEP_TOL = 1e-12
#: ``eps / 4``: half an ulp of ``phi``, the predicted error below which quadratic convergence stops.
_QUADRATIC_TOL = 0.25 * np.finfo(float).eps
