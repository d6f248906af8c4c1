"""The result of :func:`~bild_mdo.results.design.design_rotor`: :class:`DesignResult` and the names it holds.

A :class:`DesignResult` holds one BILD design or a batch, as arrays by name
(:attr:`DesignResult.values`), and writes them as text tables and geometry
files (CSV, JSON; the files carry the design's airfoil).
"""
from __future__ import annotations

import dataclasses
import numbers
from pathlib import Path
from typing import ClassVar

import numpy as np

from bild_mdo.airfoil.polar import Polar
from bild_mdo.fluid import Fluid, fluid_point
from bild_mdo.bem.metrics import METRICS
from bild_mdo.io.csv import write_csv
from bild_mdo.io.geometry import RotorGeometry, unit_key
from bild_mdo.io.json import write_json
from bild_mdo.results import tables
from bild_mdo.results.design_analysis import ANALYSIS_UNITS

#: Distributions of the BILD model copied into the result: name -> units.
DISTRIBUTION_UNITS = {
    "radii": "m", "dr": "m", "chord": "m", "chord_raw": "m", "twist": "rad", "lift_coefficient": None,
    "drag_coefficient": None, "phi": "rad", "eta2": None, "dthrust_dr": "N/m", "dtorque_dr": "N*m/m",
    "mach": None, "section_branch": None,
}

#: Outputs a result holds only where the model has them (the local Mach number is new in the groups; the
#: sheet of each station's section point and of the reference state only with ``section_point='local'``, the
#: sheet a station at r_ref takes only with the Reynolds-aware exact loading).
OPTIONAL_OUTPUTS = ("mach", "tip_mach", "section_branch", "section_branch_ref", "station_branch_ref")

#: Distributions design_rotor adds to the model's: the chord Reynolds number ``rho W0 c / mu`` of every station
#: (``W0 = sqrt(V_x**2 + (Omega r)**2)``, the BEM convention; 0 where the chord is 0) and whether it lies
#: outside the polar's data (1.0) or not (0.0), where the polar has a data range.
DERIVED_DISTRIBUTIONS = {"reynolds": None, "reynolds_outside_data": None}

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
    "rho": "kg/m**3", "mu": "Pa*s", "hub_radius": "m", "ref_radius": "m", "section_branch_ref": None,
    "station_branch_ref": None,
}

DISTRIBUTIONS = ("radii", "radial_fractions") + tuple(name for name in DISTRIBUTION_UNITS if name != "radii") + tuple(
    DERIVED_DISTRIBUTIONS)
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
    mach : ndarray
        Local Mach number W / a of each station (where the BILD model outputs it).
    reynolds, reynolds_outside_data : ndarray
        Chord Reynolds number ``rho W0 c / mu`` of each station, and 1.0 where it lies outside the polar's
        data (the polar extrapolates there; :meth:`summary` lists those stations).
    section_branch : ndarray
        With ``section_point='local'``: the sheet of the polar's load-path table of each station's section
        point (-1 unloaded); adjacent loaded stations on different sheets are a jump of the design.
    thrust, torque, power, efficiency, figure_of_merit, ... : float or ndarray
        Every performance metric of :data:`~bild_mdo.bem.metrics.METRICS` (Table 2)
        that the BILD model outputs (``tip_mach`` among them, once it does).
    ideal_loading_constant : float or ndarray
        lambda of Eq. (22) (m/s).
    bem_thrust, bem_torque, bem_power, bem_efficiency, bem_figure_of_merit : float or ndarray
        The BEM analysis of the design's own blade with the same polar at its operating point (each station
        at its own Reynolds number; with ``design_rotor(..., bem_analysis=True)``, the default;
        :mod:`~bild_mdo.results.design_analysis` says when and why they differ from the design's numbers);
        ``bem_invalid_stations`` counts the stations the analysis finds outside the propeller state.
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
        ``ref_chord``, ``altitude``; a thrust-target design's solved
        ``ref_chord`` is NaN); every other quantity is NaN.
    status : str or ndarray of str
        ``'ok'`` where feasible, else why the design is infeasible.
    num_blades, airfoil, loss_model, chord_form, root_chord_correction, section_point, ideal_loading
        The configuration; ``polar`` is the Polar object used.
    fluid : Fluid or None
        The fluid of ``design_rotor(..., fluid=...)`` (:mod:`bild_mdo.fluid`); None for the ISA at
        ``altitude`` (then ``altitude`` holds no meaning for a fluid design, and its geometry files keep
        the fluid's ``rho``, ``mu`` and ``speed_of_sound`` instead).

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
    section_point: str = "reference"
    ideal_loading: str = "paper"
    fluid: Fluid | None = None

    UNITS: ClassVar[dict] = {"radii": "m", "radial_fractions": None, **DISTRIBUTION_UNITS, **DERIVED_DISTRIBUTIONS,
                             **INPUT_UNITS, **NODE_OUTPUT_UNITS, **ANALYSIS_UNITS, "bem_invalid_stations": None}

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
        # Distributions are (nn, nr); per-design values (nn,) (a spanwise polar makes the max-L/D point per station).
        single = {name: np.array(value[index]) if np.ndim(value) == 2 else float(value[index])
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
                "root_chord_correction": self.root_chord_correction, "section_point": self.section_point,
                "ideal_loading": self.ideal_loading}

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
                             design_point={**{name: design.values[name] for name in _GEOMETRY_POINT
                                              if not (name == "altitude" and design.fluid is not None)},
                                           **({} if design.fluid is None else fluid_point(design.fluid))},
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
            perf = {unit_key(name, self.UNITS[name]): design.values[name] for name in NODE_OUTPUT_UNITS
                    if name in design.values}
            dist = {unit_key(name, self.UNITS[name]): design.values[name].tolist() for name in DISTRIBUTIONS
                    if name in design.values}
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
