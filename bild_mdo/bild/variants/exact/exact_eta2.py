"""eta2 of the exact ideal loading: each station's root of the annulus stationarity condition."""
import numpy as np
import openmdao.api as om

from bild_mdo.bem.blade_element import declare_section_options
from bild_mdo.bem.prandtl import loss_inputs
from bild_mdo.bild.airfoil_point import (
    add_airfoil_point_inputs,
    airfoil_point_pattern,
    declare_spanwise_option,
    per_station,
)
from bild_mdo.bild.annulus_stationarity import residual_partials, solve_stationarity, stationarity
from bild_mdo.bild.feasibility import declare_feasibility_option, report_station_status
from bild_mdo.utils.newton import complex_step_update
from bild_mdo.utils.options import add_inputs, add_outputs
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node

_NAMES = ("ideal_loading_constant", "v_axial", "v_theta", "radii", "radius", "hub_radius", "cl_star", "cd_star")
#: Status of :func:`~bild_mdo.bild.annulus_stationarity.solve_stationarity` -> (check key, reason).
_FAILURES = {
    3: ("overloaded", "lambda lies beyond the station's maximum annulus thrust before eta2 = 1/2; reduce ref_chord"),
    4: ("solve", "exact ideal loading: an input is outside its domain or the solve did not converge"),
}


