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

With option ``tip_speed_limit`` region 2 is the sum of two Lobatto rules, on ``[V_in, V_k]`` and
``[V_k, V_r]`` (``V_k``, input ``tip_speed_limit_wind_speed``, where region 2.5 begins,
:mod:`bild_mdo.energy.wind_speeds`).
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.energy.annual_energy import HOURS_PER_YEAR, weibull_density, weibull_survival
from bild_mdo.energy.wind_speeds import (
    TIP_SPEED_LIMIT_WIND_SPEED,
    curve_intervals,
    declare_tip_speed_limit_option,
    declare_wind_speed_option,
    region_sizes,
)

_YEAR = HOURS_PER_YEAR * 3600.0
#: Largest relative difference from rated power accepted at the rated point and in region 3 (a failed trim).
TRIM_RTOL = 1e-6
_LIMITS = ("cut_in_speed", "rated_wind_speed", "cut_out_speed")
_NODE_INPUTS = _LIMITS + ("rated_power", "weibull_scale", "weibull_shape")
_KNEE = TIP_SPEED_LIMIT_WIND_SPEED
_UNITS = {_KNEE: "m/s", "cut_in_speed": "m/s", "rated_wind_speed": "m/s", "cut_out_speed": "m/s", "rated_power": "W",
          "weibull_scale": "m/s", "weibull_shape": None}
