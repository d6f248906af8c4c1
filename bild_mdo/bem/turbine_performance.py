"""TurbinePerformanceComp: power extracted, C_P, C_T, C_Q and tip-speed ratio of a wind turbine."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.bem.metrics import TURBINE_OUTPUTS
from bild_mdo.bem.wind_components import add_geometry_inputs
from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.utils.options import add_inputs, declare_size_options
from bild_mdo.utils.sparsity import node_wrt_dist, node_wrt_node

#: Primitives each output depends on ('T', 'Q': the sums over the stations).
_DEPENDS = {
    "thrust": ("T",), "torque": ("Q",), "power": ("Q", "rpm"),
    "power_coefficient": ("Q", "rpm", "v_axial", "radius", "rho", "precone"),
    "thrust_coefficient": ("T", "v_axial", "radius", "rho", "precone"),
    "torque_coefficient": ("Q", "v_axial", "radius", "rho", "precone"),
    "tip_speed_ratio": ("rpm", "radius", "v_axial"),
    "tip_mach": ("v_axial", "rpm", "radius", "speed_of_sound"),
}


def turbine_performance(T, Q, v_axial, rpm, radius, rho, precone, speed_of_sound):
    """Turbine metrics (:data:`~bild_mdo.bem.metrics.TURBINE_METRICS`) and their partials.

    Parameters
    ----------
    T, Q : array_like
        Thrust downwind (N) and driving torque (N m), turbine-signed.
    v_axial, rpm, radius, rho, precone, speed_of_sound : array_like
        Wind speed at hub height (m/s, > 0), rotor speed (rpm), blade tip radius along the blade (m),
        density (kg/m^3), precone (rad), speed of sound (m/s).

    Returns
    -------
    values : dict
        Output name -> array.
    partials : dict
        Output name -> {primitive: array}; primitives 'T', 'Q' and the parameters' names.

    Raises
    ------
    openmdao.api.AnalysisError
        Where the wind speed is not positive (the coefficients divide by it).
    """
    bad = ~(np.real(np.asarray(v_axial)) > 0.0)
    if np.any(bad):
        node = int(np.flatnonzero(np.atleast_1d(bad))[0])
        raise om.AnalysisError(f"turbine performance: the wind speed v_axial must be positive at node {node} "
                               "(C_P, C_T and the tip-speed ratio divide by it)")
    omega = rpm * RPM_TO_RAD_PER_S
    cone = np.cos(precone)
    tan = np.tan(precone)
    area = np.pi * (radius * cone) ** 2
    q_area = 0.5 * rho * v_axial**2 * area
    P = omega * Q
    cp = P / (q_area * v_axial)
    ct = T / q_area
    cq = Q / (q_area * radius * cone)
    tsr = omega * radius / v_axial
    tip_speed = np.sqrt(v_axial**2 + (omega * radius) ** 2)
    tip_mach = tip_speed / speed_of_sound
    values = {"thrust": T, "torque": Q, "power": P, "power_coefficient": cp, "thrust_coefficient": ct,
              "torque_coefficient": cq, "tip_speed_ratio": tsr, "tip_mach": tip_mach}
    one = np.ones(np.shape(T))
    partials = {
        "thrust": {"T": one},
        "torque": {"Q": one},
        "power": {"Q": omega * one, "rpm": RPM_TO_RAD_PER_S * Q},
        "power_coefficient": {"Q": omega / (q_area * v_axial), "rpm": cp / rpm, "v_axial": -3.0 * cp / v_axial,
                              "radius": -2.0 * cp / radius, "rho": -cp / rho, "precone": 2.0 * cp * tan},
        "thrust_coefficient": {"T": 1.0 / q_area, "v_axial": -2.0 * ct / v_axial, "radius": -2.0 * ct / radius,
                               "rho": -ct / rho, "precone": 2.0 * ct * tan},
        "torque_coefficient": {"Q": 1.0 / (q_area * radius * cone), "v_axial": -2.0 * cq / v_axial,
                               "radius": -3.0 * cq / radius, "rho": -cq / rho, "precone": 3.0 * cq * tan},
        "tip_speed_ratio": {"rpm": tsr / rpm, "radius": tsr / radius, "v_axial": -tsr / v_axial},
        "tip_mach": {"v_axial": v_axial / (tip_speed * speed_of_sound),
                     "rpm": omega * radius**2 * RPM_TO_RAD_PER_S / (tip_speed * speed_of_sound),
                     "radius": omega**2 * radius / (tip_speed * speed_of_sound),
                     "speed_of_sound": -tip_mach / speed_of_sound},
    }
    return values, partials


class TurbinePerformanceComp(om.ExplicitComponent):
    """Wind-turbine performance from the (sector-averaged) sectional loads of the BEM kernel.

    The kernel's loads are propeller-signed (:mod:`bild_mdo.bem.turbine_polar`): the turbine's
    thrust and driving torque are ``T = -sum(dT/dr dr)`` and ``Q = -sum(dQ/dr dr)``; the power
    extracted is ``P = Omega Q``.  ``C_P = P / (1/2 rho A V^3)``, ``C_T = T / (1/2 rho A V^2)``,
    ``C_Q = Q / (1/2 rho A V^2 R_rotor)`` with the swept area ``A = pi R_rotor^2``,
    ``R_rotor = R cos(precone)`` (CCBlade's convention), and ``lambda = Omega R / V`` with the
    blade's tip radius ``R`` (as CCBlade's examples set the rotor speed from the tip-speed ratio).

    Options
    -------
    num_nodes, num_radial : int

    Inputs
    ------
    dthrust_dr[nn, nr] (N/m), dtorque_dr[nn, nr] (N*m/m), dr[nn, nr] (m)
        Propeller-signed sectional loads along the shaft (all blades) and station widths.
    v_axial[nn] (m/s), rpm[nn] (rpm), radius[nn] (m), rho[nn] (kg/m**3), precone[nn] (rad),
    speed_of_sound[nn] (m/s)
        Wind at hub height (> 0), rotor speed, tip radius, density, precone, speed of sound.

    Outputs
    -------
    thrust[nn] (N), torque[nn] (N*m), power[nn] (W), power_coefficient[nn], thrust_coefficient[nn],
    torque_coefficient[nn], tip_speed_ratio[nn], tip_mach[nn]
        :data:`~bild_mdo.bem.metrics.TURBINE_METRICS`.
    """

    def initialize(self):
        declare_size_options(self.options)

    def setup(self):
        nn = self.options["num_nodes"]
        add_inputs(self, ("dthrust_dr", "dtorque_dr", "dr", "v_axial", "rpm", "radius", "rho", "speed_of_sound"),
                   v_axial=10.0)
        add_geometry_inputs(self, ("precone",))
        for name, (units, desc) in TURBINE_OUTPUTS.items():
            self.add_output(name, val=np.ones(nn), units=units, desc=desc)

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows_d, cols_d = node_wrt_dist(nn, nr)
        rows_n, cols_n = node_wrt_node(nn)
        for out, prims in _DEPENDS.items():
            for p in prims:
                if p in ("T", "Q"):
                    for name in ("dthrust_dr" if p == "T" else "dtorque_dr", "dr"):
                        self.declare_partials(out, name, rows=rows_d, cols=cols_d)
                else:
                    self.declare_partials(out, p, rows=rows_n, cols=cols_n)

    def _performance(self, inputs):
        T = -np.sum(inputs["dthrust_dr"] * inputs["dr"], axis=1)
        Q = -np.sum(inputs["dtorque_dr"] * inputs["dr"], axis=1)
        try:
            return turbine_performance(T, Q, *(inputs[name] for name in (
                "v_axial", "rpm", "radius", "rho", "precone", "speed_of_sound")))
        except om.AnalysisError as err:
            raise om.AnalysisError(f"{self.msginfo}: {err}") from err

    def compute(self, inputs, outputs):
        values, _ = self._performance(inputs)
        for name, value in values.items():
            outputs[name] = value

    def compute_partials(self, inputs, partials):
        _, d = self._performance(inputs)
        dist = {"T": ("dthrust_dr", inputs["dthrust_dr"]), "Q": ("dtorque_dr", inputs["dtorque_dr"])}
        dr = np.real(inputs["dr"])
        for out, prims in _DEPENDS.items():
            for p in prims:
                value = np.real(d[out][p])
                if p in dist:
                    name, load = dist[p]
                    # T = -sum(dT/dr dr): d/d(dT/dr) = -dr, d/d(dr) = -dT/dr (summed over T and Q for dr).
                    partials[out, name] = (-value[:, None] * dr).ravel()
                    partials[out, "dr"] = (-value[:, None] * np.real(load)).ravel()
                else:
                    partials[out, p] = value
