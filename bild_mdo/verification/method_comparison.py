"""BILD, minimum-induced-loss design and the full-BEM optimum, compared at the same thrust (issue 12).

Per forward-flight case (J > 0) of a verification sweep: BILD with the paper's reference section point
(``bild_reference``, for the case's ``c_ref``) and with each station's own point (``bild_local``, for the
same thrust); the minimum-induced-loss design (``mil``: Adkins & Liebeck 1994, A&L's tip factor) for the
same thrust at BILD's operating and reference airfoil point; the full-BEM optimum (``optimum``) for the same
thrust, the lowest converged run from the BILD starts (it is not unique with a Reynolds-dependent polar).
Each is trimmed by collective pitch to the optimum's thrust in the optimisation's BEM model by the
optimality check's trim (:mod:`~bild_mdo.verification.optimality`) and compared with the optimum: energy
loss, and geometry as the verification measures it (``||x - x_opt||_2 / ||x_opt||_2``).
"""
from __future__ import annotations

import contextlib
import dataclasses
import inspect
import time

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.text import sweep_polar
from bild_mdo.atmosphere import isa
from bild_mdo.bild.bild_group import BILDGroup
from bild_mdo.bild.problem import bild_problem
from bild_mdo.constants import RPM_TO_REV_PER_S
from bild_mdo.mil import design_mil
from bild_mdo.optimization.problem import build_optimization_problem
from bild_mdo.optimization.run import optimize_rotor
from bild_mdo.utils.batches import isolate_failures

from .optimality import trimmed_bild_energy_loss

#: The compared methods, in table order; the optimum is the reference.
METHODS = ("bild_reference", "bild_local", "mil", "optimum")
#: Names for tables and figures.
METHOD_LABELS = {"bild_reference": "BILD (reference point)", "bild_local": "BILD (local point)",
                 "mil": "MIL (Adkins & Liebeck)", "optimum": "BEM optimum"}
_CASE_ERRORS = (om.AnalysisError, ValueError, ArithmeticError)
_BILD_POINT = ("alpha_star", "cl_star", "cd_star")
_FIELDS = ("energy_loss", "energy_excess", "efficiency", "twist_error", "chord_error", "pitch_offset",
           "thrust_residual")


def forward_flight_cases(spec):
    """The cases (list of Case) of ``spec`` (SweepSpec) with J > 0, in case-id order (54 at levels 3)."""
    return [case for case in spec.cases() if case.inputs["advance_ratio"] > 0.0]


def local_section_point_available():
    """True when BILDGroup and :func:`~bild_mdo.bild.problem.bild_problem` accept ``section_point``."""
    return ("section_point" in inspect.signature(bild_problem).parameters
            and "section_point" in BILDGroup(num_nodes=1, num_radial=2).options)


@dataclasses.dataclass
class MethodDesigns:
    """The designs of one method for every case; rows of cases without a design are NaN.

    Attributes
    ----------
    chord, twist : ndarray, shape (n, nr)
        Geometry at the stations (m, rad), as designed (before the trim).
    converged : ndarray of bool, shape (n,)
        The design exists (for the optimum: a run converged).
    time_per_design : ndarray, shape (n,)
        One design alone (s): a single-design model run (:func:`_time_singles`) or the optimiser's wall time.
    batch_time_per_design : float
        Model-run time of the batched runs that succeeded over their designs (s); NaN for the optimum.
    errors, timing_failures : dict of int to str
        By case index: why a case has no design; why one designed in the batch failed alone (untimed).
    extra : dict of str to ndarray
        Per-case outputs (see the function that made the designs).
    """

    chord: np.ndarray
    twist: np.ndarray
    converged: np.ndarray
    time_per_design: np.ndarray
    batch_time_per_design: float = float("nan")
    errors: dict = dataclasses.field(default_factory=dict)
    timing_failures: dict = dataclasses.field(default_factory=dict)
    extra: dict = dataclasses.field(default_factory=dict)


def _empty(count, num_radial, extra):
    return MethodDesigns(chord=np.full((count, num_radial), np.nan), twist=np.full((count, num_radial), np.nan),
                         converged=np.zeros(count, dtype=bool), time_per_design=np.full(count, np.nan),
                         extra={name: np.full(count, np.nan) for name in extra})


def _column(cases, key):
    return np.array([float(case.inputs[key]) for case in cases])


