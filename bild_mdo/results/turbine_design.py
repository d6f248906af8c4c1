"""Python design API for turbines: :func:`design_turbine` runs the turbine BILD and returns a :class:`TurbineDesign`.

::

    from bild_mdo.results.turbine_design import design_turbine

    rotor = design_turbine(wind_speed=10.0, tip_speed_ratio=7.0, radius=40.0)   # maximum power
    print(rotor.summary())
    limited = design_turbine(wind_speed=10.0, tip_speed_ratio=7.0, radius=40.0, thrust=2.0e5)

Scalars give one design; 1-D arrays (broadcast against each other) give a batch in one vectorised run of
:class:`~bild_mdo.bild.turbine_group.TurbineBILDGroup`.
"""
from __future__ import annotations

import numpy as np

from bild_mdo import validation
from bild_mdo.atmosphere import MAX_ALTITUDE
from bild_mdo.bem.flow_states import CRITICAL_INDUCTION
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bild.turbine_problem import TURBINE_DISTRIBUTIONS, TURBINE_VALUES, run_turbine_bild  # noqa: F401
from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.fluid import fluid_arrays, resolve_fluid
from bild_mdo.io.airfoil import resolve_airfoil
from bild_mdo.results.batch_values import BatchValues
from bild_mdo.results.design import reynolds_outside_data

__all__ = ["TurbineDesign", "design_turbine"]



class TurbineDesign(BatchValues):
    """The ideal turbine blade(s) and performance from :func:`design_turbine` (SI units, angles in rad).

    Attributes (arrays ``(nn,)`` / ``(nn, nr)`` for a batch, scalars / ``(nr,)`` for one design): the inputs
    ``wind_speed, rpm, radius, hub_radius_ratio, ref_radius_ratio``; :data:`TURBINE_VALUES` (``power`` W,
    ``thrust`` N, ``power_coefficient``, ``thrust_coefficient``, ``tip_speed_ratio`` ...) and
    :data:`TURBINE_DISTRIBUTIONS` (``radii``, ``chord``, ``twist`` ...), plus ``radial_fractions`` and, as for a
    propeller design, ``reynolds`` (each station's chord Reynolds number ``rho W c / mu``) and
    ``reynolds_outside_data`` (1.0 where it lies outside the polar's data, which extrapolates there; the
    summary lists those stations).
    ``num_blades``, ``airfoil``, ``loss_model`` and ``member`` (``'maximum power'``, ``'thrust'`` or
    ``'ref_chord'``) describe the design; ``altitude`` or ``fluid`` its air.
    """

    def __init__(self, values, num_blades, airfoil, loss_model, member, polar, is_batch, fluid=None):
        self.values = values
        self.num_blades, self.airfoil, self.loss_model, self.member = num_blades, airfoil, loss_model, member
        self.polar = polar
        self.is_batch = is_batch
        self.fluid = fluid

    def __getitem__(self, index):
        return TurbineDesign(self._row_values(index), self.num_blades, self.airfoil, self.loss_model, self.member,
                             self.polar, is_batch=False, fluid=self.fluid)

    def power_curve(self, rated_power, max_tip_speed=None, **options):
        """The power curve and AEP of the designed blade(s) at their design tip-speed ratio
        (:func:`~bild_mdo.results.power_curve.power_curve`: ``rated_power`` in W, ``max_tip_speed`` in m/s or
        None, and its keyword options ``weibull_scale``, ``weibull_shape``, ``cut_in_speed``, ``cut_out_speed``,
        ``num_wind_speeds``, ``high_induction``); the blade's airfoil, loss model and air are the design's."""
        from bild_mdo.results.power_curve import power_curve

        one = (lambda value: value) if self.is_batch else (lambda value: value[0])
        values = {name: one(value) for name, value in self.values.items()}
        air = {"fluid": self.fluid} if self.fluid is not None else {"altitude": values["altitude"]}
        return power_curve(values["chord"], values["twist"], values["radius"],
                           values["radius"] * values["hub_radius_ratio"], values["tip_speed_ratio"], rated_power,
                           num_blades=self.num_blades, airfoil=self.polar, loss_model=self.loss_model,
                           max_tip_speed=max_tip_speed, **air, **options)

    def summary(self):
        """A text summary of the design (the first one of a batch, with the batch size)."""
        one = self if not self.is_batch else self[0]
        head = f"Turbine BILD design ({self.member}); {self.num_blades} blades, airfoil {self.airfoil}, " \
               f"loss model {self.loss_model}" + (f"; design 1 of {len(self)}" if self.is_batch else "")
        rows = [("wind speed", one.wind_speed, "m/s"), ("rotor speed", one.rpm, "rpm"),
                ("radius", one.radius, "m"), ("tip-speed ratio", one.tip_speed_ratio, "-"),
                ("power", one.power / 1e3, "kW"), ("thrust", one.thrust / 1e3, "kN"),
                ("power coefficient C_P", one.power_coefficient, "-"),
                ("thrust coefficient C_T", one.thrust_coefficient, "-"),
                ("multiplier mu", one.power_thrust_multiplier, "m/s"), ("reference chord", one.ref_chord, "m"),
                ("section point alpha*", np.degrees(one.alpha_star), "deg"),
                ("section C_l*/C_d*", one.cl_star / one.cd_star if one.cd_star > 0 else np.inf, "-"),
                ("reference Reynolds number", one.reynolds_ref, "-")]
        lines = [head, "-" * len(head)] + [f"  {label:<28s} {value:>12.5g} {units}" for label, value, units in rows]
        lines.append("  stations: r/R      chord [m]   twist [deg]      a        a'")
        for frac, chord, twist, a, a_t in zip(one.radial_fractions, one.chord, np.degrees(one.twist),
                                              one.axial_induction, one.tangential_induction):
            lines.append(f"  {frac:15.4f} {chord:12.5g} {twist:12.4f} {a:9.4f} {a_t:9.5f}")
        notes = []
        outside = np.flatnonzero(one.reynolds_outside_data > 0.0)
        if outside.size:
            re = one.reynolds[outside]
            notes.append(f"  {outside.size} station(s) outside the polar's Reynolds-number data, extrapolated there "
                         f"(Re {np.min(re):.3g}..{np.max(re):.3g}) at r/R "
                         + ", ".join(f"{x:.3f}" for x in one.radial_fractions[outside]))
        heavy = np.flatnonzero(one.axial_induction > CRITICAL_INDUCTION)
        if heavy.size:
            notes.append(f"  {heavy.size} station(s) past a = {CRITICAL_INDUCTION:g} (r/R "
                         + ", ".join(f"{x:.3f}" for x in one.radial_fractions[heavy])
                         + "): the loading has momentum theory's thrust there; a turbine BEM analysis applies Buhl's "
                         "correction by default (analyze_rotor(..., high_induction='none') reproduces the design)")
        return "\n".join(lines + (["notes:"] + notes if notes else []))


