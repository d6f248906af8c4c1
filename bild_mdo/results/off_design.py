"""Off-design performance of a fixed rotor geometry: a vectorised BEM sweep over J, airspeed, rpm or collective pitch.

:func:`off_design_sweep` analyses one blade (a BILD design, a geometry file or
arrays) at many operating points in ONE call of
:func:`~bild_mdo.bem.analyze_rotor` (``num_nodes`` = number of points), as in
the paper's Fig. 9 (efficiency against advance ratio of BILD blades)::

    from bild_mdo import design_rotor, off_design_sweep

    rotor = design_rotor(advance_ratio=1.0)
    sweep = off_design_sweep(rotor, advance_ratios=np.linspace(0.2, 1.6, 15))
    print(sweep.summary())
    print(sweep.max_efficiency_point)

At its own design point the BEM analysis of a BILD blade reproduces BILD's
thrust and torque exactly when the polar does not depend on the Reynolds
number (every element then works at ``alpha*``).  With a Reynolds-dependent
polar it does not quite: BILD evaluates the max-L/D point at the reference
station's Reynolds number and uses it everywhere, while BEM uses each
station's own Reynolds number.  Measured with 30 stations over J = 0 ... 3
and c_ref = 0.08 ... 0.22 m (R = 1.5 m, 800 rpm): ``|dT/T| < 1e-13`` with the
Reynolds-independent :class:`~bild_mdo.airfoil.AnalyticPolar`; with the NACA
4412 surrogate ``|dT/T| <= 1.4e-3`` and ``|dQ/Q| <= 3.3e-3``.
"""
from __future__ import annotations

import dataclasses
import warnings
from pathlib import Path
from typing import ClassVar

import numpy as np
import openmdao.api as om

from bild_mdo import validation
from bild_mdo.bem.analyze import BEMResult, analyze_rotor
from bild_mdo.bem.flow_states import ON_INVALID
from bild_mdo.bem.metrics import METRICS, TipMachWarning
from bild_mdo.constants import RPM_TO_REV_PER_S
from bild_mdo.fluid import point_fluid, resolve_fluid
from bild_mdo.io.airfoil import resolve_airfoil
from bild_mdo.io.files import read_geometry
from bild_mdo.io.geometry import RotorGeometry, as_geometry, unit_key
from bild_mdo.io.qprop import polar_from_qprop
from bild_mdo.results import tables
from bild_mdo.results.design import DesignResult
from bild_mdo.results.point_analysis import analyze_points
from bild_mdo.results.thrust_trim import TRIM_VARIABLES, out_of_reach, trim_points

#: The operating point of each sweep point: name -> units.
POINT_UNITS = {"advance_ratio": None, "v_axial": "m/s", "rpm": "rpm"}


