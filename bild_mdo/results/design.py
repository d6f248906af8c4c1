"""Python design API: :func:`design_rotor` runs the BILD method and returns a :class:`DesignResult`.

One call designs one rotor (scalar inputs) or a batch of rotors (array inputs,
broadcast against each other) in ONE vectorised run of
:class:`~bild_mdo.bild.BILDGroup`::

    from bild_mdo import design_rotor

    rotor = design_rotor()                       # the paper's hover rotor, 30 stations
    print(rotor.summary())
    batch = design_rotor(advance_ratio=[0.5, 1.0, 1.5], ref_chord=0.15)
    print(batch[1].thrust, batch.efficiency)

A batch with infeasible members (no ideal loading: the paper's Assumption 3
fails at a station, or a hover rotor loads no station) raises one error naming
them; ``on_infeasible='skip'`` returns the batch with ``result.feasible``,
``result.status`` and ``result.feasible_designs()``.

The set-up OpenMDAO problem of each configuration is cached by
:func:`~bild_mdo.bild.problem.bild_problem`, so repeated calls of the same
size only set inputs and run the model.
"""
from __future__ import annotations

import dataclasses
import numbers
from pathlib import Path
from typing import ClassVar

import numpy as np
import openmdao.api as om

from bild_mdo import validation
from bild_mdo.airfoil.polar import Polar
from bild_mdo.atmosphere import MAX_ALTITUDE
from bild_mdo.bem.metrics import METRICS
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bild.chord import CHORD_FORMS
from bild_mdo.bild.problem import bild_problem
from bild_mdo.constants import RPM_TO_REV_PER_S
from bild_mdo.io.csv import write_csv
from bild_mdo.io.geometry import RotorGeometry, unit_key
from bild_mdo.io.json import write_json
from bild_mdo.results import tables

#: Distributions of the BILD model copied into the result: name -> units.
DISTRIBUTION_UNITS = {
    "radii": "m", "dr": "m", "chord": "m", "chord_raw": "m", "twist": "rad", "lift_coefficient": None,
    "drag_coefficient": None, "phi": "rad", "eta2": None, "dthrust_dr": "N/m", "dtorque_dr": "N*m/m",
}

#: What design_rotor does with infeasible designs.
ON_INFEASIBLE = ("raise", "skip")

#: Operating point and sizing inputs kept per design: name -> units.
INPUT_UNITS = {
    "v_axial": "m/s", "advance_ratio": None, "rpm": "rpm", "radius": "m", "hub_radius_ratio": None,
    "ref_radius_ratio": None, "ref_chord": "m", "altitude": "m",
}

#: Per-design outputs of the BILD model copied into the result: every performance metric of the
#: registry, then BILD's reference airfoil point and atmosphere: name -> units.
NODE_OUTPUT_UNITS = {
    **{metric.name: metric.units for metric in METRICS},
    "ideal_loading_constant": "m/s", "alpha_star": "rad", "cl_star": None, "cd_star": None, "reynolds_ref": None,
    "rho": "kg/m**3", "mu": "Pa*s", "hub_radius": "m", "ref_radius": "m",
}

_DISTRIBUTIONS = ("radii", "radial_fractions") + tuple(name for name in DISTRIBUTION_UNITS if name != "radii")
_PER_DESIGN = tuple(INPUT_UNITS) + tuple(NODE_OUTPUT_UNITS)
# Quantities the geometry files keep as the design point.
_GEOMETRY_POINT = ("v_axial", "advance_ratio", "rpm", "altitude", "ref_chord", "ref_radius_ratio",
                   "hub_radius_ratio", "reynolds_ref", "thrust", "torque", "power", "efficiency", "figure_of_merit")


