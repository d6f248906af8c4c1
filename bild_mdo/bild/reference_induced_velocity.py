"""Induced velocities at the reference station from its solved inflow angle (Eq. (8) with F)."""
import numpy as np
import openmdao.api as om

from bild_mdo.bem.blade_element import add_section_inputs
from bild_mdo.bem.inflow_residual import induced_velocities
from bild_mdo.bem.prandtl import loss_inputs
from bild_mdo.bild.variants.reference_point.reference_station import (REFERENCE_INPUTS, declare_reference_options, reference_loss,
                                             reference_section, section_partials, section_wrt)
from bild_mdo.utils.options import add_outputs
from bild_mdo.utils.sparsity import node_wrt_node


class ReferenceInducedVelocityComp(om.ExplicitComponent):
    """Axial and tangential induced velocities at the reference station (Algorithm 1, step 2).

    Eq. (8) generalised by Prandtl's loss factor ``F``::

        D       = 4 F sin(phi) cos(phi) + sigma C_theta
        u_theta = 2 sigma C_theta V_theta / D
        u_axial = V_x + sigma C_x V_theta / D

    at ``phi = phi_ref`` with ``C_l*``, ``C_d*`` fixed.  They define the
    ideal-loading constant (Eq. (22)).

    Options
    -------
    num_nodes, num_blades, loss_model
        Those of :class:`~bild_mdo.bild.variants.reference_point.reference_station.ReferenceStationComp`.

    Inputs
    ------
    phi_ref[nn] (rad)
        Inflow angle at the reference station, and the reference-section inputs
        of :class:`~bild_mdo.bild.variants.reference_point.reference_station.ReferenceStationComp`
        (:data:`~bild_mdo.bild.variants.reference_point.reference_station.REFERENCE_INPUTS`).

    Outputs
    -------
    u_axial_ref[nn] (m/s)
        Axial velocity at the disk at the reference station.
    u_theta_ref[nn] (m/s)
        Tangential induced velocity at the reference station.
    """

    def initialize(self):
        declare_reference_options(self.options)

    def setup(self):
        add_section_inputs(self, ("phi_ref",) + REFERENCE_INPUTS)
        add_outputs(self, ("u_axial_ref", "u_theta_ref"))

    def setup_partials(self):
        rows, cols = node_wrt_node(self.options["num_nodes"])
        wrt = ["phi_ref"] + section_wrt(self.options["loss_model"])
        self.declare_partials("u_axial_ref", wrt, rows=rows, cols=cols)
        self.declare_partials("u_theta_ref", [name for name in wrt if name != "v_axial"],
                              rows=rows, cols=cols)

    def _velocities(self, inputs):
        section = reference_section(inputs["phi_ref"], inputs, self.options["num_blades"],
                                    self.options["loss_model"])
        vel = induced_velocities(inputs["phi_ref"], inputs["v_axial"], inputs["v_theta_ref"],
                                 section.sigma, inputs["cl_star"], inputs["cd_star"], section.loss.F)
        return section, vel

    def compute(self, inputs, outputs):
        values = None if np.iscomplexobj(inputs["phi_ref"]) else self._values(inputs)
        if values is None:
            # Complex step, or a value that is not finite (induced_velocities raises the error).
            _, vel = self._velocities(inputs)
            values = vel.u_axial, vel.u_theta
        outputs["u_axial_ref"], outputs["u_theta_ref"] = values

    def _terms(self, inputs, radii):
        """Real ``F`` (:func:`~bild_mdo.bild.variants.reference_point.reference_station.reference_loss`) and the terms of Eq. (8)."""
        b, model = self.options["num_blades"], self.options["loss_model"]
        # One design: NumPy scalars (the same operations, without the cost of one-element arrays).
        scalar = self.options["num_nodes"] == 1
        v = {name: (inputs[name][0] if scalar else inputs[name]) for name in ("phi_ref",) + REFERENCE_INPUTS}
        loss = reference_loss(v["phi_ref"], v["ref_radius"], v["radius"], v["hub_radius"], b, model, radii=radii)
        s, c, cl, cd = loss.sin, loss.cos, v["cl_star"], v["cd_star"]
        sigma = b * v["ref_chord"] / (2.0 * np.pi * v["ref_radius"])
        c_x, c_theta = cl * c - cd * s, cl * s + cd * c
        abs_sin_cos = loss.sign * s * c
        denominator = 4.0 * loss.F * abs_sin_cos + sigma * c_theta
        return v, loss, sigma, c_x, c_theta, abs_sin_cos, denominator

    def _values(self, inputs):
        """``u_axial, u_theta`` of Eq. (8) alone (real inputs; the partials in compute_partials), or None."""
        with np.errstate(all="ignore"):
            v, _, sigma, c_x, c_theta, _, denominator = self._terms(inputs, radii=False)
            v_t = v["v_theta_ref"]
            u_theta = 2.0 * v_t * sigma * c_theta / denominator
            u_axial = v["v_axial"] + v_t * sigma * c_x / denominator
        if not np.isfinite(u_axial + u_theta).all():
            return None
        return u_axial, u_theta

    def compute_partials(self, inputs, partials):
        names = ("phi_ref",) + REFERENCE_INPUTS
        if np.iscomplexobj(inputs["phi_ref"]):
            self._general_partials({name: inputs[name] for name in names}, partials)
            return
        b, model = self.options["num_blades"], self.options["loss_model"]
        with np.errstate(all="ignore"):
            v, loss, sigma, c_x, c_theta, abs_sin_cos, denominator = self._terms(inputs, radii=True)
            s, c, v_t, r_ref = loss.sin, loss.cos, v["v_theta_ref"], v["ref_radius"]
            n_term, m_term = sigma * c_theta, sigma * c_x
            # P = 4 F |sin| cos: its total phi derivative (F(phi) included) and its F derivative.
            dP_dF = 4.0 * abs_sin_cos
            dP_dphi = 4.0 * loss.F * loss.sign * (c * c - s * s) + dP_dF * loss.dF_dphi
            # u_theta = 2 V N / D, u_axial = V_x + V M / D, D = P + N.
            ut_n = 2.0 * v_t * (dP_dF * loss.F) / denominator ** 2
            ut_p = -2.0 * v_t * n_term / denominator ** 2
            ux_m = v_t / denominator
            ux_d = -v_t * m_term / denominator ** 2
            ux_sigma, ut_sigma = ux_m * c_x + ux_d * c_theta, ut_n * c_theta
            dsigma_dchord, dsigma_dradius = b / (2.0 * np.pi * r_ref), -sigma / r_ref
            axial = {"phi_ref": -ux_m * n_term + ux_d * (dP_dphi + m_term), "v_axial": np.ones_like(v_t),
                     "v_theta_ref": m_term / denominator, "ref_chord": ux_sigma * dsigma_dchord,
                     "ref_radius": ux_sigma * dsigma_dradius + ux_d * dP_dF * loss.dF_dref_radius,
                     "cl_star": sigma * (ux_m * c + ux_d * s), "cd_star": sigma * (ux_d * c - ux_m * s)}
            tangential = {"phi_ref": ut_n * m_term + ut_p * dP_dphi, "v_theta_ref": 2.0 * n_term / denominator,
                          "ref_chord": ut_sigma * dsigma_dchord,
                          "ref_radius": ut_sigma * dsigma_dradius + ut_p * dP_dF * loss.dF_dref_radius,
                          "cl_star": ut_n * sigma * s, "cd_star": ut_n * sigma * c}
            for name in loss_inputs(model):
                dF = getattr(loss, f"dF_d{name}")
                axial[name] = ux_d * dP_dF * dF
                tangential[name] = ut_p * dP_dF * dF
            finite = np.isfinite(sum(axial.values()) + sum(tangential.values())).all()
        if not finite:
            # Beyond the floating-point range: the general path (its overflow guards and error message).
            self._general_partials({name: inputs[name] for name in names}, partials)
            return
        for name, value in axial.items():
            partials["u_axial_ref", name] = value
        for name, value in tangential.items():
            partials["u_theta_ref", name] = value

    def _general_partials(self, inputs, partials):
        model = self.options["loss_model"]
        section, vel = self._velocities(inputs)
        axial = section_partials(vel.du_axial_dphi, vel.du_axial_dsigma, vel.du_axial_dF,
                                 vel.du_axial_dv_axial, vel.du_axial_dv_theta, vel.du_axial_dcl,
                                 vel.du_axial_dcd, section, model)
        tangential = section_partials(vel.du_theta_dphi, vel.du_theta_dsigma, vel.du_theta_dF,
                                      vel.du_theta_dv_axial, vel.du_theta_dv_theta, vel.du_theta_dcl,
                                      vel.du_theta_dcd, section, model)
        for name, value in axial.items():
            partials["u_axial_ref", "phi_ref" if name == "phi" else name] = value
        for name, value in tangential.items():
            if name != "v_axial":
                partials["u_theta_ref", "phi_ref" if name == "phi" else name] = value