@dataclasses.dataclass(frozen=True, eq=False)
class OffDesignResult:
    """Performance of one rotor geometry over a sweep of operating points (arrays of shape ``(n,)``).

    Every performance metric of :data:`~bild_mdo.bem.metrics.METRICS` is an
    attribute (``result.thrust``, ``result.efficiency``, ...), held in
    :attr:`performance`.

    Attributes
    ----------
    sweep : str
        ``'advance_ratio'``, ``'v_axial'`` (airspeed), ``'rpm'`` or ``'collective_pitch'``: the swept
        variable (a J, airspeed or rpm sweep at several pitches repeats it for each pitch).
    advance_ratio, v_axial, rpm : ndarray
        Operating points: J = V/(nD) (-), axial velocity (m/s), rotor speed (rpm).
    collective_pitch : ndarray
        Collective pitch (rad) added to the twist, per point (``collective_pitch_deg`` in degrees).
    performance : dict
        Metric name -> array (units in :attr:`UNITS`): T (N), Q (N m), P (W), C_T, C_Q, C_P, eta, FM, ...
    geometry : RotorGeometry
        The analysed blade.
    altitude : float
        Altitude of the ISA state (m).
    design_advance_ratio : float or None
        J of the design point, if the geometry knows it.
    bem : BEMResult or None
        The full BEM result (distributions of shape ``(n, nr)``); None when
        some point failed (then see :attr:`status`).
    status : ndarray of str
        ``'ok'``, or why the point failed (its performance values are NaN).
    flow_state : ndarray of int or None
        BEM flow-state code of every station, shape ``(n, nr)``
        (:mod:`bild_mdo.bem.flow_states`); -1 at failed points.
    mach : ndarray or None
        Local Mach number of every station, shape ``(n, nr)``; NaN at failed
        points.  The tip Mach number ``tip_mach`` is one of the metrics.

    Notes
    -----
    ``efficiency`` and ``figure_of_merit`` hold the formulas' values
    (``eta = T V / P``, ``FM = T sqrt(T / (2 rho A)) / P``) at every point;
    they are physical efficiencies only where ``T > 0`` and ``P > 0``: a
    windmilling point (``T < 0``, ``P < 0``) can give ``eta > 1``.  The text
    table prints "n/a" there.
    """

    sweep: str
    advance_ratio: np.ndarray
    v_axial: np.ndarray
    rpm: np.ndarray
    performance: dict = dataclasses.field(repr=False)
    geometry: RotorGeometry = dataclasses.field(repr=False)
    altitude: float = 0.0
    design_advance_ratio: float | None = None
    bem: BEMResult | None = dataclasses.field(default=None, repr=False)
    status: np.ndarray | None = dataclasses.field(default=None, repr=False)
    flow_state: np.ndarray | None = dataclasses.field(default=None, repr=False)
    mach: np.ndarray | None = dataclasses.field(default=None, repr=False)
    collective_pitch: np.ndarray | None = None

    def __post_init__(self):
        if self.status is None:
            object.__setattr__(self, "status", np.full(self.rpm.size, "ok", dtype=object))
        if self.collective_pitch is None:
            object.__setattr__(self, "collective_pitch", np.zeros(self.rpm.size))

    @property
    def collective_pitch_deg(self):
        """Collective pitch of every point (deg)."""
        return np.degrees(self.collective_pitch)

    @property
    def ok(self):
        """ndarray of bool: True at the points that were analysed (``status == 'ok'``)."""
        return np.asarray(self.status == "ok", dtype=bool)

    # The pitch comes last, so the columns of the CSV table before it keep their places.
    UNITS: ClassVar[dict] = {**POINT_UNITS, **{metric.name: metric.units for metric in METRICS},
                             "collective_pitch": "rad"}

    def __getattr__(self, name):
        # Only called for names that are not fields: the performance metrics.
        if name.startswith("__") or name == "performance":
            raise AttributeError(name)
        try:
            return self.performance[name]
        except KeyError:
            raise AttributeError(f"OffDesignResult has no quantity {name!r}") from None

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(self.performance))

    def __len__(self):
        return self.rpm.size

    @property
    def max_efficiency_index(self):
        """Index of the most efficient point with forward speed, thrust and power > 0 (None if there is none)."""
        useful = (self.thrust > 0.0) & (self.power > 0.0) & (self.v_axial > 0.0)
        eta = np.where(useful, self.efficiency, -np.inf)
        if not np.any(np.isfinite(eta)):
            return None
        return int(np.argmax(eta))

    @property
    def max_efficiency_point(self):
        """``{'advance_ratio', 'v_axial', 'rpm', 'collective_pitch', 'efficiency', 'thrust', 'power'}`` at the
        best point, or None."""
        i = self.max_efficiency_index
        if i is None:
            return None
        return {name: float(getattr(self, name)[i])
                for name in ("advance_ratio", "v_axial", "rpm", "collective_pitch", "efficiency", "thrust", "power")}

    def to_dict(self):
        """The per-point arrays (units in :attr:`UNITS`) and the sweep metadata."""
        data = {name: getattr(self, name) for name in self.UNITS}
        data.update(sweep=self.sweep, altitude=self.altitude, design_advance_ratio=self.design_advance_ratio,
                    status=self.status)
        return data

    def to_csv(self, path):
        """Write the performance table as CSV with units in the header.

        Returns
        -------
        pathlib.Path
        """
        names = list(self.UNITS)
        lines = [f"# bild-mdo off-design sweep over {self.sweep}, altitude [m]: {self.altitude:g}"]
        lines += [f"# point {i} failed (values nan): {self.status[i]}" for i in np.flatnonzero(~self.ok)]
        lines.append(",".join(unit_key(n, self.UNITS[n]) for n in names))
        for i in range(len(self)):
            lines.append(",".join(f"{float(getattr(self, n)[i]):.10g}" for n in names))
        path = Path(path)
        path.write_text("\n".join(lines) + "\n", encoding="utf-8")
        return path

    def summary(self):
        """Text table of the sweep with units, and the maximum-efficiency point."""
        lines = [f"Off-design BEM analysis: {self.geometry.name}, B = {self.geometry.num_blades}, "
                 f"R = {self.geometry.radius:g} m, altitude {self.altitude:g} m, swept {self.sweep}"]
        lines += tables.sweep_table(self)
        lines += tables.status_footer(self, "points")
        best = self.max_efficiency_point
        if best is None:
            lines.append("maximum efficiency: none (no point with forward speed and positive thrust)")
        else:
            lines.append(f"maximum efficiency: eta = {best['efficiency']:.4f} at J = {best['advance_ratio']:.4f} "
                         f"(V = {best['v_axial']:.3f} m/s, {best['rpm']:.1f} rpm"
                         + (f", pitch {np.degrees(best['collective_pitch']):.3f} deg)" if np.any(self.collective_pitch)
                            else ")"))
        return "\n".join(lines)


