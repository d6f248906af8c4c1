"""PitchTrimGroup: the collective pitch that holds rated power above the rated wind speed, and its first guess.

Above rated the rotor turns at its rated speed and the blades pitch to feather (``theta = twist
+ pitch`` grows, so the angle of attack ``alpha = phi - theta`` falls; the usual direction of
pitch-regulated turbines, e.g. the NREL 5-MW reference rotor's 0 to 23 deg over 11.4 to 25 m/s,
Jonkman et al. 2009, NREL/TP-500-38060, Table 7-1).  The power is not monotonic in the pitch:
at a high wind speed the unpitched blade is stalled and pitching first raises the power, so a
Newton solve started at zero pitch would climb toward the stall side.  Each solve therefore
starts from a momentum-theory estimate (:func:`pitch_guess`) on the feather side.
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.bem.analyze import station_radii
from bild_mdo.bem.flow_states import ON_INVALID
from bild_mdo.bem.inclined_bem_group import InclinedBEMGroup
from bild_mdo.bem.inflow_residual import HIGH_INDUCTION
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bem.metrics import TURBINE_OUTPUTS
from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.utils.options import declare_size_options

#: Default (lower, upper) bounds of the trimmed pitch (rad): from zero to 60 deg toward feather.
PITCH_BOUNDS = (0.0, np.radians(60.0))
#: Radius of the section the guess is taken at, over the tip radius (the customary 0.75 R).
GUESS_RADIUS_RATIO = 0.75
#: Inputs of the BEM that the group promotes (the operating points and the blade).
BEM_INPUTS = ("v_axial", "rpm", "chord", "twist", "radius", "hub_radius", "rho", "mu", "speed_of_sound")
_ALPHA_LOW = np.radians(-20.0)
#: Residual reference of the trim states and the Newton atol: the norm the solvers test also holds the explicit
#: outputs (Reynolds numbers ~1e7, power ~1e6 W), whose round-off under complex step reaches ~1e-8; scaled by
#: ``res_ref`` the state's own residual dominates, and the solve stops with it below ``atol * res_ref = 1e-10``
#: (relative power for the pitch, m/s for the rated wind speed).
RESIDUAL_REF = 1e-6
NEWTON_ATOL = 1e-4


def _axial_induction(cp):
    """The smaller root ``a`` of the actuator disk's ``C_P = 4 a (1 - a)**2`` (``C_P`` clipped to ``[0, 16/27]``)."""
    cp = np.clip(cp, 0.0, 16.0 / 27.0)
    low, high = np.zeros_like(cp), np.full_like(cp, 1.0 / 3.0)
    for _ in range(50):
        mid = 0.5 * (low + high)
        above = 4.0 * mid * (1.0 - mid) ** 2 > cp
        low, high = np.where(above, low, mid), np.where(above, mid, high)
    return 0.5 * (low + high)


