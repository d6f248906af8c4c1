"""RatedWindSpeedComp: the wind speed at which the BEM power at the design tip-speed ratio reaches rated power.

At a fixed tip-speed ratio and pitch the BEM inflow angles do not depend on the wind speed, so
the power grows as ``P(V) = 1/2 rho A C_P V**3`` with a ``C_P`` that changes only through the
Reynolds (and Mach) numbers of the sections.  The residual is written in the cube root of the
power::

    R(V_r) = V_r - V_r (P_r / P(V_r))**(1/3)

which is linear in ``V_r`` when ``C_P`` is constant (``R = V_r - (P_r / K)**(1/3)``), so the
Newton solve of the enclosing group (:class:`~bild_mdo.energy.rated_speed.RatedSpeedGroup`)
converges in one or two iterations from any positive guess.  The state Jacobian is diagonal
(``dR/dV_r = 1 - (P_r/P)**(1/3)`` plus the BEM's ``dP/dV_r`` through the group); the group's
direct solver inverts the coupled system.
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.energy.pitch_trim import RESIDUAL_REF


class RatedWindSpeedComp(om.ImplicitComponent):
    """Implicit rated wind speed: ``V_r (P_r / P)**(1/3) = V_r`` (module docstring).

    Options
    -------
    num_nodes : int
        Rotors (axis 0).

    Inputs
    ------
    power[nn] (W)
        BEM power at the design tip-speed ratio, zero pitch and wind speed ``rated_wind_speed``.
    rated_power[nn] (W)

    Outputs
    -------
    rated_wind_speed[nn] (m/s)
        Implicit state.

    Raises
    ------
    openmdao.api.AnalysisError
        Where the power is not positive (the rotor extracts no energy at its design tip-speed ratio).
    """

    def initialize(self):
        self.options.declare("num_nodes", types=int, default=1, lower=1, desc="rotors (axis 0)")

    def setup(self):
        nn = self.options["num_nodes"]
        self.add_input("power", val=np.full(nn, 5.0e6), units="W", desc="BEM power at the rated wind speed")
        self.add_input("rated_power", val=np.full(nn, 5.0e6), units="W", desc="rated (generator) power P_r")
        self.add_output("rated_wind_speed", val=np.full(nn, 11.0), units="m/s", lower=1e-3, res_ref=RESIDUAL_REF,
                        desc="wind speed where the power at the design tip-speed ratio reaches rated power")
        rows = np.arange(nn)
        self.declare_partials("rated_wind_speed", ["rated_wind_speed", "power", "rated_power"], rows=rows, cols=rows)

    def _ratio(self, inputs):
        power, p_rated = inputs["power"], inputs["rated_power"]
        bad = ~(np.real(power) > 0.0) | ~(np.real(p_rated) > 0.0)
        if np.any(bad):
            i = int(np.flatnonzero(bad)[0])
            raise om.AnalysisError(
                f"{self.msginfo}: rotor {i} extracts no power at its design tip-speed ratio, or at its tip-speed "
                f"limit where it has one (BEM power {np.real(power[i]):.6g} W, rated power "
                f"{np.real(p_rated[i]):.6g} W); the rated wind speed is undefined")
        return (p_rated / power) ** (1.0 / 3.0)

    def apply_nonlinear(self, inputs, outputs, residuals):
        v = outputs["rated_wind_speed"]
        residuals["rated_wind_speed"] = v - v * self._ratio(inputs)

    def linearize(self, inputs, outputs, jacobian):
        v, s = outputs["rated_wind_speed"], self._ratio(inputs)
        jacobian["rated_wind_speed", "rated_wind_speed"] = 1.0 - s
        jacobian["rated_wind_speed", "power"] = v * s / (3.0 * inputs["power"])
        jacobian["rated_wind_speed", "rated_power"] = -v * s / (3.0 * inputs["rated_power"])
