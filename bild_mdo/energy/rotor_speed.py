"""RotorSpeedComp: the rotor speed of a variable-speed turbine along its power curve, from the design tip-speed ratio.

Below rated the rotor tracks its design tip-speed ratio ``lambda`` (region 2); from the rated
wind speed on it holds the rated rotor speed (region 3)::

    Omega(V) = lambda min(V, V_r) / R        (rad/s; output in rpm)

With option ``capped=False`` the rotor speed is ``lambda V / R`` at every input wind speed (no
input ``rated_wind_speed``): the rated-speed solve evaluates the rotor there.  With option
``tip_speed_limit`` the rotor speed is also held where its tip reaches ``max_tip_speed``
(region 2.5, as WISDEM's ``control_maxTS``)::

    Omega(V) = min(lambda min(V, V_r), V_tip,max) / R

The ``min`` has kinks at ``V = V_r`` and at ``lambda V = V_tip,max``; the partials are those of
the branch the real parts select, the first one (``V`` below ``V_r``, ``lambda V`` below the limit)
where two are equal.  The wind-speed nodes of :mod:`bild_mdo.energy.wind_speeds` sit on a kink only
at the ends of their intervals (the rated point; the start of region 2.5, and where the limit is
not reached below rated the points that repeat the rated point), where both branches give the
same value and, at the start of region 2.5, the same total derivative.
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.energy.wind_speeds import declare_tip_speed_limit_option


class RotorSpeedComp(om.ExplicitComponent):
    """Rotor speed at the design tip-speed ratio, held at its rated value above rated (module docstring).

    Options
    -------
    num_nodes : int
        Rotors (axis 0).
    num_points : int or None
        Wind speeds per rotor (axis 1); None (default): one, and the arrays have shape ``(nn,)``.
    capped : bool
        True (default): hold the rotor speed above ``rated_wind_speed``.
    tip_speed_limit : bool
        False (default); True: hold the rotor speed where the tip speed reaches ``max_tip_speed``.

    Inputs
    ------
    wind_speed[nn, np] or [nn] (m/s), tip_speed_ratio[nn] (-), radius[nn] (m), rated_wind_speed[nn] (m/s) (``capped``),
    max_tip_speed[nn] (m/s) (``tip_speed_limit``)

    Outputs
    -------
    rpm[nn, np] or [nn] (rpm)
    """

    def initialize(self):
        self.options.declare("num_nodes", types=int, default=1, lower=1, desc="rotors (axis 0)")
        self.options.declare("num_points", types=int, default=None, allow_none=True, lower=1,
                             desc="wind speeds per rotor (axis 1); None: one, shape (nn,)")
        self.options.declare("capped", types=bool, default=True, desc="hold the rated rotor speed above rated")
        declare_tip_speed_limit_option(self.options)

    def setup(self):
        nn, npt = self.options["num_nodes"], self.options["num_points"]
        shape = (nn,) if npt is None else (nn, npt)
        self.add_input("wind_speed", val=np.full(shape, 8.0), units="m/s", desc="wind speed at hub height")
        self.add_input("tip_speed_ratio", val=np.full(nn, 7.0), units=None, desc="design tip-speed ratio")
        self.add_input("radius", val=np.full(nn, 40.0), units="m", desc="rotor tip radius R")
        if self.options["capped"]:
            self.add_input("rated_wind_speed", val=np.full(nn, 11.0), units="m/s", desc="rated wind speed V_r")
        if self.options["tip_speed_limit"]:
            self.add_input("max_tip_speed", val=np.full(nn, 80.0), units="m/s", desc="largest tip speed Omega R")
        self.add_output("rpm", val=np.full(shape, 10.0), units="rpm", desc="rotor speed")

    def setup_partials(self):
        nn, npt = self.options["num_nodes"], self.options["num_points"] or 1
        rows, cols = np.arange(nn * npt), np.repeat(np.arange(nn), npt)
        self.declare_partials("rpm", "wind_speed", rows=rows, cols=rows)
        names = ["tip_speed_ratio", "radius"] + (["rated_wind_speed"] if self.options["capped"] else [])
        names += ["max_tip_speed"] if self.options["tip_speed_limit"] else []
        self.declare_partials("rpm", names, rows=rows, cols=cols)

    def _speed(self, inputs):
        """The governing wind speed ``min(V, V_r)``, whether ``V`` is below ``V_r``, the tip speed
        ``min(lambda min(V, V_r), V_tip,max)`` and whether it is below the limit (real parts)."""
        v = inputs["wind_speed"].reshape(self.options["num_nodes"], -1)
        tsr = inputs["tip_speed_ratio"][:, None]
        if self.options["capped"]:
            v_r = np.broadcast_to(inputs["rated_wind_speed"][:, None], v.shape)
            below = np.real(v) <= np.real(v_r)
            speed = np.where(below, v, v_r)
        else:
            speed, below = v, np.ones(v.shape, dtype=bool)
        tip = tsr * speed
        free = np.ones(v.shape, dtype=bool)
        if self.options["tip_speed_limit"]:
            limit = np.broadcast_to(inputs["max_tip_speed"][:, None], v.shape)
            free = np.real(tip) <= np.real(limit)
            tip = np.where(free, tip, limit)
        return speed, below, tip, free

    def compute(self, inputs, outputs):
        _, _, tip, _ = self._speed(inputs)
        outputs["rpm"] = (tip / inputs["radius"][:, None] / RPM_TO_RAD_PER_S).reshape(outputs["rpm"].shape)

    def compute_partials(self, inputs, partials):
        speed, below, tip, free = self._speed(inputs)
        tsr, radius = inputs["tip_speed_ratio"][:, None], inputs["radius"][:, None]
        scale = 1.0 / (radius * RPM_TO_RAD_PER_S)
        d_speed = np.where(free, tsr * scale, 0.0)
        partials["rpm", "wind_speed"] = np.where(below, d_speed, 0.0).ravel()
        partials["rpm", "tip_speed_ratio"] = np.where(free, speed * scale, 0.0).ravel()
        partials["rpm", "radius"] = (-tip * scale / radius).ravel()
        if self.options["capped"]:
            partials["rpm", "rated_wind_speed"] = np.where(below, 0.0, d_speed).ravel()
        if self.options["tip_speed_limit"]:
            partials["rpm", "max_tip_speed"] = np.where(free, 0.0, scale * np.ones(tip.shape)).ravel()
