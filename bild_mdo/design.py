"""Python design API: :func:`design_rotor` runs the BILD method and returns a :class:`DesignResult`.

One call designs one rotor (scalar inputs) or a batch of rotors (array inputs,
broadcast against each other) in ONE vectorised run of
:class:`~bild_mdo.bild.BILDGroup`::

    from bild_mdo.design import design_rotor

    rotor = design_rotor()                       # the paper's hover rotor, 30 stations
    print(rotor.summary())
    batch = design_rotor(advance_ratio=[0.5, 1.0, 1.5], ref_chord=0.15)
    print(batch[1].thrust, batch.efficiency)

The set-up OpenMDAO problem of each configuration (number of designs and
stations, blades, polar, loss model, chord form, root-chord correction, input
mode) is cached, so repeated calls of the same size only set inputs and run
the model.
"""
from __future__ import annotations

import collections
import dataclasses
import functools
import numbers
from pathlib import Path
from typing import ClassVar

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.builtin import available_polars, get_polar
from bild_mdo.airfoil.polar import Polar
from bild_mdo.atmosphere import MAX_ALTITUDE
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bild.bild_group import BILDGroup
from bild_mdo.bild.chord import CHORD_FORMS

#: Per-design outputs of the BILD model copied into the result: field -> (model output, units).
_NODE_OUTPUTS = {
    "thrust": ("thrust", "N"),
    "torque": ("torque", "N*m"),
    "power": ("power", "W"),
    "energy_loss": ("energy_loss", "W"),
    "efficiency": ("efficiency", None),
    "figure_of_merit": ("figure_of_merit", None),
    "thrust_coefficient": ("thrust_coefficient", None),
    "torque_coefficient": ("torque_coefficient", None),
    "power_coefficient": ("power_coefficient", None),
    "solidity": ("solidity", None),
    "blade_loading": ("blade_loading", None),
    "ideal_loading_constant": ("ideal_loading_constant", "m/s"),
    "alpha_star": ("alpha_star", "rad"),
    "cl_star": ("cl_star", None),
    "cd_star": ("cd_star", None),
    "reynolds_ref": ("reynolds_ref", None),
    "rho": ("rho", "kg/m**3"),
    "mu": ("mu", "Pa*s"),
    "hub_radius": ("hub_radius", "m"),
    "ref_radius": ("ref_radius", "m"),
}

#: Distributions copied into the result: field -> (model output, units).
_DIST_OUTPUTS = {
    "radii": ("radii", "m"),
    "dr": ("dr", "m"),
    "chord": ("chord", "m"),
    "chord_raw": ("chord_raw", "m"),
    "twist": ("twist", "rad"),
    "cl": ("lift_coefficient", None),
    "cd": ("drag_coefficient", None),
    "phi": ("phi", "rad"),
    "eta2": ("eta2", None),
    "dthrust_dr": ("dthrust_dr", "N/m"),
    "dtorque_dr": ("dtorque_dr", "N*m/m"),
}

#: Operating point and sizing inputs kept per design, with their units.
_INPUT_UNITS = {
    "v_axial": "m/s",
    "advance_ratio": None,
    "rpm": "rpm",
    "radius": "m",
    "hub_radius_ratio": None,
    "ref_radius_ratio": None,
    "ref_chord": "m",
    "altitude": "m",
}

_DISTRIBUTIONS = ("radii", "radial_fractions") + tuple(k for k in _DIST_OUTPUTS if k != "radii")
_PER_DESIGN = tuple(_INPUT_UNITS) + tuple(_NODE_OUTPUTS)

# Set-up problems by configuration; a 10,000-design model holds a few hundred MB of
# vectors and Jacobians, so only a handful are kept.
_PROBLEM_CACHE = collections.OrderedDict()
_PROBLEM_CACHE_SIZE = 4


def clear_model_cache():
    """Forget the set-up BILD problems cached by :func:`design_rotor` (frees their memory)."""
    _PROBLEM_CACHE.clear()


def _fmt(value, width=11):
    if isinstance(value, str):
        return f"{value:>{width}s}"
    return f"{value:>{width}.5g}"


