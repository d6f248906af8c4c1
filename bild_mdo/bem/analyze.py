"""Plain-Python entry point to the BEM analysis: :func:`analyze_rotor` and :class:`BEMResult`."""
from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np
import openmdao.api as om

from bild_mdo import validation
from bild_mdo.airfoil.text import polar_from
from bild_mdo.atmosphere import MAX_ALTITUDE, isa
from bild_mdo.bem.analyze_inclined import check_inflow, inclined_arguments, run_inclined
from bild_mdo.bem.bem_group import BEMAnalysisGroup
from bild_mdo.bem.blade_element import evaluate_section
from bild_mdo.bem.flow_states import ON_INVALID, SOLVE_RANGES
from bild_mdo.bem.inflow_residual import HIGH_INDUCTION, resolve_high_induction
from bild_mdo.bem.loads import SECTION_OUTPUTS
from bild_mdo.bem.metrics import PERFORMANCE_OUTPUTS, warn_supersonic_tip
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.fluid import resolve_fluid


def station_radii(radius, hub_radius, num_radial):
    """Default station radii: midpoints of ``num_radial`` equal annuli from hub to tip (m).

    Use these to sample chord and twist for :func:`analyze_rotor` when ``radii`` is not given.

    Returns
    -------
    ndarray
        Shape ``(num_radial,)`` for scalar radii, ``(nn, num_radial)`` for arrays.
    """
    radius = np.asarray(radius, dtype=float)[..., None]
    hub_radius = np.asarray(hub_radius, dtype=float)[..., None]
    return hub_radius + (np.arange(num_radial) + 0.5) * (radius - hub_radius) / num_radial


#: Per-station quantities of the analysis besides the section outputs: name -> units.
_STATE_UNITS = {"rho": "kg/m**3", "mu": "Pa*s", "speed_of_sound": "m/s",
                "radii": "m", "dr": "m", "phi": "rad", "flow_state": None}


def _to_dict(self):
    """All fields as a dict of numpy arrays (units in :attr:`UNITS`)."""
    return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}


# The fields follow the output registries (bem.metrics.METRICS, bem.loads.SECTION_OUTPUTS), so a new
# per-design metric appears here without an edit.
BEMResult = dataclasses.make_dataclass(
    "BEMResult",
    [(name, np.ndarray) for name in (*PERFORMANCE_OUTPUTS, *_STATE_UNITS, *SECTION_OUTPUTS, "residual")]
    + [("UNITS", ClassVar[dict], dataclasses.field(default={
        **{name: units for name, (units, _) in PERFORMANCE_OUTPUTS.items()},
        **_STATE_UNITS,
        **{name: units for name, (units, _) in SECTION_OUTPUTS.items()},
        "residual": None}))],
    frozen=True,
    namespace={"to_dict": _to_dict, "__module__": __name__},
)
BEMResult.__doc__ = """Result of :func:`analyze_rotor`.

    Per-design quantities (every entry of :data:`bild_mdo.bem.metrics.METRICS`, among them
    ``tip_mach``, plus ``rho``, ``mu`` and ``speed_of_sound``) have shape ``(nn,)`` for a batch
    and are 0-d arrays for a single case; distributions
    (``radii``, ``dr``, ``phi``, the section outputs of :data:`bild_mdo.bem.loads.SECTION_OUTPUTS`
    and the inflow ``residual``) have shape ``(nn, nr)`` or ``(nr,)``.  Units are listed in
    :attr:`UNITS` (SI; angles in rad; ``None`` = dimensionless).

    ``flow_state`` holds the integer code of every station (:mod:`bild_mdo.bem.flow_states`:
    0 no momentum solution (zero-loading fallback), 1 propeller, 2 propeller brake, 3 windmill,
    4 turbulent wake / vortex ring, 5 mirror root with ``solve_range='full'``).  ``residual`` is
    the momentum residual at ``phi``: zero to round-off except at code-0 stations, where no
    momentum equation is solved.

    ``efficiency`` (``V_x T / P``) and ``figure_of_merit`` (``T sqrt(|T|) / (P sqrt(2 rho pi R^2))``)
    hold the formula's value at every design (smooth, so derivatives exist), but they mean
    something only where ``thrust > 0`` and ``power > 0``: a windmilling rotor (T < 0, P < 0) can
    show an "efficiency" above 1 and a braking one a negative figure of merit.  Text tables
    print "n/a" there; filter with ``(result.thrust > 0) & (result.power > 0)``.
    """


