"""BILDGroup: the BEM-based ideal-loading design method (paper Sec. 4, Algorithm 1) as one group."""
import numbers

import numpy as np
import openmdao.api as om

from bild_mdo.acoustics.noise_options import NOISE_OUTPUTS, declare_noise_options
from bild_mdo.acoustics.rotor_noise_group import make_noise_group
from bild_mdo.acoustics.station_angle import StationAngleComp
from bild_mdo.airfoil.polar import Polar
from bild_mdo.atmosphere import AtmosphereComp
from bild_mdo.fluid import FLUIDS, fluid_arrays
from bild_mdo.bem.metrics import PERFORMANCE_OUTPUTS
from bild_mdo.bem.performance import RotorPerformanceComp
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bem.stations import StationsComp, declare_station_options
from bild_mdo.bild.advance_ratio import AdvanceRatioComp
from bild_mdo.bild.annulus_stationarity import IDEAL_LOADINGS
from bild_mdo.bild.chord import CHORD_FORMS
from bild_mdo.bild.feasibility import ON_INFEASIBLE, FeasibilityComp, FeasibilityLedger
from bild_mdo.bild.geometry import GeometryComp
from bild_mdo.bild.variants import SECTION_POINTS
from bild_mdo.bild.mach import LocalMachComp
from bild_mdo.bild.variants.reference_point.reference_airfoil import default_polar
from bild_mdo.bild.root_chord_correction import RootChordCorrectionComp
from bild_mdo.bild.rotational_speed import RotationalSpeedComp
from bild_mdo.bild.thrust_target import ReferenceChordSolver, ThrustTargetComp
from bild_mdo.bild.variants import VARIANTS
from bild_mdo.bild.variants.base import Wiring
from bild_mdo.utils.linear_solvers import TriangularDirectSolver
from bild_mdo.utils.options import VARIABLES, declare_size_options

INPUT_MODES = ("v_axial", "advance_ratio")


def _check_polar(name, value):
    if value is not None and not isinstance(value, Polar):
        raise ValueError(f"{name} must be a bild_mdo.airfoil.Polar or None (built-in NACA 4412), "
                         f"got {type(value).__name__}")


def _check_section_point(name, value):
    if not (isinstance(value, str) and value in SECTION_POINTS):
        raise ValueError(f"{name} must be 'reference' or 'local', got {value!r}")


def _check_correction(name, value):
    if value is None:
        return
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not value > 0.0:
        raise ValueError(f"{name} must be None (no correction) or a positive number k, got {value!r}")


