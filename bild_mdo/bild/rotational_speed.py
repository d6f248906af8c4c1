"""Blade rotational speed V_theta = Omega r at the stations and at the reference station."""
import numpy as np
import openmdao.api as om

from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node, node_wrt_node

RPM_TO_RAD_PER_S = 2.0 * np.pi / 60.0


class RotationalSpeedComp(om.ExplicitComponent):
    """Rotational blade speed ``V_theta = Omega r`` (paper nomenclature, Fig. 1b).

    Options
    -------
    num_nodes : int
        Number of designs / operating points.
    num_radial : int
        Number of radial stations.

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
        self.options.declare("num_nodes", types=int, default=1, desc="number of designs / operating points")
        self.options.declare("num_radial", types=int, default=10, desc="number of radial stations")

    def setup(self):
        nn = self.options["num_nodes"]
        nr = self.options["num_radial"]
        self.add_input("rpm", val=np.full(nn, 1000.0), units="rpm", desc="rotor speed")
        self.add_input("radii", val=np.ones((nn, nr)), units="m", desc="radii of the blade stations")
        self.add_input("ref_radius", val=np.ones(nn), units="m", desc="radius of the reference station")
        self.add_output("v_theta", val=np.ones((nn, nr)), units="m/s",
                        desc="rotational blade speed Omega*r at the stations")
        self.add_output("v_theta_ref", val=np.ones(nn), units="m/s",
                        desc="rotational blade speed Omega*r_ref at the reference station")

    def setup_partials(self):
        nn = self.options["num_nodes"]
        nr = self.options["num_radial"]
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