@dataclasses.dataclass(frozen=True, eq=False)
class DesignResult:
    """BILD design(s) of :func:`design_rotor`.

    A single design holds floats for per-design quantities and arrays of shape
    ``(nr,)`` for distributions; a batch holds arrays of shape ``(nn,)`` and
    ``(nn, nr)``.  ``len(result)`` is the number of designs, ``result[i]`` is
    design ``i`` as a single :class:`DesignResult` (slices give batches), and
    iterating yields the single designs.  Units are in :attr:`UNITS` (SI,
    angles in rad; ``None`` is dimensionless); ``*_deg`` properties give
    angles in degrees.

    Attributes
    ----------
    radii, radial_fractions, dr : ndarray
        Station radii r (m), r/R (-), station widths (m).
    chord, chord_raw : ndarray
        Chord after / before the root-chord correction, Eq. (32) (m).
    twist, phi : ndarray
        Twist (pitch) and inflow angle, Eq. (30) (rad).
    cl, cd : ndarray
        Section lift and drag coefficients (those of the max-L/D point).
    eta2 : ndarray
        Local annular efficiency, root of the quartic Eq. (27).
    dthrust_dr, dtorque_dr : ndarray
        Sectional thrust (N/m) and torque (N m/m), all blades, Eqs. (1), (2).
    thrust, torque, power, energy_loss : float or ndarray
        T (N), Q (N m), P (W), rate of energy loss E (W).
    efficiency, figure_of_merit : float or ndarray
        eta and FM (Table 2).
    thrust_coefficient, torque_coefficient, power_coefficient : float or ndarray
        C_T, C_Q, C_P with n in rev/s and D = 2R.
    solidity, blade_loading : float or ndarray
        sigma_r and C_T/sigma_r.
    ideal_loading_constant : float or ndarray
        lambda of Eq. (22) (m/s).
    alpha_star, cl_star, cd_star, reynolds_ref : float or ndarray
        Max-L/D point at the reference Reynolds number.
    rho, mu : float or ndarray
        ISA density (kg/m^3) and viscosity (Pa s).
    v_axial, advance_ratio, rpm, radius, hub_radius, hub_radius_ratio, ref_radius,
    ref_radius_ratio, ref_chord, altitude : float or ndarray
        The design inputs (both v_axial and J = V/(nD), whichever was given).
    num_blades, airfoil, loss_model, chord_form, root_chord_correction
        The configuration; ``polar`` is the Polar object used.
    """

    radii: np.ndarray
    radial_fractions: np.ndarray
    dr: np.ndarray
    chord: np.ndarray
    chord_raw: np.ndarray
    twist: np.ndarray
    cl: np.ndarray
    cd: np.ndarray
    phi: np.ndarray
    eta2: np.ndarray
    dthrust_dr: np.ndarray
    dtorque_dr: np.ndarray
    v_axial: np.ndarray
    advance_ratio: np.ndarray
    rpm: np.ndarray
    radius: np.ndarray
    hub_radius_ratio: np.ndarray
    ref_radius_ratio: np.ndarray
    ref_chord: np.ndarray
    altitude: np.ndarray
    thrust: np.ndarray
    torque: np.ndarray
    power: np.ndarray
    energy_loss: np.ndarray
    efficiency: np.ndarray
    figure_of_merit: np.ndarray
    thrust_coefficient: np.ndarray
    torque_coefficient: np.ndarray
    power_coefficient: np.ndarray
    solidity: np.ndarray
    blade_loading: np.ndarray
    ideal_loading_constant: np.ndarray
    alpha_star: np.ndarray
    cl_star: np.ndarray
    cd_star: np.ndarray
    reynolds_ref: np.ndarray
    rho: np.ndarray
    mu: np.ndarray
    hub_radius: np.ndarray
    ref_radius: np.ndarray
    num_blades: int
    airfoil: str
    loss_model: str
    chord_form: str
    root_chord_correction: float | None
    polar: Polar = dataclasses.field(repr=False)
    is_batch: bool = True

    UNITS: ClassVar[dict] = {
        **{name: units for name, (_, units) in _DIST_OUTPUTS.items()},
        "radial_fractions": None,
        **_INPUT_UNITS,
        **{name: units for name, (_, units) in _NODE_OUTPUTS.items()},
    }

    # -- container protocol -------------------------------------------------------------------
    def __len__(self):
        return int(np.size(self.thrust)) if self.is_batch else 1

    def __getitem__(self, index):
        if not self.is_batch:
            if index in (0, -1):
                return self
            raise IndexError(f"a single design has only index 0, got {index!r}")
        if isinstance(index, slice):
            sliced = {name: getattr(self, name)[index] for name in _DISTRIBUTIONS + _PER_DESIGN}
            return dataclasses.replace(self, **sliced)
        if not isinstance(index, (numbers.Integral, np.integer)):
            raise TypeError(f"design index must be an integer or a slice, got {type(index).__name__}")
        n = len(self)
        if not -n <= index < n:
            raise IndexError(f"design index {index} out of range for {n} designs")
        single = {name: np.array(getattr(self, name)[index]) for name in _DISTRIBUTIONS}
        single.update({name: float(getattr(self, name)[index]) for name in _PER_DESIGN})
        return dataclasses.replace(self, is_batch=False, **single)

    def __iter__(self):
        for i in range(len(self)):
            yield self[i]

    # -- degree accessors ---------------------------------------------------------------------
    @property
    def twist_deg(self):
        """Twist (deg)."""
        return np.degrees(self.twist)

    @property
    def phi_deg(self):
        """Inflow angle (deg)."""
        return np.degrees(self.phi)

    @property
    def alpha_star_deg(self):
        """Angle of attack of maximum L/D (deg)."""
        return np.degrees(self.alpha_star)

    @property
    def lift_to_drag(self):
        """Maximum lift-to-drag ratio cl*/cd* (-)."""
        return self.cl_star / self.cd_star

    # -- export ---------------------------------------------------------------------------------
    def to_dict(self):
        """Every quantity as a dict (numpy arrays or floats; units in :attr:`UNITS`) plus the configuration."""
        data = {name: getattr(self, name) for name in _DISTRIBUTIONS + _PER_DESIGN}
        data.update(num_blades=self.num_blades, airfoil=self.airfoil, loss_model=self.loss_model,
                    chord_form=self.chord_form, root_chord_correction=self.root_chord_correction)
        return data

    def geometry(self, index=None):
        """The blade geometry of one design as a :class:`~bild_mdo.geometry_io.RotorGeometry`.

        Parameters
        ----------
        index : int, optional
            Design of a batch (required for a batch of more than one design).
        """
        from bild_mdo.geometry_io import RotorGeometry

        design = self._single(index)
        point = {name: getattr(design, name) for name in
                 ("v_axial", "advance_ratio", "rpm", "altitude", "ref_chord", "ref_radius_ratio",
                  "hub_radius_ratio", "reynolds_ref", "thrust", "torque", "power", "efficiency",
                  "figure_of_merit")}
        return RotorGeometry(radii=design.radii, chord=design.chord, twist=design.twist,
                             radius=design.radius, hub_radius=design.hub_radius,
                             num_blades=design.num_blades, airfoil=design.airfoil,
                             loss_model=design.loss_model, design_point=point,
                             name=f"bild-mdo design ({design.airfoil}, B={design.num_blades})")

    def _single(self, index):
        if index is not None:
            return self[index]
        if self.is_batch and len(self) != 1:
            raise ValueError(f"this result holds {len(self)} designs; pick one with index=i or result[i]")
        return self[0]

    def to_csv(self, path):
        """Write the blade geometry table (r [m], chord [m], twist [deg] and metadata) as CSV.

        A single design goes to ``path``; a batch writes one file per design,
        ``<stem>_<i><suffix>`` next to ``path`` (each readable by
        ``bild-mdo analyze``).

        Returns
        -------
        list of pathlib.Path
            The files written.
        """
        from bild_mdo.geometry_io import write_csv

        path = Path(path)
        if not self.is_batch:
            write_csv(path, self.geometry())
            return [path]
        digits = len(str(len(self) - 1))
        paths = []
        for i in range(len(self)):
            target = path.with_name(f"{path.stem}_{i:0{digits}d}{path.suffix}")
            write_csv(target, self.geometry(i))
            paths.append(target)
        return paths

    def to_json(self, path):
        """Write every design (geometry, design point, performance, distributions) to one JSON file.

        The file is the :mod:`bild_mdo.geometry_io` JSON format (readable by
        ``bild-mdo analyze``, one design per entry of ``"designs"``) with two
        more blocks per design: ``"performance"`` and ``"distributions"``,
        keys carrying units as ``"name [unit]"``.

        Returns
        -------
        pathlib.Path
        """
        from bild_mdo.geometry_io import unit_key, write_json

        geometries, extras = [], []
        for design in self:
            geometries.append(design.geometry())
            perf = {unit_key(name, self.UNITS[name]): getattr(design, name) for name in _NODE_OUTPUTS}
            dist = {unit_key(name, self.UNITS[name]): getattr(design, name).tolist()
                    for name in _DISTRIBUTIONS}
            extras.append({"chord_form": design.chord_form,
                           "root_chord_correction": design.root_chord_correction,
                           "performance": perf, "distributions": dist})
        return write_json(path, geometries, extras=extras)

    # -- text output ----------------------------------------------------------------------------
    def station_table(self, index=None):
        """Text table of the stations of one design: r [m], r/R, chord [m], twist [deg], C_l, C_d."""
        d = self._single(index)
        lines = [f"{'r [m]':>10} {'r/R [-]':>9} {'chord [m]':>10} {'twist [deg]':>11} {'C_l [-]':>8} "
                 f"{'C_d [-]':>8}"]
        for row in zip(d.radii, d.radial_fractions, d.chord, d.twist_deg, d.cl, d.cd):
            lines.append(f"{row[0]:>10.4f} {row[1]:>9.4f} {row[2]:>10.5f} {row[3]:>11.3f} {row[4]:>8.4f} "
                         f"{row[5]:>8.5f}")
        return "\n".join(lines)

    def summary(self, max_rows=20):
        """Readable text: the inputs and performance of a single design, or one row per design of a batch.

        Parameters
        ----------
        max_rows : int
            For a batch, rows shown (first and last designs; the middle is elided).
        """
        config = (f"BILD design: airfoil {self.airfoil}, B = {self.num_blades}, "
                  f"{np.shape(self.radii)[-1]} stations, loss model {self.loss_model}, "
                  f"chord from {self.chord_form}"
                  + ("" if self.root_chord_correction is None
                     else f", root-chord correction k = {self.root_chord_correction:g}"))
        if not self.is_batch:
            return config + "\n" + self._single_summary()
        columns = [("J [-]", "advance_ratio", 1.0), ("V [m/s]", "v_axial", 1.0), ("rpm", "rpm", 1.0),
                   ("R [m]", "radius", 1.0), ("c_ref [m]", "ref_chord", 1.0), ("alt [m]", "altitude", 1.0),
                   ("T [N]", "thrust", 1.0), ("Q [N m]", "torque", 1.0), ("P [kW]", "power", 1e-3),
                   ("eta [-]", "efficiency", 1.0), ("FM [-]", "figure_of_merit", 1.0),
                   ("C_T [-]", "thrust_coefficient", 1.0), ("sigma [-]", "solidity", 1.0)]
        lines = [config, f"{len(self)} designs",
                 f"{'#':>6} " + " ".join(f"{title:>11}" for title, _, _ in columns)]
        n = len(self)
        shown = list(range(n)) if n <= max_rows else list(range(max_rows // 2)) + [None] + list(
            range(n - (max_rows - max_rows // 2), n))
        for i in shown:
            if i is None:
                lines.append(f"{'...':>6}")
                continue
            lines.append(f"{i:>6d} " + " ".join(_fmt(getattr(self, name)[i] * scale)
                                                 for _, name, scale in columns))
        return "\n".join(lines)

    def _single_summary(self):
        rows = [
            ("operating point", None, None),
            ("axial velocity V_x", self.v_axial, "m/s"),
            ("advance ratio J = V/(nD)", self.advance_ratio, "-"),
            ("rotor speed", self.rpm, "rpm"),
            ("altitude", self.altitude, "m"),
            ("air density rho", self.rho, "kg/m^3"),
            ("geometry", None, None),
            ("tip radius R", self.radius, "m"),
            ("hub radius", self.hub_radius, "m"),
            ("reference radius r_ref", self.ref_radius, "m"),
            ("reference chord c_ref", self.ref_chord, "m"),
            ("solidity sigma_r", self.solidity, "-"),
            ("reference airfoil point", None, None),
            ("Reynolds number Re_ref", self.reynolds_ref, "-"),
            ("alpha* (max L/D)", self.alpha_star_deg, "deg"),
            ("C_l*, C_d*", f"{self.cl_star:.4f}, {self.cd_star:.5f}", "-"),
            ("ideal-loading constant lambda", self.ideal_loading_constant, "m/s"),
            ("performance", None, None),
            ("thrust T", self.thrust, "N"),
            ("torque Q", self.torque, "N m"),
            ("power P", self.power / 1e3, "kW"),
            ("energy loss E", self.energy_loss / 1e3, "kW"),
            ("efficiency eta", self.efficiency, "-"),
            ("figure of merit FM", self.figure_of_merit, "-"),
            ("C_T", self.thrust_coefficient, "-"),
            ("C_Q", self.torque_coefficient, "-"),
            ("C_P", self.power_coefficient, "-"),
            ("blade loading C_T/sigma_r", self.blade_loading, "-"),
        ]
        lines = []
        for label, value, units in rows:
            if value is None:
                lines.append(f"{label}:")
            elif isinstance(value, str):
                lines.append(f"  {label:<32s} {value:>14s} {units}")
            else:
                lines.append(f"  {label:<32s} {value:>14.6g} {units}")
        return "\n".join(lines)


# -- validation -----------------------------------------------------------------------------------
def _numeric(name, value):
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number or a list of numbers, got {value!r}") from None
    if arr.ndim > 1:
        raise ValueError(f"{name} must be a scalar or a 1-D list of values, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return arr


def _first_bad(name, arr, mask, requirement):
    if np.any(mask):
        bad = np.atleast_1d(arr)[np.atleast_1d(mask)][0]
        where = "" if arr.ndim == 0 else f" (design {int(np.flatnonzero(np.atleast_1d(mask))[0])})"
        raise ValueError(f"{name} must be {requirement}, got {bad:g}{where}")


def _positive_int(name, value, minimum=1):
    if isinstance(value, bool) or not isinstance(value, (numbers.Integral, np.integer)) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return int(value)


@functools.lru_cache(maxsize=None)
def _builtin_polar(name):
    # One object per name, so the model cache (keyed on the polar object) is hit on repeated calls.
    return get_polar(name)


def _resolve_polar(airfoil):
    if isinstance(airfoil, Polar):
        return airfoil, getattr(airfoil, "name", type(airfoil).__name__)
    if isinstance(airfoil, str):
        key = airfoil.strip().lower()
        if key not in available_polars():
            raise ValueError(f"unknown airfoil {airfoil!r}; available: {', '.join(available_polars())} "
                             "(or pass a bild_mdo.airfoil.Polar object)")
        return _builtin_polar(key), key
    raise ValueError(f"airfoil must be a name ({', '.join(available_polars())}) or a Polar object, "
                     f"got {type(airfoil).__name__}")


def _validate_inputs(values):
    """Check the per-design inputs (arrays, possibly 0-d) and raise ValueError naming the first bad value."""
    if "v_axial" in values:
        _first_bad("v_axial [m/s]", values["v_axial"], values["v_axial"] < 0.0,
                   ">= 0 (axial inflow from ahead; 0 is hover)")
    else:
        _first_bad("advance_ratio", values["advance_ratio"], values["advance_ratio"] < 0.0,
                   ">= 0 (0 is hover)")
    for name, units in (("rpm", "rpm"), ("radius", "m"), ("ref_chord", "m")):
        _first_bad(f"{name} [{units}]", values[name], values[name] <= 0.0, "positive")
    for name in ("hub_radius_ratio", "ref_radius_ratio"):
        arr = values[name]
        _first_bad(name, arr, (arr <= 0.0) | (arr >= 1.0), "between 0 and 1 (exclusive)")
    hub, ref = np.broadcast_arrays(values["hub_radius_ratio"], values["ref_radius_ratio"])
    if np.any(hub >= ref):
        i = int(np.flatnonzero(np.atleast_1d(hub >= ref))[0])
        raise ValueError("hub_radius_ratio must be smaller than ref_radius_ratio (the reference station lies "
                         f"on the blade), got hub {np.atleast_1d(hub)[i]:g} >= ref {np.atleast_1d(ref)[i]:g}")
    alt = values["altitude"]
    _first_bad("altitude [m]", alt, (alt < 0.0) | (alt > MAX_ALTITUDE), f"within 0 ... {MAX_ALTITUDE:g} (ISA)")


def _bild_problem(num_nodes, num_radial, num_blades, polar, loss_model, chord_form, correction, input_mode):
    key = (num_nodes, num_radial, num_blades, id(polar), loss_model, chord_form, correction, input_mode)
    hit = _PROBLEM_CACHE.get(key)
    # id() can be reused after an object dies; the stored reference proves it is the same polar.
    if hit is not None and hit[0] is polar:
        _PROBLEM_CACHE.move_to_end(key)
        return hit[1]
    group = BILDGroup(num_nodes=num_nodes, num_radial=num_radial, num_blades=num_blades, polar=polar,
                      loss_model=loss_model, chord_form=chord_form, root_chord_correction=correction,
                      input_mode=input_mode)
    prob = om.Problem(group, reports=False)
    prob.setup(check=False)
    prob.final_setup()
    _PROBLEM_CACHE[key] = (polar, prob)
    while len(_PROBLEM_CACHE) > _PROBLEM_CACHE_SIZE:
        _PROBLEM_CACHE.popitem(last=False)
    return prob


def bild_problem(num_nodes=1, num_radial=30, num_blades=3, airfoil="naca4412", loss_model="tip_hub",
                 chord_form="thrust", root_chord_correction=None, input_mode="v_axial"):
    """The cached, set-up BILD problem :func:`design_rotor` uses for this configuration.

    For users who want OpenMDAO access (totals, recorders) to the same model;
    inputs are promoted names of :class:`~bild_mdo.bild.BILDGroup`.

    Returns
    -------
    openmdao.api.Problem
    """
    polar, _ = _resolve_polar(airfoil)
    return _bild_problem(_positive_int("num_nodes", num_nodes), _positive_int("num_radial", num_radial),
                         _positive_int("num_blades", num_blades), polar, loss_model, chord_form,
                         root_chord_correction, input_mode)


def design_rotor(v_axial=None, advance_ratio=None, rpm=800.0, radius=1.5, hub_radius_ratio=0.2,
                 ref_radius_ratio=0.5, ref_chord=0.15, altitude=0.0, num_blades=3, airfoil="naca4412",
                 num_radial=30, loss_model="tip_hub", chord_form="thrust", root_chord_correction=None):
    """Design the ideal rotor(s) for given operating points with the BILD method (paper Alg. 1).

    Scalars give one design; lists or 1-D arrays (broadcast against each
    other and the scalars) give a batch, computed in one vectorised run.

    Parameters
    ----------
    v_axial : float or array_like, optional
        Axial (climb / flight) velocity (m/s), >= 0.  Default 0 (hover).
        Give this or ``advance_ratio``, not both.
    advance_ratio : float or array_like, optional
        Advance ratio J = V_x/(n D) (-), >= 0.
    rpm : float or array_like
        Rotor speed (rpm), > 0.  Default 800 (paper Sec. 5.1).
    radius : float or array_like
        Tip radius R (m), > 0.  Default 1.5.
    hub_radius_ratio : float or array_like
        Hub radius / R (-), in (0, 1) and below ``ref_radius_ratio``.  Default 0.2.
    ref_radius_ratio : float or array_like
        Reference station r_ref / R (-), in (0, 1).  Default 0.5.
    ref_chord : float or array_like
        Chord at the reference station c_ref (m), > 0.  Default 0.15.
    altitude : float or array_like
        Geometric altitude for the ISA (m), 0 ... 11,000.  Default 0.
    num_blades : int
        Number of blades B.  Default 3.
    airfoil : str or Polar
        ``'naca4412'`` (built-in XFOIL surrogate, default), ``'analytic'``
        or any :class:`~bild_mdo.airfoil.Polar`.
    num_radial : int
        Radial stations (midpoints of equal annuli from hub to tip).  Default 30.
    loss_model : {'tip_hub', 'tip', 'none'}
        Prandtl loss factor.
    chord_form : {'thrust', 'torque'}
        Back-compute the chord from the thrust (Eq. (31)) or the torque balance.
    root_chord_correction : float, optional
        ``k`` of the root-chord correction, Eq. (32); None (default) for none.

    Returns
    -------
    DesignResult

    Raises
    ------
    ValueError
        For invalid inputs; the message names the argument (and the design of a batch).
    openmdao.api.AnalysisError
        If the BILD model cannot be solved for some design.
    """
    if v_axial is not None and advance_ratio is not None:
        raise ValueError("give either v_axial [m/s] or advance_ratio, not both")
    input_mode = "advance_ratio" if advance_ratio is not None else "v_axial"
    speed_value = advance_ratio if advance_ratio is not None else (0.0 if v_axial is None else v_axial)
    num_blades = _positive_int("num_blades", num_blades)
    num_radial = _positive_int("num_radial", num_radial)
    if loss_model not in LOSS_MODELS:
        raise ValueError(f"loss_model must be one of {', '.join(LOSS_MODELS)}, got {loss_model!r}")
    if chord_form not in CHORD_FORMS:
        raise ValueError(f"chord_form must be one of {', '.join(CHORD_FORMS)}, got {chord_form!r}")
    if root_chord_correction is not None:
        if (isinstance(root_chord_correction, bool) or not isinstance(root_chord_correction, numbers.Real)
                or not root_chord_correction > 0.0):
            raise ValueError("root_chord_correction must be None or a positive number k (Eq. (32)), "
                             f"got {root_chord_correction!r}")
        root_chord_correction = float(root_chord_correction)
    polar, airfoil_name = _resolve_polar(airfoil)

    raw = {input_mode: speed_value, "rpm": rpm, "radius": radius, "hub_radius_ratio": hub_radius_ratio,
           "ref_radius_ratio": ref_radius_ratio, "ref_chord": ref_chord, "altitude": altitude}
    values = {name: _numeric(name, value) for name, value in raw.items()}
    _validate_inputs(values)
    lengths = {name: arr.size for name, arr in values.items() if arr.ndim == 1}
    if len(set(lengths.values())) > 1:
        raise ValueError("batch inputs must have equal lengths (or be scalars), got "
                         + ", ".join(f"{name}: {n}" for name, n in lengths.items()))
    is_batch = bool(lengths)
    nn = next(iter(lengths.values())) if lengths else 1
    if nn == 0:
        raise ValueError("batch inputs are empty")
    values = {name: np.broadcast_to(arr, (nn,)).astype(float) for name, arr in values.items()}

    prob = _bild_problem(nn, num_radial, num_blades, polar, loss_model, chord_form, root_chord_correction,
                         input_mode)
    for name, arr in values.items():
        prob.set_val(name, arr, units=_INPUT_UNITS[name])
    prob.run_model()

    out = {field: np.array(prob.get_val(name, units=units)) for field, (name, units) in _NODE_OUTPUTS.items()}
    out.update({field: np.array(prob.get_val(name, units=units))
                for field, (name, units) in _DIST_OUTPUTS.items()})
    for name in ("thrust", "torque", "chord", "twist"):
        bad = ~np.isfinite(out[name])
        if np.any(bad):
            designs = np.unique(np.nonzero(bad)[0])
            raise om.AnalysisError(f"BILD returned non-finite {name} for design(s) {designs[:10].tolist()}")
    if input_mode == "v_axial":
        values["advance_ratio"] = values["v_axial"] / (values["rpm"] / 60.0 * 2.0 * values["radius"])
    else:
        values["v_axial"] = np.array(prob.get_val("v_axial", units="m/s"))
    out.update(values)
    out["radial_fractions"] = out["radii"] / values["radius"][:, None]
    result = DesignResult(num_blades=num_blades, airfoil=airfoil_name, loss_model=loss_model,
                          chord_form=chord_form, root_chord_correction=root_chord_correction, polar=polar,
                          is_batch=True, **out)
    return result if is_batch else result[0]