def pitch_guess(chord, twist, radius, hub_radius, v_axial, rpm, rho, mu, power, polar, num_blades):
    """Momentum-theory estimate of the collective pitch (rad) at which the rotor extracts ``power``.

    The actuator disk gives the axial induction of the required ``C_P = P / (1/2 rho pi R^2 V^3)``
    (smaller root of ``4 a (1 - a)^2``); at ``r = 0.75 R`` the inflow angle is ``tan(phi) =
    (1 - a) V / (Omega r)`` and blade-element momentum (no losses, drag neglected) asks for the lift
    coefficient ``C_l = 4 a sin(phi)^2 / ((1 - a) sigma' cos(phi))``, ``sigma' = B c / (2 pi r)``.
    The angle of attack is that ``C_l`` on the polar's attached branch (from -20 deg up to the
    maximum-L/D angle, where the lift rises with the angle), and ``pitch = phi - alpha - twist``.

    Parameters
    ----------
    chord, twist : ndarray, shape (K, nr)
        Blade at its stations (midpoints of equal annuli from hub to tip).
    radius, hub_radius, v_axial, rpm, rho, mu, power : ndarray, shape (K,)
        Tip and hub radius (m), wind speed (m/s), rotor speed (rpm), density (kg/m^3), viscosity
        (Pa s) and the required power (W).
    polar : Polar
        The airfoil's own polar (turbine convention).
    num_blades : int

    Returns
    -------
    ndarray, shape (K,)
    """
    stations = station_radii(radius, hub_radius, chord.shape[1])
    r = GUESS_RADIUS_RATIO * radius
    weights = np.clip(1.0 - np.abs(stations - r[:, None]) * chord.shape[1] / (radius - hub_radius)[:, None], 0, 1)
    weights /= np.sum(weights, axis=1, keepdims=True)
    c_r, twist_r = np.sum(weights * chord, axis=1), np.sum(weights * twist, axis=1)
    a = _axial_induction(power / (0.5 * rho * np.pi * radius ** 2 * v_axial ** 3))
    axial, tangential = (1.0 - a) * v_axial, rpm * RPM_TO_RAD_PER_S * r
    phi = np.arctan2(axial, tangential)
    solidity = num_blades * c_r / (2.0 * np.pi * r)
    cl_needed = 4.0 * a * np.sin(phi) ** 2 / ((1.0 - a) * solidity * np.cos(phi))
    reynolds = rho * np.hypot(axial, tangential) * c_r / mu
    extra = {"radial_fraction": np.full_like(reynolds, GUESS_RADIUS_RATIO)} if polar.varies_along_span else {}
    alpha_top = np.real(polar.max_lift_to_drag(reynolds, **extra).alpha)
    grid = np.linspace(0.0, 1.0, 41)[None, :]
    alphas = _ALPHA_LOW + (alpha_top[:, None] - _ALPHA_LOW) * grid
    extra = {name: value[:, None] * np.ones_like(grid) for name, value in extra.items()}
    cl = np.real(polar.evaluate(alphas, reynolds[:, None] * np.ones_like(grid), **extra).cl)
    # The first grid angle whose lift reaches the need, interpolated linearly from the one before it.
    reached = np.argmax(cl >= cl_needed[:, None], axis=1)
    reached = np.where(np.any(cl >= cl_needed[:, None], axis=1), reached, grid.size - 1)
    hi = np.maximum(reached, 1)
    rows = np.arange(cl.shape[0])
    cl0, cl1, a0, a1 = cl[rows, hi - 1], cl[rows, hi], alphas[rows, hi - 1], alphas[rows, hi]
    frac = np.clip((cl_needed - cl0) / np.where(cl1 != cl0, cl1 - cl0, 1.0), 0.0, 1.0)
    alpha = a0 + frac * (a1 - a0)
    return phi - alpha - twist_r


class ExplainedNewton(om.NewtonSolver):
    """A NewtonSolver whose convergence failure (an ``om.AnalysisError``) says what failed to the user.

    Parameters
    ----------
    hint : str
        Appended to OpenMDAO's failure message.
    **kwargs
        Options of :class:`openmdao.api.NewtonSolver`.
    """

    def __init__(self, hint, **kwargs):
        super().__init__(**kwargs)
        self.hint = hint

    def report_failure(self, msg):
        """Raise (``err_on_non_converge``) or warn with the hint appended."""
        super().report_failure(f"{msg} {self.hint}")


def declare_turbine_bem_options(options):
    """The options of a turbine BEM inside the power curve: ``num_blades``, ``polar`` (the airfoil's own),
    ``loss_model``, ``on_invalid``, ``high_induction`` (Buhl's correction by default, as CCBlade)."""
    options.declare("num_blades", types=int, default=3, desc="number of blades B")
    options.declare("polar", recordable=False, desc="the airfoil's own Polar (turbine convention)")
    options.declare("loss_model", default="tip_hub", values=LOSS_MODELS, desc="Prandtl losses")
    options.declare("on_invalid", default="warn", values=ON_INVALID, desc="BEM stations in an invalid flow state")
    options.declare("high_induction", default="buhl", values=HIGH_INDUCTION,
                    desc="thrust past a = 0.4: 'buhl' (Buhl 2005, as CCBlade) or 'none' (momentum theory, flagged)")


