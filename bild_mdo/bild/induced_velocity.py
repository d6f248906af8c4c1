"""Ideal induced velocities u_x, u_theta from the annular efficiency eta2 (Eqs. (24), (26))."""
import numpy as np
import openmdao.api as om

from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node


class InducedVelocityComp(om.ExplicitComponent):
    """Axial and tangential induced velocities of the ideally loaded rotor.

    With ``s = C_d*/C_l*`` (inverse maximum lift-to-drag ratio)::

        u_theta = 2 V_theta (1 - eta2)                                  Eq. (24)
        b       = (V_x - V_theta s) / 2
        q       = b**2 + eta2 V_theta**2 (1 - eta2 + (V_x/V_theta) s)
        u_x     = b + sqrt(q)                                           Eq. (26)

    ``q >= b**2 >= 0`` for ``0.5 <= eta2 <= 1``, so the root is real; an
    unloaded station in hover (``eta2 = 1``, ``V_x = 0``) gives ``u_x = 0``
    and ``u_theta = 0`` with finite derivatives (``q = b**2 > 0``).

    Options
    -------
    num_nodes : int
        Number of designs / operating points.
    num_radial : int
        Number of radial stations.

    Inputs
    ------
    eta2[nn, nr] (-)
        Annular efficiency for tangential induced losses, Eq. (23).
    v_axial[nn] (m/s)
        Axial free-stream velocity.
    v_theta[nn, nr] (m/s)
        Rotational blade speed ``Omega r``.
    cl_star[nn] (-), cd_star[nn] (-)
        Lift and drag coefficients at the maximum lift-to-drag ratio.

    Outputs
    -------
    u_x[nn, nr] (m/s)
        Axial velocity at the rotor disk (free stream plus induction), Eq. (26).
    u_theta[nn, nr] (m/s)
        Tangential induced velocity in the far wake, Eq. (24).
    """

    def initialize(self):
        self.options.declare("num_nodes", types=int, default=1, desc="number of designs / operating points")
        self.options.declare("num_radial", types=int, default=10, desc="number of radial stations")

    def setup(self):
        nn = self.options["num_nodes"]
        nr = self.options["num_radial"]
        self.add_input("eta2", val=0.95 * np.ones((nn, nr)), units=None,
                       desc="annular efficiency for tangential induced losses, Eq. (23)")
        self.add_input("v_axial", val=np.zeros(nn), units="m/s", desc="axial free-stream velocity")
        self.add_input("v_theta", val=np.full((nn, nr), 50.0), units="m/s",
                       desc="rotational blade speed Omega*r at the stations")
        self.add_input("cl_star", val=np.ones(nn), units=None,
                       desc="lift coefficient at the maximum lift-to-drag ratio")
        self.add_input("cd_star", val=np.full(nn, 0.01), units=None,
                       desc="drag coefficient at the maximum lift-to-drag ratio")
        self.add_output("u_x", val=np.full((nn, nr), 5.0), units="m/s",
                        desc="axial velocity at the rotor disk, Eq. (26)")
        self.add_output("u_theta", val=np.ones((nn, nr)), units="m/s",
                        desc="tangential induced velocity, Eq. (24)")

    def setup_partials(self):
        nn = self.options["num_nodes"]
        nr = self.options["num_radial"]
        rows, cols = dist_wrt_dist(nn, nr)
        self.declare_partials("u_x", ["eta2", "v_theta"], rows=rows, cols=cols)
        self.declare_partials("u_theta", ["eta2", "v_theta"], rows=rows, cols=cols)
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials("u_x", ["v_axial", "cl_star", "cd_star"], rows=rows, cols=cols)

    def _terms(self, inputs):
        eta2 = inputs["eta2"]
        v_t = inputs["v_theta"]
        v_x = inputs["v_axial"][:, None]
        s = (inputs["cd_star"] / inputs["cl_star"])[:, None]
        b = 0.5 * (v_x - v_t * s)
        q = b ** 2 + eta2 * v_t ** 2 * (1.0 - eta2) + eta2 * v_t * v_x * s
        return eta2, v_t, v_x, s, b, q

    def compute(self, inputs, outputs):
        eta2, v_t, _, _, b, q = self._terms(inputs)
        outputs["u_x"] = b + np.sqrt(q)
        outputs["u_theta"] = 2.0 * v_t * (1.0 - eta2)

    def compute_partials(self, inputs, partials):
        eta2, v_t, v_x, s, b, q = self._terms(inputs)
        half_inv_sqrt = 0.5 / np.sqrt(q)
        cl = inputs["cl_star"][:, None]
        cd = inputs["cd_star"][:, None]

        dq_deta2 = v_t ** 2 * (1.0 - 2.0 * eta2) + v_t * v_x * s
        dq_dvx = b + eta2 * v_t * s
        dq_dvt = -b * s + 2.0 * eta2 * v_t * (1.0 - eta2) + eta2 * v_x * s
        dq_ds = -b * v_t + eta2 * v_t * v_x
        dux_ds = -0.5 * v_t + dq_ds * half_inv_sqrt

        partials["u_x", "eta2"] = (dq_deta2 * half_inv_sqrt).ravel()
        partials["u_x", "v_axial"] = (0.5 + dq_dvx * half_inv_sqrt).ravel()
        partials["u_x", "v_theta"] = (-0.5 * s + dq_dvt * half_inv_sqrt).ravel()
        partials["u_x", "cl_star"] = (dux_ds * (-cd / cl ** 2)).ravel()
        partials["u_x", "cd_star"] = (dux_ds / cl).ravel()
        partials["u_theta", "eta2"] = (-2.0 * v_t).ravel()
        partials["u_theta", "v_theta"] = (2.0 * (1.0 - eta2)).ravel()
