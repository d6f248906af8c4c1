"""MILBladeComp: chord and twist of the minimum-induced-loss blade (Adkins & Liebeck 1994)."""
import numpy as np
import openmdao.api as om

from bild_mdo.mil.kernel import add_mil_inputs, declare_design_options, station_state
from bild_mdo.utils.options import add_inputs, add_outputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node


class MILBladeComp(om.ExplicitComponent):
    """Blade geometry of the design with displacement velocity ratio ``zeta`` (A&L design steps).

    With the station relations of :mod:`bild_mdo.mil.kernel` (``phi``, ``F``,
    ``G``, the axial interference factor ``a``)::

        W c  = 4 pi lambda G V R zeta / (C_l B)       product of local speed and chord
        W    = V (1 + a) / sin(phi)                   local total velocity
        c    = W c / W = 4 pi lambda G R zeta sin(phi) / (C_l B (1 + a))
        beta = alpha + phi                            blade (twist) angle

    Every section works at the same airfoil point ``(alpha*, C_l*, C_d*)``,
    BILD's reference point, so the comparison with BILD differs only in the
    loading.

    Options
    -------
    num_nodes, num_radial, num_blades : int
        Sizes and the number of blades B.
    loss_form : {'adkins_liebeck', 'local', 'qmil'}
        Prandtl exponent (see :mod:`bild_mdo.mil.kernel`).

    Inputs
    ------
    speed_ratio[nn] (-), radius_fraction[nn, nr] (-), zeta[nn] (-)
        ``lambda``, ``xi`` and the displacement velocity ratio.
    cl_star[nn] (-), cd_star[nn] (-), alpha_star[nn] (rad)
        Design airfoil point.
    radius[nn] (m), v_axial[nn] (m/s)
        Tip radius and flight speed.

    Outputs
    -------
    chord[nn, nr] (m), twist[nn, nr] (rad)
        Blade geometry.
    phi[nn, nr] (rad), inflow_speed[nn, nr] (m/s), loss_factor[nn, nr] (-)
        Flow angle, local total velocity ``W`` and Prandtl's ``F`` of the design.
    """

    def initialize(self):
        declare_size_options(self.options)
        declare_design_options(self.options)

    def setup(self):
        add_mil_inputs(self, ("speed_ratio", "radius_fraction", "zeta"))
        add_inputs(self, ("cl_star", "cd_star", "alpha_star", "radius", "v_axial"), cl_star=0.7, v_axial=50.0)
        add_outputs(self, ("chord", "twist", "phi", "inflow_speed", "loss_factor"))

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = dist_wrt_node(nn, nr)
        outputs = ("chord", "twist", "phi", "inflow_speed", "loss_factor")
        for name in outputs:
            wrt = ["speed_ratio", "zeta", "cd_star", "cl_star"]
            wrt += {"chord": ["radius"], "twist": ["alpha_star"], "inflow_speed": ["v_axial"]}.get(name, [])
            self.declare_partials(name, wrt, rows=rows, cols=cols)
        rows, cols = dist_wrt_dist(nn, nr)
        self.declare_partials(list(outputs), "radius_fraction", rows=rows, cols=cols)

    def _state(self, inputs):
        cl, cd = inputs["cl_star"][:, None], inputs["cd_star"][:, None]
        state = station_state(inputs["speed_ratio"][:, None], inputs["radius_fraction"], inputs["zeta"][:, None],
                              cd / cl, self.options["num_blades"], self.options["loss_form"])
        chord_shape = (inputs["speed_ratio"][:, None] * inputs["zeta"][:, None]) * state.circulation \
            * state.sin_phi / (1.0 + state.axial_interference)
        speed_shape = (1.0 + state.axial_interference) / state.sin_phi
        scale = 4.0 * np.pi * inputs["radius"][:, None] / (cl * self.options["num_blades"])
        return state, chord_shape, speed_shape, scale

    def compute(self, inputs, outputs):
        state, chord_shape, speed_shape, scale = self._state(inputs)
        outputs["chord"] = scale * chord_shape.value
        outputs["phi"] = state.phi.value
        outputs["twist"] = inputs["alpha_star"][:, None] + state.phi.value
        outputs["inflow_speed"] = inputs["v_axial"][:, None] * speed_shape.value
        outputs["loss_factor"] = state.loss_factor.value

    def compute_partials(self, inputs, partials):
        state, chord_shape, speed_shape, scale = self._state(inputs)
        # chord_shape holds lambda and zeta as plain factors: add their own partials to the chain rule's.
        lam, zeta = inputs["speed_ratio"][:, None], inputs["zeta"][:, None]
        base = chord_shape.value / (lam * zeta)
        chord_grad = chord_shape.grad.copy()
        chord_grad[0] += base * zeta
        chord_grad[2] += base * lam
        cl, cd = inputs["cl_star"][:, None], inputs["cd_star"][:, None]
        chord = scale * chord_shape.value
        v = inputs["v_axial"][:, None]
        jets = {"chord": (scale * chord_grad, chord), "phi": (state.phi.grad, None),
                "twist": (state.phi.grad, None), "inflow_speed": (v * speed_shape.grad, None),
                "loss_factor": (state.loss_factor.grad, None)}
        for name, (grad, value) in jets.items():
            partials[name, "speed_ratio"] = grad[0].ravel()
            partials[name, "radius_fraction"] = grad[1].ravel()
            partials[name, "zeta"] = grad[2].ravel()
            partials[name, "cd_star"] = (grad[3] / cl).ravel()
            dcl = -grad[3] * cd / cl ** 2
            if name == "chord":
                dcl = dcl - value / cl
            partials[name, "cl_star"] = dcl.ravel()
        partials["chord", "radius"] = (chord / inputs["radius"][:, None]).ravel()
        partials["twist", "alpha_star"] = np.ones(chord.size)
        partials["inflow_speed", "v_axial"] = np.broadcast_to(speed_shape.value, chord.shape).ravel()
