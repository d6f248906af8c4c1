"""Inflow angle, inflow speed and twist of the ideal blade (Eqs. (7), (30), theta = phi + alpha)."""
import numpy as np
import openmdao.api as om

from bild_mdo.bild.airfoil_point import (
    add_airfoil_point_inputs,
    airfoil_point_pattern,
    declare_spanwise_option,
    per_station,
)
from bild_mdo.bild.feasibility import declare_feasibility_option, report_infeasible, station_details
from bild_mdo.utils.options import add_inputs, add_outputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_dist


class InflowAngleComp(om.ExplicitComponent):
    """Inflow angle ``phi``, inflow speed ``W`` and blade twist ``theta``.

    With the tangential velocity seen by the blade ``V_t = V_theta - u_theta/2``::

        phi   = atan(u_axial / V_t)                   Eq. (30)
        W     = sqrt(u_axial**2 + V_t**2)              Eq. (7)
        theta = phi + alpha*                       Sec. 4.3 (Fig. 1b)

    Every blade element works at the angle of attack of maximum ``C_l/C_d``
    (Assumption 2), so the twist is the inflow angle shifted by ``alpha*``.

    ``u_theta >= 2 V_theta`` (``eta2 <= 0``, never reached by the quartic's
    root) raises :class:`openmdao.api.AnalysisError` naming every failing
    node, or, inside a BILDGroup, records them in the group's feasibility
    ledger (placeholder ``V_t = V_theta``).

    Options: the sizes ``num_nodes`` and ``num_radial``
    (:func:`~bild_mdo.utils.options.declare_size_options`) and ``feasibility``
    (:func:`~bild_mdo.bild.feasibility.declare_feasibility_option`).

    Inputs
    ------
    u_axial[nn, nr] (m/s)
        Axial velocity at the rotor disk.
    u_theta[nn, nr] (m/s)
        Tangential induced velocity.
    v_theta[nn, nr] (m/s)
        Rotational blade speed ``Omega r``.
    alpha_star[nn] (rad)
        Angle of attack of maximum lift-to-drag ratio (``[nn, nr]`` with
        ``varies_along_span=True``, :mod:`~bild_mdo.bild.airfoil_point`).

    Outputs
    -------
    phi[nn, nr] (rad)
        Inflow angle.
    inflow_speed[nn, nr] (m/s)
        Resultant inflow speed ``W``.
    twist[nn, nr] (rad)
        Blade twist angle.
    """

    def initialize(self):
        declare_size_options(self.options)
        declare_feasibility_option(self.options)
        declare_spanwise_option(self.options)

    def setup(self):
        add_inputs(self, ("u_axial", "u_theta", "v_theta"))
        add_airfoil_point_inputs(self, ("alpha_star",))
        add_outputs(self, ("phi", "inflow_speed", "twist"))

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = dist_wrt_dist(nn, nr)
        for name in ("phi", "inflow_speed", "twist"):
            self.declare_partials(name, ["u_axial", "u_theta", "v_theta"], rows=rows, cols=cols)
        rows, cols = airfoil_point_pattern(self)
        self.declare_partials("twist", "alpha_star", rows=rows, cols=cols, val=1.0)

    def compute(self, inputs, outputs):
        u_axial = inputs["u_axial"]
        v_t = inputs["v_theta"] - 0.5 * inputs["u_theta"]
        positive = np.real(v_t) > 0.0
        bad = None if positive.all() else ~positive
        report_infeasible(self, "swirl", np.zeros(v_t.shape[0], dtype=bool) if bad is None else np.any(bad, axis=1),
                          "u_theta >= 2 V_theta (eta2 <= 0): the inflow angle is undefined",
                          {} if bad is None else station_details(bad, {"u_theta [m/s]": inputs["u_theta"],
                                                                       "V_theta [m/s]": inputs["v_theta"]}))
        if bad is not None:
            v_t = np.where(bad, inputs["v_theta"], v_t)  # placeholder of infeasible nodes inside a BILDGroup
        # V_t = eta2 V_theta > 0 (Eq. (23)), so the plain arctan is the right branch and complex-step safe.
        phi = np.arctan(u_axial / v_t, out=outputs["phi"])
        np.sqrt(u_axial * u_axial + v_t * v_t, out=outputs["inflow_speed"])
        np.add(phi, per_station(inputs["alpha_star"]), out=outputs["twist"])

    def compute_partials(self, inputs, partials):
        u_axial = inputs["u_axial"]
        v_t = inputs["v_theta"] - 0.5 * inputs["u_theta"]
        w2 = u_axial ** 2 + v_t ** 2
        w = np.sqrt(w2)
        dphi_dux = (v_t / w2).ravel()
        dphi_dvt = (-u_axial / w2).ravel()
        dw_dux = (u_axial / w).ravel()
        dw_dvt = (v_t / w).ravel()
        for name, d_ux, d_vt in (("phi", dphi_dux, dphi_dvt), ("twist", dphi_dux, dphi_dvt),
                                 ("inflow_speed", dw_dux, dw_dvt)):
            partials[name, "u_axial"] = d_ux
            partials[name, "v_theta"] = d_vt
            partials[name, "u_theta"] = -0.5 * d_vt