#: Magnitudes the analysis accepts: name -> (lowest, highest, units).  They lie far beyond any rotor
#: (a micrometre to 1,000 km, up to 1e12 rpm, a third of the speed of light) and keep the products and
#: powers of the BEM (W^2, rho n^3 D^5, V_x / (Omega r)) inside the floating-point range, so an
#: accepted input gives finite numbers instead of overflow.
PLAUSIBLE_RANGES = {
    "radius": (1e-6, 1e6, "m"), "hub_radius": (0.0, 1e6, "m"), "chord": (1e-9, 1e6, "m"),
    "radii": (1e-6, 1e6, "m"), "dr": (1e-12, 1e6, "m"), "rpm": (1e-6, 1e12, "rpm"),
    "v_axial": (0.0, 1e8, "m/s"), "rho": (1e-12, 1e6, "kg/m**3"), "mu": (1e-12, 1e6, "Pa*s"),
    "speed_of_sound": (1e-3, 1e8, "m/s"), "num_blades": (1, 1000, None),
    # Angles: one turn either way (a larger angle is the same blade; the polars take alpha in one turn).
    "twist": (-2.0 * np.pi, 2.0 * np.pi, "rad"), "collective_pitch": (-2.0 * np.pi, 2.0 * np.pi, "rad"),
}


def _plausible(name, value):
    """Reject a magnitude outside :data:`PLAUSIBLE_RANGES` with one line naming the bound and why."""
    low, high, units = PLAUSIBLE_RANGES[name]
    why = ("one turn either way; a larger angle is the same blade" if units == "rad" else
           "far beyond any rotor; larger or smaller magnitudes would overflow the BEM's floating-point arithmetic")
    # An integer count may exceed the float range: compare it capped.
    arr = np.asarray(min(value, 10**300) if isinstance(value, int) else value, dtype=float)
    bad = (arr > high) | (arr < low)
    validation.check(name, arr, bad, f"within {low:g} ... {high:g}", units=units, hint=why)


def _axes(value):
    """Names of the axes of a distribution argument, for error messages."""
    return ("design", "station") if np.ndim(value) == 2 else ("station",)


def _voronoi_widths(radii, hub_radius, radius):
    """Widths of the cells around given station radii, bounded by hub and tip."""
    mid = 0.5 * (radii[:, 1:] + radii[:, :-1])
    edges = np.concatenate([hub_radius[:, None], mid, radius[:, None]], axis=1)
    return np.diff(edges, axis=1)


