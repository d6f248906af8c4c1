"""The inclined-flow and wind-turbine path of :func:`~bild_mdo.bem.analyze.analyze_rotor` and its result objects."""
from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np
import openmdao.api as om

from bild_mdo import validation
from bild_mdo.bem.blade_element import evaluate_section
from bild_mdo.bem.inflow_residual import resolve_high_induction
from bild_mdo.bem.inclined_bem_group import ROTOR_TYPES, InclinedBEMGroup
from bild_mdo.bem.loads import SECTION_OUTPUTS
from bild_mdo.bem.metrics import PERFORMANCE_OUTPUTS, TURBINE_OUTPUTS, warn_supersonic_tip
from bild_mdo.bem.sectors import sector_azimuths
from bild_mdo.bem.turbine_polar import TurbinePolar
from bild_mdo.bem.wind_components import wind_components

#: Largest number of azimuth sectors accepted (one per degree).
MAX_SECTORS = 360
#: Per-station fields of every sector, shape (nn, ns, nr): name -> units.
_SECTOR_UNITS = {"v_axial_local": "m/s", "v_theta_local": "m/s", "phi": "rad", "flow_state": None,
                 **{name: units for name, (units, _) in SECTION_OUTPUTS.items() if name not in ("dthrust_dr",
                                                                                                "dtorque_dr")},
                 "sector_dthrust_dr": "N/m", "sector_dtorque_dr": "N*m/m", "residual": None}
_STATE_UNITS = {"rho": "kg/m**3", "mu": "Pa*s", "speed_of_sound": "m/s", "radii": "m", "dr": "m",
                "dthrust_dr": "N/m", "dtorque_dr": "N*m/m", "azimuth": "rad"}
#: Station fields whose sign a turbine's result flips to its own convention (:mod:`bild_mdo.bem.turbine_polar`).
TURBINE_FLIPPED = ("alpha", "lift_coefficient", "sector_dthrust_dr", "sector_dtorque_dr", "dthrust_dr", "dtorque_dr")


def _to_dict(self):
    """All fields as a dict of numpy arrays (units in :attr:`UNITS`)."""
    return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}


def _result_class(name, outputs, doc):
    units = {**{n: u for n, (u, _) in outputs.items()}, **_STATE_UNITS, **_SECTOR_UNITS}
    cls = dataclasses.make_dataclass(
        name, [(n, np.ndarray) for n in units] + [("UNITS", ClassVar[dict], dataclasses.field(default=units))],
        frozen=True, namespace={"to_dict": _to_dict, "__module__": __name__})
    cls.__doc__ = doc
    return cls


_LAYOUT = """

    Per-design fields have shape ``(nn,)`` (0-d for a single case); ``radii``, ``dr`` and the
    sector-mean loads along the shaft ``dthrust_dr``, ``dtorque_dr`` have shape ``(nn, nr)``; the
    fields of every azimuth sector (``v_axial_local``, ``v_theta_local``, ``phi``, ``flow_state``,
    the station outputs of :data:`bild_mdo.bem.loads.SECTION_OUTPUTS`, ``sector_dthrust_dr``,
    ``sector_dtorque_dr`` and the momentum ``residual``) have shape ``(nn, ns, nr)`` (``(ns, nr)``
    for a single case), at the angles ``azimuth[ns]`` (rad).  Units in :attr:`UNITS`.
    """
InclinedBEMResult = _result_class("InclinedBEMResult", PERFORMANCE_OUTPUTS, """Result of
    :func:`~bild_mdo.bem.analyze.analyze_rotor` for a propeller or lift rotor with precone, tilt, yaw,
    shear or several sectors: the per-design metrics of :data:`bild_mdo.bem.metrics.METRICS` from the
    sector-averaged loads, and every sector's stations.""" + _LAYOUT)
TurbineBEMResult = _result_class("TurbineBEMResult", TURBINE_OUTPUTS, """Result of
    :func:`~bild_mdo.bem.analyze.analyze_rotor` with ``rotor_type='turbine'``: the turbine-signed metrics
    of :data:`bild_mdo.bem.metrics.TURBINE_METRICS` (thrust downwind, driving torque, power extracted,
    C_P, C_T, C_Q, tip-speed ratio) and the stations in the turbine's convention: ``alpha = phi -
    theta``, the airfoil's own ``lift_coefficient``, loads positive downwind and driving the rotor
    (:data:`TURBINE_FLIPPED`; ``phi``, ``u_axial`` and ``u_theta`` stay those of the kernel).""" + _LAYOUT)


