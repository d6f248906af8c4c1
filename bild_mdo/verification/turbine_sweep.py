"""The turbine verification (``bild-mdo verify --turbine``): the turbine BILD against the full-BEM optimum.

The paper's verification (Sec. 5.1) carried over to energy extraction.  A
full-factorial sweep of tip-speed ratio, tip radius, altitude and thrust
coefficient (:class:`TurbineSweepSpec`); every case is designed by the
turbine BILD for its thrust (:func:`turbine_bild_batch`, one vectorised
run) and optimised with the full BEM model for the most power at that thrust
(:func:`optimize_turbine_cases`, the lockstep SLSQP of
:mod:`bild_mdo.optimization.lockstep` with ``rotor_type='turbine'``:
:mod:`bild_mdo.optimization.turbine`), from the BILD blade and, with
``starts=2``, from a linear cold start.  The runner, the results store and
Table 3 are the propeller sweep's (:mod:`~bild_mdo.verification.runner`).

In a turbine sweep the stored quantities are the turbine's: ``thrust`` downwind and
``power`` extracted, ``thrust_coefficient`` ``T / (1/2 rho A V^2)``,
``power_coefficient`` ``P / (1/2 rho A V^3)``, ``torque_coefficient``
``Q / (1/2 rho A V^2 R)`` with ``A = pi R^2``, ``efficiency`` ``P / (V T)``,
``energy_loss`` ``V T - P`` (the quantity both methods minimise at the
thrust), ``figure_of_merit`` empty (hover only).  The store's ``advance_ratio``
column holds ``J = V / (n D) = pi / lambda`` and its ``reference_chord``
column is empty: a turbine case is set by its thrust, which BILD's
``thrust_coefficient`` gives back.

Defaults: wind 8 m/s, B = 3, NACA 4412, 30 stations, hub at 0.1 R, reference
station at 0.7 R, lambda 4 ... 10, R 2 ... 8 m (so that the reference
sections' Reynolds numbers, 6e4 ... 1.9e6, stay inside the built-in table, which
other stations leave a little, up to about 2.03e6 at the largest rotors; below
R = 2 m the reference station's best lift-to-drag point jumps between two
branches across the Reynolds numbers of the candidate chords, and at lambda 10,
R 1 m no reference chord runs at its own section point), altitude
0 ... 3000 m, C_T 0.4 ... 0.75 (below the maximum-power member's, 0.77 ... 0.82
over the sweep: every case is a member that trades power for a lower thrust).
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
from dataclasses import dataclass

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.text import sweep_polar
from bild_mdo.atmosphere import isa
from bild_mdo.bild.turbine_problem import run_turbine_bild
from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.optimization.problem import OPTIMIZERS
from bild_mdo.utils.batches import isolate_failures

from .case_functions import optimize_start
from .cases import CASE_LAYOUT_VERSION, MAX_LEVELS, Case, axis_point
from .starts import combine_starts

#: Swept axes in case-id order (the first varies slowest).
TURBINE_AXES = ("tip_speed_ratio", "radius", "altitude", "thrust_coefficient")
#: The optimiser's starts per turbine case: the turbine BILD blade, the linear cold start.  In the store's
#: ``best_start`` column they count as the propeller sweep's starts 1 and 3.
TURBINE_STARTS = ("bild", "linear")


@dataclass(frozen=True)
class TurbineSweepSpec:
    """A turbine verification sweep: ``levels**4`` cases over :data:`TURBINE_AXES` (module docstring).

    ``section_point`` and ``ideal_loading`` are fixed ('reference', 'turbine'): they name the turbine BILD
    in the reports and the store's file name; ``starts`` is 1 or 2 (:data:`TURBINE_STARTS`).
    """

    levels: int = 10
    tip_speed_ratio_range: tuple = (4.0, 10.0)
    radius_range: tuple = (2.0, 8.0)
    altitude_range: tuple = (0.0, 3000.0)
    thrust_coefficient_range: tuple = (0.4, 0.75)
    wind_speed: float = 8.0
    reference_radius_fraction: float = 0.7
    hub_radius_fraction: float = 0.1
    num_blades: int = 3
    num_radial: int = 30
    airfoil: str = "naca4412"
    optimizer: str = "slsqp"
    starts: int = 1
    section_point: str = "reference"
    ideal_loading: str = "turbine"

    def __post_init__(self):
        if isinstance(self.levels, bool) or not isinstance(self.levels, (int, np.integer)) or not \
                2 <= self.levels <= MAX_LEVELS:
            raise ValueError(f"levels must be an integer from 2 to {MAX_LEVELS}, got {self.levels!r}")
        for name in TURBINE_AXES:
            lo, hi = (float(v) for v in getattr(self, f"{name}_range"))
            if not (np.isfinite(lo) and np.isfinite(hi) and 0.0 <= lo <= hi):
                raise ValueError(f"{name}_range must be finite with 0 <= min <= max, got {(lo, hi)!r}")
        if not (self.tip_speed_ratio_range[0] > 0.0 and self.radius_range[0] > 0.0 and self.wind_speed > 0.0
                and 0.0 < self.thrust_coefficient_range[0] and self.thrust_coefficient_range[1] < 8.0 / 9.0):
            raise ValueError("tip-speed ratio, radius, wind speed and thrust coefficient must be positive, the "
                             "thrust coefficient below Betz's 8/9")
        if not 0.0 < self.hub_radius_fraction < self.reference_radius_fraction < 1.0:
            raise ValueError("need 0 < hub_radius_fraction < reference_radius_fraction < 1")
        if int(self.num_blades) < 1 or int(self.num_radial) < 2:
            raise ValueError("num_blades must be >= 1 and num_radial >= 2")
        if self.optimizer not in OPTIMIZERS:
            raise ValueError(f"optimizer must be one of {OPTIMIZERS}, got {self.optimizer!r}")
        if self.starts not in (1, 2):
            raise ValueError(f"starts must be 1 or 2 ({', '.join(TURBINE_STARTS)}) in a turbine sweep, "
                             f"got {self.starts!r}")
        if (self.section_point, self.ideal_loading) != ("reference", "turbine"):
            raise ValueError("a turbine sweep designs with the turbine BILD (section point 'reference')")

    @property
    def num_cases(self):
        """``levels**4``."""
        return int(self.levels) ** len(TURBINE_AXES)

    def axis_values(self):
        """``{axis: values[levels]}``, end points equal to the range bounds."""
        return {name: np.linspace(*(float(v) for v in getattr(self, f"{name}_range")), int(self.levels))
                for name in TURBINE_AXES}

    def to_dict(self):
        """Every field, JSON-able, with ``rotor_type: 'turbine'``."""
        out = {"rotor_type": "turbine"}
        for field in dataclasses.fields(self):
            value = getattr(self, field.name)
            out[field.name] = [float(v) for v in value] if isinstance(value, tuple) else value
        return out

    def fingerprint(self):
        """16 hex digits of the SHA-256 of the canonical JSON of the spec and the case layout."""
        payload = {"case_layout": CASE_LAYOUT_VERSION, "spec": self.to_dict()}
        return hashlib.sha256(json.dumps(payload, sort_keys=True, separators=(",", ":")).encode()).hexdigest()[:16]

    def case(self, case_id):
        """The case of ``case_id`` in ``[0, num_cases)``."""
        return self.cases([case_id])[0]

    def cases(self, case_ids=None):
        """Cases in id order (all without ``case_ids``)."""
        ids = range(self.num_cases) if case_ids is None else sorted(int(i) for i in case_ids)
        values, levels = self.axis_values(), int(self.levels)
        out = []
        for case_id in ids:
            point = axis_point(case_id, levels, values, TURBINE_AXES)
            radius, wind = point["radius"], float(self.wind_speed)
            rpm = point["tip_speed_ratio"] * wind / radius / RPM_TO_RAD_PER_S
            inputs = dict(point, advance_ratio=np.pi / point["tip_speed_ratio"], reference_chord=None, rpm=rpm,
                          v_axial=wind, reference_radius=float(self.reference_radius_fraction) * radius,
                          hub_radius=float(self.hub_radius_fraction) * radius, num_blades=int(self.num_blades),
                          num_radial=int(self.num_radial), airfoil=str(self.airfoil), rotor_type="turbine",
                          thrust=point["thrust_coefficient"] * 0.5 * float(isa(point["altitude"]).rho) * np.pi
                          * radius**2 * wind**2)
            out.append(Case(case_id=case_id, inputs=inputs, optimizer=self.optimizer, starts=int(self.starts),
                            ideal_loading="turbine"))
        return out


def _bild_rows(out, values):
    """The stored quantities of a batch of turbine BILD designs (module docstring), per design."""
    rows = []
    for k in range(values["radius"].size):
        thrust, power, torque = (float(out[name][k]) for name in ("thrust", "power", "torque"))
        wind = float(values["wind_speed"][k])
        row = {"thrust_coefficient": float(out["thrust_coefficient"][k]),
               "power_coefficient": float(out["power_coefficient"][k]),
               "torque_coefficient": float(out["power_coefficient"][k]) / float(out["tip_speed_ratio"][k]),
               "efficiency": power / (wind * thrust), "figure_of_merit": None, "energy_loss": wind * thrust - power,
               "chord": out["chord"][k].copy(), "twist": out["twist"][k].copy(), "thrust": thrust, "torque": torque}
        row["converged"] = bool(np.all(np.isfinite(row["chord"])) and np.isfinite(row["energy_loss"]))
        if not row["converged"]:
            row["error"] = "turbine BILD returned non-finite values"
        rows.append(row)
    return rows


def turbine_bild_batch(cases):
    """Turbine BILD designs of ``cases`` (one vectorised :func:`~bild_mdo.bild.turbine_problem.run_turbine_bild`
    per configuration, as ``design_turbine(thrust=...)``), each for its thrust; a failing case (no member for its
    thrust) gets its own error by bisection.  Rows as :func:`~bild_mdo.verification.case_functions.bild_batch`'s
    (module docstring)."""
    results = [None] * len(cases)
    groups = {}
    for index, case in enumerate(cases):
        groups.setdefault(tuple(case.inputs[k] for k in ("num_radial", "num_blades", "airfoil")), []).append(index)
    for (num_radial, num_blades, airfoil), indices in groups.items():
        polar = sweep_polar(airfoil)

        def run(part):
            column = {key: np.array([cases[i].inputs[key] for i in part], dtype=float)
                      for key in ("v_axial", "rpm", "radius", "hub_radius", "reference_radius", "altitude", "thrust")}
            values = {"wind_speed": column["v_axial"], "rpm": column["rpm"], "radius": column["radius"],
                      "hub_radius_ratio": column["hub_radius"] / column["radius"],
                      "ref_radius_ratio": column["reference_radius"] / column["radius"],
                      "altitude": column["altitude"], "thrust": column["thrust"]}
            return _bild_rows(run_turbine_bild(values, int(num_radial), int(num_blades), polar, "tip_hub", "thrust"),
                              values)

        successes, failures = isolate_failures(run, indices, (om.AnalysisError, ValueError, ArithmeticError))
        for i, exc in failures:
            results[i] = {"converged": False, "error": f"turbine BILD failed: {' '.join(str(exc).split())}"}
        for part, rows in successes:
            for i, row in zip(part, rows):
                results[i] = row
    return results


def optimize_turbine_cases(payloads, optimizer=None):
    """Full-BEM optimisations of a chunk of turbine cases in lockstep, each the most power at its BILD design's
    thrust; with ``starts == 2`` also from the linear cold start, the row then the better optimum with the
    spread (:func:`~bild_mdo.verification.starts.combine_starts`).  Per case a row or the exception it raised."""
    first = optimize_start(payloads, optimizer, "bild")
    chosen = [k for k, (case, _bild) in enumerate(payloads) if case.starts >= 2]
    second = [None] * len(payloads)
    if chosen:
        for k, row in zip(chosen, optimize_start([payloads[k] for k in chosen], optimizer, "linear")):
            second[k] = row
    return [combine_starts([first[k], None, second[k]]) if case.starts >= 2 else first[k]
            for k, (case, _bild) in enumerate(payloads)]


def optimize_turbine_case(case, bild_result):
    """:func:`optimize_turbine_cases` of one case (the runner's ``optimize_fn``)."""
    result = optimize_turbine_cases([(case, bild_result)])[0]
    if isinstance(result, Exception):
        raise result
    return result