def _blade(geometry, design):
    """The RotorGeometry to analyse (``design`` picks one of a batch or a multi-design JSON file)."""
    if isinstance(geometry, DesignResult):
        count = len(geometry)
        if design is None:
            if geometry.is_batch and count > 1:
                raise ValueError(f"the DesignResult holds {count} designs; choose one with design=i")
            return geometry.geometry(None)
        design = validation.integer("design", design, minimum=-count)
        if design >= count:
            raise ValueError(f"design must be an index of the DesignResult's {count} design(s), got {design}")
        return geometry.geometry(design)
    if design is not None:
        design = validation.integer("design", design, minimum=0)
    if isinstance(geometry, (str, Path)):
        return read_geometry(geometry, design=0 if design is None else design)
    return as_geometry(geometry, index=design)


def _default_polar(geometry):
    if geometry.polar is not None:
        return geometry.polar
    if geometry.airfoil:
        return resolve_airfoil(geometry.airfoil)
    if geometry.polar_coefficients:
        return polar_from_qprop(geometry.polar_coefficients)
    raise ValueError("the geometry names no airfoil; pass polar= (a Polar or a built-in airfoil name)")


def _sweep_points(name, values, check, units):
    points = np.atleast_1d(check(name, values, units=units, axes=("point",)))
    if points.size == 0:
        raise ValueError(f"{name} must be a non-empty 1-D list of values")
    return points