@dataclasses.dataclass(frozen=True, eq=False)
class DesignResult:
    """BILD design(s) of :func:`design_rotor`.

    Every quantity is an attribute: ``result.thrust``, ``result.chord``.  A
    single design holds floats for per-design quantities and arrays of shape
    ``(nr,)`` for distributions; a batch holds arrays of shape ``(nn,)`` and
    ``(nn, nr)``.  ``len(result)`` is the number of designs, ``result[i]`` is
    design ``i`` as a single :class:`DesignResult` (slices give batches), and
    iterating yields the single designs.  Units are in :attr:`UNITS` (SI,
    angles in rad; ``None`` is dimensionless); each angle ``x`` also has
    ``x_deg`` in degrees (``twist_deg``, ``phi_deg``, ``alpha_star_deg``).

    Attributes
    ----------
    radii, radial_fractions, dr : ndarray
        Station radii r (m), r/R (-), station widths (m).
    chord, chord_raw : ndarray
        Chord after / before the root-chord correction, Eq. (32) (m).
    twist, phi : ndarray
        Twist (pitch) and inflow angle, Eq. (30) (rad).
    lift_coefficient, drag_coefficient : ndarray
        Section lift and drag coefficients (those of the max-L/D point).
    eta2 : ndarray
        Local annular efficiency, root of the quartic Eq. (27).
    dthrust_dr, dtorque_dr : ndarray
        Sectional thrust (N/m) and torque (N m/m), all blades, Eqs. (1), (2).
    thrust, torque, power, efficiency, figure_of_merit, ... : float or ndarray
        Every performance metric of :data:`~bild_mdo.bem.metrics.METRICS` (Table 2).
    ideal_loading_constant : float or ndarray
        lambda of Eq. (22) (m/s).
    alpha_star, cl_star, cd_star, reynolds_ref : float or ndarray
        Max-L/D point at the reference Reynolds number.
    rho, mu : float or ndarray
        ISA density (kg/m^3) and viscosity (Pa s).
    v_axial, advance_ratio, rpm, radius, hub_radius, hub_radius_ratio, ref_radius,
    ref_radius_ratio, ref_chord, altitude : float or ndarray
        The design inputs (both v_axial and J = V/(nD), whichever was given).
    values : dict
        All of the above by name.
    feasible : bool or ndarray of bool
        True where the ideal loading exists.  An infeasible design (only in a
        result of ``on_infeasible='skip'``) keeps its inputs (``v_axial``,
        ``advance_ratio``, ``rpm``, ``radius``, the radius ratios,
        ``ref_chord``, ``altitude``); every other quantity is NaN.
    status : str or ndarray of str
        ``'ok'`` where feasible, else why the design is infeasible.
    num_blades, airfoil, loss_model, chord_form, root_chord_correction
        The configuration; ``polar`` is the Polar object used.

    Notes
    -----
    ``efficiency`` and ``figure_of_merit`` hold the formulas' values
    (``eta = T V / P``, ``FM = T sqrt(T / (2 rho A)) / P``) for every feasible
    design; they are physical efficiencies only where ``T > 0`` and ``P > 0``,
    which every feasible BILD design satisfies, and the text tables print
    "n/a" elsewhere.
    """

    values: dict = dataclasses.field(repr=False)
    num_blades: int
    airfoil: str
    loss_model: str
    chord_form: str
    root_chord_correction: float | None
    polar: Polar = dataclasses.field(repr=False)
    is_batch: bool = True
    feasible: np.ndarray | bool = True
    status: np.ndarray | str = "ok"

    UNITS: ClassVar[dict] = {"radii": "m", "radial_fractions": None, **DISTRIBUTION_UNITS, **INPUT_UNITS,
                             **NODE_OUTPUT_UNITS}

    def __getattr__(self, name):
        # Only called for names that are not fields: the quantities and their *_deg forms.
        if name.startswith("__") or name == "values":
            raise AttributeError(name)
        if name in self.values:
            return self.values[name]
        base = name[:-4] if name.endswith("_deg") else None
        if base in self.values and self.UNITS.get(base) == "rad":
            return np.degrees(self.values[base])
        raise AttributeError(f"DesignResult has no quantity {name!r}")

    def __dir__(self):
        degrees = {f"{name}_deg" for name in self.values if self.UNITS.get(name) == "rad"}
        return sorted(set(super().__dir__()) | set(self.values) | degrees)

    # -- container protocol -------------------------------------------------------------------
    def __len__(self):
        return int(np.size(self.thrust)) if self.is_batch else 1

    def __getitem__(self, index):
        if not self.is_batch:
            if index in (0, -1):
                return self
            raise IndexError(f"a single design has only index 0, got {index!r}")
        if isinstance(index, slice):
            return self._take(np.arange(len(self))[index])
        if not isinstance(index, (numbers.Integral, np.integer)):
            raise TypeError(f"design index must be an integer or a slice, got {type(index).__name__}")
        n = len(self)
        if not -n <= index < n:
            raise IndexError(f"design index {index} out of range for {n} designs")
        single = {name: np.array(value[index]) if name in _DISTRIBUTIONS else float(value[index])
                  for name, value in self.values.items()}
        return dataclasses.replace(self, values=single, is_batch=False, feasible=bool(self._mask()[index]),
                                   status=str(self._statuses()[index]))

    def _mask(self):
        return np.broadcast_to(np.asarray(self.feasible, dtype=bool), (len(self),))

    def _statuses(self):
        return np.broadcast_to(np.asarray(self.status, dtype=object), (len(self),))

    def _take(self, indices):
        """The designs ``indices`` (an integer array) of a batch, as a batch."""
        return dataclasses.replace(self, values={name: value[indices] for name, value in self.values.items()},
                                   feasible=self._mask()[indices].copy(), status=self._statuses()[indices].copy())

    def feasible_designs(self):
        """The feasible designs of a batch, as a batch (in order; ``result.feasible`` picks them).

        A single design is returned as is if it is feasible; otherwise ValueError.
        """
        if not self.is_batch:
            if not self.feasible:
                raise ValueError(f"this design is infeasible: {self.status}")
            return self
        return self._take(np.flatnonzero(self._mask()))

    def __iter__(self):
        for i in range(len(self)):
            yield self[i]

    @property
    def lift_to_drag(self):
        """Maximum lift-to-drag ratio cl*/cd* (-)."""
        return self.cl_star / self.cd_star

    # -- export ---------------------------------------------------------------------------------
    def to_dict(self):
        """Every quantity as a dict (numpy arrays or floats; units in :attr:`UNITS`) plus the configuration."""
        return {**self.values, "feasible": self.feasible, "status": self.status,
                "num_blades": self.num_blades, "airfoil": self.airfoil,
                "loss_model": self.loss_model, "chord_form": self.chord_form,
                "root_chord_correction": self.root_chord_correction}

    def geometry(self, index=None):
        """The blade geometry of one design as a :class:`~bild_mdo.io.geometry.RotorGeometry`.

        Parameters
        ----------
        index : int, optional
            Design of a batch (required for a batch of more than one design).
        """
        design = self._single(index)
        if not design.feasible:
            raise ValueError(f"design {0 if index is None else index} is infeasible and has no geometry: "
                             f"{design.status}")
        return RotorGeometry(radii=design.radii, chord=design.chord, twist=design.twist,
                             radius=design.radius, hub_radius=design.hub_radius,
                             num_blades=design.num_blades, airfoil=design.airfoil,
                             loss_model=design.loss_model,
                             design_point={name: design.values[name] for name in _GEOMETRY_POINT},
                             name=f"bild-mdo design ({design.airfoil}, B={design.num_blades})", polar=design.polar)

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
        path = Path(path)
        self._require_feasible()
        if not self.is_batch:
            return [write_csv(path, self.geometry())]
        digits = len(str(len(self) - 1))
        return [write_csv(path.with_name(f"{path.stem}_{i:0{digits}d}{path.suffix}"), self.geometry(i))
                for i in range(len(self))]

    def to_json(self, path):
        """Write every design (geometry, design point, performance, distributions) to one JSON file.

        The file is the :mod:`bild_mdo.io.json` format (readable by
        ``bild-mdo analyze``, one design per entry of ``"designs"``) with two
        more blocks per design: ``"performance"`` and ``"distributions"``,
        keys carrying units as ``"name [unit]"``.

        Returns
        -------
        pathlib.Path
        """
        self._require_feasible()
        geometries, extras = [], []
        for design in self:
            geometries.append(design.geometry())
            perf = {unit_key(name, self.UNITS[name]): design.values[name] for name in NODE_OUTPUT_UNITS}
            dist = {unit_key(name, self.UNITS[name]): design.values[name].tolist() for name in _DISTRIBUTIONS}
            extras.append({"chord_form": design.chord_form,
                           "root_chord_correction": design.root_chord_correction,
                           "performance": perf, "distributions": dist})
        return write_json(path, geometries, extras=extras)

    def _require_feasible(self):
        bad = np.flatnonzero(~self._mask())
        if bad.size:
            raise ValueError(f"{bad.size} of {len(self)} designs are infeasible (first: design {bad[0]}, "
                             f"{self._statuses()[bad[0]]}); write result.feasible_designs() instead")

    # -- text output ----------------------------------------------------------------------------
    def station_table(self, index=None):
        """Text table of the stations of one design: r [m], r/R, chord [m], twist [deg], C_l, C_d."""
        return tables.station_table(self._single(index))

    def summary(self, max_rows=20):
        """Readable text: the inputs and performance of a single design, or one row per design of a batch.

        Parameters
        ----------
        max_rows : int
            For a batch, rows shown (first and last designs; the middle is elided).
        """
        body = tables.design_batch_table(self, max_rows) if self.is_batch else tables.single_design_table(self)
        return "\n".join([tables.design_configuration(self)] + body)


