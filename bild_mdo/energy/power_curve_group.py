"""PowerCurveGroup: the BEM power curve of a variable-speed, pitch-regulated rotor and its annual energy.

The turbine counterpart of WISDEM's ``RotorSE`` power curve (``ComputePowerCurve``), as exact-derivative
OpenMDAO components.  For each of ``num_nodes`` rotors (a blade ``chord[nn, nr]``, ``twist[nn, nr]``)::

    [atmosphere]  AtmosphereComp            altitude -> rho, mu, speed_of_sound  (use_atmosphere)
    rated         RatedSpeedGroup           V_r: BEM power at lambda, pitch 0 = P_r     (Newton, implicit)
    wind          WindSpeedsComp            Gauss-Lobatto nodes on [V_in, V_r] ([V_in, V_k], [V_k, V_r]), [V_r, V_out]
    speed         RotorSpeedComp            Omega = lambda min(V, V_r) / R  (at most V_tip,max / R)
    region2_blade RotorBroadcastComp        the blade and the fluid at every wind speed (and region3_blade)
    region2       InclinedBEMGroup          turbine BEM at the region-2 nodes, pitch 0
    region3       PitchTrimGroup            turbine BEM at the region-3 nodes, pitch solved: power = P_r (Newton)
    curve         CurveAssemblyComp         power, thrust, ... and pitch per wind speed
    energy        CurveEnergyComp           AEP and capacity factor over the Weibull wind

Region 2 (cut-in to rated): the rotor tracks its design tip-speed ratio ``lambda`` at zero pitch and
the power is the BEM's at every wind speed, so the Reynolds numbers of the sections (and a
Mach-dependent polar) change ``C_P`` along the curve.  The rated wind speed is where that power
reaches ``rated_power`` (:class:`~bild_mdo.energy.rated_speed.RatedSpeedGroup`).  Region 3 (rated to
cut-out): the rotor holds its rated speed and the collective pitch, solved per wind speed, holds
the rated power, pitching to feather (positive pitch lowers the angle of attack;
:mod:`bild_mdo.energy.pitch_trim`).  With option ``tip_speed_limit`` the rotor speed is also held
where the tip speed reaches input ``max_tip_speed`` (region 2.5, WISDEM's ``control_maxTS``):
from ``V_k = max_tip_speed / lambda`` to rated the rotor turns at ``max_tip_speed / R`` at zero
pitch, its tip-speed ratio falls below the design one, and rated power is reached where that
rotor's power reaches it; region 2 is then integrated on ``[V_in, V_k]`` and ``[V_k, V_r]``
(:mod:`bild_mdo.energy.wind_speeds`; output ``tip_speed_limit_wind_speed``).  No drivetrain
losses or availability are modelled (``rated_power`` is the aerodynamic power); the year is 8760 h.

Difference from :class:`~bild_mdo.energy.annual_energy.AnnualEnergyComp`: that component takes one
``C_P`` for all of region 2 and assumes rated power above rated without computing a pitch; this
group analyses the blade itself at every wind speed.  With a polar that depends on neither the
Reynolds nor the Mach number, ``C_P`` at a fixed tip-speed ratio is constant and the two agree to
quadrature and solver tolerance (``tests/energy/test_power_curve_group.py``).

Options
-------
num_nodes, num_radial : int
    Rotors (axis 0) and blade stations.
num_wind_speeds : int
    Points of the curve from cut-in to cut-out (default 13; :mod:`bild_mdo.energy.wind_speeds`).
num_blades, polar, loss_model, on_invalid
    As for :class:`~bild_mdo.bem.inclined_bem_group.InclinedBEMGroup` (``polar``: the airfoil's own
    polar; None is the built-in NACA 4412).
high_induction : {'buhl', 'none'}
    The thrust of an annulus past ``a = 0.4``: Buhl's (default, as CCBlade) or momentum theory's
    (:mod:`bild_mdo.bem.inflow_residual`).  Buhl's thrust is continuously differentiable at ``a = 0.4``,
    not twice, so where an annulus crosses it between nodes (region 2.5, where the tip-speed ratio
    falls) the Lobatto rule's error is of lower order (up to 3.5e-7 of the AEP at 21 points on the test
    rotors).
use_atmosphere : bool
    True (default): input ``altitude``; False: inputs ``rho``, ``mu``, ``speed_of_sound``.
pitch_bounds : tuple of float
    (lower, upper) of the region-3 pitch (rad), default :data:`~bild_mdo.energy.pitch_trim.PITCH_BOUNDS`.
tip_speed_limit : bool
    False (default); True: input ``max_tip_speed`` (region 2.5).

Inputs
------
chord[nn, nr] (m), twist[nn, nr] (rad), radius[nn] (m), hub_radius[nn] (m)
    The blade (stations at the midpoints of equal annuli, as :class:`~bild_mdo.bem.stations.StationsComp`).
tip_speed_ratio[nn] (-), rated_power[nn] (W), cut_in_speed[nn] (m/s), cut_out_speed[nn] (m/s)
    Design tip-speed ratio (region 2), rated power, cut-in and cut-out wind speeds.
weibull_scale[nn] (m/s), weibull_shape[nn] (-)
    Weibull ``c`` and ``k`` (``k = 2``: Rayleigh).
altitude[nn] (m), or rho[nn] (kg/m**3), mu[nn] (Pa*s), speed_of_sound[nn] (m/s)
    ISA altitude (``use_atmosphere``) or the fluid.
max_tip_speed[nn] (m/s)
    Largest tip speed ``Omega R`` (``tip_speed_limit``; default 80 m/s).

Outputs
-------
rated_wind_speed[nn] (m/s)
    Where the BEM power at the design tip-speed ratio (the tip-speed limit's rotor speed beyond ``V_k``) and
    zero pitch reaches rated power.
wind_speed[nn, nw] (m/s), rpm[nn, nw] (rpm), collective_pitch[nn, nw] (rad), power[nn, nw] (W), thrust[nn, nw] (N)
    The power curve, also ``torque[nn, nw] (N*m)``, ``power_coefficient[nn, nw]``, ``thrust_coefficient[nn, nw]``;
    index ``n2 - 1`` (:func:`~bild_mdo.energy.wind_speeds.region_sizes`, with ``tip_speed_limit``) is the rated
    point.
tip_speed_limit_wind_speed[nn] (m/s)
    Where region 2.5 begins, ``min(max_tip_speed / lambda, V_r)`` (``tip_speed_limit``; the rated wind speed
    where the limit is not reached below rated); index ``n2a - 1``
    (:func:`~bild_mdo.energy.wind_speeds.region2_split`).
annual_energy[nn] (J), capacity_factor[nn] (-)
    AEP over the Weibull wind (``get_val(..., units="GW*h")``) and ``AEP / (8760 h P_r)``.

Raises
------
openmdao.api.AnalysisError
    Where rated power is not reached between cut-in and cut-out at the design tip-speed ratio, or the
    pitch trim does not hold it (:class:`~bild_mdo.energy.curve_energy.CurveEnergyComp`).
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.builtin import resolve_polar
from bild_mdo.atmosphere import AtmosphereComp
from bild_mdo.bem.flow_states import ON_INVALID
from bild_mdo.bem.inclined_bem_group import InclinedBEMGroup
from bild_mdo.bem.inflow_residual import HIGH_INDUCTION
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.energy.curve_assembly import CURVE_OUTPUTS, CurveAssemblyComp
from bild_mdo.energy.curve_energy import CurveEnergyComp
from bild_mdo.energy.pitch_trim import PITCH_BOUNDS, PitchTrimGroup
from bild_mdo.energy.rated_speed import RatedSpeedGroup
from bild_mdo.energy.rotor_broadcast import BROADCAST_DISTRIBUTIONS, BROADCAST_SCALARS, RotorBroadcastComp
from bild_mdo.energy.rotor_speed import RotorSpeedComp
from bild_mdo.energy.wind_speeds import (
    TIP_SPEED_LIMIT_WIND_SPEED,
    WindSpeedsComp,
    declare_tip_speed_limit_option,
    declare_wind_speed_option,
    region_sizes,
)
from bild_mdo.utils.options import declare_size_options

_BLADE = ("chord", "twist", "radius", "hub_radius")
_FLUID = ("rho", "mu", "speed_of_sound")
_WIND = ("cut_in_speed", "cut_out_speed", "weibull_scale", "weibull_shape")
#: Inputs of the group besides the blade and the fluid: name -> (default, units).
_DEFAULTS = {"tip_speed_ratio": (7.0, None), "rated_power": (5.0e6, "W"), "cut_in_speed": (3.0, "m/s"),
             "cut_out_speed": (25.0, "m/s"), "weibull_scale": (8.0, "m/s"), "weibull_shape": (2.0, None),
             "radius": (63.0, "m"), "hub_radius": (3.0, "m"), "altitude": (0.0, "m"), "rho": (1.225, "kg/m**3"),
             "mu": (1.789e-5, "Pa*s"), "speed_of_sound": (340.294, "m/s"), "max_tip_speed": (80.0, "m/s")}


class PowerCurveGroup(om.Group):
    """BEM power curve with the pitch trimmed to rated power above rated, and the AEP (module docstring)."""

    def initialize(self):
        declare_size_options(self.options)
        declare_wind_speed_option(self.options)
        self.options.declare("num_blades", types=int, default=3, desc="number of blades B")
        self.options.declare("polar", default=None, allow_none=True, recordable=False,
                             desc="the airfoil's own Polar; None selects the built-in NACA 4412")
        self.options.declare("loss_model", default="tip_hub", values=LOSS_MODELS,
                             desc="Prandtl losses: 'tip_hub', 'tip' or 'none'")
        self.options.declare("on_invalid", default="warn", values=ON_INVALID,
                             desc="BEM stations in an invalid flow state: 'warn', 'raise' or 'ignore'")
        self.options.declare("high_induction", default="buhl", values=HIGH_INDUCTION,
                             desc="thrust past a = 0.4: 'buhl' (Buhl 2005, as CCBlade) or 'none' (momentum theory)")
        self.options.declare("use_atmosphere", types=bool, default=True,
                             desc="rho, mu and speed_of_sound from the ISA at input altitude (else inputs)")
        self.options.declare("pitch_bounds", default=PITCH_BOUNDS, desc="(lower, upper) of the region-3 pitch (rad)")
        declare_tip_speed_limit_option(self.options)

    def setup(self):
        opts = self.options
        nn, nr, nw = opts["num_nodes"], opts["num_radial"], opts["num_wind_speeds"]
        limited = opts["tip_speed_limit"]
        n2, n3 = region_sizes(nw, limited)
        tip = ["max_tip_speed"] if limited else []
        polar = resolve_polar("naca4412") if opts["polar"] is None else opts["polar"]
        bem = dict(num_radial=nr, num_blades=opts["num_blades"], polar=polar, loss_model=opts["loss_model"],
                   on_invalid=opts["on_invalid"], high_induction=opts["high_induction"])
        if opts["use_atmosphere"]:
            self.add_subsystem("atmosphere", AtmosphereComp(num_nodes=nn), promotes_inputs=["altitude"],
                               promotes_outputs=list(_FLUID))
        self.add_subsystem("rated", RatedSpeedGroup(num_nodes=nn, tip_speed_limit=limited, **bem),
                           promotes_inputs=list(_BLADE + _FLUID) + ["tip_speed_ratio", "rated_power"] + tip,
                           promotes_outputs=["rated_wind_speed"])
        knee = [TIP_SPEED_LIMIT_WIND_SPEED] if limited else []
        self.add_subsystem("wind", WindSpeedsComp(num_nodes=nn, num_wind_speeds=nw, tip_speed_limit=limited),
                           promotes_inputs=["cut_in_speed", "rated_wind_speed", "cut_out_speed"]
                           + (tip + ["tip_speed_ratio"] if limited else []),
                           promotes_outputs=["wind_speed"] + knee)
        self.add_subsystem("speed", RotorSpeedComp(num_nodes=nn, num_points=nw, tip_speed_limit=limited),
                           promotes_inputs=["wind_speed", "tip_speed_ratio", "radius", "rated_wind_speed"] + tip,
                           promotes_outputs=["rpm"])
        for region, size in (("region2", n2), ("region3", n3 - 1)):
            self.add_subsystem(f"{region}_blade", RotorBroadcastComp(num_nodes=nn, num_radial=nr, num_points=size),
                               promotes_inputs=list(BROADCAST_DISTRIBUTIONS + BROADCAST_SCALARS))
        self.add_subsystem("region2", InclinedBEMGroup(num_nodes=nn * n2, rotor_type="turbine",
                                                       use_atmosphere=False, **bem))
        self.add_subsystem("region3", PitchTrimGroup(num_nodes=nn * (n3 - 1), pitch_bounds=opts["pitch_bounds"],
                                                     **bem))
        self.add_subsystem("curve", CurveAssemblyComp(num_nodes=nn, num_wind_speeds=nw, tip_speed_limit=limited),
                           promotes_outputs=list(CURVE_OUTPUTS) + ["collective_pitch"])
        self.add_subsystem("energy", CurveEnergyComp(num_nodes=nn, num_wind_speeds=nw, tip_speed_limit=limited),
                           promotes_inputs=["wind_speed", "power", "rated_wind_speed", "rated_power", *_WIND, *knee],
                           promotes_outputs=["annual_energy", "capacity_factor"])

        index = np.arange(nn * nw).reshape(nn, nw)
        points = {"region2": index[:, :n2].ravel(), "region3": index[:, n2:].ravel()}
        for region, rows in points.items():
            self.connect("wind_speed", f"{region}.v_axial", src_indices=rows, flat_src_indices=True)
            self.connect("rpm", f"{region}.rpm", src_indices=rows, flat_src_indices=True)
            for name in BROADCAST_DISTRIBUTIONS + BROADCAST_SCALARS:
                self.connect(f"{region}_blade.point_{name}", f"{region}.{name}")
            for name in CURVE_OUTPUTS:
                self.connect(f"{region}.{name}", f"curve.{region}_{name}")
        self.connect("region3.collective_pitch", "curve.region3_collective_pitch")
        self.promotes("region3", inputs=["rated_power"], src_indices=np.repeat(np.arange(nn), n3 - 1),
                      flat_src_indices=True, src_shape=(nn,))

        names = list(_BLADE) + ["tip_speed_ratio", "rated_power", *_WIND, *tip]
        names += ["altitude"] if opts["use_atmosphere"] else list(_FLUID)
        for name in names:
            if name in ("chord", "twist"):
                continue
            default, units = _DEFAULTS[name]
            self.set_input_defaults(name, val=np.full(nn, default), units=units)
        self.set_input_defaults("chord", val=np.full((nn, nr), 2.0), units="m")
        self.set_input_defaults("twist", val=np.full((nn, nr), 0.1), units="rad")
