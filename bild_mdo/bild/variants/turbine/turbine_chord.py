"""Back-computed chord and twist of the turbine blade (the paper's Sec. 4.3 with the windmill signs)."""
import numpy as np
import openmdao.api as om

from bild_mdo.bild.variants.turbine.kernel import station_chords
from bild_mdo.utils.options import add_inputs, add_outputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node


class TurbineChordComp(om.ExplicitComponent):
    """Chord that makes the blade element carry the ideal thrust, and the twist of the section point.

    The paper's Eq. (31) with the turbine's normal-force coefficient (lift and thrust both downwind)::

        c = 2 dT/dr / (C_n rho W**2 B),   C_n = C_l* cos(phi) + C_d* sin(phi),   theta = phi - alpha*

    (``alpha = phi - theta``: the wind meets the section from its pressure side).  ``C_n > 0`` for
    ``0 < phi < pi/2``; an unloaded station (zero thrust) gets zero chord.

    Options: ``num_nodes``, ``num_radial``, ``num_blades``.

    Inputs
    ------
    dthrust_dr[nn, nr] (N/m), phi[nn, nr] (rad), inflow_speed[nn, nr] (m/s)
    rho[nn] (kg/m**3), alpha_star[nn] (rad), cl_star[nn] (-), cd_star[nn] (-)

    Outputs
    -------
    chord[nn, nr] (m), twist[nn, nr] (rad)
        Blade chord and twist (pitch from the rotor plane, turbine convention).
    lift_coefficient[nn, nr] (-), drag_coefficient[nn, nr] (-)
        ``C_l*``, ``C_d*`` at every station.
    """

    def initialize(self):
        declare_size_options(self.options)
        self.options.declare("num_blades", types=int, default=3, desc="number of blades B")

    def setup(self):
        add_inputs(self, ("dthrust_dr", "phi", "inflow_speed", "rho", "alpha_star", "cl_star", "cd_star"))
        add_outputs(self, ("chord", "twist", "lift_coefficient", "drag_coefficient"))

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = dist_wrt_dist(nn, nr)
        self.declare_partials("chord", ["dthrust_dr", "phi", "inflow_speed"], rows=rows, cols=cols)
        self.declare_partials("twist", "phi", rows=rows, cols=cols, val=1.0)
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials("chord", ["rho", "cl_star", "cd_star"], rows=rows, cols=cols)
        self.declare_partials("twist", "alpha_star", rows=rows, cols=cols, val=-1.0)
        self.declare_partials("lift_coefficient", "cl_star", rows=rows, cols=cols, val=1.0)
        self.declare_partials("drag_coefficient", "cd_star", rows=rows, cols=cols, val=1.0)

    def _not_positive(self):
        raise om.AnalysisError(f"{self.msginfo}: the normal-force coefficient C_l cos(phi) + C_d sin(phi) is "
                               "not positive: the section point needs C_l* > 0 (check the airfoil)")

    def _terms(self, inputs):
        phi = inputs["phi"]
        cl, cd = inputs["cl_star"][:, None], inputs["cd_star"][:, None]
        normal = cl * np.cos(phi) + cd * np.sin(phi)
        if np.any(np.real(normal) <= 0.0):
            self._not_positive()
        scale = 2.0 / (inputs["rho"][:, None] * inputs["inflow_speed"] ** 2 * self.options["num_blades"])
        return phi, cl, cd, normal, scale

    def compute(self, inputs, outputs):
        if not np.iscomplexobj(inputs["phi"]):
            names = ("dthrust_dr", "phi", "inflow_speed", "rho", "alpha_star", "cl_star", "cd_star")
            if not station_chords(*(inputs[name] for name in names), self.options["num_blades"], outputs):
                self._not_positive()
            return
        phi, cl, cd, normal, scale = self._terms(inputs)
        outputs["chord"] = scale * inputs["dthrust_dr"] / normal
        outputs["twist"] = phi - inputs["alpha_star"][:, None]
        outputs["lift_coefficient"] = np.broadcast_to(cl, phi.shape)
        outputs["drag_coefficient"] = np.broadcast_to(cd, phi.shape)

    def compute_partials(self, inputs, partials):
        phi, cl, cd, normal, scale = self._terms(inputs)
        chord = scale * inputs["dthrust_dr"] / normal
        partials["chord", "dthrust_dr"] = (scale / normal).ravel()
        partials["chord", "phi"] = (-chord / normal * (cd * np.cos(phi) - cl * np.sin(phi))).ravel()
        partials["chord", "inflow_speed"] = (-2.0 * chord / inputs["inflow_speed"]).ravel()
        partials["chord", "rho"] = (-chord / inputs["rho"][:, None]).ravel()
        partials["chord", "cl_star"] = (-chord / normal * np.cos(phi)).ravel()
        partials["chord", "cd_star"] = (-chord / normal * np.sin(phi)).ravel()
