"""AnnualEnergyComp: annual energy production of a variable-speed, pitch-regulated turbine, with exact partials.

The rotor runs at its design tip-speed ratio below rated wind speed, so its
power coefficient stays the design's ``C_P`` (region 2); from the rated wind
speed to cut-out the collective pitch holds the rated power ``P_r`` (region 3);
below cut-in and above cut-out it makes nothing::

    P(V) = K V**3          for V_in <= V < V_r,   K = rho pi R**2 C_P / 2
    P(V) = P_r             for V_r <= V <= V_out,  V_r = (P_r / K)**(1/3)

With the Weibull density of the wind speed ``f(V) = (k/c) (V/c)**(k-1)
exp(-(V/c)**k)`` (scale ``c``, shape ``k``; ``k = 2`` is the Rayleigh
distribution) the annual energy is::

    AEP = H [ K int_{V_in}^{b} V**3 f(V) dV + P_r (exp(-(b/c)**k) - exp(-(V_out/c)**k)) ],
    b = min(max(V_r, V_in), V_out),   H = 8760 h

The region-2 integral is Gauss-Legendre quadrature on ``[V_in, b]`` (option
``num_quadrature``, default 48 points: its integrand is smooth, and the test
against the closed form ``c**3 [gamma(1 + 3/k, z)]`` of the lower incomplete
gamma function agrees to 1e-12); its nodes move with ``b``, so the partials are
exact in every input.  Where ``V_in < V_r < V_out`` the two regions meet with
equal power, so the derivative of ``AEP`` in ``V_r`` vanishes and ``AEP`` is
smooth there; where ``V_r`` leaves ``[V_in, V_out]`` (a rotor that never
reaches rated power, or one rated below cut-in) ``b`` is clipped: a kink.

Assumptions (stated, not modelled): in region 3 the pitch holds exactly the
rated power (the pitch angle itself is not computed here:
:class:`~bild_mdo.energy.power_curve_group.PowerCurveGroup` solves it, with the
BEM power of the blade at every wind speed); the design ``C_P`` holds
at every wind speed of region 2 (the Reynolds number of the sections changes with the wind
speed; the rotor-speed limit that usually ends region 2 early is not
modelled here: ``PowerCurveGroup(tip_speed_limit=True)`` models it); no drivetrain
or availability losses; the year is 8760 hours.

Options
-------
num_nodes : int
    Rotors (axis 0).
num_quadrature : int
    Gauss-Legendre points of the region-2 integral (default 48).

Inputs
------
power_coefficient[nn] (-), radius[nn] (m), rho[nn] (kg/m**3)
    The rotor's design ``C_P`` (e.g. of :class:`~bild_mdo.bild.turbine_group.TurbineBILDGroup`), tip radius and
    air density.
rated_power[nn] (W), weibull_scale[nn] (m/s), weibull_shape[nn] (-)
    Rated power, Weibull scale ``c`` and shape ``k``.
cut_in_speed[nn] (m/s), cut_out_speed[nn] (m/s)
    Cut-in and cut-out wind speeds.

Outputs
-------
annual_energy[nn] (J)
    AEP (``get_val(..., units="MW*h")`` for megawatt hours).
capacity_factor[nn] (-)
    ``AEP / (H P_r)``.
rated_wind_speed[nn] (m/s)
    ``V_r = (P_r / K)**(1/3)`` (unclipped).
"""
import numpy as np
import openmdao.api as om

#: Hours of the year of the AEP (365 days).
HOURS_PER_YEAR = 8760.0
_YEAR = HOURS_PER_YEAR * 3600.0
_INPUTS = ("power_coefficient", "radius", "rho", "rated_power", "weibull_scale", "weibull_shape", "cut_in_speed",
           "cut_out_speed")
_UNITS = {"power_coefficient": None, "radius": "m", "rho": "kg/m**3", "rated_power": "W", "weibull_scale": "m/s",
          "weibull_shape": None, "cut_in_speed": "m/s", "cut_out_speed": "m/s"}