class PitchTrimGroup(om.Group):
    """Turbine BEM at K operating points with the collective pitch solved so that the power equals ``rated_power``.

    An ``om.BalanceComp`` makes ``collective_pitch[K]`` an output with the residual
    ``(power - rated_power) / |rated_power|``; a Newton solver (kept inside ``pitch_bounds`` by a
    ``BoundsEnforceLS`` line search; a direct linear solver) converges it, started every time from
    :func:`pitch_guess` (no dependence on the previous iterate); the totals are exact (implicit
    function theorem).  Where it does not converge (no pitch within the bounds gives rated power)
    it raises ``om.AnalysisError`` saying so (:class:`ExplainedNewton`); the power curve's energy
    component checks the result again (:class:`~bild_mdo.energy.curve_energy.CurveEnergyComp`).

    Options
    -------
    num_nodes, num_radial, num_blades, polar, loss_model, on_invalid
        Operating points K, stations and the options of
        :class:`~bild_mdo.bem.inclined_bem_group.InclinedBEMGroup` (``polar`` the airfoil's own polar).
    pitch_bounds : tuple of float
        (lower, upper) of the pitch (rad), default :data:`PITCH_BOUNDS`.

    Inputs
    ------
    v_axial[K] (m/s), rpm[K] (rpm), chord[K, nr] (m), twist[K, nr] (rad), radius[K] (m), hub_radius[K] (m),
    rho[K] (kg/m**3), mu[K] (Pa*s), speed_of_sound[K] (m/s), rated_power[K] (W)

    Outputs
    -------
    collective_pitch[K] (rad), and the turbine metrics of :data:`~bild_mdo.bem.metrics.TURBINE_OUTPUTS` [K]
    """

    def initialize(self):
        declare_size_options(self.options)
        declare_turbine_bem_options(self.options)
        self.options.declare("pitch_bounds", default=PITCH_BOUNDS, desc="(lower, upper) of the pitch (rad)")

    def setup(self):
        opts = self.options
        nn, nr = opts["num_nodes"], opts["num_radial"]
        lower, upper = opts["pitch_bounds"]
        self.add_subsystem("bem", InclinedBEMGroup(num_nodes=nn, num_radial=nr, num_blades=opts["num_blades"],
                                                   polar=opts["polar"], loss_model=opts["loss_model"],
                                                   on_invalid=opts["on_invalid"], rotor_type="turbine",
                                                   high_induction=opts["high_induction"], use_atmosphere=False),
                           promotes_inputs=list(BEM_INPUTS) + ["collective_pitch"],
                           promotes_outputs=list(TURBINE_OUTPUTS))
        balance = self.add_subsystem("trim", om.BalanceComp(), promotes_inputs=["power", "rated_power"],
                                     promotes_outputs=["collective_pitch"])
        balance.add_balance("collective_pitch", shape=(nn,), val=np.zeros(nn), units="rad", eq_units="W",
                            lhs_name="power", rhs_name="rated_power", rhs_val=np.full(nn, 5.0e6),
                            lower=lower, upper=upper, normalize=True, res_ref=RESIDUAL_REF,
                            desc="collective pitch (to feather > 0) holding the rated power")
        hint = (f"The collective pitch that holds rated power above the rated wind speed was not found within "
                f"pitch_bounds ({np.degrees(lower):.4g}, {np.degrees(upper):.4g}) deg: the rotor cannot shed the "
                "power by feathering there, or the solve diverged.")
        newton = ExplainedNewton(hint, solve_subsystems=True, maxiter=30, atol=NEWTON_ATOL, rtol=1e-14, iprint=-1,
                                 err_on_non_converge=True)
        newton.linesearch = om.BoundsEnforceLS()
        self.nonlinear_solver = newton
        self.linear_solver = om.DirectSolver()

    def guess_nonlinear(self, inputs, outputs, residuals):
        if self.under_complex_step:
            # A complex step perturbs the converged real solve: starting from it, the one Newton iteration
            # OpenMDAO forces under complex step carries the exact derivative in the imaginary part (a fresh
            # guess would leave it at the accuracy of the first iterate).
            return
        def value(name):
            return np.real(inputs[name])
        guess = pitch_guess(value("bem.sectors.chord"), value("bem.sectors.twist"), value("bem.stations.radius"),
                            value("bem.stations.hub_radius"), value("bem.wind.v_axial"), value("bem.wind.rpm"),
                            value("bem.inflow.rho"), value("bem.inflow.mu"), value("trim.rated_power"),
                            self.options["polar"], self.options["num_blades"])
        outputs["collective_pitch"] = np.clip(guess, *self.options["pitch_bounds"])