def _station_reynolds(out, polar):
    """``reynolds`` and ``reynolds_outside_data`` of every station (as
    :func:`~bild_mdo.results.design.station_reynolds` for a propeller)."""
    reynolds = out["rho"][:, None] * out["inflow_speed"] * out["chord"] / out["mu"][:, None]
    return {"reynolds": reynolds, "reynolds_outside_data": reynolds_outside_data(reynolds, out["chord"], polar)}


def _inputs(wind_speed, tip_speed_ratio, rpm, radius, hub_radius_ratio, ref_radius_ratio, altitude, thrust,
            ref_chord):
    values = {"wind_speed": validation.positive("wind_speed", wind_speed, units="m/s"),
              "radius": validation.positive("radius", radius, units="m")}
    if rpm is not None:
        values["rpm"] = validation.positive("rpm", rpm, units="rpm")
    else:
        values["tip_speed_ratio"] = validation.positive("tip_speed_ratio", tip_speed_ratio)
    for name, value in (("hub_radius_ratio", hub_radius_ratio), ("ref_radius_ratio", ref_radius_ratio)):
        values[name] = validation.in_range(name, value, 0.0, 1.0, open_low=True, open_high=True)
    validation.smaller("hub_radius_ratio", values["hub_radius_ratio"], "ref_radius_ratio",
                       values["ref_radius_ratio"], hint="the reference station lies on the blade")
    values["altitude"] = validation.in_range("altitude", altitude, 0.0, MAX_ALTITUDE, units="m", hint="ISA")
    if thrust is not None:
        values["thrust"] = validation.positive("thrust", thrust, units="N")
    if ref_chord is not None:
        values["ref_chord"] = validation.positive("ref_chord", ref_chord, units="m")
    return values