_DEFAULTS = {"power_coefficient": 0.48, "radius": 63.0, "rho": 1.225, "rated_power": 5.0e6, "weibull_scale": 8.0,
             "weibull_shape": 2.0, "cut_in_speed": 3.0, "cut_out_speed": 25.0}


def weibull_density(v, c, k):
    """``f(V)`` and its partials ``(df/dV, df/dc, df/dk)`` (complex-safe)."""
    log_ratio = np.log(v / c)
    z = np.exp(k * log_ratio)
    f = k / c * np.exp((k - 1.0) * log_ratio - z)
    return f, f * (k - 1.0 - k * z) / v, f * k * (z - 1.0) / c, f * (1.0 / k + log_ratio * (1.0 - z))


def weibull_survival(v, c, k):
    """``exp(-(V/c)**k)`` and its partials ``(d/dV, d/dc, d/dk)``."""
    log_ratio = np.log(v / c)
    z = np.exp(k * log_ratio)
    s = np.exp(-z)
    return s, -s * k * z / v, s * k * z / c, -s * z * log_ratio


class AnnualEnergyComp(om.ExplicitComponent):
    """Annual energy production, capacity factor and rated wind speed (module docstring)."""

    def initialize(self):
        self.options.declare("num_nodes", types=int, default=1, desc="rotors (axis 0)")
        self.options.declare("num_quadrature", types=int, default=48, desc="Gauss-Legendre points of region 2")

    def setup(self):
        nn = self.options["num_nodes"]
        if nn < 1:
            raise ValueError(f"{self.msginfo}: num_nodes must be at least 1, got {nn}")
        if self.options["num_quadrature"] < 2:
            raise ValueError(f"{self.msginfo}: num_quadrature must be at least 2, got {self.options['num_quadrature']}")
        for name in _INPUTS:
            self.add_input(name, val=np.full(nn, _DEFAULTS[name]), units=_UNITS[name])
        self.add_output("annual_energy", val=np.ones(nn), units="J", ref=1e13)
        self.add_output("capacity_factor", val=np.ones(nn), units=None)
        self.add_output("rated_wind_speed", val=np.ones(nn), units="m/s")
        self._nodes, self._weights = np.polynomial.legendre.leggauss(self.options["num_quadrature"])
        rows = np.arange(nn)
        for out in ("annual_energy", "capacity_factor"):
            self.declare_partials(out, list(_INPUTS), rows=rows, cols=rows)
        self.declare_partials("rated_wind_speed", ["power_coefficient", "radius", "rho", "rated_power"],
                              rows=rows, cols=rows)

    def _check(self, inputs):
        values = {name: np.real(inputs[name]) for name in _INPUTS}
        for name in ("power_coefficient", "radius", "rho", "rated_power", "weibull_scale", "weibull_shape",
                     "cut_in_speed"):
            bad = ~(values[name] > 0.0)
            if np.any(bad):
                i = int(np.flatnonzero(bad)[0])
                raise om.AnalysisError(f"{self.msginfo}: {name} must be positive and finite, got {values[name][i]:.6g}"
                                       f" (node {i})")
        bad = ~(values["cut_out_speed"] > values["cut_in_speed"])
        if np.any(bad):
            i = int(np.flatnonzero(bad)[0])
            raise om.AnalysisError(f"{self.msginfo}: cut_out_speed {values['cut_out_speed'][i]:.6g} m/s must exceed "
                                   f"cut_in_speed {values['cut_in_speed'][i]:.6g} m/s (node {i})")

    def _terms(self, inputs):
        """Everything the outputs and partials need (complex-safe; branch decisions on real parts)."""
        cp, radius, rho, p_rated = (inputs[n] for n in ("power_coefficient", "radius", "rho", "rated_power"))
        c, k, v_in, v_out = (inputs[n] for n in ("weibull_scale", "weibull_shape", "cut_in_speed", "cut_out_speed"))
        gain = 0.5 * rho * np.pi * radius ** 2 * cp
        v_rated = (p_rated / gain) ** (1.0 / 3.0)
        below, above = np.real(v_rated) < np.real(v_in), np.real(v_rated) > np.real(v_out)
        b = np.where(below, v_in, np.where(above, v_out, v_rated))
        half = 0.5 * (b - v_in)
        t = 0.5 * (self._nodes + 1.0)
        v = v_in[:, None] + (b - v_in)[:, None] * t
        f, f_v, f_c, f_k = weibull_density(v, c[:, None], k[:, None])
        v3 = v ** 3
        g, g_v, g_c, g_k = v3 * f, 3.0 * v * v * f + v3 * f_v, v3 * f_c, v3 * f_k    # V**3 f(V) and its partials
        w = self._weights
        integral = half * (g @ w)
        survival_b, survival_o = weibull_survival(b, c, k), weibull_survival(v_out, c, k)
        energy = _YEAR * (gain * integral + p_rated * (survival_b[0] - survival_o[0]))
        return dict(cp=cp, radius=radius, rho=rho, p_rated=p_rated, gain=gain, v_rated=v_rated, below=below,
                    above=above, b=b, half=half, t=t, g=g, g_v=g_v, g_c=g_c, g_k=g_k, integral=integral,
                    survival_b=survival_b, survival_o=survival_o, energy=energy)

    def compute(self, inputs, outputs):
        self._check(inputs)
        s = self._terms(inputs)
        outputs["annual_energy"] = s["energy"]
        outputs["capacity_factor"] = s["energy"] / (_YEAR * s["p_rated"])
        outputs["rated_wind_speed"] = s["v_rated"]

    def compute_partials(self, inputs, partials):
        s = self._terms(inputs)
        w = self._weights
        t, half, gain, p_rated = (s[n] for n in ("t", "half", "gain", "p_rated"))
        g, g_v = s["g"], s["g_v"]
        sum_g = g @ w
        # The region-2 integral: its limits a = V_in, b and the Weibull parameters.
        d_int_a = half * (g_v @ (w * (1.0 - t))) - 0.5 * sum_g
        d_int_b = half * (g_v @ (w * t)) + 0.5 * sum_g
        d_int_c, d_int_k = half * (s["g_c"] @ w), half * (s["g_k"] @ w)
        # The region-3 energy P_r (exp(-z_b) - exp(-z_o)).
        (s_b, s_b_v, s_b_c, s_b_k), (s_o, s_o_v, s_o_c, s_o_k) = s["survival_b"], s["survival_o"]
        d3_b = p_rated * s_b_v
        d3_c = p_rated * (s_b_c - s_o_c)
        d3_k = p_rated * (s_b_k - s_o_k)
        d_b = gain * d_int_b + d3_b
        inside = ~(s["below"] | s["above"])
        db_vr = np.where(inside, 1.0, 0.0)
        v_rated = s["v_rated"]
        dvr_gain, dvr_p = -v_rated / (3.0 * gain), v_rated / (3.0 * p_rated)
        d_gain = s["integral"] + d_b * db_vr * dvr_gain
        d_gain_x = {"power_coefficient": gain / s["cp"], "radius": 2.0 * gain / s["radius"], "rho": gain / s["rho"]}
        energy = {name: _YEAR * d_gain * value for name, value in d_gain_x.items()}
        energy["rated_power"] = _YEAR * (s_b - s_o + d_b * db_vr * dvr_p)
        energy["weibull_scale"] = _YEAR * (gain * d_int_c + d3_c)
        energy["weibull_shape"] = _YEAR * (gain * d_int_k + d3_k)
        energy["cut_in_speed"] = _YEAR * (gain * d_int_a + d_b * np.where(s["below"], 1.0, 0.0))
        energy["cut_out_speed"] = _YEAR * (-p_rated * s_o_v + d_b * np.where(s["above"], 1.0, 0.0))
        scale = 1.0 / (_YEAR * p_rated)
        for name, value in energy.items():
            partials["annual_energy", name] = value
            partials["capacity_factor", name] = value * scale
        partials["capacity_factor", "rated_power"] = energy["rated_power"] * scale - s["energy"] * scale / p_rated
        for name, value in d_gain_x.items():
            partials["rated_wind_speed", name] = dvr_gain * value
        partials["rated_wind_speed", "rated_power"] = dvr_p
