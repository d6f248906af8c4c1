"""The member of the turbine family with a given thrust: its multiplier mu, solved per design."""
import numpy as np
import openmdao.api as om

from bild_mdo.bem.blade_element import declare_section_options
from bild_mdo.bem.prandtl import loss_inputs
from bild_mdo.bild.variants.turbine.kernel import implicit_sensitivities, station_jets
from bild_mdo.bild.variants.turbine.turbine_inflow import (add_multiplier, loading_arguments, raise_failed,
                                                          station_angles)
from bild_mdo.utils.newton import bracketed_newton
from bild_mdo.utils.options import add_inputs
from bild_mdo.utils.sparsity import node_wrt_dist, node_wrt_node

#: Most negative multiplier tried, in units of the wind speed (the loading is then at a -> 1/2 everywhere).
_MU_FLOOR = -1.0e4
_NODE = ("v_axial", "radius", "hub_radius", "rho", "cl_star", "cd_star")


class ThrustLimitComp(om.ExplicitComponent):
    """Multiplier ``mu`` of the turbine ideal loading whose thrust equals ``thrust_target``.

    ``T(mu) = sum_j 4 pi rho r_j F t(phi_j(mu)) dr_j`` falls monotonically from the largest thrust of the
    windmill state (``a -> 1/2`` at every station, ``mu -> -inf``) to zero (``mu >= max G(phi0)``, every
    station unloaded), so a thrust below the maximum-power thrust gives ``mu > 0`` (the most power for
    that thrust) and one above it ``mu < 0``.  Each design is one scalar root, solved by the package's
    bracketed Newton solver in ``mu`` with ``dT/dmu`` from the stations' implicit derivatives (every
    station's loading solved inside each step, vectorised).  Partials by the implicit-function theorem,
    ``dmu/dx = -(dT/dx)/(dT/dmu)``.  A target above the largest windmill-state thrust raises AnalysisError.

    Options: ``num_nodes``, ``num_radial``, ``num_blades``, ``loss_model``.

    Inputs
    ------
    thrust_target[nn] (N), v_axial[nn] (m/s), radius[nn] (m), hub_radius[nn] (m), rho[nn] (kg/m**3),
    cl_star[nn] (-), cd_star[nn] (-), v_theta[nn, nr] (m/s), radii[nn, nr] (m), dr[nn, nr] (m)

    Outputs
    -------
    power_thrust_multiplier[nn] (m/s)
    """

    def initialize(self):
        declare_section_options(self.options, radial=True, polar=False)

    def setup(self):
        nn = self.options["num_nodes"]
        self.add_input("thrust_target", val=np.ones(nn), units="N", desc="thrust of the member T* (> 0)")
        add_inputs(self, _NODE + ("v_theta", "radii", "dr"))
        add_multiplier(self.add_output, nn)

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = node_wrt_node(nn)
        node = ["thrust_target", "v_axial", "rho", "cl_star", "cd_star"] + list(loss_inputs(self.options["loss_model"]))
        self.declare_partials("power_thrust_multiplier", node, rows=rows, cols=cols)
        rows, cols = node_wrt_dist(nn, nr)
        self.declare_partials("power_thrust_multiplier", ["v_theta", "radii", "dr"], rows=rows, cols=cols)

    def _thrust(self, inputs, mu, idx, derivatives=False):
        """Thrust of nodes ``idx`` at ``mu[idx]`` (and ``dT/dmu``, or every partial with ``derivatives``)."""
        sub = {name: inputs[name][idx] for name in _NODE}
        v_theta, radii, dr = (inputs[name][idx] for name in ("v_theta", "radii", "dr"))
        args = loading_arguments(sub, v_theta, radii, mu)
        opts = (self.options["num_blades"], self.options["loss_model"])
        phi, status = station_angles(sub, v_theta, radii, mu, *opts)
        nr = self.options["num_radial"]
        raise_failed(self, status, lambda i: f"node {idx[i // nr]}, station {i % nr}")
        jets = station_jets(phi, *args[1:], *opts)
        ft = jets["F"] * jets["t"]
        weight = 4.0 * np.pi * np.repeat(sub["rho"], nr) * args[4] * dr.ravel()
        thrust = np.sum((weight * ft.v).reshape(-1, nr), axis=1)
        real = [np.real(a) for a in args]
        sens = implicit_sensitivities(np.real(phi), real[0], status, *real[1:], *opts)
        if not derivatives:
            return thrust, np.sum((weight * np.real(ft.partial("phi")) * sens["mu"]).reshape(-1, nr), axis=1)
        per = {name: weight * (ft.partial(name) + ft.partial("phi") * sens[name]) for name in sens}
        per["r"] = per["r"] + weight / args[4] * ft.v
        per["dr"] = weight / dr.ravel() * ft.v
        return thrust, per, real[3]

    def _solve_multiplier(self, inputs):
        real = {name: np.real(inputs[name]) for name in _NODE + ("v_theta", "radii", "dr", "thrust_target")}
        nn, target = self.options["num_nodes"], real["thrust_target"]
        if not np.all(target > 0.0):
            raise om.AnalysisError(f"{self.msginfo}: thrust_target must be positive, got {target}")
        all_nodes = np.arange(nn)
        hi = 2.0 * real["v_axial"]  # above G(phi0) <= V of every station: no load
        lo = -real["v_axial"]
        t_lo, _ = self._thrust(real, lo, all_nodes)
        while np.any(t_lo <= target) and np.all(lo >= _MU_FLOOR * real["v_axial"]):
            lo = np.where(t_lo <= target, 4.0 * lo, lo)
            t_lo, _ = self._thrust(real, lo, all_nodes)
        bad = t_lo <= target
        if np.any(bad):
            i = int(np.flatnonzero(bad)[0])
            raise om.AnalysisError(f"{self.msginfo}: thrust {target[i]:.6g} N (node {i}) is above the largest "
                                   f"thrust of the windmill state ({t_lo[i]:.6g} N, a -> 1/2 at every station): "
                                   "give a smaller thrust")

        def function(x, idx):
            thrust, slope = self._thrust(real, x, idx)
            return thrust / target[idx] - 1.0, slope / target[idx]

        result = bracketed_newton(function, lo, hi, np.ones(nn), atol=1e-13, quadratic_stop=True)
        if not np.all(result.converged):
            i = result.first_failure()
            raise om.AnalysisError(f"{self.msginfo}: the multiplier for thrust {target[i]:.6g} N (node {i}) "
                                   "did not converge")
        return result.x, real

    def compute(self, inputs, outputs):
        mu, real = self._solve_multiplier(inputs)
        if self.under_complex_step:
            thrust, _ = self._thrust(inputs, mu, np.arange(mu.size))
            _, slope = self._thrust(real, mu, np.arange(mu.size))
            mu = mu - 1j * np.imag(thrust - inputs["thrust_target"]) / slope
        outputs["power_thrust_multiplier"] = mu

    def compute_partials(self, inputs, partials):
        mu, real = self._solve_multiplier(inputs)
        idx = np.arange(mu.size)
        _, slope = self._thrust(real, mu, idx)
        _, per, ratio = self._thrust(real, mu, idx, derivatives=True)
        nr = self.options["num_radial"]
        scale = -1.0 / np.repeat(slope, nr)

        def node(x):
            return np.sum(np.real(x).reshape(-1, nr) * scale.reshape(-1, nr), axis=1)

        partials["power_thrust_multiplier", "thrust_target"] = 1.0 / slope
        partials["power_thrust_multiplier", "v_theta"] = np.real(per["v_theta"]) * scale
        partials["power_thrust_multiplier", "radii"] = np.real(per["r"]) * scale
        partials["power_thrust_multiplier", "dr"] = np.real(per["dr"]) * scale
        partials["power_thrust_multiplier", "v_axial"] = node(per["v_axial"])
        for name in loss_inputs(self.options["loss_model"]):
            partials["power_thrust_multiplier", name] = node(per[name])
        thrust = np.sum(np.real(per["dr"]).reshape(-1, nr) * real["dr"], axis=1)
        partials["power_thrust_multiplier", "rho"] = -thrust / real["rho"] / slope
        d_ratio = node(per["drag_to_lift"])
        partials["power_thrust_multiplier", "cd_star"] = d_ratio / real["cl_star"]
        partials["power_thrust_multiplier", "cl_star"] = -d_ratio * ratio.reshape(-1, nr)[:, 0] / real["cl_star"]