class BILDGroup(om.Group):
    """Ideal chord and twist of a rotor and its performance, by the BILD method.

    Algorithm 1 of the paper as a feed-forward chain on RunOnce (implicit components solve themselves;
    ``section_point='local'`` and ``thrust_target=True`` add Newton solves).  The linear solver is
    ``TriangularDirectSolver(assemble_jac=True)`` (a DirectSolver that factors the chain in dependency
    order, :mod:`bild_mdo.utils.linear_solvers`) unless the user sets another after construction: totals in
    either mode cost one sparse factorisation and one back-substitution per seed (per variable of reverse
    seeds)::

        atmosphere (ISA)            altitude -> rho, mu, a
        [advance_ratio]             J, rpm, R -> V_x            (input_mode='advance_ratio')
        geometry                    R, ratios -> r_hub, r_ref
        stations                    R, r_hub -> radii, dr       (midpoints of equal annuli)
        rotational_speed            V_theta = Omega r, Omega r_ref
        reference_airfoil           Re_ref, M_ref -> alpha*, C_l*, C_d*                step 1
        reference_station           BEM inflow angle at r_ref with c_ref (implicit)     step 2
        reference_induced_velocity  u_axial, u_theta at r_ref, Eq. (8)                  step 2
        ideal_loading               lambda, Eq. (22) (or exact, option ideal_loading)   step 3
        eta2                        quartic, Eq. (27) (implicit; exact: ExactEta2Comp)  step 4
        induced_velocity            u_axial, u_theta, Eqs. (26), (24)                   step 5
        inflow_angle                phi, W, twist, Eq. (30)                             step 7
        momentum_loads              F, dT/dr, dQ/dr, dE/dr, Eqs. (1), (2), (12)         step 6
        chord                       Eq. (31) (or the torque form)                       step 7
        root_chord_correction       Eq. (32) (optional)
        local_mach                  M = W / a at every station
        performance                 T, Q, P, eta, FM, C_T, C_Q, C_P, E, sigma_r, C_T/sigma_r (Table 2), M_tip
        feasibility_check           feasible (1/0); one error for every infeasible node

    Airfoils.  A polar with ``varies_with_mach`` is queried at the reference
    station's Mach number ``M_ref = W0 / a`` (``W0`` as for ``Re_ref``); a
    polar with ``varies_along_span``
    (:class:`~bild_mdo.airfoil.spanwise.SpanwisePolar`) gives every station
    its own maximum-L/D point at ``Re_ref`` and ``M_ref`` (Assumption 2 per
    station): ``alpha_star, cl_star, cd_star`` are then ``[nn, nr]`` and the
    reference station uses the airfoil at ``r_ref`` (``alpha_star_ref,
    cl_star_ref, cd_star_ref``, ``[nn]``), so ``chord(r_ref) = c_ref`` still
    holds.  Other polars give exactly the one-airfoil, Reynolds-only chain.

    The thrust and torque are those of the ideal loading; the root-chord
    correction changes only the chord (and with it the solidity), as in the
    paper's Sec. 5.2.2.

    Limits of the ideal loading (infeasible designs):

    * Hover: a station where ``lambda <= V_theta / (2 L/D)`` (``lambda`` of
      Eq. (22), ``L/D = C_l*/C_d*``) cannot be loaded; it gets ``eta2 = 1``,
      no induction and zero chord.  This is the continuous limit
      ``V_x -> 0+`` of the quartic root, not a special case.  If every
      station is unloaded the rotor has no torque: infeasible.
    * The reference station must produce thrust and not be overloaded
      (Assumption 3 at ``r_ref``: ``u_axial_ref > V_x``, ``0 < u_theta_ref <
      V_theta_ref``; remedies: a smaller ``ref_chord`` or advance ratio).
    * Forward flight: every station must produce thrust (Assumption 3,
      ``u_axial > V_x``), which needs ``V_x < eta2 V_theta C_l*/C_d*``.  Inboard
      stations at a high advance ratio with a low-L/D airfoil break it
      (remedies: a larger ``hub_radius_ratio``, a lower advance ratio /
      ``V_x``, or an airfoil with a higher L/D).

    The checks run vectorised in the components, which record the failing
    nodes in the group's :attr:`feasibility` ledger
    (:class:`~bild_mdo.bild.feasibility.FeasibilityLedger`) and give them
    finite placeholder values, so one run finds every infeasible node.  The
    last component then raises ONE :class:`openmdao.api.AnalysisError`
    listing every infeasible node with its reason
    (``on_infeasible='raise'``, default) or only sets the output
    ``feasible`` to 0 there (``'flag'``; the other outputs of those nodes are
    placeholders without meaning).  A feasible node's outputs do not depend
    on the other nodes of the batch.
    * User stations (``radial_fractions``) must lie on the blade outside the
      hub (see :class:`~bild_mdo.bem.stations.StationsComp`).

    Options
    -------
    num_nodes, num_radial : int
        Designs / operating points (axis 0) and radial stations (axis 1).
    num_blades : int
        Number of blades B (default 3).
    polar : Polar or None
        Airfoil polar; ``None`` (default) is the built-in NACA 4412.
    loss_model : str
        Prandtl loss factor: ``'tip_hub'`` (default), ``'tip'`` or ``'none'``.
    chord_form : str
        ``'thrust'`` (Eq. (31), default) or ``'torque'``.
    root_chord_correction : float or None
        ``k`` of Eq. (32) on ``r/R``; ``None`` (default) leaves the chord as
        back-computed.
    input_mode : str
        ``'v_axial'`` (default): the axial velocity is an input;
        ``'advance_ratio'``: the advance ratio ``J = V_x/(n D)`` is, as in the
        paper's Algorithm 1.
    on_infeasible : str
        ``'raise'`` (default) or ``'flag'``: see above.
    radial_fractions, width_fractions : array_like or None
        User stations ``r/R`` and widths ``dr/R`` (shape ``(nr,)`` or
        ``(nn, nr)``), see :class:`~bild_mdo.bem.stations.StationsComp`;
        ``None`` (default): midpoints of ``nr`` equal annuli from hub to tip.
    section_point : str
        ``'reference'`` (default, the paper): every station at the max-L/D
        point of the reference station's Reynolds number.  ``'local'``: each
        station (and the reference station) minimises its ``cd/cl`` along the
        path on which its load per unit span stays fixed while the chord, and
        so ``Re = rho W0 c / mu``, follows from the load
        (:mod:`bild_mdo.bild.variants.local_point`, solved once per polar on
        its load-path table, :mod:`bild_mdo.airfoil.load_path_table`); eta2
        then uses each station's own ``cd/cl``, and every station is solved on
        its own given lambda (a feed-forward chain).  Extra outputs:
        ``reynolds[nn, nr]``, ``load_reynolds[nn, nr]``,
        ``section_branch[nn, nr]`` (the table's sheet of each station's point,
        -1 unloaded), ``alpha_star_ref, cl_star_ref, cd_star_ref,
        section_branch_ref``; ``alpha_star, cl_star, cd_star`` are
        ``[nn, nr]`` and ``mach_ref`` is not computed.  Needs a polar that
        varies with the Reynolds number only.  Where two minima of
        ``cd/cl`` are nearly equal the lower is taken, so the design can jump
        (a kink in chord and twist as functions of the inputs) where they swap.
    ideal_loading : str
        ``'paper'`` (default): Eq. (22) and the quartic (27), which leave
        ``dF/dphi`` out.  ``'exact'``: ``(F e)' = lambda (F t)'`` at every
        station (:mod:`bild_mdo.bild.annulus_stationarity`), the optimum of the
        BEM model for a fixed airfoil point.  With ``section_point='local'``:
        the Reynolds-aware exact loading
        (:mod:`bild_mdo.bild.variants.reynolds_exact`), where each annulus
        minimises ``F (e - lambda t)`` with its section point following its
        own load (the derivative of ``cd/cl`` with the load through the
        chord's Reynolds number enters the condition); every station is solved
        on its own given lambda (no loop), and a station whose best loaded
        state does not beat the unloaded one gets zero chord.
    thrust_target : bool
        False (default): ``ref_chord`` is an input.  True: ``thrust_target``
        is, and ``ref_chord`` is the output that gives ``thrust =
        thrust_target`` (to 1e-12 relative), solved per design by
        :class:`~bild_mdo.bild.thrust_target.ReferenceChordSolver` with exact
        totals; a target out of
        reach is an infeasible design.  With the Reynolds-aware exact loading
        (``section_point='local', ideal_loading='exact'``) lambda
        (``ideal_loading_constant``) is solved instead, and ``ref_chord`` is the
        design's chord at ``r_ref`` (the reference chord names that loading's
        designs only piecewise).
    noise_observers : array_like or None
        None (default): no noise, the group as without this option.  An ``(n, 3)`` array of observer
        positions (m, rotor frame: x along the thrust, so an observer below a hovering lift rotor has
        ``x < 0``) adds the subsystem ``noise``
        (:class:`~bild_mdo.acoustics.rotor_noise_group.RotorNoiseGroup`) fed by the ideal rotor's loads,
        chord, inflow speed and section angle of attack (``alpha_star`` at every station), with the input
        ``observer_position[nn, n, 3]`` (default: these positions at every node) and the outputs
        ``oaspl[nn, n]``, ``oaspl_dba[nn, n]``, ``tonal_spl``, ``band_spl`` and the mean-square pressures.
    noise_harmonics : int
        Blade-passage harmonics of the tonal noise (default 10).
    noise_boundary_layer : str
        ``'tripped'`` (default) or ``'untripped'``: BPM's boundary-layer fits.

    Inputs
    ------
    v_axial[nn] (m/s) or advance_ratio[nn] (-)
        Operating condition (see ``input_mode``); ``v_axial >= 0``, 0 is hover.
    rpm[nn] (rpm)
        Rotor speed.
    radius[nn] (m)
        Tip radius.
    hub_radius_ratio[nn] (-), ref_radius_ratio[nn] (-)
        Hub and reference radii over the tip radius, ``0 < hub < ref < 1``.
    ref_chord[nn] (m)
        Chord at the reference station (an output with ``thrust_target=True``).
    thrust_target[nn] (N)
        Required thrust, > 0 (only with ``thrust_target=True``).
    altitude[nn] (m)
        Geometric altitude for the ISA atmosphere; with ``use_atmosphere=False``
        instead ``rho[nn] (kg/m**3)``, ``mu[nn] (Pa*s)`` and
        ``speed_of_sound[nn] (m/s)`` of any fluid (default: sea-level air;
        :mod:`bild_mdo.fluid`).

    Outputs
    -------
    chord[nn, nr] (m), chord_raw[nn, nr] (m), twist[nn, nr] (rad)
        Blade geometry (after / before the root-chord correction).
    radii[nn, nr] (m), dr[nn, nr] (m)
        Stations.
    phi, inflow_speed, u_axial, u_theta, eta2, loss_factor, dthrust_dr, dtorque_dr,
    denergy_loss_dr, lift_coefficient, drag_coefficient : [nn, nr]
        Distributions of the ideal rotor.
    mach[nn, nr] (-)
        Local Mach number ``W / a`` (``W`` the inflow speed with induction).
    thrust, torque, power, efficiency, figure_of_merit, thrust_coefficient,
    torque_coefficient, power_coefficient, energy_loss, solidity, blade_loading, tip_mach : [nn]
        Performance (Table 2) and the tip Mach number ``sqrt(V_x**2 + (Omega R)**2) / a``.
    feasible : [nn]
        1.0 where the design is feasible, 0.0 where it is not (``'flag'`` mode).
    alpha_star, cl_star, cd_star, reynolds_ref, mach_ref, phi_ref, u_axial_ref, u_theta_ref,
    ideal_loading_constant, v_axial (advance-ratio mode), rho, mu, speed_of_sound : [nn]
        Intermediate per-design quantities (``alpha_star, cl_star, cd_star``
        ``[nn, nr]`` and ``alpha_star_ref, cl_star_ref, cd_star_ref`` ``[nn]``
        for a polar that varies along the span).
    """

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        # One sparse factorisation (without fill: the chain is triangular in dependency order) per
        # linearisation, then one back-substitution per seed (per variable of reverse seeds): with
        # LinearRunOnce a reverse compute_totals sweeps the whole chain once per seed
        # (benchmarks/bild_speed.py).  Set here, not in setup, so that a solver the user sets after
        # construction wins.
        self.linear_solver = TriangularDirectSolver(assemble_jac=True)

    def initialize(self):
        declare_size_options(self.options)
        self.options.declare("num_blades", types=int, default=3, desc="number of blades B")
        self.options.declare("polar", default=None, allow_none=True, recordable=False, check_valid=_check_polar,
                             desc="airfoil Polar; None selects the built-in NACA 4412")
        self.options.declare("loss_model", default="tip_hub", values=LOSS_MODELS,
                             desc="Prandtl losses: 'tip_hub', 'tip' or 'none'")
        self.options.declare("chord_form", default="thrust", values=CHORD_FORMS,
                             desc="chord from the thrust (Eq. (31)) or the torque (Eq. (6)) balance")
        self.options.declare("root_chord_correction", default=None, allow_none=True,
                             check_valid=_check_correction,
                             desc="k of the root-chord correction Eq. (32) on r/R; None for no correction")
        self.options.declare("input_mode", default="v_axial", values=INPUT_MODES,
                             desc="operating-condition input: 'v_axial' (m/s) or 'advance_ratio' J")
        self.options.declare("on_infeasible", default="raise", values=ON_INFEASIBLE,
                             desc="'raise': one AnalysisError naming every infeasible node; 'flag': output feasible")
        declare_station_options(self.options)
        self.options.declare("thrust_target", types=bool, default=False,
                             desc="True: input thrust_target (N) and the reference chord solved for it")
        self.options.declare("section_point", default="reference", check_valid=_check_section_point,
                             desc="'reference': every station at the max-L/D point of the reference Reynolds "
                                  "number (the paper); 'local': each station minimises cd/cl at its fixed load")
        self.options.declare("use_atmosphere", types=bool, default=True,
                             desc="rho, mu and speed_of_sound from the ISA at input altitude (else they are inputs: "
                                  "any fluid, bild_mdo.fluid)")
        self.options.declare("ideal_loading", default="paper", values=IDEAL_LOADINGS,
                             desc="'paper': lambda and eta2 of Eqs. (22), (27); 'exact': each annulus makes "
                                  "E - lambda T stationary with the Prandtl factor F differentiated too")
        declare_noise_options(self.options)

    def setup(self):
        opts = self.options
        nn, nr, b = opts["num_nodes"], opts["num_radial"], opts["num_blades"]
        if nr < 2:
            raise ValueError(f"{self.msginfo}: num_radial must be at least 2 (a blade needs stations from hub to tip "
                             f"for its loading and chord), got {nr}")
        # Per-design components get num_nodes only; components with stations also get num_radial.
        node = dict(num_nodes=nn)
        size = dict(num_nodes=nn, num_radial=nr)
        polar = default_polar() if opts["polar"] is None else opts["polar"]
        loss = dict(num_blades=b, loss_model=opts["loss_model"])
        #: Infeasible nodes found by the checks of the last run (read it after run_model).
        self.feasibility = FeasibilityLedger(nn)
        checked = dict(feasibility=self.feasibility)

        if opts["use_atmosphere"]:
            self.add_subsystem("atmosphere", AtmosphereComp(num_nodes=nn), promotes_inputs=["altitude"],
                               promotes_outputs=["rho", "mu", "speed_of_sound"])
        if opts["input_mode"] == "advance_ratio":
            self.add_subsystem("advance_ratio", AdvanceRatioComp(**node),
                               promotes_inputs=["advance_ratio", "rpm", "radius"], promotes_outputs=["v_axial"])
        self.add_subsystem("geometry", GeometryComp(**node),
                           promotes_inputs=["radius", "hub_radius_ratio", "ref_radius_ratio"],
                           promotes_outputs=["hub_radius", "ref_radius"])
        self.add_subsystem("stations", StationsComp(**size, radial_fractions=opts["radial_fractions"],
                                                    width_fractions=opts["width_fractions"]),
                           promotes_inputs=["radius", "hub_radius"], promotes_outputs=["radii", "dr"])
        self.add_subsystem("rotational_speed", RotationalSpeedComp(**size),
                           promotes_inputs=["rpm", "radii", "ref_radius"],
                           promotes_outputs=["v_theta", "v_theta_ref"])
        wiring = Wiring(self, polar, node, size, loss, checked, opts["chord_form"])
        #: The member of the BILD family the options select (:mod:`bild_mdo.bild.variants`).
        self.variant = VARIANTS[opts["ideal_loading"], opts["section_point"]](wiring)
        self.variant.add()
        self.add_subsystem("root_chord_correction",
                           RootChordCorrectionComp(**size, correction_constant=opts["root_chord_correction"]),
                           promotes_inputs=["chord_raw", "ref_chord", "radii", "radius"],
                           promotes_outputs=["chord"])
        self.add_subsystem("local_mach", LocalMachComp(**size), promotes_inputs=["inflow_speed", "speed_of_sound"],
                           promotes_outputs=["mach"])
        self.add_subsystem("performance", RotorPerformanceComp(**size, num_blades=b),
                           promotes_inputs=["dthrust_dr", "dtorque_dr", "dr", "chord", "v_axial", "rpm",
                                            "radius", "rho", "speed_of_sound"],
                           promotes_outputs=list(PERFORMANCE_OUTPUTS))
        if opts["thrust_target"]:
            #: The balance of the thrust-target solve (read by ReferenceChordSolver).
            self.thrust_target_balance = self.add_subsystem(
                "thrust_target_balance", ThrustTargetComp(**size, **checked, state=self.variant.thrust_target_state),
                promotes_inputs=["dthrust_dr", "dr", "thrust_target"],
                promotes_outputs=[self.variant.thrust_target_state])
            self.nonlinear_solver = ReferenceChordSolver()
        self.add_subsystem("feasibility_check", FeasibilityComp(**node, ledger=self.feasibility,
                                                                on_infeasible=opts["on_infeasible"]),
                           promotes_outputs=["feasible"])
        noise = make_noise_group(opts, nn, nr, b, polar)
        if noise is not None:
            if polar.varies_along_span or opts["section_point"] == "local":
                # alpha_star is already one angle per station.
                self.connect("alpha_star", "alpha")
            else:
                self.add_subsystem("noise_alpha", StationAngleComp(**size), promotes_inputs=["alpha_star"],
                                   promotes_outputs=["alpha"])
            # The noise group's inputs are the chain's outputs of the same names (rpm, radii, chord, ...).
            self.add_subsystem("noise", noise, promotes_inputs=["*"], promotes_outputs=list(NOISE_OUTPUTS))

        if opts["input_mode"] == "advance_ratio":
            self.set_input_defaults("advance_ratio", val=np.zeros(nn), units=None)
        else:
            self.set_input_defaults("v_axial", val=np.zeros(nn), units="m/s")
        self.set_input_defaults("rpm", val=np.full(nn, 800.0), units="rpm")
        self.set_input_defaults("radius", val=np.full(nn, 1.5), units="m")
        self.set_input_defaults("hub_radius_ratio", val=np.full(nn, 0.2), units=None)
        self.set_input_defaults("ref_radius_ratio", val=np.full(nn, 0.5), units=None)
        if opts["thrust_target"]:
            self.set_input_defaults("thrust_target", val=np.full(nn, 1000.0), units="N")
        else:
            self.set_input_defaults("ref_chord", val=np.full(nn, 0.15), units="m")
        if opts["use_atmosphere"]:
            self.set_input_defaults("altitude", val=np.zeros(nn), units="m")
        else:
            for name, value in fluid_arrays(FLUIDS["air"], nn).items():
                self.set_input_defaults(name, val=value, units=VARIABLES[name][2])