def analyze_rotor(chord, twist, radius, hub_radius, rpm, v_axial, num_blades, polar,
                  altitude=0.0, loss_model="tip_hub", radii=None, dr=None, rho=None, mu=None,
                  on_invalid="warn", solve_range="physical", collective_pitch=0.0, speed_of_sound=None, fluid=None,
                  rotor_type="propeller", precone=0.0, tilt=0.0, yaw=0.0, hub_height=None, shear_exponent=0.0,
                  num_sectors=1, high_induction=None):
    """Analyse one rotor or a batch of rotors with BEM theory: in axial flow, inclined flow, or as a wind turbine.

    Parameters
    ----------
    chord : array_like
        Chord at the stations (m), shape ``(nr,)`` or ``(nn, nr)``.
    twist : array_like
        Twist (pitch) angle at the stations (rad), same shape as ``chord``.
    radius, hub_radius : float or array_like
        Tip and hub radius (m), scalar or ``(nn,)``; ``0 <= hub_radius < radius``
        (``hub_radius > 0`` with ``loss_model='tip_hub'``).
    rpm : float or array_like
        Rotational speed (rpm), > 0.
    v_axial : float or array_like
        Freestream axial velocity (m/s), >= 0 (0 is hover).
    num_blades : int
        Number of blades.
    polar : Polar or str
        Airfoil polar, or airfoil text as :func:`~bild_mdo.airfoil.text.sweep_polar` reads it (a built-in name
        such as ``'naca4412'`` or ``'analytic'``, a NACA designation, polar files, a polar frozen at one Reynolds
        number ``'naca4412@re=2e6'``, a spanwise set ``'0.2:naca4415;1:naca4412'``).
    altitude : float or array_like
        Geometric altitude (m) for the ISA, 0 ... 11,000.  With ``rho`` and ``mu`` given it
        sets only the speed of sound (unless ``speed_of_sound`` is given too).
    loss_model : {'tip_hub', 'tip', 'none'}
        Prandtl loss factor model.
    radii : array_like, optional
        Station radii (m), shape ``(nr,)`` or ``(nn, nr)``, increasing, within
        ``[hub_radius, radius]``.  Default: midpoints of equal annuli
        (:func:`station_radii`).
    dr : array_like, optional
        Station widths (m) for ``radii``; default: cells between the midpoints of
        neighbouring stations, bounded by hub and tip.
    rho, mu : float or array_like, optional
        Air density (kg/m^3) and viscosity (Pa s) overriding the ISA (give both).
    speed_of_sound : float or array_like, optional
        Speed of sound (m/s) for the Mach numbers, with ``rho`` and ``mu`` only; default the
        ISA's at ``altitude``.
    collective_pitch : float or array_like
        Collective pitch (rad), scalar or ``(nn,)``, added to ``twist`` at every station.
    fluid : Fluid, str or (rho, mu, speed_of_sound), optional
        Any fluid (:mod:`bild_mdo.fluid`: ``'water'``, ``'seawater'``, ``'air'`` ...) instead of the
        ISA; the same as giving its ``rho``, ``mu`` and ``speed_of_sound`` (not together with them).

    on_invalid : {'warn', 'raise', 'ignore'}
        Stations in a flow state the momentum model does not represent: no momentum solution
        (zero loading returned), turbulent wake / vortex ring (``V_x > 0``, ``dT < 0``, axial
        induction ``a > 0.4``; ``a > 0.95`` instead with ``high_induction='buhl'``) or, with
        ``solve_range='full'``, a mirror root (``W < 0``); see
        :mod:`bild_mdo.bem.flow_states`.  'warn' (default): one
        :class:`~bild_mdo.bem.flow_states.BEMStateWarning` naming them (node, station, r/R, state;
        the first few and the count); 'raise': :class:`openmdao.api.AnalysisError` naming them;
        'ignore': nothing (the codes are still in ``result.flow_state``).
    solve_range : {'physical', 'full'}
        'physical' (default): CCBlade.jl's search order (Q1, then flow reversed through the disk,
        then, for ``V_x > 0``, reversed tangential flow), accepting only roots with ``W > 0``.
        'full': the first sign change of the residual in ``[-pi/2, pi)``, as before the flow
        states existed (mirror roots kept and flagged).
    high_induction : {None, 'none', 'buhl'}
        The momentum thrust of an annulus past ``a = 0.4`` (``V_x > 0``): 'none', momentum theory, the
        station flagged ``TURBULENT_WAKE``; 'buhl', Buhl's (2005) empirical thrust, as CCBlade and AeroDyn
        apply, the station valid up to ``a = 0.95`` (:mod:`bild_mdo.bem.inflow_residual`).  None (default): 'buhl' for a
        turbine, 'none' for a propeller.
    rotor_type : {'propeller', 'turbine'}
        'propeller' (default): thrust-producing rotors, as always.  'turbine': a wind turbine,
        ``v_axial`` the wind speed at hub height (> 0), ``polar`` the airfoil's own polar,
        ``twist + collective_pitch`` CCBlade's ``theta`` (``alpha = phi - theta``); the result is a
        :class:`~bild_mdo.bem.analyze_inclined.TurbineBEMResult` (power extracted, C_P, C_T,
        tip-speed ratio; :class:`~bild_mdo.bem.inclined_bem_group.InclinedBEMGroup`).
    precone, tilt, yaw : float or array_like
        Precone, shaft tilt and yaw (rad), scalar or ``(nn,)``, in ``(-pi/2, pi/2)``; CCBlade's
        conventions (:mod:`bild_mdo.bem.wind_components`).  Radii are then distances along the blade.
    hub_height : float or array_like, optional
        Hub height above the ground (m), > radius; needed with ``shear_exponent``.
    shear_exponent : float or array_like
        Power-law wind shear ``V = v_axial (1 + z / hub_height)**shear_exponent``, 0 ... 1 (default 0).
    num_sectors : int
        Azimuth sectors averaged (default 1; CCBlade uses at least 4 with tilt, yaw or shear).
        Any of these options (or a turbine) gives an
        :class:`~bild_mdo.bem.analyze_inclined.InclinedBEMResult` (per-sector stations, shape
        ``(nn, ns, nr)``); all at their defaults, the axial analysis and its :class:`BEMResult`.

    Returns
    -------
    BEMResult, InclinedBEMResult or TurbineBEMResult

    Raises
    ------
    ValueError
        Invalid input (the message names the argument), including magnitudes outside
        :data:`PLAUSIBLE_RANGES` (far beyond any rotor; they would overflow the arithmetic).
    openmdao.api.AnalysisError
        With ``on_invalid='raise'`` and invalid stations; with ``solve_range='full'`` where no
        sign change exists; where the total torque is zero (no performance metrics).
    """
    polar = polar_from(polar)
    if fluid is not None:
        if rho is not None or mu is not None or speed_of_sound is not None:
            raise ValueError("give either fluid or rho, mu (and speed_of_sound), not both")
        fluid = resolve_fluid(fluid)
        rho, mu, speed_of_sound = fluid.rho, fluid.mu, fluid.speed_of_sound
    validation.choice("loss_model", loss_model, LOSS_MODELS)
    validation.choice("on_invalid", on_invalid, ON_INVALID)
    validation.choice("solve_range", solve_range, SOLVE_RANGES)
    high_induction = resolve_high_induction(high_induction, rotor_type)
    validation.choice("high_induction", high_induction, HIGH_INDUCTION)
    num_blades = validation.integer("num_blades", num_blades)
    if (rho is None) != (mu is None):
        raise ValueError("give both rho and mu, or neither (then the ISA at altitude is used)")
    if speed_of_sound is not None and rho is None:
        raise ValueError("speed_of_sound overrides the ISA together with rho and mu; give rho and mu too, "
                         "or leave it out (then the ISA at altitude is used)")
    geometry, num_sectors, inclined = inclined_arguments(rotor_type, precone, tilt, yaw, hub_height, shear_exponent,
                                                         num_sectors)

    chord = validation.positive("chord", chord, units="m", ndim=(1, 2), axes=_axes(chord))
    twist = validation.real_array("twist", twist, units="rad", ndim=(1, 2))
    if twist.shape != chord.shape:
        raise ValueError(f"twist must have the shape of chord {chord.shape}, got {twist.shape}")
    nr = chord.shape[-1]

    scalars = {"radius": validation.positive("radius", radius, units="m"),
               "hub_radius": validation.non_negative("hub_radius", hub_radius, units="m"),
               "rpm": validation.positive("rpm", rpm, units="rpm"),
               "v_axial": validation.non_negative("v_axial", v_axial, units="m/s",
                                                  hint="axial inflow from ahead; 0 is hover"),
               "collective_pitch": validation.real_array("collective_pitch", collective_pitch, units="rad")}
    if speed_of_sound is None:
        scalars["altitude"] = validation.in_range("altitude", altitude, 0.0, MAX_ALTITUDE, units="m",
                                                  hint="ISA troposphere")
    else:
        scalars["speed_of_sound"] = validation.positive("speed_of_sound", speed_of_sound, units="m/s")
    if rho is not None:
        scalars.update(rho=validation.positive("rho", rho, units="kg/m**3"),
                       mu=validation.positive("mu", mu, units="Pa*s"))
    if rotor_type == "turbine":
        scalars["v_axial"] = validation.positive("v_axial", v_axial, units="m/s", hint="the wind speed at hub height")
    sizes = {name: arr.size for name, arr in (*scalars.items(), *geometry.items()) if arr is not None and arr.ndim == 1}
    if chord.ndim == 2:
        sizes["chord"] = chord.shape[0]
    extra = {}
    for name, val in (("radii", radii), ("dr", dr)):
        if val is not None:
            arr = validation.positive(name, val, units="m", ndim=(1, 2), axes=_axes(val))
            if arr.shape[-1:] != (nr,):
                raise ValueError(f"{name} must have shape ({nr},) or (nn, {nr}) like chord, got {arr.shape}")
            if arr.ndim == 2:
                sizes[name] = arr.shape[0]
            extra[name] = arr
    nn = validation.batch_size(sizes)
    single = not sizes

    def per_node(arr):
        return np.broadcast_to(arr, (nn,)).astype(float)

    def per_station(arr):
        return np.broadcast_to(arr, (nn, nr)).astype(float)

    s = {k: per_node(v) for k, v in scalars.items()}
    chord, twist = per_station(chord), per_station(twist)
    for name, value in (*s.items(), ("chord", chord), ("twist", twist), ("num_blades", num_blades)):
        if name in PLAUSIBLE_RANGES:
            _plausible(name, value)
    for name, value in extra.items():
        _plausible(name, value)
    if loss_model == "tip_hub":
        validation.check("hub_radius", s["hub_radius"], s["hub_radius"] <= 0.0, "positive with loss_model='tip_hub'",
                         hint="use 'tip' without a hub")
    validation.smaller("hub_radius", s["hub_radius"], "radius", s["radius"], hint="the tip radius")

    group_kw = {}
    if "radii" in extra:
        r = per_station(extra["radii"])
        validation.check("radii", r, (r < s["hub_radius"][:, None]) | (r > s["radius"][:, None]),
                         "within [hub_radius, radius]", units="m")
        if nr > 1 and np.any(np.diff(r, axis=1) <= 0.0):
            raise ValueError("radii must be strictly increasing")
        if "dr" in extra:
            widths = per_station(extra["dr"])
        else:
            widths = _voronoi_widths(r, s["hub_radius"], s["radius"])
        group_kw = dict(radial_fractions=r / s["radius"][:, None],
                        width_fractions=widths / s["radius"][:, None])
    elif "dr" in extra:
        raise ValueError("dr needs radii (station widths belong to given station radii)")

    use_atmosphere = "rho" not in s
    if not use_atmosphere and "speed_of_sound" not in s:
        s["speed_of_sound"] = np.asarray(isa(s["altitude"]).speed_of_sound, dtype=float)
    validation.memory_bound("designs", nn * num_sectors, nr, hint="analyse in smaller batches or with fewer stations")
    if inclined:
        geometry = {name: per_node(10.0 * s["radius"] if value is None else value) for name, value in geometry.items()}
        radii_all = (per_station(extra["radii"]) if "radii" in extra
                     else station_radii(s["radius"], s["hub_radius"], nr).reshape(nn, nr))
        check_inflow(s, radii_all, geometry, num_sectors)
        values = dict({k: v for k, v in s.items() if k != "altitude" or use_atmosphere}, chord=chord, twist=twist)
        group_kw.update(num_blades=int(num_blades), polar=polar, loss_model=loss_model, use_atmosphere=use_atmosphere,
                        on_invalid=on_invalid, solve_range=solve_range, high_induction=high_induction)
        return run_inclined(values, group_kw, nn, nr, single, rotor_type, num_sectors, geometry)
    prob = om.Problem(BEMAnalysisGroup(num_nodes=nn, num_radial=nr, num_blades=int(num_blades),
                                       polar=polar, loss_model=loss_model,
                                       use_atmosphere=use_atmosphere, on_invalid=on_invalid,
                                       solve_range=solve_range, high_induction=high_induction, **group_kw),
                      reports=False)
    prob.setup(check=False)
    for name in ("radius", "hub_radius", "rpm", "v_axial", "collective_pitch"):
        prob.set_val(name, s[name])
    prob.set_val("chord", chord)
    prob.set_val("twist", twist)
    if use_atmosphere:
        prob.set_val("altitude", s["altitude"])
    else:
        prob.set_val("rho", s["rho"])
        prob.set_val("mu", s["mu"])
        prob.set_val("speed_of_sound", s["speed_of_sound"])
    prob.run_model()

    fields = {f.name: np.array(prob.get_val(f.name)) for f in dataclasses.fields(BEMResult)
              if f.name != "residual"}
    node = {name: fields[name][:, None] if name in fields else s[name][:, None]
            for name in ("v_axial", "rpm", "rho", "mu", "radius", "hub_radius", "speed_of_sound",
                         "collective_pitch")}
    values, _ = evaluate_section(fields["phi"], radii=fields["radii"], chord=chord, twist=twist,
                                 num_blades=int(num_blades), polar=polar, loss_model=loss_model,
                                 loads=False, partials=False, high_induction=high_induction, **node)
    fields["residual"] = values["residual"]
    fields["flow_state"] = np.rint(fields["flow_state"]).astype(int)
    warn_supersonic_tip(fields["tip_mach"], what="rotor")
    if single:
        fields = {k: v[0] for k, v in fields.items()}
    return BEMResult(**fields)