def _checked_inputs(input_mode, speed, rpm, radius, hub_radius_ratio, ref_radius_ratio, ref_chord, altitude):
    """The per-design inputs as float arrays (0-d or 1-D), each checked; ValueError names the first bad one."""
    values = {input_mode: validation.non_negative(input_mode, speed, units=INPUT_UNITS[input_mode],
                                                  hint="axial inflow from ahead; 0 is hover"),
              "rpm": validation.positive("rpm", rpm, units="rpm"),
              "radius": validation.positive("radius", radius, units="m")}
    for name, value in (("hub_radius_ratio", hub_radius_ratio), ("ref_radius_ratio", ref_radius_ratio)):
        values[name] = validation.in_range(name, value, 0.0, 1.0, open_low=True, open_high=True)
    validation.smaller("hub_radius_ratio", values["hub_radius_ratio"], "ref_radius_ratio",
                       values["ref_radius_ratio"], hint="the reference station lies on the blade")
    values["ref_chord"] = validation.positive("ref_chord", ref_chord, units="m")
    values["altitude"] = validation.in_range("altitude", altitude, 0.0, MAX_ALTITUDE, units="m", hint="ISA")
    return values


def design_rotor(v_axial=None, advance_ratio=None, rpm=800.0, radius=1.5, hub_radius_ratio=0.2,
                 ref_radius_ratio=0.5, ref_chord=0.15, altitude=0.0, num_blades=3, airfoil="naca4412",
                 num_radial=30, loss_model="tip_hub", chord_form="thrust", root_chord_correction=None,
                 on_infeasible="raise"):
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
    on_infeasible : {'raise', 'skip'}
        What to do with designs whose ideal loading does not exist (the
        paper's Assumption 3 fails at a station, or a hover rotor cannot load
        any station).  ``'raise'`` (default): one AnalysisError counting them
        and naming the first 10 with their reasons.  ``'skip'``: return the
        whole batch with ``result.feasible`` and ``result.status``; the
        infeasible designs' outputs are NaN (their inputs are kept), and
        ``result.feasible_designs()`` is the feasible subset.  Either way the
        batch runs once, vectorised, and a feasible design's values are
        bitwise those of a batch without the infeasible ones.

    Returns
    -------
    DesignResult

    Raises
    ------
    ValueError
        For invalid inputs; the message names the argument (and the design of a batch).
    openmdao.api.AnalysisError
        With ``on_infeasible='raise'``, if some design is infeasible (or, not
        expected for valid inputs, if the BILD model fails).
    """
    if v_axial is not None and advance_ratio is not None:
        raise ValueError("give either v_axial [m/s] or advance_ratio, not both")
    input_mode = "advance_ratio" if advance_ratio is not None else "v_axial"
    speed = advance_ratio if advance_ratio is not None else (0.0 if v_axial is None else v_axial)
    num_blades = validation.integer("num_blades", num_blades)
    num_radial = validation.integer("num_radial", num_radial)
    validation.choice("loss_model", loss_model, LOSS_MODELS)
    validation.choice("chord_form", chord_form, CHORD_FORMS)
    validation.choice("on_infeasible", on_infeasible, ON_INFEASIBLE)
    if root_chord_correction is not None:
        root_chord_correction = float(validation.positive("root_chord_correction", root_chord_correction,
                                                          hint="k of Eq. (32), or None", ndim=(0,)))
    values = _checked_inputs(input_mode, speed, rpm, radius, hub_radius_ratio, ref_radius_ratio, ref_chord,
                             altitude)
    is_batch = any(arr.ndim == 1 for arr in values.values())
    nn = validation.batch_size({name: arr.size for name, arr in values.items() if arr.ndim == 1})
    values = {name: np.broadcast_to(arr, (nn,)).astype(float) for name, arr in values.items()}

    # A built-in name (not its polar object) goes to bild_problem, which keeps one polar per name and so
    # reuses the set-up problem on repeated calls.
    prob = bild_problem(num_nodes=nn, num_radial=num_radial, num_blades=num_blades, airfoil=airfoil,
                        loss_model=loss_model, chord_form=chord_form, root_chord_correction=root_chord_correction,
                        input_mode=input_mode, on_infeasible="flag")
    polar = prob.model.options["polar"]
    for name, arr in values.items():
        prob.set_val(name, arr, units=INPUT_UNITS[name])
    prob.run_model()

    infeasible = prob.model.feasibility.infeasible
    if on_infeasible == "raise" and np.any(infeasible):
        raise om.AnalysisError(f"BILD: {prob.model.feasibility.message(noun='design', limit=10)}\n  "
                               "(design_rotor(..., on_infeasible='skip') returns the whole batch with "
                               "result.feasible and result.status)")
    # Infeasible designs hold placeholder values in the model: NaN in the result.
    outputs = {name: np.where(infeasible if np.ndim(value) == 1 else infeasible[:, None], np.nan, value)
               for name, value in ((name, np.array(prob.get_val(name, units=units)))
                                   for name, units in {**DISTRIBUTION_UNITS, **NODE_OUTPUT_UNITS}.items())}
    for name in ("thrust", "torque", "chord", "twist"):
        bad = ~np.isfinite(outputs[name]) & (~infeasible if outputs[name].ndim == 1 else ~infeasible[:, None])
        if np.any(bad):
            designs = np.unique(np.nonzero(bad)[0])
            raise om.AnalysisError(f"BILD returned non-finite {name} for design(s) {designs[:10].tolist()}")
    if input_mode == "v_axial":
        values["advance_ratio"] = values["v_axial"] / (values["rpm"] * RPM_TO_REV_PER_S * 2.0 * values["radius"])
    else:
        values["v_axial"] = np.array(prob.get_val("v_axial", units="m/s"))
    outputs["radial_fractions"] = outputs["radii"] / values["radius"][:, None]
    ordered = {name: outputs[name] for name in _DISTRIBUTIONS}
    ordered.update({name: values[name] for name in INPUT_UNITS})
    ordered.update({name: outputs[name] for name in NODE_OUTPUT_UNITS})
    result = DesignResult(values=ordered, num_blades=num_blades, airfoil=getattr(polar, "name", type(polar).__name__),
                          loss_model=loss_model, chord_form=chord_form,
                          root_chord_correction=root_chord_correction, polar=polar, is_batch=True,
                          feasible=~infeasible, status=prob.model.feasibility.status())
    return result if is_batch else result[0]
