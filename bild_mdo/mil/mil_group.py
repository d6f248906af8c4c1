"""MILGroup: minimum-induced-loss propeller design (Adkins & Liebeck 1994) beside BILD."""
import numpy as np
import openmdao.api as om

from bild_mdo.atmosphere import AtmosphereComp
from bild_mdo.fluid import FLUIDS
from bild_mdo.bem.stations import StationsComp
from bild_mdo.mil.blade import MILBladeComp
from bild_mdo.mil.displacement_velocity import DESIGN_FOR, DisplacementVelocityComp
from bild_mdo.mil.kernel import declare_design_options
from bild_mdo.mil.performance import MIL_OUTPUTS, MILPerformanceComp
from bild_mdo.mil.speed_ratio import SpeedRatioComp
from bild_mdo.utils.options import declare_size_options


class MILGroup(om.Group):
    """Chord and twist of the minimum-induced-loss propeller for a thrust (or power) target.

    Adkins & Liebeck, "Design of optimum propellers", J. Propulsion and Power
    10(5), 1994, with Prandtl's momentum loss factor and the viscous terms
    (``eps = C_d/C_l``), at BILD's operating point and airfoil point, as a
    feed-forward chain on RunOnce (the one implicit component solves itself
    and provides its linear solve)::

        atmosphere             altitude -> rho, mu (ISA)
        stations               R, r_hub -> radii, dr  (midpoints of equal annuli)
        speed_ratio            lambda = V/(Omega R), xi = r/R, dxi = dr/R
        displacement_velocity  zeta from T_c = I1 zeta - I2 zeta^2 (or P_c = J1 zeta + J2 zeta^2), implicit
        blade                  chord (W c / W), twist (alpha* + phi), phi, W, F
        performance            T, P, Q, eta from the integrals

    Forward flight only (``v_axial > 0``, ``J > 0``): hover raises
    :class:`openmdao.api.AnalysisError`.  Every section works at the airfoil
    point ``(alpha_star, cl_star, cd_star)`` given as inputs (BILD's
    reference point: connect or copy BILDGroup's outputs of the same names);
    A&L's Reynolds-number update of ``eps`` and ``alpha`` per station is not
    made, as in BILD's reference-point method.  Prandtl's factor is A&L's tip
    factor only (no hub loss).

    Options
    -------
    num_nodes, num_radial : int
        Designs (axis 0) and stations (axis 1).
    num_blades : int
        Number of blades B (default 2).
    design_for : {'thrust', 'power'}
        Target: ``design_thrust`` (default) or ``design_power``.
    loss_form : {'adkins_liebeck', 'local', 'qmil'}
        Prandtl exponent with the tip flow angle (A&L, default) or the local
        one (the package's BEM analysis with ``loss_model='tip'``, which then
        reproduces the design exactly), or Drela's QMIL factor (wake advance
        ratio in the exponent and a root self-induction factor:
        :mod:`bild_mdo.mil.kernel`), to compare with QMIL designs.
    radial_fractions, width_fractions : array_like or None
        User stations (see :class:`~bild_mdo.bem.stations.StationsComp`).

    Inputs
    ------
    v_axial[nn] (m/s), rpm[nn] (rpm), radius[nn] (m), hub_radius[nn] (m), altitude[nn] (m) (with
    ``use_atmosphere=False`` instead rho[nn] (kg/m**3) of any fluid: MIL needs no viscosity)
        Operating point.
    design_thrust[nn] (N) or design_power[nn] (W)
        Target.
    alpha_star[nn] (rad), cl_star[nn] (-), cd_star[nn] (-)
        Airfoil point of every section.

    Outputs
    -------
    chord[nn, nr] (m), twist[nn, nr] (rad), phi[nn, nr] (rad), inflow_speed[nn, nr] (m/s), loss_factor[nn, nr] (-)
        Blade and flow of the design.
    zeta[nn] (-), speed_ratio[nn] (-)
        Displacement velocity ratio and speed ratio.
    thrust[nn] (N), power[nn] (W), torque[nn] (N*m), efficiency[nn] (-)
        Performance from A&L's integrals.
    radii[nn, nr] (m), dr[nn, nr] (m), rho[nn] (kg/m**3), mu[nn] (Pa*s)
        Stations and atmosphere.
    """

    def initialize(self):
        declare_size_options(self.options)
        declare_design_options(self.options)
        self.options.declare("design_for", default="thrust", values=DESIGN_FOR, desc="target: thrust or power")
        self.options.declare("use_atmosphere", types=bool, default=True,
                             desc="rho from the ISA at input altitude (else rho is an input: any fluid)")
        # User stations, passed to StationsComp; None for the midpoints of equal annuli.
        for name, what in (("radial_fractions", "radii r/R"), ("width_fractions", "widths dr/R")):
            self.options.declare(name, default=None, allow_none=True, desc=f"user station {what} or None")

    def setup(self):
        opts = self.options
        nn, nr = opts["num_nodes"], opts["num_radial"]
        size = dict(num_nodes=nn, num_radial=nr)
        design = dict(num_blades=opts["num_blades"], loss_form=opts["loss_form"])
        target = "design_thrust" if opts["design_for"] == "thrust" else "design_power"
        point = ["v_axial", "radius", "cl_star", "cd_star"]
        stations = ["speed_ratio", "radius_fraction", "width_fraction"]
        # (name, component, promoted inputs, promoted outputs), in data-flow order.
        atmosphere = ("atmosphere", AtmosphereComp(num_nodes=nn), ["altitude"], ["rho", "mu"])
        chain = ((atmosphere,) if opts["use_atmosphere"] else ()) + (
            ("stations", StationsComp(**size, radial_fractions=opts["radial_fractions"],
                                      width_fractions=opts["width_fractions"]),
             ["radius", "hub_radius"], ["radii", "dr"]),
            ("speed_ratio", SpeedRatioComp(**size), ["v_axial", "rpm", "radius", "radii", "dr"], stations),
            ("displacement_velocity", DisplacementVelocityComp(**size, **design, design_for=opts["design_for"]),
             stations + point + [target, "rho"], ["zeta"]),
            ("blade", MILBladeComp(**size, **design), stations[:2] + point + ["zeta", "alpha_star"],
             ["chord", "twist", "phi", "inflow_speed", "loss_factor"]),
            ("performance", MILPerformanceComp(**size, **design), stations + point + ["zeta", "rho", "rpm"],
             list(MIL_OUTPUTS)),
        )
        for name, component, inputs, outputs in chain:
            self.add_subsystem(name, component, promotes_inputs=inputs, promotes_outputs=outputs)
        # MIL's relations use the density only (its airfoil point is given, not looked up at a Reynolds number).
        fluid = {"altitude": (0.0, "m")} if opts["use_atmosphere"] else {"rho": (FLUIDS["air"].rho, "kg/m**3")}

        defaults = {"v_axial": (50.0, "m/s"), "rpm": (2400.0, "rpm"), "radius": (0.875, "m"),
                    "hub_radius": (0.1, "m"), **fluid,
                    target: (1000.0, "N" if target == "design_thrust" else "W"),
                    "alpha_star": (np.radians(4.0), "rad"), "cl_star": (0.7, None), "cd_star": (0.01, None)}
        for name, (value, units) in defaults.items():
            self.set_input_defaults(name, val=np.full(nn, value), units=units)
