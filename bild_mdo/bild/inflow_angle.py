"""Inflow angle, inflow speed and twist of the ideal blade (Eqs. (7), (30), theta = phi + alpha)."""
import numpy as np
import openmdao.api as om

from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node


class InflowAngleComp(om.ExplicitComponent):
    """Inflow angle ``phi``, inflow speed ``W`` and blade twist ``theta``.

    With the tangential velocity seen by the blade ``V_t = V_theta - u_theta/2``::

        phi   = atan(u_x / V_t)                   Eq. (30)
        W     = sqrt(u_x**2 + V_t**2)              Eq. (7)
        theta = phi + alpha*                       Sec. 4.3 (Fig. 1b)

    Every blade element works at the angle of attack of maximum ``C_l/C_d``
    (Assumption 2), so the twist is the inflow angle shifted by ``alpha*``.

    Options
    -------
    num_nodes : int
        Number of designs / operating points.
    num_radial : int
        Number of radial stations.

    Inputs
    ------
    u_x[nn, nr] (m/s)
        Axial velocity at the rotor disk.
    u_theta[nn, nr] (m/s)
        Tangential induced velocity.
    v_theta[nn, nr] (m/s)
        Rotational blade speed ``Omega r``.
    alpha_star[nn] (rad)
        Angle of attack of maximum lift-to-drag ratio.

    Outputs
    -------
    phi[nn, nr] (rad)
        Inflow angle.
    inflow_velocity[nn, nr] (m/s)
        Resultant inflow speed ``W``.
    twist[nn, nr] (rad)
        Blade twist angle.
    """

    def initialize(self):
        self.options.declare("num_nodes", types=int, default=1, desc="number of designs / operating points")
        self.options.declare("num_radial", types=int, default=10, desc="number of radial stations")

    def setup(self):
        nn = self.options["num_nodes"]
        nr = self.options["num_radial"]
        self.add_input("u_x", val=np.full((nn, nr), 5.0), units="m/s",
                       desc="axial velocity at the rotor disk")
        self.add_input("u_theta", val=np.ones((nn, nr)), units="m/s", desc="tangential induced velocity")
        self.add_input("v_theta", val=np.full((nn, nr), 50.0), units="m/s",
                       desc="rotational blade speed Omega*r at the stations")
        self.add_input("alpha_star", val=np.full(nn, 0.1), units="rad",
                       desc="angle of attack of maximum lift-to-drag ratio")
        self.add_output("phi", val=np.full((nn, nr), 0.1), units="rad", desc="inflow angle, Eq. (30)")
        self.add_output("inflow_velocity", val=np.full((nn, nr), 50.0), units="m/s",
                        desc="resultant inflow speed W at the blade element, Eq. (7)")
        self.add_output("twist", val=np.full((nn, nr), 0.2), units="rad",
                        desc="blade twist angle theta = phi + alpha*")

    def setup_partials(self):
        nn = self.options["num_nodes"]
        nr = self.options["num_radial"]
        rows, cols = dist_wrt_dist(nn, nr)
        for name in ("phi", "inflow_velocity", "twist"):
            self.declare_partials(name, ["u_x", "u_theta", "v_theta"], rows=rows, cols=cols)
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials("twist", "alpha_star", rows=rows, cols=cols, val=1.0)

    def compute(self, inputs, outputs):
        u_x = inputs["u_x"]
        v_t = inputs["v_theta"] - 0.5 * inputs["u_theta"]
        bad = ~(np.real(v_t) > 0.0)
        if np.any(bad):
            node, station = (int(i) for i in np.argwhere(bad)[0])
            raise om.AnalysisError(
                f"{self.msginfo}: u_theta >= 2 V_theta (eta2 <= 0) at {int(np.sum(bad))} station(s), first at "
                f"node {node}, station {station} (u_theta = {np.real(inputs['u_theta'][node, station]):.6g} m/s, "
                f"V_theta = {np.real(inputs['v_theta'][node, station]):.6g} m/s); the inflow angle is undefined")
        # V_t = eta2 V_theta > 0 (Eq. (23)), so the plain arctan is the right branch and complex-step safe.
        phi = np.arctan(u_x / v_t)
        outputs["phi"] = phi
        outputs["inflow_velocity"] = np.sqrt(u_x ** 2 + v_t ** 2)
        outputs["twist"] = phi + inputs["alpha_star"][:, None]

    def compute_partials(self, inputs, partials):
        u_x = inputs["u_x"]
        v_t = inputs["v_theta"] - 0.5 * inputs["u_theta"]
        w2 = u_x ** 2 + v_t ** 2
        w = np.sqrt(w2)
        dphi_dux = (v_t / w2).ravel()
        dphi_dvt = (-u_x / w2).ravel()
        dw_dux = (u_x / w).ravel()
        dw_dvt = (v_t / w).ravel()
        for name, d_ux, d_vt in (("phi", dphi_dux, dphi_dvt), ("twist", dphi_dux, dphi_dvt),
                                 ("inflow_velocity", dw_dux, dw_dvt)):
            partials[name, "u_x"] = d_ux
            partials[name, "v_theta"] = d_vt
            partials[name, "u_theta"] = -0.5 * d_vt
