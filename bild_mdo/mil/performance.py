"""MILPerformanceComp: thrust, torque, power and efficiency of a minimum-induced-loss design from A&L's integrals."""
import numpy as np
import openmdao.api as om

from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.mil.kernel import add_mil_inputs, declare_design_options, nondimensional_load, station_state
from bild_mdo.utils.options import add_inputs, declare_size_options
from bild_mdo.utils.sparsity import node_wrt_dist, node_wrt_node

#: Per-design outputs: name -> (units, description).
MIL_OUTPUTS = {
    "thrust": ("N", "thrust of the design, T = T_c rho V^2 pi R^2 / 2"),
    "power": ("W", "shaft power of the design, P = P_c rho V^3 pi R^2 / 2"),
    "torque": ("N*m", "shaft torque of the design, Q = P / Omega"),
    "efficiency": (None, "propeller efficiency of the design, eta = T_c / P_c"),
}


class MILPerformanceComp(om.ExplicitComponent):
    """Performance of the design from Adkins & Liebeck's integrals.

    ::

        T_c = I1 zeta - I2 zeta^2,   P_c = J1 zeta + J2 zeta^2,   eta = T_c / P_c
        T   = T_c rho V^2 pi R^2 / 2,   P = P_c rho V^3 pi R^2 / 2,   Q = P / Omega

    with the integrals as midpoint sums over the stations.  At the solved
    ``zeta`` the thrust (power) equals the target; the other quantities are
    the design's.  Without drag (``cd_star = 0``) the integrands satisfy
    ``J1' = I1'`` and ``J2' + (1 + zeta/2) I2' = I1'/2`` at every station, so
    ``eta = 1/(1 + zeta/2)`` exactly, for any blade number and stations (the
    derivation is in ``tests/mil/test_closed_form_limits.py``).

    Options
    -------
    num_nodes, num_radial : int
        Designs (axis 0) and stations (axis 1).
    num_blades : int
        Number of blades B.
    loss_form : {'adkins_liebeck', 'local', 'qmil'}
        Form of Prandtl's exponent (:data:`~bild_mdo.mil.kernel.LOSS_FORMS`).

    Inputs
    ------
    speed_ratio[nn] (-), radius_fraction[nn, nr] (-), width_fraction[nn, nr] (-), zeta[nn] (-)
        ``lambda``, ``xi``, ``dxi`` and the displacement velocity ratio.
    cl_star[nn] (-), cd_star[nn] (-)
        Design airfoil point.
    rho[nn] (kg/m**3), v_axial[nn] (m/s), radius[nn] (m), rpm[nn] (rpm)
        Operating point.

    Outputs
    -------
    thrust[nn] (N), power[nn] (W), torque[nn] (N*m), efficiency[nn] (-)
    """

    def initialize(self):
        declare_size_options(self.options)
        declare_design_options(self.options)

    def setup(self):
        nn = self.options["num_nodes"]
        add_mil_inputs(self, ("speed_ratio", "radius_fraction", "width_fraction", "zeta"))
        add_inputs(self, ("cl_star", "cd_star", "rho", "v_axial", "radius", "rpm"), cl_star=0.7, v_axial=50.0,
                   rpm=2400.0)
        for name, (units, desc) in MIL_OUTPUTS.items():
            self.add_output(name, val=np.ones(nn), units=units, desc=desc)

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = node_wrt_node(nn)
        common = ["speed_ratio", "zeta", "cl_star", "cd_star"]
        operating = ["rho", "v_axial", "radius"]
        self.declare_partials("thrust", common + operating, rows=rows, cols=cols)
        self.declare_partials("power", common + operating, rows=rows, cols=cols)
        self.declare_partials("torque", common + operating + ["rpm"], rows=rows, cols=cols)
        self.declare_partials("efficiency", common, rows=rows, cols=cols)
        rows, cols = node_wrt_dist(nn, nr)
        self.declare_partials(list(MIL_OUTPUTS), ["radius_fraction", "width_fraction"], rows=rows, cols=cols)

    def _coefficients(self, inputs):
        cl, cd = inputs["cl_star"], inputs["cd_star"]
        state = station_state(inputs["speed_ratio"][:, None], inputs["radius_fraction"], inputs["zeta"][:, None],
                              (cd / cl)[:, None], self.options["num_blades"], self.options["loss_form"])
        width = inputs["width_fraction"]
        return (nondimensional_load(state, inputs["zeta"], width, "thrust"),
                nondimensional_load(state, inputs["zeta"], width, "power"))

    def compute(self, inputs, outputs):
        (tc, _, _), (pc, _, _) = self._coefficients(inputs)
        v, radius = inputs["v_axial"], inputs["radius"]
        outputs["thrust"] = 0.5 * tc * inputs["rho"] * v ** 2 * np.pi * radius ** 2
        outputs["power"] = 0.5 * pc * inputs["rho"] * v ** 3 * np.pi * radius ** 2
        outputs["torque"] = outputs["power"] / (inputs["rpm"] * RPM_TO_RAD_PER_S)
        outputs["efficiency"] = tc / pc

    def compute_partials(self, inputs, partials):
        (tc, tgrad, tlocal), (pc, pgrad, plocal) = self._coefficients(inputs)
        rho, v, radius, rpm = inputs["rho"], inputs["v_axial"], inputs["radius"], inputs["rpm"]
        cl, cd = inputs["cl_star"], inputs["cd_star"]
        omega = rpm * RPM_TO_RAD_PER_S
        eta = tc / pc

        def coefficient_partials(grad, local):
            deps = np.sum(grad[3], axis=1)
            return {"speed_ratio": np.sum(grad[0], axis=1), "zeta": np.sum(grad[2], axis=1),
                    "cl_star": -deps * cd / cl ** 2, "cd_star": deps / cl,
                    "radius_fraction": grad[1], "width_fraction": local}

        dtc, dpc = coefficient_partials(tgrad, tlocal), coefficient_partials(pgrad, plocal)
        thrust_scale = 0.5 * rho * v ** 2 * np.pi * radius ** 2
        power_scale = thrust_scale * v
        thrust, power = tc * thrust_scale, pc * power_scale
        for name in dtc:
            per_node = dtc[name].ndim == 1
            expand = (lambda a: a) if per_node else (lambda a: a[:, None])
            partials["thrust", name] = (dtc[name] * expand(thrust_scale)).ravel()
            partials["power", name] = (dpc[name] * expand(power_scale)).ravel()
            partials["torque", name] = (dpc[name] * expand(power_scale / omega)).ravel()
            partials["efficiency", name] = ((dtc[name] - expand(eta) * dpc[name]) / expand(pc)).ravel()
        for name, value, exponent in (("thrust", thrust, 2.0), ("power", power, 3.0),
                                      ("torque", power / omega, 3.0)):
            partials[name, "rho"] = value / rho
            partials[name, "v_axial"] = exponent * value / v
            partials[name, "radius"] = 2.0 * value / radius
        partials["torque", "rpm"] = -power / omega / rpm
