"""Plain-Python entry point to the BEM analysis: :func:`analyze_rotor` and :class:`BEMResult`."""
from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.polar import Polar
from bild_mdo.atmosphere import MAX_ALTITUDE
from bild_mdo.bem.bem_analysis_group import BEMAnalysisGroup
from bild_mdo.bem.performance import PERFORMANCE_OUTPUTS
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bem.section import evaluate_section
from bild_mdo.bem.section_loads import SECTION_OUTPUTS


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


@dataclasses.dataclass(frozen=True)
class BEMResult:
    """Result of :func:`analyze_rotor`.

    Per-design quantities have shape ``(nn,)`` for a batch and are 0-d arrays
    for a single case; distributions have shape ``(nn, nr)`` or ``(nr,)``.
    Units are listed in :attr:`UNITS` (SI; angles in rad; ``None`` = dimensionless).
    """

    thrust: np.ndarray
    torque: np.ndarray
    power: np.ndarray
    efficiency: np.ndarray
    figure_of_merit: np.ndarray
    thrust_coefficient: np.ndarray
    torque_coefficient: np.ndarray
    power_coefficient: np.ndarray
    energy_loss: np.ndarray
    solidity: np.ndarray
    blade_loading: np.ndarray
    rho: np.ndarray
    mu: np.ndarray
    radii: np.ndarray
    dr: np.ndarray
    phi: np.ndarray
    alpha: np.ndarray
    reynolds: np.ndarray
    cl: np.ndarray
    cd: np.ndarray
    u_axial: np.ndarray
    u_theta: np.ndarray
    loss_factor: np.ndarray
    inflow_speed: np.ndarray
    dthrust_dr: np.ndarray
    dtorque_dr: np.ndarray
    residual: np.ndarray

    UNITS: ClassVar[dict] = {
        **{name: units for name, (units, _) in PERFORMANCE_OUTPUTS.items()},
        **{name: units for name, (units, _) in SECTION_OUTPUTS.items()},
        "rho": "kg/m**3", "mu": "Pa*s", "radii": "m", "dr": "m", "phi": "rad", "residual": None,
    }

    def to_dict(self):
        """All fields as a dict of numpy arrays (units in :attr:`UNITS`)."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}


def _as_float_array(value, name):
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be numeric, got {value!r}") from exc
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return arr


def _voronoi_widths(radii, hub_radius, radius):
    """Widths of the cells around given station radii, bounded by hub and tip."""
    mid = 0.5 * (radii[:, 1:] + radii[:, :-1])
    edges = np.concatenate([hub_radius[:, None], mid, radius[:, None]], axis=1)
    return np.diff(edges, axis=1)


def analyze_rotor(chord, twist, radius, hub_radius, rpm, v_axial, num_blades, polar,
                  altitude=0.0, loss_model="tip_hub", radii=None, dr=None, rho=None, mu=None):
    """Analyse one rotor or a batch of rotors in axial flow with BEM theory.

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
    polar : Polar
        Airfoil polar.
    altitude : float or array_like
        Geometric altitude (m) for the ISA, 0 ... 11,000.  Ignored where
        ``rho`` and ``mu`` are both given.
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

    Returns
    -------
    BEMResult

    Raises
    ------
    ValueError
        Invalid input (the message names the argument).
    openmdao.api.AnalysisError
        If the inflow solve finds no bracket at some station.
    """
    if not isinstance(polar, Polar):
        raise ValueError(f"polar must be a bild_mdo.airfoil.Polar, got {type(polar).__name__}")
    if loss_model not in LOSS_MODELS:
        raise ValueError(f"loss_model must be one of {LOSS_MODELS}, got {loss_model!r}")
    if isinstance(num_blades, bool) or not isinstance(num_blades, (int, np.integer)) or num_blades < 1:
        raise ValueError(f"num_blades must be a positive integer, got {num_blades!r}")
    if (rho is None) != (mu is None):
        raise ValueError("give both rho and mu, or neither (then the ISA at altitude is used)")

    chord = _as_float_array(chord, "chord")
    twist = _as_float_array(twist, "twist")
    if chord.ndim not in (1, 2) or chord.shape[-1] < 1:
        raise ValueError(f"chord must have shape (nr,) or (nn, nr), got {chord.shape}")
    if twist.shape != chord.shape:
        raise ValueError(f"twist must have the shape of chord {chord.shape}, got {twist.shape}")
    nr = chord.shape[-1]

    scalars = {"radius": radius, "hub_radius": hub_radius, "rpm": rpm, "v_axial": v_axial,
               "altitude": altitude}
    if rho is not None:
        scalars.update(rho=rho, mu=mu)
    scalars = {k: _as_float_array(v, k) for k, v in scalars.items()}
    for name, arr in scalars.items():
        if arr.ndim > 1:
            raise ValueError(f"{name} must be a scalar or have shape (nn,), got {arr.shape}")
    sizes = {name: arr.size for name, arr in scalars.items() if arr.ndim == 1}
    if chord.ndim == 2:
        sizes["chord"] = chord.shape[0]
    extra = {}
    for name, val in (("radii", radii), ("dr", dr)):
        if val is not None:
            arr = _as_float_array(val, name)
            if arr.shape[-1:] != (nr,) or arr.ndim not in (1, 2):
                raise ValueError(f"{name} must have shape ({nr},) or (nn, {nr}) like chord, got {arr.shape}")
            if arr.ndim == 2:
                sizes[name] = arr.shape[0]
            extra[name] = arr
    nn_set = set(sizes.values())
    if len(nn_set) > 1:
        raise ValueError(f"batch sizes disagree: {sizes}; every batched argument needs the same length nn")
    nn = nn_set.pop() if nn_set else 1
    single = not sizes

    def per_node(arr):
        return np.broadcast_to(arr, (nn,)).astype(float)

    def per_station(arr):
        return np.broadcast_to(arr, (nn, nr)).astype(float)

    s = {k: per_node(v) for k, v in scalars.items()}
    chord, twist = per_station(chord), per_station(twist)

    if np.any(s["radius"] <= 0.0):
        raise ValueError("radius must be positive")
    if np.any(s["hub_radius"] < 0.0):
        raise ValueError("hub_radius must be non-negative")
    if loss_model == "tip_hub" and np.any(s["hub_radius"] <= 0.0):
        raise ValueError("hub_radius must be positive with loss_model='tip_hub' (use 'tip' without a hub)")
    if np.any(s["hub_radius"] >= s["radius"]):
        raise ValueError("hub_radius must be smaller than radius (tip radius)")
    if np.any(s["rpm"] <= 0.0):
        raise ValueError("rpm must be positive")
    if np.any(s["v_axial"] < 0.0):
        raise ValueError("v_axial must be non-negative (axial inflow from ahead; 0 is hover)")
    if np.any(chord <= 0.0):
        raise ValueError("chord must be positive at every station")
    if "rho" in s and (np.any(s["rho"] <= 0.0) or np.any(s["mu"] <= 0.0)):
        raise ValueError("rho and mu must be positive")
    if "rho" not in s and (np.any(s["altitude"] < 0.0) or np.any(s["altitude"] > MAX_ALTITUDE)):
        raise ValueError(f"altitude must be within 0 ... {MAX_ALTITUDE:g} m (ISA troposphere)")

    group_kw = {}
    if "radii" in extra:
        r = per_station(extra["radii"])
        if np.any(r < s["hub_radius"][:, None]) or np.any(r > s["radius"][:, None]):
            raise ValueError("radii must lie within [hub_radius, radius]")
        if nr > 1 and np.any(np.diff(r, axis=1) <= 0.0):
            raise ValueError("radii must be strictly increasing")
        if "dr" in extra:
            widths = per_station(extra["dr"])
            if np.any(widths <= 0.0):
                raise ValueError("dr must be positive")
        else:
            widths = _voronoi_widths(r, s["hub_radius"], s["radius"])
        group_kw = dict(radial_fractions=r / s["radius"][:, None],
                        width_fractions=widths / s["radius"][:, None])
    elif "dr" in extra:
        raise ValueError("dr needs radii (station widths belong to given station radii)")

    use_atmosphere = "rho" not in s
    prob = om.Problem(BEMAnalysisGroup(num_nodes=nn, num_radial=nr, num_blades=int(num_blades),
                                       polar=polar, loss_model=loss_model,
                                       use_atmosphere=use_atmosphere, **group_kw),
                      reports=False)
    prob.setup(check=False)
    for name in ("radius", "hub_radius", "rpm", "v_axial"):
        prob.set_val(name, s[name])
    prob.set_val("chord", chord)
    prob.set_val("twist", twist)
    if use_atmosphere:
        prob.set_val("altitude", s["altitude"])
    else:
        prob.set_val("rho", s["rho"])
        prob.set_val("mu", s["mu"])
    prob.run_model()

    fields = {f.name: np.array(prob.get_val(f.name)) for f in dataclasses.fields(BEMResult)
              if f.name != "residual"}
    node = {name: fields[name][:, None] if name in fields else s[name][:, None]
            for name in ("v_axial", "rpm", "rho", "mu", "radius", "hub_radius")}
    values, _ = evaluate_section(fields["phi"], radii=fields["radii"], chord=chord, twist=twist,
                                 num_blades=int(num_blades), polar=polar, loss_model=loss_model,
                                 loads=False, partials=False, **node)
    fields["residual"] = values["residual"]
    if single:
        fields = {k: v[0] for k, v in fields.items()}
    return BEMResult(**fields)
