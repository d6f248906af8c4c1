"""MultipointRotorGroup: one blade designed by BILD at one condition and analysed by the BEM at several others."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.acoustics.noise_options import NOISE_OUTPUTS, declare_noise_options
from bild_mdo.acoustics.rotor_noise_group import make_noise_group
from bild_mdo.airfoil.builtin import resolve_polar
from bild_mdo.bem.flow_states import ON_INVALID
from bild_mdo.bem.metrics import PERFORMANCE_OUTPUTS
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bild.bild_group import BILDGroup
from bild_mdo.bild.chord import CHORD_FORMS
from bild_mdo.multipoint.trim import TRIM_VARIABLES, AnalysisGroup
from bild_mdo.utils.options import declare_size_options

#: Inputs of the BILD design that keep their names; the operating condition gets the prefix ``design_``.
_DESIGN_INPUTS = ("radius", "hub_radius_ratio", "ref_radius_ratio", "ref_chord")
_DESIGN_CONDITION = ("v_axial", "rpm", "altitude")
#: Where the noise group's inputs come from at each analysis condition (the BEM's and the blade's outputs).
_NOISE_SOURCES = {name: f"analysis.bem.{name}" for name in ("radii", "dr", "dthrust_dr", "dtorque_dr", "alpha",
                                                            "phi", "inflow_speed", "rho", "mu", "speed_of_sound")}
_NOISE_SOURCES.update({name: f"analysis.{name}" for name in ("chord", "radius", "hub_radius")})


def _check_trim_bounds(name, value):
    if value is None:
        return
    try:
        lower, upper = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be None or a pair (lower, upper) of numbers, got {value!r}") from None
    if not (np.isfinite(lower) and np.isfinite(upper) and lower < upper):
        raise ValueError(f"{name} must be None or finite (lower, upper) with lower < upper, got {value!r}")


class MultipointRotorGroup(om.Group):
    """One blade at several operating conditions: designed by BILD at one, analysed by the BEM at ``num_nodes``.

    ::

        design     BILDGroup(num_nodes=1)       design_v_axial, design_rpm, design_altitude, radius,
                                                hub_radius_ratio, ref_radius_ratio, ref_chord
                                                -> chord[1, nr], twist[1, nr], hub_radius, design_<metric>
        analysis   blade   BladeBroadcastComp   the blade's chord, twist, radius at every condition
                   bem     BEMAnalysisGroup(num_nodes=K)   collective_pitch[K] added to the twist
                                                -> thrust[K], torque[K], power[K], ...
                   [trim   om.BalanceComp]      collective_pitch[K] or rpm[K] such that thrust = thrust_target

    Both the BILD design and the analyses place their stations with
    :class:`~bild_mdo.bem.stations.StationsComp` from the same tip and hub radius (midpoints of equal
    annuli), so station ``j`` of every analysis is station ``j`` of the design and the geometry is
    passed on unchanged.  Analysed at its own design condition with zero pitch, the blade gives
    BILD's thrust and torque up to the polar evaluation: BILD takes every section at the
    maximum-L/D point of the reference Reynolds number (paper Assumption 2), the BEM at its local
    Reynolds number; with a Reynolds-independent polar the two agree to solver tolerance.

    With ``trim`` the analysis group (:class:`~bild_mdo.multipoint.trim.AnalysisGroup`) holds an
    ``om.BalanceComp`` and a Newton solver (kept inside ``trim_bounds`` by a ``BoundsEnforceLS``
    line search, started from a momentum-theory estimate; a direct linear solver): the collective
    pitch (or the rotor speed) of each condition becomes an output, solved so that the BEM thrust
    equals input ``thrust_target``; its total derivatives are exact (implicit function theorem).
    Without ``trim`` every group is feed-forward (RunOnce).

    Options
    -------
    num_nodes : int
        Number K of analysis conditions.
    num_radial : int
        Radial stations of the blade.
    num_blades, polar, loss_model
        As for :class:`~bild_mdo.bild.bild_group.BILDGroup` (the BEM uses the same ones;
        ``polar=None`` is the built-in NACA 4412).
    chord_form, root_chord_correction
        Options of the BILD design (a root-chord correction changes the blade, so the analysis at
        the design condition no longer reproduces BILD's loads).
    design_thrust_target : bool
        False (default): input ``ref_chord``; True: input ``design_thrust_target`` and BILD solves for
        the reference chord (``BILDGroup(thrust_target=True)``), output ``ref_chord``.
    on_invalid : str
        BEM flow states: ``'warn'`` (default), ``'raise'`` or ``'ignore'``.
    trim : {None, 'collective_pitch', 'rpm'}
        Quantity solved per condition so that the thrust is ``thrust_target``; None (default): none.
    trim_bounds : tuple of float or None
        (lower, upper) of the trimmed quantity in rad or rpm; None: :data:`TRIM_DEFAULTS`.
    noise_observers : array_like or None
        None (default): no noise.  An ``(n, 3)`` array of observer positions (m, rotor frame, x along
        the thrust) adds the subsystem ``noise``
        (:class:`~bild_mdo.acoustics.rotor_noise_group.RotorNoiseGroup`, ``num_nodes=K``) after the
        analyses: the noise of the blade at every analysis condition, outputs ``oaspl[K, n]``,
        ``oaspl_dba[K, n]`` ..., input ``observer_position[K, n, 3]`` (default: these positions).
    noise_harmonics, noise_boundary_layer
        Harmonics of the tonal noise (default 10) and BPM boundary layer (``'tripped'`` or
        ``'untripped'``), with ``noise_observers``.

    Inputs
    ------
    design_v_axial[1] (m/s), design_rpm[1] (rpm), design_altitude[1] (m)
        Design condition of the BILD blade.
    radius[1] (m), hub_radius_ratio[1] (-), ref_radius_ratio[1] (-), ref_chord[1] (m)
        Blade size and the BILD design parameters (``design_thrust_target[1] (N)`` in place of
        ``ref_chord`` with option ``design_thrust_target``).
    v_axial[K] (m/s), altitude[K] (m)
        Analysis conditions.
    rpm[K] (rpm)
        Rotor speed at each condition (an output with ``trim='rpm'``).
    collective_pitch[K] (rad)
        Pitch added to the twist at every station (an output with ``trim='collective_pitch'``).
    thrust_target[K] (N)
        Required thrust at each condition (with ``trim`` only).

    Outputs
    -------
    chord[1, nr] (m), twist[1, nr] (rad), radii[1, nr] (m), hub_radius[1] (m)
        The blade designed by BILD.
    design_<metric>[1]
        BILD's performance at the design condition, for every metric of
        :data:`~bild_mdo.bem.metrics.PERFORMANCE_OUTPUTS` (``design_thrust``, ``design_power`` ...).
    <metric>[K]
        BEM performance at each condition: ``thrust``, ``torque``, ``power``, ``efficiency``,
        ``figure_of_merit``, ``tip_mach`` ... (every metric of the registry).
    """

    def initialize(self):
        declare_size_options(self.options)
        self.options.declare("num_blades", types=int, default=3, desc="number of blades B")
        self.options.declare("polar", default=None, allow_none=True, recordable=False,
                             desc="airfoil Polar; None selects the built-in NACA 4412")
        self.options.declare("loss_model", default="tip_hub", values=LOSS_MODELS,
                             desc="Prandtl losses: 'tip_hub', 'tip' or 'none'")
        self.options.declare("chord_form", default="thrust", values=CHORD_FORMS,
                             desc="BILD chord from the thrust (Eq. (31)) or the torque balance")
        self.options.declare("root_chord_correction", default=None, allow_none=True,
                             desc="k of the root-chord correction Eq. (32); None for no correction")
        self.options.declare("design_thrust_target", types=bool, default=False,
                             desc="True: BILD solves ref_chord for input design_thrust_target (N)")
        self.options.declare("on_invalid", default="warn", values=ON_INVALID,
                             desc="BEM stations in an invalid flow state: 'warn', 'raise' or 'ignore'")
        self.options.declare("trim", default=None, values=TRIM_VARIABLES,
                             desc="per-condition quantity solved for thrust = thrust_target, or None")
        self.options.declare("trim_bounds", default=None, allow_none=True, check_valid=_check_trim_bounds,
                             desc="(lower, upper) of the trimmed quantity (rad or rpm); None for the defaults")
        declare_noise_options(self.options)

    def setup(self):
        opts = self.options
        nn, nr, trim = opts["num_nodes"], opts["num_radial"], opts["trim"]
        # One polar object for design and analyses (the built-in NACA 4412 unless given).
        polar = resolve_polar("naca4412") if opts["polar"] is None else opts["polar"]
        loss = dict(num_blades=opts["num_blades"], loss_model=opts["loss_model"])
        metrics = list(PERFORMANCE_OUTPUTS)
        by_thrust = opts["design_thrust_target"]
        design_inputs = [(name, f"design_{name}") for name in _DESIGN_CONDITION] + list(_DESIGN_INPUTS)
        design_outputs = ["chord", "twist", "radii", "hub_radius"] + [(m, f"design_{m}") for m in metrics]
        if by_thrust:
            design_inputs = [name for name in design_inputs if name != "ref_chord"]
            design_inputs.append(("thrust_target", "design_thrust_target"))
            design_outputs.append("ref_chord")

        self.add_subsystem(
            "design",
            BILDGroup(num_nodes=1, num_radial=nr, polar=polar, chord_form=opts["chord_form"],
                      root_chord_correction=opts["root_chord_correction"], thrust_target=by_thrust, **loss),
            promotes_inputs=design_inputs, promotes_outputs=design_outputs)

        self.add_subsystem("analysis", AnalysisGroup(num_nodes=nn, num_radial=nr, polar=polar,
                                                     on_invalid=opts["on_invalid"], trim=trim,
                                                     trim_bounds=opts["trim_bounds"], **loss),
                           promotes_outputs=metrics + ([trim] if trim else []))
        noise = make_noise_group(opts, nn, nr, opts["num_blades"], polar)
        if noise is not None:
            # Inputs are promoted or connected in configure, once the sources have declared theirs.
            self.add_subsystem("noise", noise, promotes_outputs=list(NOISE_OUTPUTS))
        condition = ["v_axial", "altitude", "rpm", "collective_pitch"]
        if trim is not None:
            condition.remove(trim)
            condition.append("thrust_target")
        self.promotes("analysis", inputs=condition + [("blade_chord", "chord"), ("blade_twist", "twist"),
                                                      ("blade_radius", "radius"),
                                                      ("blade_hub_radius", "hub_radius")])

        self.set_input_defaults("design_v_axial", val=np.zeros(1), units="m/s")
        self.set_input_defaults("design_rpm", val=np.full(1, 800.0), units="rpm")
        self.set_input_defaults("design_altitude", val=np.zeros(1), units="m")
        self.set_input_defaults("radius", val=np.full(1, 1.5), units="m")
        self.set_input_defaults("v_axial", val=np.zeros(nn), units="m/s")
        self.set_input_defaults("altitude", val=np.zeros(nn), units="m")
        if trim != "rpm":
            self.set_input_defaults("rpm", val=np.full(nn, 800.0), units="rpm")
        if trim != "collective_pitch":
            self.set_input_defaults("collective_pitch", val=np.zeros(nn), units="rad")
        if trim is not None:
            self.set_input_defaults("thrust_target", val=np.ones(nn), units="N")

    def configure(self):
        if self.options["noise_observers"] is None:
            return
        noise = self._get_subsystem("noise")
        names = {meta["prom_name"] for meta in noise.get_io_metadata(iotypes="input").values()}
        promoted = [name for name in ("observer_position", "v_axial", "rpm", "trailing_edge_thickness")
                    if name in names]
        self.promotes("noise", inputs=promoted)
        for name in sorted(names & set(_NOISE_SOURCES)):
            self.connect(_NOISE_SOURCES[name], f"noise.{name}")