def _configuration(cases):
    keys = {tuple(case.inputs[k] for k in ("num_radial", "num_blades", "airfoil")) for case in cases}
    if len(keys) != 1:
        raise ValueError(f"the cases must share stations, blades and airfoil, got {sorted(keys)}")
    num_radial, num_blades, airfoil = keys.pop()
    return int(num_radial), int(num_blades), airfoil


def _set_bild_inputs(prob, cases, thrust=None):
    radius = _column(cases, "radius")
    values = {"v_axial": _column(cases, "v_axial"), "rpm": _column(cases, "rpm"), "radius": radius,
              "altitude": _column(cases, "altitude"), "hub_radius_ratio": _column(cases, "hub_radius") / radius,
              "ref_radius_ratio": _column(cases, "reference_radius") / radius}
    if thrust is None:
        values["ref_chord"] = _column(cases, "reference_chord")
    else:
        values["thrust_target"] = thrust
    for name, value in values.items():  # SI units, BILDGroup's own
        prob.set_val(name, value)


def _time_singles(out, run, repeats, budget=120.0):
    """Best wall time of ``run(i)`` per designed case ``i`` over up to ``repeats`` passes through the cases.

    Each run starts from the state the previous case left (as designing them one at a time would), so a
    solve that reuses its last solution is never timed from its own answer.  One untimed run of the last
    case warms up; passes stop after the first once ``budget`` seconds are spent; ``repeats=0``: no timing.
    """
    designed = [int(i) for i in np.flatnonzero(out.converged)] if repeats >= 1 else []
    best = np.full(len(out.converged), np.inf)
    begin = time.perf_counter()
    for k in range(int(repeats) + 1):
        for i in designed[-1:] if k == 0 else designed:
            if i in out.timing_failures:
                continue
            start = time.perf_counter()
            try:
                run(i)
            except _CASE_ERRORS as exc:
                out.timing_failures[i] = " ".join(str(exc).split())
                continue
            if k:
                best[i] = min(best[i], time.perf_counter() - start)
        if k and time.perf_counter() - begin > budget:
            break
    timed = np.isfinite(best)
    out.time_per_design[timed] = best[timed]


def bild_designs(cases, section_point="reference", repeats=3, thrust=None):
    """BILD designs of ``cases``: one batched run (failing cases isolated by bisection), then each alone, timed.

    Parameters
    ----------
    cases : list of Case
        Cases of one configuration (stations, blades, airfoil).
    section_point : {'reference', 'local'}
    repeats : int
        Timed passes of single-design runs (:func:`_time_singles`).
    thrust : ndarray, optional
        Thrust (N) to design for instead of the case's c_ref (``thrust_target=True``).

    Returns
    -------
    MethodDesigns
        ``extra``: ``thrust`` (N), ``ref_chord`` (m) and the reference station's ``alpha_star, cl_star, cd_star``.
    """
    num_radial, num_blades, airfoil = _configuration(cases)
    out = _empty(len(cases), num_radial, ("thrust",) + _BILD_POINT + ("ref_chord",))
    names = ("thrust",) + tuple(f"{n}_ref" if section_point == "local" else n for n in _BILD_POINT) + ("ref_chord",)
    # Keywords only where they differ from the paper's method, so that method runs on any BILD.
    mode = {} if section_point == "reference" else {"section_point": section_point}
    if thrust is not None:
        mode["thrust_target"] = True
    usable = np.arange(len(cases)) if thrust is None else np.flatnonzero(np.isfinite(thrust))

    def run(part):
        prob = bild_problem(len(part), num_radial, num_blades, airfoil, **mode)
        _set_bild_inputs(prob, [cases[i] for i in part], None if thrust is None else thrust[part])
        start = time.perf_counter()
        prob.run_model()
        return (time.perf_counter() - start, [prob.get_val(name).copy() for name in names],
                prob.get_val("chord", units="m").copy(), prob.get_val("twist", units="rad").copy())

    out.errors.update({int(i): "no thrust target" for i in np.setdiff1d(np.arange(len(cases)), usable)})
    if usable.size == 0:
        return out
    with contextlib.suppress(*_CASE_ERRORS):  # set-up, first-run costs untimed; rolled: no case starts at its answer
        run(np.roll(usable, 1))
    successes, failures = isolate_failures(run, usable, _CASE_ERRORS)
    # Model runs of the batches that succeeded (set-ups and failed runs of the bisection excluded).
    out.batch_time_per_design = sum(r[0] for _, r in successes) / max(sum(p.size for p, _ in successes), 1)
    for i, exc in failures:
        out.errors[i] = f"BILD ({section_point}) failed: {' '.join(str(exc).split())}"
    for part, (_, values, chord, twist) in successes:
        out.chord[part], out.twist[part], out.converged[part] = chord, twist, True
        for key, value in zip(out.extra, values):
            out.extra[key][part] = value
    single = bild_problem(1, num_radial, num_blades, airfoil, **mode)

    def run_single(i):
        _set_bild_inputs(single, [cases[i]], None if thrust is None else thrust[[i]])
        single.run_model()

    _time_singles(out, run_single, repeats)
    return out