def design_turbine(wind_speed=10.0, tip_speed_ratio=None, rpm=None, radius=40.0, hub_radius_ratio=0.05,
                   ref_radius_ratio=0.7, num_blades=3, airfoil="naca4412", loss_model="tip_hub", num_radial=30,
                   thrust=None, ref_chord=None, altitude=0.0, fluid=None):
    """Design the ideal turbine rotor(s) by the turbine BILD loading (:mod:`bild_mdo.bild.variants.turbine`).

    The design extracts the most power at the tip-speed ratio (the member ``mu = 0``) unless ``thrust``
    (the member whose thrust is ``thrust``: the most power for that thrust) or ``ref_chord`` (the member
    with that chord at ``r_ref``) picks another member of the family.

    Parameters
    ----------
    wind_speed : float or array_like
        Wind speed V (m/s), > 0.
    tip_speed_ratio : float or array_like, optional
        ``Omega R / V`` (-), > 0.  Default 7 (unless ``rpm`` is given).
    rpm : float or array_like, optional
        Rotor speed (rpm), > 0, instead of ``tip_speed_ratio``.
    radius : float or array_like
        Tip radius R (m).
    hub_radius_ratio, ref_radius_ratio : float or array_like
        Hub and reference radii over R, ``0 < hub < ref < 1``.
    num_blades : int
        Number of blades B.
    airfoil : str or Polar
        Anything :func:`~bild_mdo.io.airfoil.resolve_airfoil` accepts (one airfoil along the span).
    loss_model : {'tip_hub', 'tip', 'none'}
        Prandtl loss factor (inside the loading, differentiated).
    num_radial : int
        Radial stations (midpoints of equal annuli).
    thrust : float or array_like, optional
        Thrust of the member (N), > 0.
    ref_chord : float or array_like, optional
        Chord at ``r_ref`` (m), > 0 (not with ``thrust``).
    altitude : float or array_like
        ISA altitude (m); or ``fluid`` (:mod:`bild_mdo.fluid`), then altitude stays 0.

    Returns
    -------
    TurbineDesign

    Raises
    ------
    ValueError
        For invalid inputs (one line naming the argument).
    openmdao.api.AnalysisError
        If the member does not exist (a thrust above the windmill state's largest, or a reference chord
        that loads the reference station to ``a = 1/2``).
    """
    if rpm is not None and tip_speed_ratio is not None:
        raise ValueError("give either tip_speed_ratio or rpm [rpm], not both")
    if thrust is not None and ref_chord is not None:
        raise ValueError("give either thrust [N] or ref_chord [m] (or neither: maximum power), not both")
    tip_speed_ratio = 7.0 if rpm is None and tip_speed_ratio is None else tip_speed_ratio
    num_blades = validation.integer("num_blades", num_blades)
    num_radial = validation.integer("num_radial", num_radial, minimum=2)
    validation.choice("loss_model", loss_model, LOSS_MODELS)
    if fluid is not None:
        fluid = resolve_fluid(fluid)
        if np.any(np.asarray(altitude, dtype=float) != 0.0):
            raise ValueError("give either altitude [m] (the ISA) or fluid, not both")
    polar = resolve_airfoil(airfoil)
    if polar.varies_along_span:
        raise ValueError("airfoil: the turbine BILD takes one airfoil along the span")
    values = _inputs(wind_speed, tip_speed_ratio, rpm, radius, hub_radius_ratio, ref_radius_ratio, altitude,
                     thrust, ref_chord)
    is_batch = any(arr.ndim == 1 for arr in values.values())
    nn = validation.batch_size({name: arr.size for name, arr in values.items() if arr.ndim == 1})
    values = {name: np.broadcast_to(arr, (nn,)).astype(float) for name, arr in values.items()}
    if rpm is None:
        values["rpm"] = values.pop("tip_speed_ratio") * values["wind_speed"] / values["radius"] / RPM_TO_RAD_PER_S
    design_for = "thrust" if thrust is not None else ("ref_chord" if ref_chord is not None else "multiplier")

    out = run_turbine_bild(values, num_radial, num_blades, polar, loss_model, design_for,
                           None if fluid is None else fluid_arrays(fluid, nn))
    out["radial_fractions"] = out["radii"] / values["radius"][:, None]
    out.update(_station_reynolds(out, polar))
    result = {"wind_speed": values["wind_speed"], **{name: values[name] for name in
                                                     ("rpm", "radius", "hub_radius_ratio", "ref_radius_ratio",
                                                      "altitude")},
              **out}
    member = {"multiplier": "maximum power", "thrust": "thrust", "ref_chord": "ref_chord"}[design_for]
    return TurbineDesign(result, num_blades, getattr(polar, "name", type(polar).__name__), loss_model, member,
                         polar, is_batch, fluid=fluid)
