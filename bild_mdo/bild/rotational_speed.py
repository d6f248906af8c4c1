"""Blade rotational speed V_theta = Omega r at the stations and at the reference station."""
import numpy as np
import openmdao.api as om

from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.utils.options import add_inputs, add_outputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node, node_wrt_node


class RotationalSpeedComp(om.ExplicitComponent):
    """Rotational blade speed ``V_theta = Omega r`` (paper nomenclature, Fig. 1b).

    Options: the sizes ``num_nodes`` and ``num_radial``
    (:func:`~bild_mdo.utils.options.declare_size_options`).

    Inputs
    ------
    rpm[nn] (rpm)
        Rotor speed.
    radii[nn, nr] (m)
        Radii of the blade stations.
    ref_radius[nn] (m)
        Radius of the reference station.

    Outputs
    -------
    v_theta[nn, nr] (m/s)
        ``Omega r`` at every station.
    v_theta_ref[nn] (m/s)
        ``Omega r_ref`` at the reference station.
    """

    def initialize(self):
        declare_size_options(self.options)

    def setup(self):
        add_inputs(self, ("rpm", "radii", "ref_radius"))
        add_outputs(self, ("v_theta", "v_theta_ref"))

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials("v_theta", "rpm", rows=rows, cols=cols)
        rows, cols = dist_wrt_dist(nn, nr)
        self.declare_partials("v_theta", "radii", rows=rows, cols=cols)
        rows, cols = node_wrt_node(nn)
        self.declare_partials("v_theta_ref", ["rpm", "ref_radius"], rows=rows, cols=cols)

    def compute(self, inputs, outputs):
        omega = inputs["rpm"] * RPM_TO_RAD_PER_S
        outputs["v_theta"] = omega[:, None] * inputs["radii"]
        outputs["v_theta_ref"] = omega * inputs["ref_radius"]

    def compute_partials(self, inputs, partials):
        omega = inputs["rpm"] * RPM_TO_RAD_PER_S
        nr = self.options["num_radial"]
        partials["v_theta", "rpm"] = (RPM_TO_RAD_PER_S * inputs["radii"]).ravel()
        partials["v_theta", "radii"] = np.repeat(omega, nr)
        partials["v_theta_ref", "rpm"] = RPM_TO_RAD_PER_S * inputs["ref_radius"]
        partials["v_theta_ref", "ref_radius"] = omega