def mil_designs(cases, bild, repeats=3):
    """Minimum-induced-loss designs for BILD's thrust at BILD's reference airfoil point, batched, then timed alone.

    Parameters
    ----------
    cases : list of Case
    bild : MethodDesigns
        From :func:`bild_designs` (``section_point='reference'``).
    repeats : int
        Timed passes of single-design runs (:func:`_time_singles`).

    Returns
    -------
    MethodDesigns
        ``extra``: ``design_thrust`` (A&L's integral, N), ``efficiency`` (A&L's, -) and ``zeta``.
    """
    num_radial, num_blades, _ = _configuration(cases)
    out = _empty(len(cases), num_radial, ("design_thrust", "efficiency", "zeta"))
    args = {key: _column(cases, key) for key in ("v_axial", "rpm", "radius", "hub_radius", "altitude")}
    args.update({name: bild.extra[name] for name in _BILD_POINT}, thrust=bild.extra["thrust"])
    usable = np.flatnonzero(bild.converged)

    def design(part):
        return design_mil(num_blades=num_blades, num_radial=num_radial, **{k: v[part] for k, v in args.items()})

    out.errors.update({int(i): "no BILD design (thrust and airfoil point)" for i in np.flatnonzero(~bild.converged)})
    if usable.size:
        isolate_failures(design, usable, _CASE_ERRORS)  # sets up the models untimed (the solve is stateless)
        start = time.perf_counter()
        successes, failures = isolate_failures(design, usable, _CASE_ERRORS)
        out.batch_time_per_design = (time.perf_counter() - start) / usable.size
        for i, exc in failures:
            out.errors[i] = f"MIL failed: {' '.join(str(exc).split())}"
        for part, res in successes:
            out.chord[part], out.twist[part], out.converged[part] = res.chord, res.twist, True
            out.extra["design_thrust"][part], out.extra["efficiency"][part] = res.thrust, res.efficiency
            out.extra["zeta"][part] = res.zeta
    _time_singles(out, lambda i: design(np.array([i])), repeats)
    return out


def optimum_designs(cases, starts, restarts=1):
    """The full-BEM optimum of every case for BILD's thrust: the lowest converged run over the starts.

    Parameters
    ----------
    cases : list of Case
    starts : dict of str to MethodDesigns
        Start designs; the first is BILD's reference design, whose ``extra['thrust']`` is the target.
    restarts : int
        Restarts of a failed run (:func:`~bild_mdo.optimization.run.optimize_rotor`).

    Returns
    -------
    MethodDesigns
        ``time_per_design``: the optimiser's wall time from the first start (set-up untimed).  ``extra``:
        ``thrust`` (N), ``energy_loss`` (W), ``start`` (index of the best start) and ``energy_loss_<start>``.
    """
    (num_radial, num_blades, airfoil), names = _configuration(cases), list(starts)
    thrust = starts[names[0]].extra["thrust"]
    out = _empty(len(cases), num_radial, ["thrust", "energy_loss", "start"] + [f"energy_loss_{n}" for n in names])
    prob = build_optimization_problem(optimizer=cases[0].optimizer, num_radial=num_radial, num_blades=num_blades,
                                      polar=sweep_polar(airfoil))
    for i, case in enumerate(cases):
        inputs, status = case.inputs, []
        for k, name in enumerate(names):
            if not (starts[name].converged[i] and np.isfinite(thrust[i])):
                continue
            result = optimize_rotor(inputs["v_axial"], inputs["rpm"], inputs["radius"], inputs["hub_radius"],
                                    float(thrust[i]), inputs["altitude"], problem=prob, restarts=restarts,
                                    initial="bild", bild_chord=starts[name].chord[i],
                                    bild_twist=starts[name].twist[i], reference_chord=inputs["reference_chord"])
            out.time_per_design[i] = result.wall_time if k == 0 else out.time_per_design[i]
            if not result.converged:
                status.append(f"from {name}: {result.status}")
                continue
            energy = result.performance["energy_loss"]
            out.extra[f"energy_loss_{name}"][i] = energy
            if not energy >= out.extra["energy_loss"][i]:  # also while that is NaN
                out.chord[i], out.twist[i], out.converged[i] = result.chord, result.twist, True
                out.extra["start"][i], out.extra["thrust"][i], out.extra["energy_loss"][i] = (
                    k, result.performance["thrust"], energy)
        if not out.converged[i]:
            out.errors[i] = "optimiser not converged " + ("; ".join(status) if status else "(no start design)")
    return out


