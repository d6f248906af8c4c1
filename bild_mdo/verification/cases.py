"""Full-factorial cases of the verification sweep (paper Sec. 5.1).

The paper sweeps advance ratio J in [0, 3], rotor radius R in [0.5, 1.5] m,
altitude in [0, 3000] m and reference chord c_ref in [0.08, 0.22] m with ten
levels per axis (10,000 cases) at 800 rpm and r_ref / R = 0.5.  The number of
blades, airfoil, number of stations and hub radius are not given in Sec. 5.1;
the defaults below (B = 3, NACA 4412, 30 stations, hub at 0.2 R) are this
library's choice and are part of the sweep fingerprint, so a results store can
never mix cases of different settings.
"""
import dataclasses
import hashlib
import json
from dataclasses import dataclass

import numpy as np

from bild_mdo.bild.annulus_stationarity import IDEAL_LOADINGS
from bild_mdo.bild.variants import SECTION_POINTS
from bild_mdo.constants import RPM_TO_REV_PER_S
from bild_mdo.optimization.problem import OPTIMIZERS

# Bumped whenever the mapping case_id -> inputs changes, so that old stores are
# refused instead of being silently resumed with different cases.
CASE_LAYOUT_VERSION = 1

# Swept axes in case-id order: the first axis varies slowest.
AXES = ("advance_ratio", "radius", "altitude", "reference_chord")

#: The optimiser's starts per case, in order (``SweepSpec.starts`` takes the first N): BILD at the sweep's
#: section point, BILD at the other section point, the linear cold start.
START_KINDS = ("bild", "other_bild", "linear")

#: Settings that joined the sweep after stores were written; at these defaults they stay out of
#: :meth:`SweepSpec.to_dict`, so the fingerprint of a sweep that does not use them is unchanged.
_LATER_DEFAULTS = {"section_point": "reference", "starts": 1, "ideal_loading": "paper"}

#: Largest number of levels per axis: 15**4 = 50,625 cases (five times the paper's sweep).
MAX_LEVELS = 15
# Measured on the paper's sweep (levels=10, 30 stations): peak memory per case of the
# batched BILD run plus the stored rows, and wall time of one warm-started SLSQP optimisation.
MEMORY_PER_CASE = 80.0e3  # bytes
OPTIMIZATION_TIME_PER_CASE = 0.5  # s


class CaseSetupError(ValueError):
    """A case could not be set up (optimiser missing, model set-up failed); it is not stored, so a rerun retries it."""


def bild_setting(section_point="reference", ideal_loading="paper"):
    """BILD's setting in words: ``'local section point'``, plus ``', exact ideal loading'`` off the paper's."""
    return f"{section_point} section point" + ("" if ideal_loading == "paper" else f", {ideal_loading} ideal loading")


def check_workers(workers):
    """Return ``workers`` as an int, or raise ValueError unless it is an integer >= 1.

    Parameters
    ----------
    workers : int
        Number of local worker processes (1 = in this process).
    """
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 1:
        raise ValueError(f"workers must be an integer >= 1 (1 runs in this process), got {workers!r}")
    return int(workers)


def _format_bytes(num):
    for unit, size in (("PB", 1e15), ("TB", 1e12), ("GB", 1e9), ("MB", 1e6)):
        if num >= size:
            return f"{num / size:.3g} {unit}"
    return f"{num / 1e3:.3g} kB"


def _format_cpu_time(seconds):
    for unit, size in (("years", 365.25 * 86400.0), ("days", 86400.0), ("hours", 3600.0), ("minutes", 60.0)):
        if seconds >= size:
            return f"{seconds / size:.3g} CPU-{unit}"
    return f"{seconds:.3g} CPU-seconds"


def sweep_estimate(levels):
    """Estimated peak memory and CPU time of a sweep with ``levels`` levels per axis.

    Parameters
    ----------
    levels : int

    Returns
    -------
    str
        For example ``'10,000 cases: about 800 MB of memory and 1.39 CPU-hours of BEM optimisation'``.
    """
    cases = int(levels) ** len(AXES)
    return (f"{cases:,} cases: about {_format_bytes(cases * MEMORY_PER_CASE)} of memory and "
            f"{_format_cpu_time(cases * OPTIMIZATION_TIME_PER_CASE)} of BEM optimisation")


def axis_point(case_id, levels, values, axes):
    """``{axis: value}`` of case ``case_id`` of a full-factorial sweep over ``axes`` (the first varies slowest),
    ``values[axis]`` its ``levels`` levels; ValueError outside ``[0, levels**len(axes))``."""
    count = levels ** len(axes)
    if not 0 <= case_id < count:
        raise ValueError(f"case_id must be in [0, {count}), got {case_id}")
    index, rest = {}, case_id
    for name in reversed(axes):
        rest, index[name] = divmod(rest, levels)
    return {name: float(values[name][index[name]]) for name in axes}


