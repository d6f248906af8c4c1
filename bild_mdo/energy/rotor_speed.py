"""RotorSpeedComp: the rotor speed of a variable-speed turbine along its power curve, from the design tip-speed ratio.

Below rated the rotor tracks its design tip-speed ratio ``lambda`` (region 2); from the rated
wind speed on it holds the rated rotor speed (region 3)::

    Omega(V) = lambda min(V, V_r) / R        (rad/s; output in rpm)

With option ``capped=False`` the rotor speed is ``lambda V / R`` at every input wind speed (no
input ``rated_wind_speed``): the rated-speed solve evaluates the rotor there.  The ``min`` has a
kink at ``V = V_r``; its partials are those of the branch the real parts select (the wind-speed
nodes of :mod:`bild_mdo.energy.wind_speeds` sit at ``V_r`` exactly only at the rated point,
which is evaluated at the design tip-speed ratio, the ``V < V_r`` branch by convention).
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.constants import RPM_TO_RAD_PER_S


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

    Inputs
    ------
    wind_speed[nn, np] or [nn] (m/s), tip_speed_ratio[nn] (-), radius[nn] (m), rated_wind_speed[nn] (m/s) (``capped``)

    Outputs
    -------
    rpm[nn, np] or [nn] (rpm)
    """

    def initialize(self):
        self.options.declare("num_nodes", types=int, default=1, lower=1, desc="rotors (axis 0)")
        self.options.declare("num_points", types=int, default=None, allow_none=True, lower=1,
                             desc="wind speeds per rotor (axis 1); None: one, shape (nn,)")
        self.options.declare("capped", types=bool, default=True, desc="hold the rated rotor speed above rated")

    def setup(self):
        nn, npt = self.options["num_nodes"], self.options["num_points"]
        shape = (nn,) if npt is None else (nn, npt)
        self.add_input("wind_speed", val=np.full(shape, 8.0), units="m/s", desc="wind speed at hub height")
        self.add_input("tip_speed_ratio", val=np.full(nn, 7.0), units=None, desc="design tip-speed ratio")
        self.add_input("radius", val=np.full(nn, 40.0), units="m", desc="rotor tip radius R")
        if self.options["capped"]:
            self.add_input("rated_wind_speed", val=np.full(nn, 11.0), units="m/s", desc="rated wind speed V_r")
        self.add_output("rpm", val=np.full(shape, 10.0), units="rpm", desc="rotor speed")

    def setup_partials(self):
        nn, npt = self.options["num_nodes"], self.options["num_points"] or 1
        rows, cols = np.arange(nn * npt), np.repeat(np.arange(nn), npt)
        self.declare_partials("rpm", "wind_speed", rows=rows, cols=rows)
        names = ["tip_speed_ratio", "radius"] + (["rated_wind_speed"] if self.options["capped"] else [])
        self.declare_partials("rpm", names, rows=rows, cols=cols)

    def _speed(self, inputs):
        """The governing wind speed ``min(V, V_r)`` and whether ``V`` is below ``V_r`` (real parts)."""
        v = inputs["wind_speed"].reshape(self.options["num_nodes"], -1)
        if not self.options["capped"]:
            return v, np.ones(v.shape, dtype=bool)
        v_r = np.broadcast_to(inputs["rated_wind_speed"][:, None], v.shape)
        below = np.real(v) <= np.real(v_r)
        return np.where(below, v, v_r), below

    def compute(self, inputs, outputs):
        speed, _ = self._speed(inputs)
        tsr, radius = inputs["tip_speed_ratio"][:, None], inputs["radius"][:, None]
        outputs["rpm"] = (tsr * speed / radius / RPM_TO_RAD_PER_S).reshape(outputs["rpm"].shape)

    def compute_partials(self, inputs, partials):
        speed, below = self._speed(inputs)
        tsr, radius = inputs["tip_speed_ratio"][:, None], inputs["radius"][:, None]
        rpm = tsr * speed / radius / RPM_TO_RAD_PER_S
        d_speed = tsr / radius / RPM_TO_RAD_PER_S * np.ones(speed.shape)
        partials["rpm", "wind_speed"] = np.where(below, d_speed, 0.0).ravel()
        partials["rpm", "tip_speed_ratio"] = (speed / radius / RPM_TO_RAD_PER_S).ravel()
        partials["rpm", "radius"] = (-rpm / radius).ravel()
        if self.options["capped"]:
            partials["rpm", "rated_wind_speed"] = np.where(below, 0.0, d_speed).ravel()