def trim_to_thrust_target(cases, designs, thrust, tol=1.0e-10):
    """Trim each design by collective pitch to ``thrust`` (N, per case; NaN: none) in the optimisation's BEM model.

    The optimality check's trim (:func:`~bild_mdo.verification.optimality.trimmed_bild_energy_loss`, to
    ``|T/T* - 1| <= tol``) with the design's geometry in place of BILD's.

    Returns
    -------
    indices : ndarray of int
        The trimmed cases (a design and a finite target).
    trim : BildTrim or None
        In the order of ``indices``; None without a case.
    """
    indices = np.flatnonzero(designs.converged & np.isfinite(thrust))
    if indices.size == 0:
        return indices, None
    rows = []
    for i in indices:
        inputs = cases[i].inputs
        # T* = C_T rho n^2 D^4 with the ISA rho, as the trim computes it back.
        scale = float(isa(inputs["altitude"]).rho) * (inputs["rpm"] * RPM_TO_REV_PER_S * 2.0 * inputs["radius"]) ** 2 \
            * (2.0 * inputs["radius"]) ** 2
        rows.append(dict(inputs, case_id=cases[i].case_id, bild_chord=designs.chord[i], bild_twist=designs.twist[i],
                         bild_thrust_coefficient=float(thrust[i]) / scale))
    return indices, trimmed_bild_energy_loss(rows, tol=tol)


@dataclasses.dataclass
class MethodComparison:
    """The outcome of :func:`compare_methods`: ``cases``, ``designs`` (by method) and the fields below.

    Per-method fields are dicts by method name (:data:`METHODS`) of arrays ``(n,)``, NaN where the method
    has no compared design (no design, no optimum, or the trim did not converge).

    Attributes
    ----------
    thrust : ndarray
        The common thrust, the optimum's BEM thrust (N).
    energy_loss, energy_excess, efficiency : dict
        Of the trimmed design: BEM energy loss (W), ``(E - E_opt) / E_opt`` and ``T V / P`` (-).
    twist_error, chord_error : dict
        ``||x - x_opt||_2 / ||x_opt||_2`` of the trimmed design (-).
    pitch_offset, thrust_residual : dict
        Collective-pitch trim (rad) and ``T/T_opt - 1`` after it (-).
    twist_trimmed : dict
        Twist of the trimmed design, ``(n, nr)`` (rad).
    notes : list of str
        What was skipped, and why.
    """

    cases: list
    designs: dict
    thrust: np.ndarray
    energy_loss: dict
    energy_excess: dict
    twist_error: dict
    chord_error: dict
    pitch_offset: dict
    thrust_residual: dict
    efficiency: dict
    twist_trimmed: dict
    notes: list

    @property
    def methods(self):
        """The methods compared, in :data:`METHODS` order."""
        return [m for m in METHODS if m in self.designs]

    def summary(self, method):
        """Means and extremes of ``method`` over its compared cases (dict of floats; NaN without cases)."""
        ok, designs = np.isfinite(self.energy_excess[method]), self.designs[method]

        def stat(fn, values):
            values = values[np.isfinite(values)]
            return float(fn(values)) if values.size else float("nan")

        out = {"num_cases": int(ok.sum()), "pitch_offset_max": stat(np.max, np.abs(self.pitch_offset[method][ok])),
               "energy_excess_min": stat(np.min, self.energy_excess[method][ok]),
               "time_per_design": stat(np.mean, designs.time_per_design[designs.converged]),
               "batch_time_per_design": float(designs.batch_time_per_design)}
        for name in ("energy_excess", "twist_error", "chord_error"):
            out[f"{name}_mean"] = stat(np.mean, getattr(self, name)[method][ok])
            out[f"{name}_max"] = stat(np.max, getattr(self, name)[method][ok])
        return out