@dataclass(frozen=True)
class Case:
    """One design point of the sweep.

    Attributes
    ----------
    case_id : int
        Stable index in ``[0, levels**4)``: ``((i_J * L + i_R) * L + i_h) * L + i_c``
        with ``L`` levels and ``i_*`` the level index along each axis.
    inputs : dict
        Everything the BILD model and the BEM optimisation need, SI units:
        ``advance_ratio`` (-), ``radius`` (m), ``altitude`` (m),
        ``reference_chord`` (m), ``rpm`` (rpm), ``v_axial`` (m/s, = J n D),
        ``reference_radius`` (m), ``hub_radius`` (m), ``num_blades`` (-),
        ``num_radial`` (-), ``airfoil`` (text of :attr:`SweepSpec.airfoil`).
    optimizer : str
        Name of the NLP optimiser the reference optimisation should use
        (``'ipopt'``, ``'slsqp'`` or ``'snopt'``).
    section_point : {'reference', 'local'}
        BILD's section point (:class:`~bild_mdo.bild.BILDGroup`); its design is the sweep's BILD design.
    starts : int
        Starts of the optimiser, the first ``starts`` of :data:`START_KINDS`.
    ideal_loading : {'paper', 'exact'}
        BILD's ideal loading (:class:`~bild_mdo.bild.BILDGroup`), of every BILD start.
    """

    case_id: int
    inputs: dict
    optimizer: str = "slsqp"
    section_point: str = "reference"
    starts: int = 1
    ideal_loading: str = "paper"