def inclined_arguments(rotor_type, precone, tilt, yaw, hub_height, shear_exponent, num_sectors):
    """Validate the inclined-flow arguments of :func:`~bild_mdo.bem.analyze.analyze_rotor`.

    Returns
    -------
    geometry : dict
        Name of :data:`~bild_mdo.bem.wind_components.INFLOW_GEOMETRY` -> array (scalar or (nn,));
        ``hub_height`` None when not given.
    num_sectors : int
    inclined : bool
        Whether the inclined-flow path is needed (a turbine, an angle or shear, or several sectors).
    """
    validation.choice("rotor_type", rotor_type, ROTOR_TYPES)
    num_sectors = validation.integer("num_sectors", num_sectors)
    if num_sectors > MAX_SECTORS:
        raise ValueError(f"num_sectors must be at most {MAX_SECTORS}, got {num_sectors}")
    geometry = {}
    for name, value in (("precone", precone), ("tilt", tilt), ("yaw", yaw)):
        geometry[name] = validation.in_range(name, value, -0.5 * np.pi, 0.5 * np.pi, open_low=True, open_high=True,
                                             units="rad", hint="the wind must reach the rotor from ahead")
    geometry["shear_exponent"] = validation.in_range("shear_exponent", shear_exponent, 0.0, 1.0,
                                                     hint="power-law wind shear; 0 is uniform wind")
    if hub_height is None and np.any(geometry["shear_exponent"] != 0.0):
        raise ValueError("give hub_height (m) with a nonzero shear_exponent: the wind shear is relative to it")
    geometry["hub_height"] = None if hub_height is None else validation.positive("hub_height", hub_height, units="m")
    inclined = (rotor_type != "propeller" or num_sectors > 1
                or any(np.any(geometry[name] != 0.0) for name in ("precone", "tilt", "yaw", "shear_exponent")))
    return geometry, num_sectors, inclined


def check_inflow(s, radii, geometry, num_sectors):
    """ValueError where the blade reaches the ground or the in-plane wind reverses a station's tangential flow."""
    validation.check("hub_height", geometry["hub_height"], geometry["hub_height"] <= s["radius"],
                     "larger than the tip radius (the blade must clear the ground)", units="m")
    values = dict(geometry, v_axial=s["v_axial"], rpm=s["rpm"], radii=radii)
    _, v_theta = wind_components(values, num_sectors)
    bad = v_theta.reshape(radii.shape[0], num_sectors, -1) <= 0.0
    if np.any(bad):
        node, sector, station = np.unravel_index(int(np.flatnonzero(bad)[0]), bad.shape)
        raise ValueError(f"yaw and tilt are too large for the rotor speed: the in-plane wind reverses the flow "
                         f"at station {station} (r = {radii[node, station]:.4g} m) in sector {sector} (design "
                         f"{node}); the BEM needs V_theta = Omega r cos(precone) + in-plane wind > 0 (raise rpm, "
                         "lower yaw or tilt)")


def run_inclined(prob_values, group_kw, nn, nr, single, rotor_type, num_sectors, geometry):
    """Run :class:`~bild_mdo.bem.inclined_bem_group.InclinedBEMGroup` and collect the result object.

    Parameters
    ----------
    prob_values : dict
        Input name -> array of the group (already validated, broadcast to (nn,) or (nn, nr)).
    group_kw : dict
        Options of the group besides the sizes, ``rotor_type`` and ``num_sectors``.
    nn, nr : int
    single : bool
        Drop the node axis of the result.
    rotor_type : str
    num_sectors : int
    geometry : dict
        The inflow geometry, broadcast to (nn,).

    Returns
    -------
    InclinedBEMResult or TurbineBEMResult
    """
    turbine = rotor_type == "turbine"
    prob = om.Problem(InclinedBEMGroup(num_nodes=nn, num_radial=nr, num_sectors=num_sectors, rotor_type=rotor_type,
                                       **group_kw), reports=False)
    prob.setup(check=False)
    for name, value in {**prob_values, **geometry}.items():
        prob.set_val(name, value)
    prob.run_model()
    cls, outputs = (TurbineBEMResult, TURBINE_OUTPUTS) if turbine else (InclinedBEMResult, PERFORMANCE_OUTPUTS)
    names = [f.name for f in dataclasses.fields(cls) if f.name not in ("residual", "azimuth")]
    fields = {name: np.array(prob.get_val(name)) for name in names if name not in ("rho", "mu", "speed_of_sound")
              or group_kw["use_atmosphere"]}
    for name in ("rho", "mu", "speed_of_sound"):
        if name not in fields:
            fields[name] = np.asarray(prob_values[name], dtype=float)
    polar = TurbinePolar(group_kw["polar"]) if turbine else group_kw["polar"]
    node = {name: (fields[name] if name in fields else prob_values[name])[:, None]
            for name in ("rho", "mu", "radius", "hub_radius", "speed_of_sound", "collective_pitch")}
    values, _ = evaluate_section(fields["phi"], v_axial=fields["v_axial_local"], rpm=None,
                                 v_theta=fields["v_theta_local"], radii=np.tile(fields["radii"], (1, num_sectors)),
                                 chord=np.tile(prob_values["chord"], (1, num_sectors)),
                                 twist=np.tile(prob_values["twist"], (1, num_sectors)),
                                 num_blades=group_kw["num_blades"], polar=polar, loss_model=group_kw["loss_model"],
                                 high_induction=resolve_high_induction(group_kw.get("high_induction"), rotor_type),
                                 loads=False, partials=False,
                                 **node)
    fields["residual"] = values["residual"]
    fields["flow_state"] = np.rint(fields["flow_state"]).astype(int)
    for name in _SECTOR_UNITS:
        fields[name] = fields[name].reshape(nn, num_sectors, nr)
    if turbine:
        for name in TURBINE_FLIPPED:
            fields[name] = -fields[name]
    fields["azimuth"] = sector_azimuths(num_sectors)
    warn_supersonic_tip(fields["tip_mach"], what="rotor")
    if single:
        fields = {k: v if k == "azimuth" else v[0] for k, v in fields.items()}
    return cls(**fields)


__all__ = ["InclinedBEMResult", "TurbineBEMResult", "inclined_arguments", "check_inflow", "run_inclined"]
