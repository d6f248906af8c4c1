"""Python API for a turbine blade's power curve and annual energy: :func:`power_curve` returns a :class:`PowerCurve`.

::

    from bild_mdo import design_turbine

    rotor = design_turbine(wind_speed=10.0, tip_speed_ratio=8.0, radius=63.0)
    curve = rotor.power_curve(rated_power=5.3e6, max_tip_speed=80.0, weibull_scale=9.0)
    print(curve.summary())

One run of :class:`~bild_mdo.energy.PowerCurveGroup` (the turbine BEM of the blade from cut-in to cut-out,
region 2.5 where ``max_tip_speed`` is given, the pitch trimmed to rated power above rated).  A 2-D ``chord``
and ``twist`` (and 1-D arrays of the scalars, broadcast against them) give a batch.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import openmdao.api as om

from bild_mdo import validation
from bild_mdo.atmosphere import MAX_ALTITUDE, isa
from bild_mdo.bem.inflow_residual import HIGH_INDUCTION, resolve_high_induction
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.energy.power_curve_group import PowerCurveGroup
from bild_mdo.energy.wind_speeds import MIN_WIND_SPEEDS, TIP_SPEED_LIMIT_WIND_SPEED
from bild_mdo.fluid import fluid_point, resolve_fluid
from bild_mdo.io.airfoil import resolve_airfoil
from bild_mdo.io.geometry import unit_key
from bild_mdo.results.batch_values import BatchValues

__all__ = ["PowerCurve", "power_curve"]

#: Outputs of the group a PowerCurve holds: name -> units.
CURVE_VALUES = {"wind_speed": "m/s", "rpm": "rpm", "collective_pitch": "rad", "power": "W", "thrust": "N",
                "torque": "N*m", "power_coefficient": None, "thrust_coefficient": None}
ROTOR_VALUES = {"rated_wind_speed": "m/s", "annual_energy": "J", "capacity_factor": None}
_KNEE = TIP_SPEED_LIMIT_WIND_SPEED


class PowerCurve(BatchValues):
    """The power curve(s) and AEP from :func:`power_curve` (SI units, angles in rad).

    Attributes (``(nw,)`` per curve and scalars for one rotor, ``(nn, nw)`` and ``(nn,)`` for a batch):
    the curve ``wind_speed, rpm, collective_pitch, power, thrust, torque, power_coefficient,
    thrust_coefficient``; ``rated_wind_speed``, ``annual_energy`` (J), ``capacity_factor``,
    ``tip_speed_limit_wind_speed`` (where region 2.5 begins; NaN without a tip-speed limit); and the inputs
    ``rated_power, tip_speed_ratio, max_tip_speed`` (inf: none), ``weibull_scale, weibull_shape,
    cut_in_speed, cut_out_speed``.
    """

    def __init__(self, values, is_batch):
        self.values = values
        self.is_batch = is_batch

    def __getitem__(self, index):
        return PowerCurve(self._row_values(index), is_batch=False)

    def to_csv(self, path):
        """Write the curve(s) as CSV with units in the header, one row per wind speed (and rotor), the pitch in
        degrees; each rotor's rated wind speed, AEP and capacity factor on every row of it, its inputs in a comment
        line before its rows.

        Returns
        -------
        pathlib.Path
        """
        columns = {"wind_speed": "m/s", "rpm": "rpm", "collective_pitch": "deg", "power": "W", "thrust": "N",
                   "torque": "N*m", "power_coefficient": None, "thrust_coefficient": None,
                   "rated_wind_speed": "m/s", "annual_energy": "GW*h", "capacity_factor": None}
        lines = ["# bild-mdo power curve (turbine BEM, pitch trimmed to rated power above rated)",
                 ",".join(["rotor [-]"] + [unit_key(name, units) for name, units in columns.items()])]
        for i in range(len(self)):
            one = self[i]
            lines.append(f"# rotor {i}: rated_power [W] {one.rated_power:.10g}, tip_speed_ratio [-] "
                         f"{one.tip_speed_ratio:.10g}, max_tip_speed [m/s] {one.max_tip_speed:.10g}, weibull_scale "
                         f"[m/s] {one.weibull_scale:.10g}, weibull_shape [-] {one.weibull_shape:.10g}")
            curve = [one.wind_speed, one.rpm, np.degrees(one.collective_pitch), one.power, one.thrust, one.torque,
                     one.power_coefficient, one.thrust_coefficient]
            tail = f"{one.rated_wind_speed:.10g},{one.annual_energy / 3.6e12:.10g},{one.capacity_factor:.10g}"
            for row in zip(*curve):
                lines.append(f"{i}," + ",".join(f"{x:.10g}" for x in row) + "," + tail)
        path = Path(path)
        path.write_text("\n".join(lines) + "\n", encoding="utf-8")
        return path

    def summary(self):
        """A text summary: the curve of the first rotor of a batch, its AEP and capacity factor."""
        one = self if not self.is_batch else self[0]
        head = "Power curve (turbine BEM, pitch trimmed to rated power above rated)" + \
            (f"; rotor 1 of {len(self)}" if self.is_batch else "")
        if not np.isfinite(one.max_tip_speed):
            limit = "none"
        elif one.tip_speed_limit_wind_speed < one.rated_wind_speed:
            limit = f"{one.max_tip_speed:.5g} m/s, reached at {one.tip_speed_limit_wind_speed:.4g} m/s (region 2.5)"
        else:
            limit = f"{one.max_tip_speed:.5g} m/s, not reached below rated"
        rows = [f"  rated power                  {one.rated_power / 1e3:12.5g} kW",
                f"  rated wind speed             {one.rated_wind_speed:12.5g} m/s",
                f"  design tip-speed ratio       {one.tip_speed_ratio:12.5g} -",
                f"  tip-speed limit              {limit}",
                f"  Weibull scale, shape         {one.weibull_scale:12.5g} m/s, {one.weibull_shape:.4g}",
                f"  annual energy                {one.annual_energy / 3.6e12:12.5g} GWh",
                f"  capacity factor              {one.capacity_factor:12.5g} -",
                "    V [m/s]   rpm   pitch [deg]    P [kW]    T [kN]     C_P      C_T"]
        for v, rpm, pitch, p, t, cp, ct in zip(one.wind_speed, one.rpm, np.degrees(one.collective_pitch), one.power,
                                               one.thrust, one.power_coefficient, one.thrust_coefficient):
            rows.append(f"  {v:9.3f} {rpm:7.3f} {pitch:10.3f} {p / 1e3:10.1f} {t / 1e3:9.2f} {cp:8.4f} {ct:8.4f}")
        return "\n".join([head, "-" * len(head)] + rows)


def _scalars(radius, hub_radius, tip_speed_ratio, rated_power, max_tip_speed, weibull_scale, weibull_shape,
             cut_in_speed, cut_out_speed, altitude):
    values = {"radius": validation.positive("radius", radius, units="m"),
              "hub_radius": validation.positive("hub_radius", hub_radius, units="m"),
              "tip_speed_ratio": validation.positive("tip_speed_ratio", tip_speed_ratio),
              "rated_power": validation.positive("rated_power", rated_power, units="W"),
              "weibull_scale": validation.positive("weibull_scale", weibull_scale, units="m/s"),
              "weibull_shape": validation.positive("weibull_shape", weibull_shape),
              "cut_in_speed": validation.positive("cut_in_speed", cut_in_speed, units="m/s"),
              "cut_out_speed": validation.positive("cut_out_speed", cut_out_speed, units="m/s"),
              "altitude": validation.in_range("altitude", altitude, 0.0, MAX_ALTITUDE, units="m", hint="ISA")}
    validation.smaller("hub_radius", values["hub_radius"], "radius", values["radius"])
    validation.smaller("cut_in_speed", values["cut_in_speed"], "cut_out_speed", values["cut_out_speed"])
    if max_tip_speed is not None:
        values["max_tip_speed"] = validation.positive("max_tip_speed", max_tip_speed, units="m/s",
                                                      hint="the largest Omega R")
        reached = values["max_tip_speed"] / values["tip_speed_ratio"]
        validation.check("max_tip_speed", values["max_tip_speed"] * np.ones_like(reached),
                         ~(reached > values["cut_in_speed"]),
                         "reached above cut_in_speed at the design tip-speed ratio (max_tip_speed / "
                         "tip_speed_ratio > cut_in_speed)", units="m/s")
    return values


def power_curve(chord, twist, radius, hub_radius, tip_speed_ratio, rated_power, num_blades=3, airfoil="naca4412",
                loss_model="tip_hub", max_tip_speed=None, weibull_scale=8.0, weibull_shape=2.0, cut_in_speed=3.0,
                cut_out_speed=25.0, altitude=0.0, fluid=None, num_wind_speeds=13, high_induction="buhl"):
    """The power curve and annual energy of turbine blade(s) (:class:`~bild_mdo.energy.PowerCurveGroup`).

    Parameters
    ----------
    chord, twist : array_like, shape (nr,) or (nn, nr)
        The blade (m, rad) at the midpoints of ``nr`` equal annuli from hub to tip (as a
        :func:`~bild_mdo.design_turbine` design's stations).
    radius, hub_radius : float or array_like
        Tip and hub radius (m), ``0 < hub_radius < radius``.
    tip_speed_ratio : float or array_like
        Design tip-speed ratio ``Omega R / V`` of region 2 (-), > 0.
    rated_power : float or array_like
        Rated (aerodynamic) power (W), > 0.
    num_blades : int
    airfoil : str or Polar
        Anything :func:`~bild_mdo.io.airfoil.resolve_airfoil` accepts.
    loss_model : {'tip_hub', 'tip', 'none'}
    max_tip_speed : float or array_like, optional
        Largest tip speed ``Omega R`` (m/s): the rotor speed is held at ``max_tip_speed / R`` from where it is
        reached (region 2.5), which must lie above cut-in.  None (default): no limit.
    weibull_scale, weibull_shape : float or array_like
        Weibull ``c`` (m/s) and ``k`` (-) of the wind at hub height (``k = 2``: Rayleigh).
    cut_in_speed, cut_out_speed : float or array_like
        (m/s), ``cut_in_speed < cut_out_speed``.
    altitude : float or array_like
        ISA altitude (m); or ``fluid`` (:mod:`bild_mdo.fluid`), then altitude stays 0.
    num_wind_speeds : int
        Points of the curve (at least 5; Gauss-Lobatto nodes, :mod:`bild_mdo.energy.wind_speeds`).
    high_induction : {'buhl', 'none', None}
        The thrust of annuli past ``a = 0.4``: Buhl's (default, as CCBlade; None too, as for
        :func:`~bild_mdo.bem.analyze_rotor` of a turbine) or momentum theory's.

    Returns
    -------
    PowerCurve

    Raises
    ------
    ValueError
        For invalid inputs (one line naming the argument).
    openmdao.api.AnalysisError
        Where rated power is not reached between cut-in and cut-out, the tip-speed limit is reached below
        cut-in, or no pitch toward feather holds rated power (the message says which, and what to change).
    """
    num_blades = validation.integer("num_blades", num_blades)
    num_wind_speeds = validation.integer("num_wind_speeds", num_wind_speeds, minimum=MIN_WIND_SPEEDS)
    validation.choice("loss_model", loss_model, LOSS_MODELS)
    high_induction = validation.choice("high_induction", resolve_high_induction(high_induction, "turbine"),
                                       HIGH_INDUCTION)
    chord = validation.positive("chord", chord, units="m", ndim=(1, 2))
    twist = validation.real_array("twist", twist, units="rad", ndim=(1, 2))
    if chord.shape[-1] != twist.shape[-1]:
        raise ValueError(f"chord and twist must have the same number of stations, got {chord.shape[-1]} and "
                         f"{twist.shape[-1]}")
    nr = validation.integer("number of stations", chord.shape[-1], minimum=2)
    if fluid is not None:
        fluid = resolve_fluid(fluid)
        if np.any(np.asarray(altitude, dtype=float) != 0.0):
            raise ValueError("give either altitude [m] (the ISA) or fluid, not both")
    values = _scalars(radius, hub_radius, tip_speed_ratio, rated_power, max_tip_speed, weibull_scale, weibull_shape,
                      cut_in_speed, cut_out_speed, altitude)
    lengths = {name: arr.size for name, arr in values.items() if arr.ndim == 1}
    lengths.update({name: arr.shape[0] for name, arr in (("chord", chord), ("twist", twist)) if arr.ndim == 2})
    is_batch = bool(lengths)
    nn = validation.batch_size(lengths)
    values = {name: np.broadcast_to(arr, (nn,)).astype(float) for name, arr in values.items()}
    polar = resolve_airfoil(airfoil)
    if fluid is None:
        state = isa(values["altitude"], derivatives=False)
        fluid_values = {"rho": state.rho, "mu": state.mu, "speed_of_sound": state.speed_of_sound}
    else:
        fluid_values = {name: np.full(nn, value) for name, value in fluid_point(fluid).items()}
    limited = "max_tip_speed" in values
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("curve", PowerCurveGroup(num_nodes=nn, num_radial=nr, num_wind_speeds=num_wind_speeds,
                                                      num_blades=num_blades, polar=polar, loss_model=loss_model,
                                                      on_invalid="warn", use_atmosphere=False,
                                                      tip_speed_limit=limited, high_induction=high_induction),
                             promotes=["*"])
    prob.setup()
    prob.set_val("chord", np.broadcast_to(chord, (nn, nr)), units="m")
    prob.set_val("twist", np.broadcast_to(twist, (nn, nr)), units="rad")
    for name, value in {**values, **fluid_values}.items():
        if name != "altitude":
            prob.set_val(name, value)
    prob.run_model()
    result = {name: np.array(prob.get_val(name, units=units)) for name, units in {**CURVE_VALUES,
                                                                                 **ROTOR_VALUES}.items()}
    result[_KNEE] = np.array(prob.get_val(_KNEE if limited else "rated_wind_speed", units="m/s"))
    for name in ("rated_power", "tip_speed_ratio", "weibull_scale", "weibull_shape", "cut_in_speed",
                 "cut_out_speed"):
        result[name] = values[name]
    result["max_tip_speed"] = values["max_tip_speed"] if limited else np.full(nn, np.inf)
    return PowerCurve(result, is_batch)