class ExactEta2Comp(om.ExplicitComponent):
    """Annular efficiency eta2 at every station of the exact ideal loading.

    Each station's inflow angle solves ``(F e)' = lambda (F t)'``
    (:mod:`~bild_mdo.bild.annulus_stationarity`, with the Prandtl loss factor
    ``F``), by the package's bracketed Newton solver on
    ``[atan(V_x/V_theta), phi(eta2 = 1/2)]``; the output is
    ``eta2 = A cos(phi) / V_theta``, from which
    :class:`~bild_mdo.bild.induced_velocity.InducedVelocityComp` recovers the
    same ``u_axial`` (Eq. (26)), so the rest of the BILD chain is unchanged.
    Partials by the implicit-function theorem, ``dphi/dx = -R_x/R_phi``; under
    complex step one Newton update in complex arithmetic carries the derivative.

    A station with ``lambda <= G(phi0)`` (in hover ``G(0+) = V_theta C_d*/C_l*``)
    is unloaded: the lightest load already costs more energy per thrust than
    lambda, so the optimum with a chord >= 0 gives it no load: ``eta2 = 1``
    (``u_axial = V_x``, zero chord), zero partials; in forward flight this happens
    at inboard stations at high advance ratios, where the paper's loading
    breaks Assumption 3.  A station that lambda would load past its maximum
    thrust, or a failed solve, is infeasible (AnalysisError, or the group's
    feasibility ledger).

    Options: ``num_nodes``, ``num_radial``, ``num_blades``, ``loss_model``,
    ``feasibility``, ``varies_along_span``.

    Inputs
    ------
    ideal_loading_constant[nn] (m/s), v_axial[nn] (m/s), radius[nn] (m), hub_radius[nn] (m)
    v_theta[nn, nr] (m/s), radii[nn, nr] (m)
    cl_star[nn] (-), cd_star[nn] (-)
        (``[nn, nr]`` with ``varies_along_span=True``).

    Outputs
    -------
    eta2[nn, nr] (-)
        Annular efficiency, in (0.5, 1].
    """

    def initialize(self):
        declare_section_options(self.options, radial=True, polar=False)
        declare_feasibility_option(self.options)
        declare_spanwise_option(self.options)
        self._cache = None

    def setup(self):
        add_inputs(self, _NAMES[:-2])
        add_airfoil_point_inputs(self, ("cl_star", "cd_star"))
        add_outputs(self, ("eta2",))

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = dist_wrt_dist(nn, nr)
        self.declare_partials("eta2", ["v_theta", "radii"], rows=rows, cols=cols)
        rows, cols = dist_wrt_node(nn, nr)
        node = ["ideal_loading_constant", "v_axial"] + list(loss_inputs(self.options["loss_model"]))
        self.declare_partials("eta2", node, rows=rows, cols=cols)
        rows, cols = airfoil_point_pattern(self)
        self.declare_partials("eta2", ["cl_star", "cd_star"], rows=rows, cols=cols)

    def _arguments(self, inputs):
        """``(lam, V_x, V_theta, s, r, R, r_hub)`` broadcast to ``(nn, nr)``."""
        shape = inputs["v_theta"].shape
        node = [np.broadcast_to(inputs[name][:, None], shape)
                for name in ("ideal_loading_constant", "v_axial", "radius", "hub_radius")]
        ratio = np.broadcast_to(per_station(inputs["cd_star"] / inputs["cl_star"]), shape)
        return node[0], node[1], inputs["v_theta"], ratio, inputs["radii"], node[2], node[3]

    def _solve(self, inputs):
        """Real roots and status per station, cached for the linearisation at the same inputs."""
        key = np.concatenate([np.real(inputs[name]).ravel() for name in _NAMES])
        if self._cache is not None and np.array_equal(self._cache[0], key):
            return self._cache[1], self._cache[2]
        args = [np.real(a) for a in self._arguments(inputs)]
        shape = args[2].shape
        phi, status = solve_stationarity(*(a.ravel() for a in args), self.options["num_blades"],
                                         self.options["loss_model"])
        phi, status = phi.reshape(shape), status.reshape(shape)
        report_station_status(self, status, _FAILURES, args[1], args[2], args[0])
        self._cache = (key, phi, status)
        return phi, status

    def compute(self, inputs, outputs):
        phi, status = self._solve(inputs)
        args = self._arguments(inputs)
        loaded = status == 0
        if self.under_complex_step:
            opts = (self.options["num_blades"], self.options["loss_model"])
            terms, d_res, _ = residual_partials(phi, *(np.real(a) for a in args), *opts)
            complex_terms = stationarity(phi, *args[1:], *opts)
            residual = complex_terms.N - args[0] * complex_terms.D
            phi = np.where(loaded, complex_step_update(phi, residual, np.where(loaded, d_res["phi"], 1.0)), phi)
        ring_w = _disk_tangential(phi, args[1], args[2], args[3])
        outputs["eta2"] = np.where(status == 1, 1.0, ring_w / args[2])

    def compute_partials(self, inputs, partials):
        phi, status = self._solve(inputs)
        args = [np.real(a) for a in self._arguments(inputs)]
        _, d_res, d_eta = residual_partials(phi, *args, self.options["num_blades"], self.options["loss_model"])
        loaded = status == 0
        slope = np.where(loaded, d_res["phi"], 1.0)

        def total(name, eta_name=None):
            dphi = -d_res[name] / slope
            value = d_eta["phi"] * dphi + (d_eta[eta_name] if eta_name else 0.0)
            return np.where(loaded, value, 0.0)

        partials["eta2", "ideal_loading_constant"] = total("lam").ravel()
        partials["eta2", "v_axial"] = total("v_axial", "v_axial").ravel()
        partials["eta2", "v_theta"] = total("v_theta", "v_theta").ravel()
        partials["eta2", "radii"] = total("r").ravel()
        for name in loss_inputs(self.options["loss_model"]):
            partials["eta2", name] = total(name).ravel()
        d_ratio = total("drag_to_lift", "drag_to_lift")
        cl = per_station(inputs["cl_star"])
        partials["eta2", "cl_star"] = (d_ratio * (-args[3] / cl)).ravel()
        partials["eta2", "cd_star"] = (d_ratio / cl).ravel()


def _disk_tangential(phi, v_axial, v_theta, drag_to_lift):
    """``w = A cos(phi)`` (m/s), ``A = V_x C_theta + V_theta C_x``."""
    sn, cs = np.sin(phi), np.cos(phi)
    return (v_axial * (sn + drag_to_lift * cs) + v_theta * (cs - drag_to_lift * sn)) * cs
