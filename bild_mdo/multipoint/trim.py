"""The analysis group of MultipointRotorGroup and the first guess of its trim solve.

Thrust is not monotonic in collective pitch: past stall it falls again, and at
a large advance ratio a small pitch gives negative thrust (windmill), so a
Newton solve started far from the operating pitch can end on the stalled root
or at a bound.  Each solve therefore starts from a momentum-theory estimate
(:func:`trim_guess`): the pitch (or rotor speed) that puts the section at
0.75 R at the airfoil's maximum-L/D angle of attack, with the inflow angle of
an actuator disk carrying the required thrust.  Starting every solve from the
same estimate also makes the trimmed result independent of the previous
iterate (no path dependence for an optimiser).
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.bem.bem_group import BEMAnalysisGroup
from bild_mdo.bem.metrics import PERFORMANCE_OUTPUTS
from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.multipoint.blade_broadcast import BladeBroadcastComp
from bild_mdo.utils.options import declare_size_options

#: What the analyses may trim to ``thrust_target``: nothing, the collective pitch or the rotor speed.
TRIM_VARIABLES = (None, "collective_pitch", "rpm")
#: Default bounds (lower, upper) and first guess of each trim variable, in its units (rad, rpm).
TRIM_DEFAULTS = {"collective_pitch": ((-0.5, 1.2), 0.0, "rad"), "rpm": ((100.0, 30000.0), 1000.0, "rpm")}
#: Radius of the section the first guess is taken at, over the tip radius (the customary 0.75 R).
GUESS_RADIUS_RATIO = 0.75
# Sea-level air for the Reynolds number of the guess only (the solve itself uses the ISA at each altitude).
_RHO, _MU = 1.225, 1.789e-5


def trim_guess(trim, blade_twist, blade_chord, radius, hub_radius, v_axial, rpm, collective_pitch, thrust_target,
               polar, rho=_RHO):
    """Momentum-theory estimate of the collective pitch (rad) or rotor speed (rpm) giving ``thrust_target``.

    Actuator disk: induced velocity ``v_i = -V/2 + sqrt((V/2)^2 + T/(2 rho A))``; at ``r = 0.75 R`` the
    inflow angle is ``phi = atan((V + v_i) / (Omega r))`` and the section should work at the polar's
    maximum-L/D angle ``alpha*``: ``twist + pitch - phi = alpha*``.

    Parameters
    ----------
    trim : {'collective_pitch', 'rpm'}
    blade_twist, blade_chord : ndarray, shape (1, nr)
        The blade at its (equal-annuli midpoint) stations.
    radius, hub_radius : float
        Tip and hub radius (m).
    v_axial, rpm, collective_pitch, thrust_target : ndarray, shape (K,)
        Conditions (the entry of the trimmed quantity is only used where the estimate fails).
    polar : Polar
    rho : float
        Air density of the estimate (kg/m^3).

    Returns
    -------
    ndarray, shape (K,)
        Estimate of the trimmed quantity; where none exists (``rpm`` trim with the section pitched below
        ``alpha*``) the current value.
    """
    nr = blade_twist.shape[-1]
    fractions = (np.arange(nr) + 0.5) / nr
    station = hub_radius + fractions * (radius - hub_radius)
    r = GUESS_RADIUS_RATIO * radius
    twist = np.interp(r, station, blade_twist.ravel())
    chord = np.interp(r, station, blade_chord.ravel())
    area = np.pi * radius**2
    half = 0.5 * v_axial
    axial = half + np.sqrt(half**2 + np.maximum(thrust_target, 0.0) / (2.0 * rho * area))
    omega = rpm * RPM_TO_RAD_PER_S
    reynolds = rho * np.hypot(axial, omega * r) * chord / _MU
    extra = {"radial_fraction": np.full_like(reynolds, GUESS_RADIUS_RATIO)} if polar.varies_along_span else {}
    alpha = np.real(polar.max_lift_to_drag(reynolds, **extra).alpha)
    if trim == "collective_pitch":
        return alpha + np.arctan2(axial, omega * r) - twist
    angle = twist + collective_pitch - alpha
    ok = angle > 0.02
    omega_guess = axial / (np.tan(np.where(ok, angle, 1.0)) * r)
    return np.where(ok, omega_guess / RPM_TO_RAD_PER_S, rpm)


class AnalysisGroup(om.Group):
    """The blade at K conditions: broadcast, BEM analyses and, with ``trim``, the thrust balance.

    With ``trim`` an ``om.BalanceComp`` makes the collective pitch (or the rotor speed) of each
    condition an output solved so that the BEM thrust equals ``thrust_target``; a Newton solver
    (kept inside ``trim_bounds`` by a ``BoundsEnforceLS`` line search; a direct linear solver)
    converges it, started every time from :func:`trim_guess`.  Without ``trim`` the group is
    feed-forward (RunOnce).

    Options
    -------
    num_nodes, num_radial, num_blades, polar, loss_model, on_invalid
        As for :class:`~bild_mdo.bem.bem_group.BEMAnalysisGroup` (``polar`` must be a Polar).
    trim : {None, 'collective_pitch', 'rpm'}
    trim_bounds : tuple of float
        (lower, upper) of the trimmed quantity (rad or rpm).

    Inputs
    ------
    blade_chord[1, nr] (m), blade_twist[1, nr] (rad), blade_radius[1] (m), blade_hub_radius[1] (m),
    v_axial[K] (m/s), altitude[K] (m), rpm[K] (rpm), collective_pitch[K] (rad) (the trimmed one is an
    output), thrust_target[K] (N) (with ``trim``)

    Outputs
    -------
    The per-design outputs of the BEM (thrust[K], torque[K], power[K], ...) and the trimmed quantity.
    """

    def initialize(self):
        declare_size_options(self.options)
        self.options.declare("num_blades", types=int, default=3, desc="number of blades B")
        self.options.declare("polar", recordable=False, desc="airfoil Polar")
        self.options.declare("loss_model", default="tip_hub", desc="Prandtl losses")
        self.options.declare("on_invalid", default="warn", desc="BEM stations in an invalid flow state")
        self.options.declare("trim", default=None, values=TRIM_VARIABLES, desc="trimmed quantity or None")
        self.options.declare("trim_bounds", default=None, allow_none=True,
                             desc="(lower, upper) of the trimmed quantity (rad or rpm)")

    def setup(self):
        opts = self.options
        nn, nr, trim = opts["num_nodes"], opts["num_radial"], opts["trim"]
        self.add_subsystem("blade", BladeBroadcastComp(num_nodes=nn, num_radial=nr),
                           promotes_inputs=["blade_chord", "blade_twist", "blade_radius", "blade_hub_radius"],
                           promotes_outputs=["chord", "twist", "radius", "hub_radius"])
        self.add_subsystem("bem", BEMAnalysisGroup(num_nodes=nn, num_radial=nr, num_blades=opts["num_blades"],
                                                   polar=opts["polar"], loss_model=opts["loss_model"],
                                                   on_invalid=opts["on_invalid"]),
                           promotes_inputs=["v_axial", "rpm", "altitude", "collective_pitch", "chord", "twist",
                                            "radius", "hub_radius"],
                           promotes_outputs=list(PERFORMANCE_OUTPUTS))
        if trim is None:
            return
        (lower, upper), guess, units = TRIM_DEFAULTS[trim]
        if opts["trim_bounds"] is not None:
            lower, upper = opts["trim_bounds"]
        self._trim_bounds = (lower, upper)
        balance = self.add_subsystem("trim", om.BalanceComp(), promotes_inputs=["thrust", "thrust_target"],
                                     promotes_outputs=[trim])
        # normalize divides the residual by |thrust_target|: one tolerance for any rotor size.
        balance.add_balance(trim, shape=(nn,), val=np.full(nn, guess), units=units, eq_units="N",
                            lhs_name="thrust", rhs_name="thrust_target", rhs_val=np.ones(nn),
                            lower=lower, upper=upper, normalize=True,
                            desc=f"{trim} trimmed so that the thrust equals thrust_target")
        # Stops at atol = 1e-9 on the normalised residual (thrust within ~1e-9 relative of its target):
        # under complex step the BEM inflow residuals stay near 1e-11, so a tighter atol would stall there.
        newton = om.NewtonSolver(solve_subsystems=True, maxiter=30, atol=1e-9, rtol=1e-12, iprint=-1,
                                 err_on_non_converge=True)
        newton.linesearch = om.BoundsEnforceLS()
        self.nonlinear_solver = newton
        self.linear_solver = om.DirectSolver()

    def guess_nonlinear(self, inputs, outputs, residuals):
        trim = self.options["trim"]
        if trim is None:
            return

        def current(name):
            # A condition input feeds several BEM components: read it at the inflow solve's copy.
            return np.real(outputs[name] if name == trim else inputs[f"bem.inflow.{name}"])

        guess = trim_guess(trim, np.real(inputs["blade_twist"]), np.real(inputs["blade_chord"]),
                           np.real(inputs["blade_radius"])[0], np.real(inputs["blade_hub_radius"])[0],
                           current("v_axial"), current("rpm"), current("collective_pitch"),
                           np.real(inputs["thrust_target"]), self.options["polar"])
        outputs[trim] = np.clip(guess, *self._trim_bounds)
