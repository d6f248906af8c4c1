"""RatedSpeedGroup: the rated wind speed of a variable-speed rotor from its BEM power at the design tip-speed ratio."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.bem.inclined_bem_group import InclinedBEMGroup
from bild_mdo.bem.metrics import TURBINE_OUTPUTS
from bild_mdo.energy.pitch_trim import BEM_INPUTS, NEWTON_ATOL, ExplainedNewton, declare_turbine_bem_options
from bild_mdo.energy.rated_wind_speed import RatedWindSpeedComp
from bild_mdo.energy.rotor_speed import RotorSpeedComp
from bild_mdo.energy.wind_speeds import declare_tip_speed_limit_option
from bild_mdo.utils.options import declare_size_options

#: Power coefficient of the first guess of the rated wind speed (any positive value converges).
GUESS_POWER_COEFFICIENT = 0.45


class RatedSpeedGroup(om.Group):
    """Rated wind speed ``V_r``: the BEM power at ``lambda``, zero pitch and wind ``V_r`` equals ``rated_power``.

    ::

        speed   RotorSpeedComp(capped=False)   rpm = lambda V_r / R  (min(lambda V_r, V_tip,max) / R: tip_speed_limit)
        bem     InclinedBEMGroup(turbine)      power at (V_r, rpm), pitch 0
        rated   RatedWindSpeedComp             V_r (P_r / P)**(1/3) = V_r

    A Newton solver with a direct linear solver converges the loop, started every time from
    ``V_r = (P_r / (1/2 rho pi R^2 C_P0))**(1/3)``, ``C_P0 =`` :data:`GUESS_POWER_COEFFICIENT`
    (the residual is nearly linear in ``V_r``, :mod:`bild_mdo.energy.rated_wind_speed`).  The other
    BEM outputs at rated (``thrust`` ... of :data:`~bild_mdo.bem.metrics.TURBINE_OUTPUTS`) are outputs too.

    With option ``tip_speed_limit`` the rotor turns at most at ``max_tip_speed / R``, so rated power may be
    reached in region 2.5.  There the power grows more slowly than ``V**3`` and can even fall as the wind
    rises (the blade leaves its design angles of attack), so rated power may be reached at more than one wind
    speed; the solve may find a later one, which the power curve's energy component refuses
    (:class:`~bild_mdo.energy.curve_energy.CurveEnergyComp`: power above rated below the rated wind speed).

    Options
    -------
    num_nodes, num_radial, num_blades, polar, loss_model, on_invalid
        Rotors and the options of :class:`~bild_mdo.bem.inclined_bem_group.InclinedBEMGroup`.
    tip_speed_limit : bool
        False (default); True: input ``max_tip_speed``.

    Inputs
    ------
    tip_speed_ratio[nn] (-), rated_power[nn] (W), chord[nn, nr] (m), twist[nn, nr] (rad), radius[nn] (m),
    hub_radius[nn] (m), rho[nn] (kg/m**3), mu[nn] (Pa*s), speed_of_sound[nn] (m/s); max_tip_speed[nn] (m/s)
    (``tip_speed_limit``)

    Outputs
    -------
    rated_wind_speed[nn] (m/s) and the turbine metrics [nn] at rated (``power`` = ``rated_power``, ``thrust`` ...;
    the tip-speed ratio is the input)
    """

    def initialize(self):
        declare_size_options(self.options)
        declare_turbine_bem_options(self.options)
        declare_tip_speed_limit_option(self.options)

    def setup(self):
        opts = self.options
        nn, nr = opts["num_nodes"], opts["num_radial"]
        limited = opts["tip_speed_limit"]
        self.add_subsystem("speed", RotorSpeedComp(num_nodes=nn, capped=False, tip_speed_limit=limited),
                           promotes_inputs=["tip_speed_ratio", "radius"] + (["max_tip_speed"] if limited else []))
        self.add_subsystem("bem", InclinedBEMGroup(num_nodes=nn, num_radial=nr, num_blades=opts["num_blades"],
                                                   polar=opts["polar"], loss_model=opts["loss_model"],
                                                   on_invalid=opts["on_invalid"], rotor_type="turbine",
                                                   high_induction=opts["high_induction"], use_atmosphere=False),
                           promotes_inputs=[name for name in BEM_INPUTS if name not in ("v_axial", "rpm")],
                           promotes_outputs=[name for name in TURBINE_OUTPUTS if name != "tip_speed_ratio"])
        self.add_subsystem("rated", RatedWindSpeedComp(num_nodes=nn), promotes_inputs=["power", "rated_power"],
                           promotes_outputs=["rated_wind_speed"])
        self.connect("rated_wind_speed", "speed.wind_speed")
        self.connect("rated_wind_speed", "bem.v_axial")
        self.connect("speed.rpm", "bem.rpm")
        hint = "The rated wind speed (BEM power at the design tip-speed ratio equal to rated power) was not found."
        self.nonlinear_solver = ExplainedNewton(hint, solve_subsystems=True, maxiter=20, atol=NEWTON_ATOL,
                                                rtol=1e-14, iprint=-1, err_on_non_converge=True)
        self.linear_solver = om.DirectSolver()

    def guess_nonlinear(self, inputs, outputs, residuals):
        if self.under_complex_step:
            # A complex step perturbs the converged real solve: starting from it, the one Newton iteration
            # OpenMDAO forces under complex step carries the exact derivative in the imaginary part (a fresh
            # guess would leave it at the accuracy of the first iterate).
            return
        rated = np.real(inputs["rated.rated_power"])
        if not np.all(np.isfinite(rated) & (rated > 0.0)):
            i = int(np.flatnonzero(~(np.isfinite(rated) & (rated > 0.0)))[0])
            raise om.AnalysisError(f"{self.msginfo}: rated_power must be positive and finite, got "
                                   f"{float(rated[i]):g} W (rotor {i})")
        area = np.pi * np.real(inputs["bem.stations.radius"]) ** 2
        gain = 0.5 * np.real(inputs["bem.inflow.rho"]) * area * GUESS_POWER_COEFFICIENT
        outputs["rated_wind_speed"] = (rated / gain) ** (1.0 / 3.0)