def off_design_sweep(geometry, advance_ratios=None, rpms=None, v_axial=None, rpm=None, altitude=None,
                     polar=None, loss_model=None, design=None, on_invalid="warn", collective_pitch=0.0, fluid=None,
                     thrust=None, trim="collective_pitch"):
    """BEM analysis of one fixed blade over a range of advance ratios, airspeeds, rotor speeds or collective pitches.

    All points run in one vectorised analysis.  A point whose analysis fails
    (no torque at all, or, with ``on_invalid='raise'``, stations outside the
    momentum model's flow states) does not stop the sweep: it is recorded in
    ``result.status`` with its reason and its values are NaN.  Only where the
    analysis raises (no torque at some point) are the failing points isolated
    by splitting the batch in halves (a few more runs).

    Parameters
    ----------
    geometry : DesignResult, RotorGeometry, dict or path
        The blade: a single BILD design (or ``design=i`` of a batch), a
        geometry, a dict of :class:`~bild_mdo.io.geometry.RotorGeometry` fields,
        or a CSV/JSON/QPROP file (its airfoil comes with it).
    advance_ratios : array_like, optional
        Sweep J = V/(nD) (-, >= 0) at rotor speed ``rpm``.
    rpms : array_like, optional
        Sweep the rotor speed (rpm, > 0) at axial velocity ``v_axial``.
        Give at most one of ``advance_ratios``, ``rpms`` and a list of
        ``v_axial``; with none, ``collective_pitch`` must be a list (a pitch
        sweep at the design point).
    v_axial : float or array_like, optional
        A number: the axial velocity (m/s) of an rpm or pitch sweep; default
        the design's, else 0.  A list: sweep the airspeed (m/s, >= 0) at rotor
        speed ``rpm`` (``result.sweep == 'v_axial'``).  An advance-ratio sweep
        fixes the airspeed by J and rpm, so it takes no ``v_axial``.
    rpm : float, optional
        Rotor speed (rpm) of an advance-ratio or pitch sweep; default the design's.
    altitude : float, optional
        ISA altitude (m); default the design's, else 0.
    fluid : Fluid, str or (rho, mu, speed_of_sound), optional
        Any fluid instead of the ISA (:mod:`bild_mdo.fluid`); default the fluid the geometry keeps (a design
        made with ``fluid=``, or its file), else the ISA at ``altitude``.
    polar : Polar or str, optional
        Default: the polar the geometry carries (a design's polar, a file's),
        its airfoil name, or its QPROP airfoil lines.  Any text
        :func:`~bild_mdo.io.airfoil.resolve_airfoil` accepts.
    loss_model : str, optional
        Default: the design's.
    design : int, optional
        Design of a batch DesignResult or multi-design JSON file.
    on_invalid : {'warn', 'raise', 'ignore'}
        Stations in a flow state the momentum model does not represent
        (:func:`~bild_mdo.bem.analyze.analyze_rotor`): one warning naming them
        (default), their points recorded as failed, or nothing.
    collective_pitch : float or array_like
        Collective pitch (rad) added to the twist at every station.  A list of
        pitches sweeps them: alone, at the design's J and rpm; with
        ``advance_ratios`` or ``rpms``, every pitch at every point (the
        pitch varies slowest: one curve per pitch).

    thrust : float, optional
        Trim every point to this thrust (N, > 0) by ``trim`` (:mod:`bild_mdo.results.thrust_trim`); alone,
        at the design point.  A point whose thrust is out of reach is recorded in ``result.status``.
    trim : {'collective_pitch', 'rpm'}
        What the thrust trim sets: the collective pitch (with a J, airspeed or rpm sweep) or the rotor
        speed (with an airspeed sweep or at the design point).

    Returns
    -------
    OffDesignResult

    Raises
    ------
    ValueError
        For invalid inputs.
    """
    pitches = np.atleast_1d(validation.real_array("collective_pitch", collective_pitch, units="rad",
                                                  axes=("pitch",)))
    pitch_sweep = np.ndim(collective_pitch) == 1
    airspeed_sweep = v_axial is not None and np.ndim(v_axial) == 1
    if sum((advance_ratios is not None, rpms is not None, airspeed_sweep)) > 1:
        raise ValueError("give at most one of advance_ratios (J sweep), rpms (rotor-speed sweep) and a list of "
                         "v_axial (airspeed sweep)")
    if advance_ratios is not None and v_axial is not None:
        raise ValueError("an advance-ratio sweep fixes the airspeed by J and rpm (V = J n D): leave v_axial out, "
                         "or sweep the airspeed with v_axial=[...] instead of advance_ratios")
    if thrust is not None:
        thrust = float(validation.positive("thrust", thrust, units="N", ndim=(0,)))
        validation.choice("trim", trim, TRIM_VARIABLES)
        if trim == "collective_pitch" and pitch_sweep:
            raise ValueError("a thrust trim by collective pitch sets each point's pitch: give no pitch sweep")
        if trim == "rpm" and (rpms is not None or advance_ratios is not None):
            raise ValueError("a thrust trim by rotor speed sets each point's rpm (and so J): sweep the airspeed "
                             "(v_axial=[...]) or trim the collective pitch")
    if advance_ratios is None and rpms is None and not airspeed_sweep and not pitch_sweep and thrust is None:
        raise ValueError("give advance_ratios (J sweep), rpms (rotor-speed sweep), a list of v_axial (airspeed "
                         "sweep) or a list of collective_pitch values (pitch sweep)")
    if pitches.size == 0:
        raise ValueError("collective_pitch must be a number or a non-empty 1-D list of values in rad")
    validation.choice("on_invalid", on_invalid, ON_INVALID)
    geom = _blade(geometry, design)
    point = geom.design_point
    polar = _default_polar(geom) if polar is None else resolve_airfoil(polar)
    if fluid is not None and altitude is not None:
        raise ValueError("give either altitude [m] (the ISA) or fluid, not both")
    fluid = resolve_fluid(fluid) if fluid is not None else (point_fluid(point) if altitude is None else None)
    altitude = point.get("altitude", 0.0) if altitude is None else float(validation.real_array("altitude", altitude,
                                                                                               units="m", ndim=(0,)))
    loss_model = geom.loss_model if loss_model is None else loss_model
    revs_per_diameter = RPM_TO_REV_PER_S * 2.0 * geom.radius  # n D per rpm

    if rpms is None:
        j = (_sweep_points("advance_ratios", advance_ratios, validation.non_negative, None)
             if advance_ratios is not None else None)
        airspeeds = _sweep_points("v_axial", v_axial, validation.non_negative, "m/s") if airspeed_sweep else None
        if rpm is None:
            if "rpm" not in point:
                raise ValueError("the geometry has no design rpm; give the rotor speed of the sweep (rpm=..., "
                                 "bild-mdo analyze --at-rpm)")
            rpm = point["rpm"]
        rpm = float(validation.positive("rpm", rpm, units="rpm", ndim=(0,)))
        if airspeeds is not None:
            j = airspeeds / (rpm * revs_per_diameter)
        if j is None:  # a pitch sweep at the design point: its J, or its axial velocity
            v = point.get("v_axial", 0.0) if v_axial is None else v_axial
            v = float(validation.non_negative("v_axial", v, units="m/s", ndim=(0,)))
            j = np.array([v / (rpm * revs_per_diameter)])
        speeds = np.full(j.shape, rpm)
        velocities = airspeeds if airspeeds is not None else j * speeds * revs_per_diameter
        sweep = ("advance_ratio" if advance_ratios is not None else "v_axial" if airspeeds is not None
                 else "collective_pitch")
    else:
        speeds = _sweep_points("rpms", rpms, validation.positive, "rpm")
        v = point.get("v_axial", 0.0) if v_axial is None else v_axial
        velocities = np.full(speeds.shape, float(validation.non_negative("v_axial", v, units="m/s", ndim=(0,))))
        j = velocities / (speeds * revs_per_diameter)
        sweep = "rpm"
    # Every pitch at every operating point, the pitch varying slowest.
    count = pitches.size * speeds.size
    validation.memory_bound("sweep points", count, geom.num_radial, hint="use fewer points or pitches")
    pitch = np.repeat(pitches, speeds.size)
    speeds, velocities, j = (np.tile(a, pitches.size) for a in (speeds, velocities, j))
    analysis = dict(altitude=0.0 if fluid is not None else altitude, fluid=fluid, loss_model=loss_model,
                    radii=geom.radii, dr=geom.dr)
    reached = np.ones(count, dtype=bool)
    if thrust is not None:
        def thrust_at(values):
            k = values.shape[1]
            x = {"collective_pitch": np.repeat(pitch, k), "rpm": np.repeat(speeds, k)}
            x[trim] = values.ravel()
            try:
                with warnings.catch_warnings():  # the scan's trial speeds may pass Mach 1; the result warns itself
                    warnings.simplefilter("ignore", TipMachWarning)
                    result = analyze_rotor(geom.chord, geom.twist, geom.radius, geom.hub_radius, x["rpm"],
                                           np.repeat(velocities, k), geom.num_blades, polar, on_invalid="ignore",
                                           collective_pitch=x["collective_pitch"], **analysis)
            except om.AnalysisError:
                return np.full(values.shape, np.nan)
            return np.asarray(result.thrust).reshape(values.shape)

        solved, reached = trim_points(thrust_at, thrust, pitch if trim == "collective_pitch" else speeds, trim)
        if trim == "collective_pitch":
            pitch = solved
        else:
            speeds = solved
            j = velocities / (speeds * revs_per_diameter)

    def run(points, mode):
        return analyze_rotor(geom.chord, geom.twist, geom.radius, geom.hub_radius, speeds[points],
                             velocities[points], geom.num_blades, polar, on_invalid=mode,
                             collective_pitch=pitch[points], **analysis)

    r_over_r = np.broadcast_to(np.asarray(geom.radii) / geom.radius, (count, np.size(geom.radii)))
    bem, performance, stations, status = analyze_points(run, count, on_invalid, r_over_r)
    if not np.all(reached):
        status[~reached] = out_of_reach(trim, thrust)
        for values in performance.values():
            values[~reached] = np.nan
        bem = None
    return OffDesignResult(sweep=sweep, advance_ratio=j, v_axial=velocities, rpm=speeds, performance=performance,
                           geometry=geom, altitude=altitude, design_advance_ratio=point.get("advance_ratio"), bem=bem,
                           status=status, flow_state=stations["flow_state"], mach=stations["mach"],
                           collective_pitch=pitch)