@dataclass(frozen=True)
class SweepSpec:
    """Definition of a verification sweep: levels per axis, ranges and fixed inputs.

    Parameters
    ----------
    levels : int
        Number of evenly spaced values per swept axis (>= 2); ``levels**4`` cases.
        ``levels=10`` gives the paper's 10,000 cases.
    advance_ratio_range : tuple of float
        ``(min, max)`` advance ratio J = V_x / (n D) (-).
    radius_range : tuple of float
        ``(min, max)`` rotor tip radius R (m).
    altitude_range : tuple of float
        ``(min, max)`` altitude (m).
    reference_chord_range : tuple of float
        ``(min, max)`` chord at the reference radius (m).
    rpm : float
        Rotational speed (rpm).
    reference_radius_fraction : float
        Reference radius as a fraction of R (-).
    hub_radius_fraction : float
        Hub radius as a fraction of R (-).
    num_blades : int
        Number of blades B.
    num_radial : int
        Number of radial stations.
    airfoil : str
        The airfoil of BILD, the optimisation and the optimality check, as text
        (stored in every row and part of the fingerprint): anything
        :func:`~bild_mdo.airfoil.builtin.resolve_polar` accepts (built-in name,
        NACA designation, polar files or folder, coordinates file), a polar
        frozen at one Reynolds number (``'naca4412@re=1e6'``) or a spanwise set
        (``'0.2:naca4415;1:naca4412'``); see
        :func:`~bild_mdo.airfoil.text.sweep_polar`.  A path is stored
        as written: rerun a sweep from the same folder.
    optimizer : str
        Optimiser used for the reference BEM optimisation; part of the
        fingerprint so results of different optimisers are never mixed.
    section_point : {'reference', 'local'}
        BILD's section point: the paper's one max-L/D point at the reference
        station, or each station's own (``BILDGroup(section_point=...)``).
    starts : int
        Optimiser starts per case, 1 to ``len(START_KINDS)`` (see
        :data:`START_KINDS`); the lowest-energy converged optimum is the
        reference.
    ideal_loading : {'paper', 'exact'}
        BILD's ideal loading: the paper's Eq. (22) or the exact one with
        Prandtl's F (``BILDGroup(ideal_loading=...)``).  ``section_point``,
        ``starts`` and ``ideal_loading`` are part of the fingerprint (left out
        of it at their defaults, so older stores of the paper's setting still resume).
    """

    levels: int = 10
    advance_ratio_range: tuple = (0.0, 3.0)
    radius_range: tuple = (0.5, 1.5)
    altitude_range: tuple = (0.0, 3000.0)
    reference_chord_range: tuple = (0.08, 0.22)
    rpm: float = 800.0
    reference_radius_fraction: float = 0.5
    hub_radius_fraction: float = 0.2
    num_blades: int = 3
    num_radial: int = 30
    airfoil: str = "naca4412"
    optimizer: str = "slsqp"
    section_point: str = "reference"
    starts: int = 1
    ideal_loading: str = "paper"

    def __post_init__(self):
        if isinstance(self.levels, bool) or not isinstance(self.levels, (int, np.integer)) or self.levels < 2:
            raise ValueError(f"levels must be an integer >= 2 (each axis spans its range), got {self.levels!r}")
        if self.levels > MAX_LEVELS:
            raise ValueError(f"levels={self.levels} is too large: {sweep_estimate(self.levels)}; "
                             f"levels <= {MAX_LEVELS} ({sweep_estimate(MAX_LEVELS)})")
        for name in AXES:
            lo, hi = self._range(name)
            if not (np.isfinite(lo) and np.isfinite(hi) and lo <= hi):
                raise ValueError(f"{name}_range must be finite with min <= max, got {(lo, hi)!r}")
        if self.radius_range[0] <= 0.0 or self.reference_chord_range[0] <= 0.0 or self.advance_ratio_range[0] < 0.0:
            raise ValueError("radius and reference chord must be positive and the advance ratio non-negative")
        if not self.rpm > 0.0:
            raise ValueError(f"rpm must be positive, got {self.rpm!r}")
        if not 0.0 <= self.hub_radius_fraction < self.reference_radius_fraction < 1.0:
            raise ValueError(
                "need 0 <= hub_radius_fraction < reference_radius_fraction < 1, got "
                f"{self.hub_radius_fraction!r} and {self.reference_radius_fraction!r}"
            )
        if int(self.num_blades) < 1 or int(self.num_radial) < 2:
            raise ValueError("num_blades must be >= 1 and num_radial >= 2")
        if not isinstance(self.airfoil, str) or not self.airfoil.strip():
            raise ValueError(f"airfoil must be a non-empty string (a store keeps it as text), got {self.airfoil!r}")
        if self.optimizer not in OPTIMIZERS:
            raise ValueError(f"optimizer must be one of {OPTIMIZERS}, got {self.optimizer!r}")
        if self.section_point not in SECTION_POINTS:
            raise ValueError(f"section point must be one of {', '.join(SECTION_POINTS)}, got {self.section_point!r}")
        if (isinstance(self.starts, bool) or not isinstance(self.starts, (int, np.integer))
                or not 1 <= self.starts <= len(START_KINDS)):
            raise ValueError(f"starts must be an integer from 1 to {len(START_KINDS)} ({', '.join(START_KINDS)}), "
                             f"got {self.starts!r}")
        if self.ideal_loading not in IDEAL_LOADINGS:
            raise ValueError(f"ideal loading must be one of {', '.join(IDEAL_LOADINGS)}, got {self.ideal_loading!r}")

    def _range(self, axis):
        lo, hi = getattr(self, f"{axis}_range")
        return float(lo), float(hi)

    @property
    def num_cases(self):
        """Number of cases, ``levels**4``."""
        return int(self.levels) ** len(AXES)

    def axis_values(self):
        """Return the levels of each swept axis.

        Returns
        -------
        dict of str to ndarray
            ``{axis: values[levels]}``; the end points equal the range bounds exactly.
        """
        return {name: np.linspace(*self._range(name), int(self.levels)) for name in AXES}

    def to_dict(self):
        """Plain JSON-able dict of every field (ranges as lists); the :data:`_LATER_DEFAULTS` only off their defaults."""
        out = {}
        for field in dataclasses.fields(self):
            value = getattr(self, field.name)
            if isinstance(value, tuple):
                value = [float(v) for v in value]
            elif isinstance(value, (np.integer, int)) and not isinstance(value, bool):
                value = int(value)
            elif isinstance(value, (np.floating, float)):
                value = float(value)
            if _LATER_DEFAULTS.get(field.name, object()) == value:
                continue
            out[field.name] = value
        return out

    def fingerprint(self):
        """Short hash identifying this sweep (fields and case layout).

        Returns
        -------
        str
            16 hex digits of the SHA-256 of the canonical JSON of the spec.
        """
        payload = {"case_layout": CASE_LAYOUT_VERSION, "spec": self.to_dict()}
        text = json.dumps(payload, sort_keys=True, separators=(",", ":"))
        return hashlib.sha256(text.encode()).hexdigest()[:16]

    def case(self, case_id):
        """Return the case with the given id.

        Parameters
        ----------
        case_id : int
            Index in ``[0, num_cases)``.

        Returns
        -------
        Case
        """
        return self._build_case(case_id, self.axis_values())

    def _build_case(self, case_id, values):
        case_id = int(case_id)
        point = axis_point(case_id, int(self.levels), values, AXES)
        radius = point["radius"]
        rev_per_second = float(self.rpm) * RPM_TO_REV_PER_S
        inputs = dict(point)
        inputs.update(
            rpm=float(self.rpm),
            v_axial=point["advance_ratio"] * rev_per_second * 2.0 * radius,  # J = V_x / (n D)
            reference_radius=float(self.reference_radius_fraction) * radius,
            hub_radius=float(self.hub_radius_fraction) * radius,
            num_blades=int(self.num_blades),
            num_radial=int(self.num_radial),
            airfoil=str(self.airfoil),
        )
        return Case(case_id=case_id, inputs=inputs, optimizer=self.optimizer, section_point=self.section_point,
                    starts=int(self.starts), ideal_loading=self.ideal_loading)

    def cases(self, case_ids=None):
        """Return cases in id order.

        Parameters
        ----------
        case_ids : iterable of int, optional
            Subset to build; all ``num_cases`` cases when omitted.

        Returns
        -------
        list of Case
        """
        ids = range(self.num_cases) if case_ids is None else sorted(int(i) for i in case_ids)
        values = self.axis_values()
        return [self._build_case(i, values) for i in ids]
