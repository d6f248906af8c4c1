"""Inductions and momentum loads of the turbine stations on the curve (T1) at their inflow angle."""
import numpy as np
import openmdao.api as om

from bild_mdo.bem.blade_element import declare_section_options
from bild_mdo.bem.prandtl import loss_inputs
from bild_mdo.bild.variants.turbine.kernel import station_jets, station_loads
from bild_mdo.utils.jet import variable
from bild_mdo.utils.options import add_inputs, add_outputs
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node

_OUTPUTS = {
    "axial_induction": (None, "windmill-state axial induction a = 1 - u_axial/V, in [0, 1/2)"),
    "tangential_induction": (None, "wake swirl (tangential induction) a' = w/(Omega r) - 1"),
}
#: Output -> jet variable -> input name (``drag_to_lift`` enters through cl_star and cd_star).
_WRT = {"phi": "phi", "v_axial": "v_axial", "v_theta": "v_theta", "radii": "r", "radius": "radius",
        "hub_radius": "hub_radius"}


class TurbineLoadsComp(om.ExplicitComponent):
    """Windmill-state inductions, inflow speed, Prandtl factor and momentum loads of every station.

    Explicit in the inflow angle at the section point's ``s = C_d*/C_l*`` (:mod:`.kernel`, Eqs. (T1))::

        u = A sin(phi),  w = A cos(phi),  W = A,  a = 1 - u/V,  a' = w/(Omega r) - 1
        dT/dr = 4 pi rho r F u (V - u)          (thrust on the rotor, downwind, > 0)
        dQ/dr = 4 pi rho r**2 F u (w - Omega r) (driving torque, > 0)

    Options: ``num_nodes``, ``num_radial``, ``num_blades``, ``loss_model``.

    Inputs
    ------
    phi[nn, nr] (rad), v_theta[nn, nr] (m/s), radii[nn, nr] (m)
    v_axial[nn] (m/s), radius[nn] (m), hub_radius[nn] (m), rho[nn] (kg/m**3), cl_star[nn] (-), cd_star[nn] (-)

    Outputs
    -------
    axial_induction[nn, nr] (-), tangential_induction[nn, nr] (-)
        ``a`` and ``a'``.
    u_axial[nn, nr] (m/s), inflow_speed[nn, nr] (m/s), loss_factor[nn, nr] (-)
        Axial velocity at the disk ``V (1 - a)``, ``W`` and ``F``.
    dthrust_dr[nn, nr] (N/m), dtorque_dr[nn, nr] (N*m/m)
        Thrust (downwind) and driving torque per unit span, all blades.
    """

    def initialize(self):
        declare_section_options(self.options, radial=True, polar=False)

    def setup(self):
        add_inputs(self, ("phi", "v_theta", "radii", "v_axial", "radius", "hub_radius", "rho", "cl_star",
                          "cd_star"))
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        for name, (units, desc) in _OUTPUTS.items():
            self.add_output(name, val=np.zeros((nn, nr)), units=units, desc=desc)
        add_outputs(self, ("u_axial", "inflow_speed", "loss_factor", "dthrust_dr", "dtorque_dr"))

    def _node_wrt(self):
        return ["v_axial", "cl_star", "cd_star"] + list(loss_inputs(self.options["loss_model"]))

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        outs = list(_OUTPUTS) + ["u_axial", "inflow_speed", "loss_factor", "dthrust_dr", "dtorque_dr"]
        rows, cols = dist_wrt_dist(nn, nr)
        self.declare_partials(outs, ["phi", "v_theta", "radii"], rows=rows, cols=cols)
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials(outs, self._node_wrt(), rows=rows, cols=cols)
        self.declare_partials(["dthrust_dr", "dtorque_dr"], "rho", rows=rows, cols=cols)

    def _jets(self, inputs):
        col = {name: inputs[name][:, None] for name in ("v_axial", "radius", "hub_radius", "rho")}
        ratio = (inputs["cd_star"] / inputs["cl_star"])[:, None]
        jets = station_jets(inputs["phi"], col["v_axial"], inputs["v_theta"], ratio, inputs["radii"],
                            col["radius"], col["hub_radius"], self.options["num_blades"], self.options["loss_model"])
        v, x = variable(col["v_axial"], "v_axial"), variable(inputs["v_theta"], "v_theta")
        r_jet = variable(inputs["radii"], "r")
        rho = 4.0 * np.pi * col["rho"]
        thrust = rho * r_jet * jets["F"] * jets["t"]
        return {"axial_induction": 1.0 - jets["u"] / v, "tangential_induction": jets["w"] / x - 1.0,
                "u_axial": jets["u"], "inflow_speed": jets["W"], "loss_factor": jets["F"],
                "dthrust_dr": thrust, "dtorque_dr": rho * r_jet * r_jet * jets["F"] * jets["q"]}, ratio

    def compute(self, inputs, outputs):
        if np.iscomplexobj(inputs["phi"]):
            jets, _ = self._jets(inputs)
            for name, jet in jets.items():
                outputs[name] = jet.v
            return
        station_loads(inputs["phi"], inputs["v_theta"], inputs["radii"], inputs["v_axial"],
                      inputs["cd_star"] / inputs["cl_star"], inputs["radius"], inputs["hub_radius"], inputs["rho"],
                      self.options["num_blades"], self.options["loss_model"], outputs)

    def compute_partials(self, inputs, partials):
        jets, ratio = self._jets(inputs)
        shape = inputs["phi"].shape
        cl = inputs["cl_star"][:, None]
        for name, jet in jets.items():
            for wrt, var in _WRT.items():
                if wrt in ("phi", "v_theta", "radii", "v_axial") or wrt in loss_inputs(self.options["loss_model"]):
                    partials[name, wrt] = np.broadcast_to(jet.partial(var), shape).ravel()
            d_ratio = np.broadcast_to(jet.partial("drag_to_lift"), shape)
            partials[name, "cd_star"] = (d_ratio / cl).ravel()
            partials[name, "cl_star"] = (-d_ratio * ratio / cl).ravel()
        for name in ("dthrust_dr", "dtorque_dr"):
            partials[name, "rho"] = (jets[name].v / inputs["rho"][:, None]).ravel()
