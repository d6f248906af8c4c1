"""Inflow angle of every station of the turbine loading (Eq. (T3) of :mod:`~bild_mdo.bild.variants.turbine.kernel`)."""
import numpy as np
import openmdao.api as om

from bild_mdo.bem.blade_element import declare_section_options
from bild_mdo.bem.prandtl import loss_inputs
from bild_mdo.bild.variants.turbine.kernel import FAILED, implicit_sensitivities, solve_designs, station_angle
from bild_mdo.utils.options import add_inputs, add_outputs
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node

#: The multiplier of the turbine loading (one declaration for every component that uses it).
MULTIPLIER = ("power_thrust_multiplier", dict(
    units="m/s", desc="multiplier mu of the turbine ideal loading: marginal power per marginal thrust (0: maximum "
                      "power)"))
_NODE = ("v_axial", "radius", "hub_radius", "cd_star", "cl_star")


def add_multiplier(method, nn, value=0.0):
    """Declare ``power_thrust_multiplier[nn]`` (m/s) with ``method`` (``add_input`` or ``add_output``)."""
    method(MULTIPLIER[0], val=np.full(nn, value), **MULTIPLIER[1])


def loading_arguments(inputs, v_theta, radii, mu):
    """Flat ``(mu, V, x, s, r, R, r_hub)`` of the stations (per-design inputs repeated along the span)."""
    shape = np.broadcast(v_theta, radii).shape
    node = [np.broadcast_to(np.reshape(inputs[name], (-1, 1)), shape).ravel() for name in _NODE[:3]]
    ratio = np.broadcast_to((inputs["cd_star"] / inputs["cl_star"]).reshape(-1, 1), shape).ravel()
    mu = np.broadcast_to(np.reshape(mu, (-1, 1)), shape).ravel()
    return (mu, node[0], np.broadcast_to(v_theta, shape).ravel(), ratio, np.broadcast_to(radii, shape).ravel(),
            node[1], node[2])


def station_angles(inputs, v_theta, radii, mu, num_blades, loss_model):
    """Flat ``phi`` and status of the stations (:func:`loading_arguments`'s order): the real solve design by design
    (:func:`~bild_mdo.bild.variants.turbine.kernel.solve_designs`), or under complex step :func:`station_angle`."""
    if any(np.iscomplexobj(a) for a in (v_theta, radii, mu) + tuple(inputs[name] for name in _NODE)):
        return station_angle(*loading_arguments(inputs, v_theta, radii, mu), num_blades, loss_model)
    phi, status = solve_designs(mu, inputs["v_axial"], inputs["cd_star"] / inputs["cl_star"], inputs["radius"],
                                inputs["hub_radius"], v_theta, radii, num_blades, loss_model)
    return phi.ravel(), status.ravel()


def raise_failed(component, status, where):
    """om.AnalysisError naming the first station whose loading solve failed."""
    bad = np.flatnonzero(status == FAILED)
    if bad.size:
        raise om.AnalysisError(f"{component.msginfo}: the turbine ideal loading has no solution at {where(bad[0])} "
                               f"({bad.size} station(s)): it needs wind_speed > 0, rpm > 0 and an airfoil point "
                               "with C_l* > 0, C_d* >= 0")


class TurbineInflowComp(om.ExplicitComponent):
    """Inflow angle ``phi`` of every station of the turbine ideal loading, ``(F p)' = mu (F t)'``.

    Solved per station by the package's bracketed Newton solver on ``[phi_half, phi0]``
    (:func:`~bild_mdo.bild.variants.turbine.kernel.solve_loading`); a station with ``mu >= G(phi0)`` is
    unloaded (``phi = phi0 = atan(V / (Omega r))``, zero chord).  Partials by the implicit-function
    theorem, ``dphi/dx = -R_x / R_phi``; under complex step one complex Newton update carries them.

    Options: ``num_nodes``, ``num_radial``, ``num_blades``, ``loss_model``.

    Inputs
    ------
    power_thrust_multiplier[nn] (m/s), v_axial[nn] (m/s), radius[nn] (m), hub_radius[nn] (m)
        Multiplier mu, wind speed V, tip and hub radii.
    v_theta[nn, nr] (m/s), radii[nn, nr] (m)
        Blade speed ``Omega r`` and station radii.
    cl_star[nn] (-), cd_star[nn] (-)
        Section point.

    Outputs
    -------
    phi[nn, nr] (rad)
        Inflow angle of the ideal loading.
    """

    def initialize(self):
        declare_section_options(self.options, radial=True, polar=False)

    def setup(self):
        add_multiplier(self.add_input, self.options["num_nodes"])
        add_inputs(self, _NODE + ("v_theta", "radii"))
        add_outputs(self, ("phi",))

    def _wrt_node(self):
        return ["power_thrust_multiplier", "v_axial", "cl_star", "cd_star"] + list(
            loss_inputs(self.options["loss_model"]))

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = dist_wrt_dist(nn, nr)
        self.declare_partials("phi", ["v_theta", "radii"], rows=rows, cols=cols)
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials("phi", self._wrt_node(), rows=rows, cols=cols)

    def _args(self, inputs):
        return loading_arguments(inputs, inputs["v_theta"], inputs["radii"], inputs["power_thrust_multiplier"])

    def compute(self, inputs, outputs):
        phi, status = station_angles(inputs, inputs["v_theta"], inputs["radii"], inputs["power_thrust_multiplier"],
                                     self.options["num_blades"], self.options["loss_model"])
        nr = self.options["num_radial"]
        raise_failed(self, status, lambda i: f"node {i // nr}, station {i % nr}")
        outputs["phi"] = phi.reshape(outputs["phi"].shape)

    def compute_partials(self, inputs, partials):
        args = [np.real(a) for a in self._args(inputs)]
        opts = (self.options["num_blades"], self.options["loss_model"])
        real = {name: np.real(inputs[name]) for name in _NODE}
        phi, status = station_angles(real, np.real(inputs["v_theta"]), np.real(inputs["radii"]),
                                     np.real(inputs["power_thrust_multiplier"]), *opts)
        sens = implicit_sensitivities(phi, args[0], status, *args[1:], *opts)
        cl = np.repeat(np.real(inputs["cl_star"]), self.options["num_radial"])
        names = {"power_thrust_multiplier": "mu", "v_axial": "v_axial", "v_theta": "v_theta", "radii": "r",
                 "radius": "radius", "hub_radius": "hub_radius"}
        for name in set(names) & (set(self._wrt_node()) | {"v_theta", "radii"}):
            partials["phi", name] = sens[names[name]]
        partials["phi", "cd_star"] = sens["drag_to_lift"] / cl
        partials["phi", "cl_star"] = -sens["drag_to_lift"] * args[3] / cl
