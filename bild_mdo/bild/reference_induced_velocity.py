"""Induced velocities at the reference station from its solved inflow angle (Eq. (8) with F)."""
import numpy as np
import openmdao.api as om

from bild_mdo.bem.inflow_residual import induced_velocities
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bild.reference_station import (SECTION_INPUTS, add_section_inputs, reference_section,
                                             section_partials, section_wrt)
from bild_mdo.utils.sparsity import node_wrt_node


class ReferenceInducedVelocityComp(om.ExplicitComponent):
    """Axial and tangential induced velocities at the reference station (Algorithm 1, step 2).

    Eq. (8) generalised by Prandtl's loss factor ``F``::

        D       = 4 F sin(phi) cos(phi) + sigma C_theta
        u_theta = 2 sigma C_theta V_theta / D
        u_x     = V_x + sigma C_x V_theta / D

    at ``phi = phi_ref`` with ``C_l*``, ``C_d*`` fixed.  They define the
    ideal-loading constant (Eq. (22)).

    Options
    -------
    num_nodes : int
        Number of designs / operating points.
    num_radial : int
        Number of radial stations (unused here).
    num_blades : int
        Number of blades B.
    loss_model : str
        ``'tip_hub'`` (default), ``'tip'`` or ``'none'``.

    Inputs
    ------
    phi_ref[nn] (rad)
        Inflow angle at the reference station.
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
    u_x_ref[nn] (m/s)
        Axial velocity at the disk at the reference station.
    u_theta_ref[nn] (m/s)
        Tangential induced velocity at the reference station.
    """

    def initialize(self):
        self.options.declare("num_nodes", types=int, default=1, desc="number of designs / operating points")
        self.options.declare("num_radial", types=int, default=1, desc="number of radial stations (unused)")
        self.options.declare("num_blades", types=int, default=3, desc="number of blades B")
        self.options.declare("loss_model", default="tip_hub", values=LOSS_MODELS,
                             desc="Prandtl losses: 'tip_hub', 'tip' or 'none'")

    def setup(self):
        nn = self.options["num_nodes"]
        self.add_input("phi_ref", val=np.full(nn, 0.1), units="rad",
                       desc="inflow angle at the reference station")
        add_section_inputs(self, nn)
        self.add_output("u_x_ref", val=np.full(nn, 5.0), units="m/s",
                        desc="axial velocity at the rotor disk at the reference station, Eq. (8)")
        self.add_output("u_theta_ref", val=np.ones(nn), units="m/s",
                        desc="tangential induced velocity at the reference station, Eq. (8)")

    def setup_partials(self):
        rows, cols = node_wrt_node(self.options["num_nodes"])
        wrt = ["phi_ref"] + section_wrt(self.options["loss_model"])
        self.declare_partials("u_x_ref", wrt, rows=rows, cols=cols)
        self.declare_partials("u_theta_ref", [name for name in wrt if name != "v_axial"],
                              rows=rows, cols=cols)

    def _velocities(self, inputs):
        section = reference_section(inputs["phi_ref"], inputs, self.options["num_blades"],
                                    self.options["loss_model"])
        vel = induced_velocities(inputs["phi_ref"], inputs["v_axial"], inputs["v_theta_ref"],
                                 section.sigma, inputs["cl_star"], inputs["cd_star"], section.loss.F)
        return section, vel

    def compute(self, inputs, outputs):
        _, vel = self._velocities(inputs)
        outputs["u_x_ref"] = vel.u_axial
        outputs["u_theta_ref"] = vel.u_theta

    def compute_partials(self, inputs, partials):
        model = self.options["loss_model"]
        section, vel = self._velocities({name: inputs[name] for name in ("phi_ref",) + SECTION_INPUTS})
        axial = section_partials(vel.du_axial_dphi, vel.du_axial_dsigma, vel.du_axial_dF,
                                 vel.du_axial_dv_axial, vel.du_axial_dv_theta, vel.du_axial_dcl,
                                 vel.du_axial_dcd, section, model)
        tangential = section_partials(vel.du_theta_dphi, vel.du_theta_dsigma, vel.du_theta_dF,
                                      vel.du_theta_dv_axial, vel.du_theta_dv_theta, vel.du_theta_dcl,
                                      vel.du_theta_dcd, section, model)
        for name, value in axial.items():
            partials["u_x_ref", "phi_ref" if name == "phi" else name] = value
        for name, value in tangential.items():
            if name != "v_axial":
                partials["u_theta_ref", "phi_ref" if name == "phi" else name] = value
