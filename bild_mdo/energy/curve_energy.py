"""CurveEnergyComp: annual energy and capacity factor of a computed power curve over a Weibull wind.

The power curve ``P_j`` at the wind speeds of :class:`~bild_mdo.energy.wind_speeds.WindSpeedsComp`
(Gauss-Lobatto nodes on ``[V_in, V_r]`` and ``[V_r, V_out]``) is integrated against the Weibull
density ``f(V) = (k/c) (V/c)**(k-1) exp(-(V/c)**k)``::

    AEP = H [ (V_r - V_in)/2  sum_i w_i P_i f(V_i)                                  region 2
            + P_r (exp(-(V_r/c)**k) - exp(-(V_out/c)**k))                          region 3 at rated
            + (V_out - V_r)/2 sum_j w_j (P_j - P_r) f(V_j) ],   H = 8760 h           its trim residue

Region 3 is written as the rated power's exact integral plus the quadrature of what the curve
differs from it by (zero to the pitch solve's tolerance where the pitch holds rated power), so
the energy of region 3 carries no quadrature error.  The wind speeds are inputs of their own
(their dependence on ``V_in, V_r, V_out`` comes through the connection), the interval limits
enter through the half-widths.  Below cut-in and above cut-out the rotor makes nothing.
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.energy.annual_energy import HOURS_PER_YEAR, weibull_density, weibull_survival
from bild_mdo.energy.wind_speeds import declare_wind_speed_option, lobatto, region_sizes

_YEAR = HOURS_PER_YEAR * 3600.0
#: Largest relative difference from rated power accepted at the rated point and in region 3 (a failed trim).
TRIM_RTOL = 1e-6
_LIMITS = ("cut_in_speed", "rated_wind_speed", "cut_out_speed")
_NODE_INPUTS = _LIMITS + ("rated_power", "weibull_scale", "weibull_shape")
_UNITS = {"cut_in_speed": "m/s", "rated_wind_speed": "m/s", "cut_out_speed": "m/s", "rated_power": "W",
          "weibull_scale": "m/s", "weibull_shape": None}
_DEFAULTS = {"cut_in_speed": 3.0, "rated_wind_speed": 11.0, "cut_out_speed": 25.0, "rated_power": 5.0e6,
             "weibull_scale": 8.0, "weibull_shape": 2.0}


class CurveEnergyComp(om.ExplicitComponent):
    """AEP and capacity factor of a power curve from cut-in to cut-out (module docstring).

    Options
    -------
    num_nodes : int
        Rotors.
    num_wind_speeds : int
        Points of the curve (:func:`~bild_mdo.energy.wind_speeds.region_sizes`).
    check_trim : bool
        True (default): raise where the curve does not hold rated power from the rated point on.

    Inputs
    ------
    wind_speed[nn, nw] (m/s), power[nn, nw] (W)
        The power curve.
    cut_in_speed[nn] (m/s), rated_wind_speed[nn] (m/s), cut_out_speed[nn] (m/s), rated_power[nn] (W),
    weibull_scale[nn] (m/s), weibull_shape[nn] (-)

    Outputs
    -------
    annual_energy[nn] (J), capacity_factor[nn] (-)
        AEP and ``AEP / (H P_r)``.

    Raises
    ------
    openmdao.api.AnalysisError
        Where the power at the rated point or in region 3 differs from ``rated_power`` by more than
        :data:`TRIM_RTOL` (relative): a failed rated-speed or pitch solve, never integrated silently.
    """

    def initialize(self):
        self.options.declare("num_nodes", types=int, default=1, lower=1, desc="rotors (axis 0)")
        declare_wind_speed_option(self.options)
        self.options.declare("check_trim", types=bool, default=True,
                             desc="raise where the rated point or region 3 does not hold rated power")

    def setup(self):
        nn, nw = self.options["num_nodes"], self.options["num_wind_speeds"]
        n2, n3 = region_sizes(nw)
        self.add_input("wind_speed", val=np.linspace(3.0, 25.0, nw)[None, :].repeat(nn, axis=0), units="m/s",
                       desc="wind speeds of the power curve")
        self.add_input("power", val=np.full((nn, nw), 1.0e6), units="W", desc="power at each wind speed")
        for name in _NODE_INPUTS:
            self.add_input(name, val=np.full(nn, _DEFAULTS[name]), units=_UNITS[name])
        self.add_output("annual_energy", val=np.ones(nn), units="J", ref=1e13, desc="annual energy production")
        self.add_output("capacity_factor", val=np.ones(nn), units=None, desc="AEP / (8760 h rated power)")
        w2, w3 = lobatto(n2)[1], lobatto(n3)[1]
        # Quadrature weight of each point in its region (the rated point, index n2 - 1, is in both).
        self._w2 = np.concatenate((w2, np.zeros(n3 - 1)))
        self._w3 = np.concatenate((np.zeros(n2 - 1), w3))
        rows_d, cols_d = np.repeat(np.arange(nn), nw), np.arange(nn * nw)
        rows = np.arange(nn)
        for out in ("annual_energy", "capacity_factor"):
            self.declare_partials(out, ["wind_speed", "power"], rows=rows_d, cols=cols_d)
            self.declare_partials(out, list(_NODE_INPUTS), rows=rows, cols=rows)

    def _terms(self, inputs):
        v_in, v_r, v_out = (inputs[name] for name in _LIMITS)
        p_r, c, k = inputs["rated_power"], inputs["weibull_scale"], inputs["weibull_shape"]
        power = inputs["power"]
        f, f_v, f_c, f_k = weibull_density(inputs["wind_speed"], c[:, None], k[:, None])
        h2, h3 = 0.5 * (v_r - v_in), 0.5 * (v_out - v_r)
        excess = power - p_r[:, None]
        s_r, s_o = weibull_survival(v_r, c, k), weibull_survival(v_out, c, k)
        sum2 = (power * f) @ self._w2
        sum3 = (excess * f) @ self._w3
        energy = _YEAR * (h2 * sum2 + p_r * (s_r[0] - s_o[0]) + h3 * sum3)
        return dict(p_r=p_r, power=power, excess=excess, f=f, f_v=f_v, f_c=f_c, f_k=f_k, h2=h2, h3=h3,
                    s_r=s_r, s_o=s_o, sum2=sum2, sum3=sum3, energy=energy)

    def _check(self, inputs):
        for name in ("rated_power", "weibull_scale", "weibull_shape", "cut_in_speed"):
            bad = ~(np.real(inputs[name]) > 0.0)
            if np.any(bad):
                i = int(np.flatnonzero(bad)[0])
                raise om.AnalysisError(f"{self.msginfo}: {name} must be positive and finite, got "
                                       f"{np.real(inputs[name][i]):.6g} (rotor {i})")

    def _check_trim(self, inputs):
        n2, _ = region_sizes(self.options["num_wind_speeds"])
        p_r = np.real(inputs["rated_power"])[:, None]
        power = np.real(inputs["power"])[:, n2 - 1:]
        bad = ~(np.abs(power - p_r) <= TRIM_RTOL * p_r)
        if np.any(bad):
            i, j = (int(x[0]) for x in np.nonzero(bad))
            speed = np.real(inputs["wind_speed"])[i, n2 - 1 + j]
            raise om.AnalysisError(
                f"{self.msginfo}: the pitch trim does not hold rated power at {speed:.6g} m/s (rotor {i}): power "
                f"{power[i, j]:.6g} W, rated {p_r[i, 0]:.6g} W; no collective pitch toward feather within the "
                "bounds gives rated power there, or its Newton solve did not converge")

    def compute(self, inputs, outputs):
        self._check(inputs)
        if self.options["check_trim"]:
            self._check_trim(inputs)
        t = self._terms(inputs)
        outputs["annual_energy"] = t["energy"]
        outputs["capacity_factor"] = t["energy"] / (_YEAR * t["p_r"])

    def compute_partials(self, inputs, partials):
        t = self._terms(inputs)
        h2, h3, p_r = t["h2"][:, None], t["h3"][:, None], t["p_r"]
        w2, w3 = self._w2[None, :], self._w3[None, :]
        d = {"power": _YEAR * (h2 * w2 + h3 * w3) * t["f"],
             "wind_speed": _YEAR * (h2 * w2 * t["power"] + h3 * w3 * t["excess"]) * t["f_v"]}
        d_in = _YEAR * -0.5 * t["sum2"]
        d_vr = _YEAR * (0.5 * t["sum2"] - 0.5 * t["sum3"] + p_r * t["s_r"][1])
        d_out = _YEAR * (0.5 * t["sum3"] - p_r * t["s_o"][1])
        d_pr = _YEAR * (t["s_r"][0] - t["s_o"][0] - t["h3"] * (t["f"] @ self._w3))
        shape = {}
        for j, name in ((2, "weibull_scale"), (3, "weibull_shape")):
            df = t[("f_c", "f_k")[j - 2]]
            shape[name] = _YEAR * (t["h2"] * ((t["power"] * df) @ self._w2) + t["h3"] * ((t["excess"] * df) @ self._w3)
                                   + p_r * (t["s_r"][j] - t["s_o"][j]))
        node = {"cut_in_speed": d_in, "rated_wind_speed": d_vr, "cut_out_speed": d_out, "rated_power": d_pr, **shape}
        scale = 1.0 / (_YEAR * p_r)
        for name, value in d.items():
            partials["annual_energy", name] = value.ravel()
            partials["capacity_factor", name] = (value * scale[:, None]).ravel()
        for name, value in node.items():
            partials["annual_energy", name] = value
            partials["capacity_factor", name] = value * scale
        partials["capacity_factor", "rated_power"] = d_pr * scale - t["energy"] * scale / p_r
