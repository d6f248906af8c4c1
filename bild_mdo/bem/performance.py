"""RotorPerformanceComp: integrate section loads into rotor performance (paper Table 2)."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.bem.metrics import PERFORMANCE_OUTPUTS
from bild_mdo.constants import RPM_TO_RAD_PER_S, RPM_TO_REV_PER_S
from bild_mdo.utils.options import VARIABLES, add_inputs, declare_size_options
from bild_mdo.utils.sparsity import node_wrt_dist, node_wrt_node

_SQRT_2PI = np.sqrt(2.0 * np.pi)

# Which per-design primitives each output depends on (T, Q, S = sum(c dr) come from distributions).
_DEPENDS = {
    "thrust": ("T",),
    "torque": ("Q",),
    "power": ("Q", "rpm"),
    "efficiency": ("T", "Q", "v_axial", "rpm"),
    "figure_of_merit": ("T", "Q", "rpm", "radius", "rho"),
    "thrust_coefficient": ("T", "rpm", "radius", "rho"),
    "torque_coefficient": ("Q", "rpm", "radius", "rho"),
    "power_coefficient": ("Q", "rpm", "radius", "rho"),
    "energy_loss": ("T", "Q", "v_axial", "rpm"),
    "solidity": ("S", "radius"),
    "blade_loading": ("T", "S", "rpm", "radius", "rho"),
    "tip_mach": ("v_axial", "rpm", "radius", "speed_of_sound"),
}
#: Sea-level ISA speed of sound (m/s), the default of the ``speed_of_sound`` input.
SEA_LEVEL_SPEED_OF_SOUND = VARIABLES["speed_of_sound"][1]


def _abs(x):
    """Complex-safe absolute value."""
    return np.where(np.real(x) < 0.0, -x, x)


def _check_power(Q, rpm):
    """Raise where the metrics of Table 2 would divide by a zero power or rotor speed."""
    q, n = np.asarray(np.real(Q)), np.asarray(np.real(rpm))
    # One pass for the usual case (this runs for every design); the messages below name the first failure.
    if (n > 0.0).all() and np.isfinite(n).all() and (q != 0.0).all() and np.isfinite(q).all():
        return
    q, n = np.broadcast_arrays(q, n)
    q, n = np.atleast_1d(q), np.atleast_1d(n)
    checks = (
        (~(n > 0.0) | ~np.isfinite(n), "rpm",
         "the rotor speed must be positive and finite (the coefficients divide by n = rpm/60)"),
        ((q == 0.0) | ~np.isfinite(q), "torque",
         "the shaft power P = Omega Q must be nonzero and finite (the efficiency and figure of merit divide by "
         "it); Q = 0 means no blade element is loaded, e.g. a hover design whose stations are all unloaded"),
    )
    for bad, name, rule in checks:
        if np.any(bad):
            node = int(np.flatnonzero(bad)[0])
            value = float((n if name == "rpm" else q)[node])
            raise om.AnalysisError(f"rotor performance: {name} = {value!r} at node {node}: {rule}.")


def rotor_performance(T, Q, S, v_axial, rpm, radius, rho, num_blades, speed_of_sound=SEA_LEVEL_SPEED_OF_SOUND,
                      partials=True):
    """Performance metrics of Table 2 and their partials with respect to the primitives.

    Parameters
    ----------
    T, Q : array_like
        Thrust (N) and torque (N m).
    S : array_like
        Blade area per blade ``sum(c dr)`` (m^2).
    v_axial, rpm, radius, rho : array_like
        Axial speed (m/s), rotational speed (rpm), tip radius (m), density (kg/m^3).
    num_blades : int
        Number of blades B.
    speed_of_sound : array_like
        Speed of sound a (m/s), for the tip Mach number ``sqrt(V_x^2 + (Omega R)^2) / a``.
    partials : bool
        False: return ``None`` for the partials (a run without derivatives).

    Returns
    -------
    values : dict
        Output name -> array.
    partials : dict or None
        Output name -> {primitive: array}; primitives are 'T', 'Q', 'S', 'v_axial',
        'rpm', 'radius', 'rho', 'speed_of_sound'.

    Raises
    ------
    openmdao.api.AnalysisError
        Where ``rpm <= 0`` or the shaft power ``P = Omega Q`` is zero (or
        either is not finite): the efficiency, figure of merit and coefficients
        divide by them and would be inf/NaN.  Negative power (``Q < 0`` at
        ``rpm > 0``: a windmilling rotor, which the BEM analysis reports) keeps
        finite, signed values.  In hover (``V_x = 0``) the efficiency is
        exactly 0.
    """
    _check_power(Q, rpm)
    omega = rpm * RPM_TO_RAD_PER_S
    n = rpm * RPM_TO_REV_PER_S
    D = 2.0 * radius
    P = omega * Q
    abs_T = _abs(T)
    sqrt_abs_T = np.sqrt(abs_T)
    eta = v_axial * T / P
    fm = T * sqrt_abs_T / (P * _SQRT_2PI * radius * np.sqrt(rho))
    ct = T / (rho * n**2 * D**4)
    cq = Q / (rho * n**2 * D**5)
    cp = P / (rho * n**3 * D**5)
    E = P - v_axial * T
    sol = num_blades * S / (np.pi * radius**2)
    # A blade without area (S = 0: every chord zero, e.g. an infeasible BILD design) carries no load.
    has_area = np.real(sol) != 0.0
    safe_sol = np.where(has_area, sol, 1.0)
    bl = np.where(has_area, ct / safe_sol, 0.0)
    tip_speed = np.sqrt(v_axial**2 + (omega * radius) ** 2)
    tip_mach = tip_speed / speed_of_sound
    values = {"tip_mach": tip_mach, "thrust": T, "torque": Q, "power": P, "efficiency": eta, "figure_of_merit": fm,
              "thrust_coefficient": ct, "torque_coefficient": cq, "power_coefficient": cp,
              "energy_loss": E, "solidity": sol, "blade_loading": bl}
    if not partials:
        return values, None

    one = np.ones(np.shape(T))
    partials = {
        "thrust": {"T": one},
        "torque": {"Q": one},
        "power": {"Q": omega * one, "rpm": RPM_TO_RAD_PER_S * Q},
        "efficiency": {"T": v_axial / P, "Q": -eta / Q, "v_axial": T / P, "rpm": -eta / rpm},
        "figure_of_merit": {"T": 1.5 * sqrt_abs_T / (P * _SQRT_2PI * radius * np.sqrt(rho)),
                            "Q": -fm / Q, "rpm": -fm / rpm, "radius": -fm / radius,
                            "rho": -0.5 * fm / rho},
        "thrust_coefficient": {"T": 1.0 / (rho * n**2 * D**4), "rpm": -2.0 * ct / rpm,
                               "radius": -4.0 * ct / radius, "rho": -ct / rho},
        "torque_coefficient": {"Q": 1.0 / (rho * n**2 * D**5), "rpm": -2.0 * cq / rpm,
                               "radius": -5.0 * cq / radius, "rho": -cq / rho},
        "power_coefficient": {"Q": omega / (rho * n**3 * D**5), "rpm": -2.0 * cp / rpm,
                              "radius": -5.0 * cp / radius, "rho": -cp / rho},
        "energy_loss": {"T": -v_axial * one, "Q": omega * one, "v_axial": -T,
                        "rpm": RPM_TO_RAD_PER_S * Q},
        "solidity": {"S": num_blades / (np.pi * radius**2) * one, "radius": -2.0 * sol / radius},
        "blade_loading": {"T": np.where(has_area, 1.0 / (rho * n**2 * D**4 * safe_sol), 0.0),
                          "S": np.where(has_area, -bl / np.where(has_area, S, 1.0), 0.0), "rpm": -2.0 * bl / rpm,
                          "radius": -2.0 * bl / radius, "rho": -bl / rho},
        "tip_mach": {"v_axial": v_axial / (tip_speed * speed_of_sound),
                     "rpm": omega * radius**2 * RPM_TO_RAD_PER_S / (tip_speed * speed_of_sound),
                     "radius": omega**2 * radius / (tip_speed * speed_of_sound),
                     "speed_of_sound": -tip_mach / speed_of_sound},
    }
    return values, partials


class RotorPerformanceComp(om.ExplicitComponent):
    """Rotor performance from sectional thrust and torque distributions (paper Table 2).

    Integrals are sums over the stations, ``T = sum(dT/dr * dr)``, consistent
    with the station widths of :class:`~bild_mdo.bem.stations.StationsComp`.
    The figure of merit is extended as an odd function of thrust,
    ``FM = T sqrt(|T|) / (P sqrt(2 pi R^2 rho))``, so that it stays real when
    a windmilling rotor produces negative thrust.  Zero torque or a
    non-positive rpm raises :class:`openmdao.api.AnalysisError` (see
    :func:`rotor_performance`).

    Options
    -------
    num_nodes, num_radial, num_blades : int
        Sizes (:func:`~bild_mdo.utils.options.declare_size_options`) and the number of blades B.

    Inputs
    ------
    dthrust_dr[nn, nr] (N/m), dtorque_dr[nn, nr] (N*m/m)
        Sectional thrust and torque per unit span (all blades).
    dr[nn, nr] (m)
        Station widths.
    chord[nn, nr] (m)
        Chord distribution (for the solidity).
    v_axial[nn] (m/s), rpm[nn] (rpm), radius[nn] (m), rho[nn] (kg/m**3)
        Axial speed, rotational speed, tip radius, air density.
    speed_of_sound[nn] (m/s)
        Speed of sound a (default: sea-level ISA), for ``tip_mach``.

    Outputs
    -------
    thrust[nn] (N), torque[nn] (N*m), power[nn] (W), efficiency[nn], figure_of_merit[nn],
    thrust_coefficient[nn], torque_coefficient[nn], power_coefficient[nn], energy_loss[nn] (W),
    solidity[nn], blade_loading[nn], tip_mach[nn]
    """

    def initialize(self):
        declare_size_options(self.options)
        self.options.declare("num_blades", types=int, default=3, desc="number of blades B")

    def setup(self):
        nn = self.options["num_nodes"]
        add_inputs(self, ("dthrust_dr", "dtorque_dr", "dr", "chord", "v_axial", "rpm", "radius", "rho",
                          "speed_of_sound"))
        for name, (units, desc) in PERFORMANCE_OUTPUTS.items():
            self.add_output(name, val=np.ones(nn), units=units, desc=desc)

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows_d, cols_d = node_wrt_dist(nn, nr)
        rows_n, cols_n = node_wrt_node(nn)
        dist_of = {"T": ("dthrust_dr",), "Q": ("dtorque_dr",), "S": ("chord",)}
        for out, prims in _DEPENDS.items():
            wrt_dist = {name for p in prims for name in dist_of.get(p, ())}
            wrt_dist = wrt_dist | {"dr"} if wrt_dist else wrt_dist
            for name in sorted(wrt_dist):
                self.declare_partials(out, name, rows=rows_d, cols=cols_d)
            for p in prims:
                if p not in dist_of:
                    self.declare_partials(out, p, rows=rows_n, cols=cols_n)

    def _primitives(self, inputs):
        T = np.sum(inputs["dthrust_dr"] * inputs["dr"], axis=1)
        Q = np.sum(inputs["dtorque_dr"] * inputs["dr"], axis=1)
        S = np.sum(inputs["chord"] * inputs["dr"], axis=1)
        return T, Q, S

    def _performance(self, inputs, partials=True):
        T, Q, S = self._primitives(inputs)
        try:
            values, d = rotor_performance(T, Q, S, inputs["v_axial"], inputs["rpm"], inputs["radius"],
                                          inputs["rho"], self.options["num_blades"], inputs["speed_of_sound"],
                                          partials=partials)
        except om.AnalysisError as err:
            raise om.AnalysisError(f"{self.msginfo}: {err}") from err
        return values, d

    def compute(self, inputs, outputs):
        values, _ = self._performance(inputs, partials=False)
        for name, val in values.items():
            outputs[name] = val

    def compute_partials(self, inputs, partials):
        _, d = self._performance(inputs)
        dr = inputs["dr"]
        # Distribution behind each primitive, and d(primitive)/d(dr) per station.
        dist_of = {"T": ("dthrust_dr", inputs["dthrust_dr"]), "Q": ("dtorque_dr", inputs["dtorque_dr"]),
                   "S": ("chord", inputs["chord"])}
        for out, prims in _DEPENDS.items():
            # Outputs of per-design inputs only (tip_mach) have no sum over the stations.
            ddr = None
            for p in prims:
                if p in dist_of:
                    name, dprim_ddr = dist_of[p]
                    coefficient = d[out][p][:, None]
                    partials[out, name] = (coefficient * dr).ravel()
                    ddr = coefficient * dprim_ddr if ddr is None else ddr + coefficient * dprim_ddr
                else:
                    partials[out, p] = d[out][p]
            if ddr is not None:
                partials[out, "dr"] = ddr.ravel()