def _design_all(cases, section_points, repeats, restarts, notes):
    if section_points is None:
        section_points = ["reference", "local"]
        if not local_section_point_available():
            section_points.remove("local")
            notes.append("BILD (local point) skipped: BILDGroup has no section_point option")
    designs = {"bild_reference": bild_designs(cases, "reference", repeats)}
    thrust = designs["bild_reference"].extra["thrust"]
    if "local" in section_points:
        # At the reference design's thrust (its reference chord follows), so that one optimum serves both.
        designs["bild_local"] = bild_designs(cases, "local", repeats, thrust=thrust)
    designs["mil"] = mil_designs(cases, designs["bild_reference"], repeats)
    designs["optimum"] = optimum_designs(
        cases, {name: designs[name] for name in ("bild_reference", "bild_local") if name in designs}, restarts)
    for method, d in designs.items():
        for what, errors in (("without a design", d.errors), ("failed alone (untimed)", d.timing_failures)):
            notes += [f"{METHOD_LABELS[method]}: {len(errors)} of {len(cases)} cases {what}; first: "
                      f"{next(iter(errors.values()))[:200]}"] if errors else []
    return designs


def compare_methods(cases, section_points=None, repeats=3, restarts=1):
    """Design every case by each method, trim all to the optimum's thrust and compare (see the module doc).

    Parameters
    ----------
    cases : list of Case
        Forward-flight cases of one configuration (:func:`forward_flight_cases`).
    section_points : sequence of str, optional
        Default ``('reference', 'local')``, without ``'local'`` (and a note) when
        :func:`local_section_point_available` is False.  ``'reference'`` is always designed.
    repeats, restarts : int
        Timed passes of single-design runs (BILD, MIL; 0: untimed); optimiser restarts.

    Returns
    -------
    MethodComparison

    Raises
    ------
    ValueError
        For a hover case (J = 0: MIL has no hover form) or cases of different configurations.
    """
    cases, notes = list(cases), []
    if any(case.inputs["v_axial"] <= 0.0 for case in cases):
        raise ValueError("the comparison is for forward flight (J > 0): MIL design has no hover form")
    designs = _design_all(cases, section_points, repeats, restarts, notes)
    thrust, fields, twist_trimmed = designs["optimum"].extra["thrust"], {name: {} for name in _FIELDS}, {}
    for method, d in designs.items():
        for values in fields.values():
            values[method] = np.full(len(cases), np.nan)
        twist_trimmed[method] = np.full_like(d.twist, np.nan)
        indices, trim = trim_to_thrust_target(cases, d, thrust)
        if trim is None:
            continue
        if not trim.converged.all():
            notes.append(f"{METHOD_LABELS[method]}: the trim to the optimum's thrust did not converge in "
                         f"{int((~trim.converged).sum())} cases (not compared)")
        ok, done = indices[trim.converged], trim.converged
        for name in ("energy_loss", "pitch_offset", "thrust_residual"):
            fields[name][method][ok] = getattr(trim, name)[done]
        twist_trimmed[method][ok] = d.twist[ok] + trim.pitch_offset[done][:, None]
    useful = thrust * _column(cases, "v_axial")
    twist_opt, chord_opt = twist_trimmed["optimum"], designs["optimum"].chord
    for method, d in designs.items():
        energy = fields["energy_loss"][method]
        fields["energy_excess"][method] = energy / fields["energy_loss"]["optimum"] - 1.0
        fields["efficiency"][method] = useful / (energy + useful)  # P = E + T V at the common thrust
        fields["twist_error"][method] = (np.linalg.norm(twist_trimmed[method] - twist_opt, axis=1)
                                         / np.linalg.norm(twist_opt, axis=1))
        fields["chord_error"][method] = np.linalg.norm(d.chord - chord_opt, axis=1) / np.linalg.norm(chord_opt, axis=1)
    return MethodComparison(cases=cases, designs=designs, thrust=thrust, twist_trimmed=twist_trimmed, notes=notes,
                            **fields)