_DEFAULTS = {_KNEE: 11.0, "cut_in_speed": 3.0, "rated_wind_speed": 11.0, "cut_out_speed": 25.0, "rated_power": 5.0e6,
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
    tip_speed_limit : bool
        False (default); True: region 2 in two intervals, split at input ``tip_speed_limit_wind_speed``.

    Inputs
    ------
    wind_speed[nn, nw] (m/s), power[nn, nw] (W)
        The power curve.
    cut_in_speed[nn] (m/s), rated_wind_speed[nn] (m/s), cut_out_speed[nn] (m/s), rated_power[nn] (W),
    weibull_scale[nn] (m/s), weibull_shape[nn] (-); tip_speed_limit_wind_speed[nn] (m/s) (``tip_speed_limit``)

    Outputs
    -------
    annual_energy[nn] (J), capacity_factor[nn] (-)
        AEP and ``AEP / (H P_r)``.

    Raises
    ------
    openmdao.api.AnalysisError
        Where the power at the rated point or in region 3 differs from ``rated_power`` by more than
        :data:`TRIM_RTOL` (relative), or exceeds it or falls as the wind rises below rated: a failed rated-speed
        or pitch solve, or a rotor stalled at its tip-speed limit that may reach rated power more than once,
        never integrated silently.
    """

    def initialize(self):
        self.options.declare("num_nodes", types=int, default=1, lower=1, desc="rotors (axis 0)")
        declare_wind_speed_option(self.options)
        self.options.declare("check_trim", types=bool, default=True,
                             desc="raise where the rated point or region 3 does not hold rated power")
        declare_tip_speed_limit_option(self.options)

    def setup(self):
        nn, nw = self.options["num_nodes"], self.options["num_wind_speeds"]
        self.add_input("wind_speed", val=np.linspace(3.0, 25.0, nw)[None, :].repeat(nn, axis=0), units="m/s",
                       desc="wind speeds of the power curve")
        self.add_input("power", val=np.full((nn, nw), 1.0e6), units="W", desc="power at each wind speed")
        limited = self.options["tip_speed_limit"]
        self._node_inputs = _NODE_INPUTS + ((_KNEE,) if limited else ())
        for name in self._node_inputs:
            self.add_input(name, val=np.full(nn, _DEFAULTS[name]), units=_UNITS[name])
        self.add_output("annual_energy", val=np.ones(nn), units="J", ref=1e13, desc="annual energy production")
        self.add_output("capacity_factor", val=np.ones(nn), units=None, desc="AEP / (8760 h rated power)")
        # The rules of region 2 (lower and upper limit, the quadrature weight of each point of the curve) and the
        # weights of region 3 (the rated point, index n2 - 1, is in region 2 too).
        weighted = []
        for interval in curve_intervals(nw, limited):
            w = np.zeros(nw)
            w[interval.points] = interval.weights
            weighted.append((interval.low, interval.high, w))
        self._intervals, self._w3 = weighted[:-1], weighted[-1][2]
        rows_d, cols_d = np.repeat(np.arange(nn), nw), np.arange(nn * nw)
        rows = np.arange(nn)
        for out in ("annual_energy", "capacity_factor"):
            self.declare_partials(out, ["wind_speed", "power"], rows=rows_d, cols=cols_d)
            self.declare_partials(out, list(self._node_inputs), rows=rows, cols=rows)

    def _terms(self, inputs):
        v_r, v_out = inputs["rated_wind_speed"], inputs["cut_out_speed"]
        p_r, c, k = inputs["rated_power"], inputs["weibull_scale"], inputs["weibull_shape"]
        power = inputs["power"]
        f, f_v, f_c, f_k = weibull_density(inputs["wind_speed"], c[:, None], k[:, None])
        # w2[nn, nw]: each point's weight in region 2, its Lobatto weight times its interval's half-width.
        w2 = sum(0.5 * (inputs[hi] - inputs[lo])[:, None] * w[None, :] for lo, hi, w in self._intervals)
        sums2 = [(power * f) @ w for _, _, w in self._intervals]
        h3 = 0.5 * (v_out - v_r)
        excess = power - p_r[:, None]
        s_r, s_o = weibull_survival(v_r, c, k), weibull_survival(v_out, c, k)
        sum3 = (excess * f) @ self._w3
        energy = _YEAR * (np.sum(w2 * power * f, axis=1) + p_r * (s_r[0] - s_o[0]) + h3 * sum3)
        return dict(p_r=p_r, power=power, excess=excess, f=f, f_v=f_v, f_c=f_c, f_k=f_k, w2=w2, sums2=sums2, h3=h3,
                    s_r=s_r, s_o=s_o, sum3=sum3, energy=energy)

    def _check(self, inputs):
        for name in ("rated_power", "weibull_scale", "weibull_shape", "cut_in_speed"):
            bad = ~(np.real(inputs[name]) > 0.0)
            if np.any(bad):
                i = int(np.flatnonzero(bad)[0])
                raise om.AnalysisError(f"{self.msginfo}: {name} must be positive and finite, got "
                                       f"{np.real(inputs[name][i]):.6g} (rotor {i})")

    def _check_trim(self, inputs):
        n2, _ = region_sizes(self.options["num_wind_speeds"], self.options["tip_speed_limit"])
        p_r = np.real(inputs["rated_power"])[:, None]
        below = np.real(inputs["power"])[:, :n2]
        # Below rated the power rises with the wind speed (P ~ C_P V**3 at the design tip-speed ratio); at a
        # tip-speed limit it can stall, fall and rise again, so that rated power is reached at several wind
        # speeds and the rated-speed solve may have found a later one: refused, never integrated silently.
        wrong = np.zeros(below.shape, dtype=bool)
        wrong[:, :-1] = below[:, :-1] > p_r * (1.0 + TRIM_RTOL)  # above rated before the rated point
        wrong[:, 1:] |= np.diff(below, axis=1) < -TRIM_RTOL * p_r  # lower than the point before it
        if np.any(wrong):
            i, j = (int(x[0]) for x in np.nonzero(wrong))
            raise om.AnalysisError(
                f"{self.msginfo}: below the rated wind speed {np.real(inputs['rated_wind_speed'][i]):.6g} m/s the power "
                f"exceeds rated power or falls as the wind rises, at {np.real(inputs['wind_speed'][i, j]):.6g} m/s "
                f"(rotor {i}: {below[i, j]:.6g} W, rated {p_r[i, 0]:.6g} W); at zero pitch the rotor stalls at its "
                "tip-speed limit and may reach rated power at more than one wind speed: raise max_tip_speed or lower "
                "the rated power")
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
        h3, p_r, w2 = t["h3"][:, None], t["p_r"], t["w2"]
        w3 = self._w3[None, :]
        d = {"power": _YEAR * (w2 + h3 * w3) * t["f"],
             "wind_speed": _YEAR * (w2 * t["power"] + h3 * w3 * t["excess"]) * t["f_v"]}
        node = {name: np.zeros_like(p_r) for name in self._node_inputs}
        for (lo, hi, _), total in zip(self._intervals, t["sums2"]):
            node[lo] = node[lo] - 0.5 * _YEAR * total
            node[hi] = node[hi] + 0.5 * _YEAR * total
        node["rated_wind_speed"] = node["rated_wind_speed"] + _YEAR * (-0.5 * t["sum3"] + p_r * t["s_r"][1])
        node["cut_out_speed"] = _YEAR * (0.5 * t["sum3"] - p_r * t["s_o"][1])
        d_pr = _YEAR * (t["s_r"][0] - t["s_o"][0] - t["h3"] * (t["f"] @ self._w3))
        node["rated_power"] = d_pr
        for j, name in ((2, "weibull_scale"), (3, "weibull_shape")):
            df = t[("f_c", "f_k")[j - 2]]
            node[name] = _YEAR * (np.sum(w2 * t["power"] * df, axis=1) + t["h3"] * ((t["excess"] * df) @ self._w3)
                                  + p_r * (t["s_r"][j] - t["s_o"][j]))
        scale = 1.0 / (_YEAR * p_r)
        for name, value in d.items():
            partials["annual_energy", name] = value.ravel()
            partials["capacity_factor", name] = (value * scale[:, None]).ravel()
        for name, value in node.items():
            partials["annual_energy", name] = value
            partials["capacity_factor", name] = value * scale
        partials["capacity_factor", "rated_power"] = d_pr * scale - t["energy"] * scale / p_r
