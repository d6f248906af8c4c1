"""Turbine performance: power extracted, power and thrust coefficients and tip-speed ratio, with their partials."""
import numpy as np
import openmdao.api as om

from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.utils.options import add_inputs, declare_size_options
from bild_mdo.utils.sparsity import node_wrt_dist, node_wrt_node

#: Per-design turbine outputs: name -> (units, description).
TURBINE_OUTPUTS = {
    "thrust": ("N", "thrust on the rotor (downwind force), T = sum(dT/dr dr)"),
    "torque": ("N*m", "driving torque of the air on the rotor, Q = sum(dQ/dr dr)"),
    "power": ("W", "power extracted from the wind, P = Omega Q (> 0)"),
    "power_coefficient": (None, "C_P = P / (1/2 rho pi R**2 V**3)"),
    "thrust_coefficient": (None, "C_T = T / (1/2 rho pi R**2 V**2)"),
    "tip_speed_ratio": (None, "tip-speed ratio Omega R / V"),
}


class TurbinePerformanceComp(om.ExplicitComponent):
    """Thrust, torque, power and the turbine coefficients (Burton et al., Sec. 3.2; Manwell et al., Sec. 3.2).

    ``T = sum(dT/dr dr)``, ``Q = sum(dQ/dr dr)``, ``P = Omega Q``, ``C_P = P / (1/2 rho A V**3)``,
    ``C_T = T / (1/2 rho A V**2)`` with ``A = pi R**2``, and ``lambda = Omega R / V``.

    Options: ``num_nodes``, ``num_radial``.

    Inputs
    ------
    dthrust_dr[nn, nr] (N/m), dtorque_dr[nn, nr] (N*m/m), dr[nn, nr] (m)
    rpm[nn] (rpm), radius[nn] (m), v_axial[nn] (m/s), rho[nn] (kg/m**3)

    Outputs
    -------
    thrust[nn] (N), torque[nn] (N*m), power[nn] (W), power_coefficient[nn] (-), thrust_coefficient[nn] (-),
    tip_speed_ratio[nn] (-)
    """

    def initialize(self):
        declare_size_options(self.options)

    def setup(self):
        add_inputs(self, ("dthrust_dr", "dtorque_dr", "dr", "rpm", "radius", "v_axial", "rho"))
        nn = self.options["num_nodes"]
        for name, (units, desc) in TURBINE_OUTPUTS.items():
            self.add_output(name, val=np.zeros(nn), units=units, desc=desc)

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = node_wrt_dist(nn, nr)
        self.declare_partials(["thrust", "thrust_coefficient"], ["dthrust_dr", "dr"], rows=rows, cols=cols)
        self.declare_partials(["torque", "power", "power_coefficient"], ["dtorque_dr", "dr"], rows=rows, cols=cols)
        rows, cols = node_wrt_node(nn)
        self.declare_partials(["power", "power_coefficient", "tip_speed_ratio"], "rpm", rows=rows, cols=cols)
        self.declare_partials(["power_coefficient", "thrust_coefficient", "tip_speed_ratio"], ["radius", "v_axial"],
                              rows=rows, cols=cols)
        self.declare_partials(["power_coefficient", "thrust_coefficient"], "rho", rows=rows, cols=cols)

    def _terms(self, inputs):
        omega = inputs["rpm"] * RPM_TO_RAD_PER_S
        radius, v, rho = inputs["radius"], inputs["v_axial"], inputs["rho"]
        if np.any(np.real(v) <= 0.0):
            raise om.AnalysisError(f"{self.msginfo}: the wind speed v_axial must be positive for the turbine "
                                   "coefficients")
        dynamic = 0.5 * rho * np.pi * radius ** 2 * v ** 2
        return omega, radius, v, rho, dynamic

    def compute(self, inputs, outputs):
        omega, radius, v, _, dynamic = self._terms(inputs)
        thrust = np.sum(inputs["dthrust_dr"] * inputs["dr"], axis=1)
        torque = np.sum(inputs["dtorque_dr"] * inputs["dr"], axis=1)
        outputs["thrust"], outputs["torque"], outputs["power"] = thrust, torque, omega * torque
        outputs["power_coefficient"] = omega * torque / (dynamic * v)
        outputs["thrust_coefficient"] = thrust / dynamic
        outputs["tip_speed_ratio"] = omega * radius / v

    def compute_partials(self, inputs, partials):
        omega, radius, v, rho, dynamic = self._terms(inputs)
        thrust = np.sum(inputs["dthrust_dr"] * inputs["dr"], axis=1)
        torque = np.sum(inputs["dtorque_dr"] * inputs["dr"], axis=1)
        c_p, c_t = omega * torque / (dynamic * v), thrust / dynamic
        nr = self.options["num_radial"]

        def rep(x):
            return np.repeat(x, nr)

        for out, load, scale in (("thrust", "dthrust_dr", 1.0), ("thrust_coefficient", "dthrust_dr", 1.0 / dynamic),
                                 ("torque", "dtorque_dr", 1.0), ("power", "dtorque_dr", omega),
                                 ("power_coefficient", "dtorque_dr", omega / (dynamic * v))):
            partials[out, load] = (inputs["dr"] * rep(scale).reshape(-1, nr)).ravel()
            partials[out, "dr"] = (inputs[load] * rep(scale).reshape(-1, nr)).ravel()
        partials["power", "rpm"] = RPM_TO_RAD_PER_S * torque
        partials["power_coefficient", "rpm"] = c_p / inputs["rpm"]
        partials["tip_speed_ratio", "rpm"] = RPM_TO_RAD_PER_S * radius / v
        partials["power_coefficient", "radius"] = -2.0 * c_p / radius
        partials["thrust_coefficient", "radius"] = -2.0 * c_t / radius
        partials["tip_speed_ratio", "radius"] = omega / v
        partials["power_coefficient", "v_axial"] = -3.0 * c_p / v
        partials["thrust_coefficient", "v_axial"] = -2.0 * c_t / v
        partials["tip_speed_ratio", "v_axial"] = -omega * radius / v ** 2
        partials["power_coefficient", "rho"] = -c_p / rho
        partials["thrust_coefficient", "rho"] = -c_t / rho
