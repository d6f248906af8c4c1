"""Induced velocities at the reference station from its solved inflow angle (Eq. (8) with F)."""
import numpy as np
import openmdao.api as om

from bild_mdo.bem.blade_element import add_section_inputs
from bild_mdo.bem.inflow_residual import induced_velocities, sign_of_sine
from bild_mdo.bem.prandtl import prandtl_loss_and_dphi
from bild_mdo.bild.reference_station import (REFERENCE_INPUTS, declare_reference_options, reference_section,
                                             section_partials, section_wrt)
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
        Those of :class:`~bild_mdo.bild.reference_station.ReferenceStationComp`.

    Inputs
    ------
    phi_ref[nn] (rad)
        Inflow angle at the reference station, and the reference-section inputs
        of :class:`~bild_mdo.bild.reference_station.ReferenceStationComp`
        (:data:`~bild_mdo.bild.reference_station.REFERENCE_INPUTS`).

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

    def _values(self, inputs):
        """``u_axial, u_theta`` of Eq. (8) alone (real inputs; the partials in compute_partials), or None."""
        b, model = self.options["num_blades"], self.options["loss_model"]
        phi, v_x, v_t = inputs["phi_ref"], inputs["v_axial"], inputs["v_theta_ref"]
        r_ref, cl, cd = inputs["ref_radius"], inputs["cl_star"], inputs["cd_star"]
        sigma = b * inputs["ref_chord"] / (2.0 * np.pi * r_ref)
        loss, _ = prandtl_loss_and_dphi(phi, r_ref, inputs["radius"], inputs["hub_radius"], b, model)
        s, c = np.sin(phi), np.cos(phi)
        n_term = sigma * (cl * s + cd * c)
        m_term = sigma * (cl * c - cd * s)
        with np.errstate(all="ignore"):
            denominator = 4.0 * loss * (sign_of_sine(phi) * s) * c + n_term
            u_theta = 2.0 * v_t * n_term / denominator
            u_axial = v_x + v_t * m_term / denominator
        if not (np.all(np.isfinite(u_axial)) and np.all(np.isfinite(u_theta))):
            return None
        return u_axial, u_theta

    def compute_partials(self, inputs, partials):
        model = self.options["loss_model"]
        section, vel = self._velocities({name: inputs[name] for name in ("phi_ref",) + REFERENCE_INPUTS})
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
