"""The designs each method of the comparison makes (:mod:`~bild_mdo.verification.method_comparison`).

BILD (any of its variants: section point and ideal loading), minimum-induced-loss design and the full-BEM
optimum, each for every forward-flight case of a sweep: one batched run (failing cases isolated by bisection)
and, for the timing, each case alone.
"""
from __future__ import annotations

import contextlib
import dataclasses
import time

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.text import sweep_polar
from bild_mdo.bild.problem import bild_problem
from bild_mdo.mil import design_mil
from bild_mdo.optimization.problem import build_optimization_problem
from bild_mdo.optimization.run import optimize_rotor
from bild_mdo.utils.batches import isolate_failures

CASE_ERRORS = (om.AnalysisError, ValueError, ArithmeticError)
_BILD_POINT = ("alpha_star", "cl_star", "cd_star")


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


def column(cases, key):
    """The input ``key`` of every case, as a float array."""
    return np.array([float(case.inputs[key]) for case in cases])


def _configuration(cases):
    keys = {tuple(case.inputs[k] for k in ("num_radial", "num_blades", "airfoil")) for case in cases}
    if len(keys) != 1:
        raise ValueError(f"the cases must share stations, blades and airfoil, got {sorted(keys)}")
    num_radial, num_blades, airfoil = keys.pop()
    return int(num_radial), int(num_blades), airfoil


def _set_bild_inputs(prob, cases, thrust=None):
    radius = column(cases, "radius")
    values = {"v_axial": column(cases, "v_axial"), "rpm": column(cases, "rpm"), "radius": radius,
              "altitude": column(cases, "altitude"), "hub_radius_ratio": column(cases, "hub_radius") / radius,
              "ref_radius_ratio": column(cases, "reference_radius") / radius}
    if thrust is None:
        values["ref_chord"] = column(cases, "reference_chord")
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
            except CASE_ERRORS as exc:
                out.timing_failures[i] = " ".join(str(exc).split())
                continue
            if k:
                best[i] = min(best[i], time.perf_counter() - start)
        if k and time.perf_counter() - begin > budget:
            break
    timed = np.isfinite(best)
    out.time_per_design[timed] = best[timed]


def _value_or_nan(prob, name, size):
    """``prob``'s output ``name``, or NaN where the model has none (the reference station's point of the
    Reynolds-aware exact loading, which with a thrust target solves lambda without a reference station)."""
    try:
        return prob.get_val(name).copy()
    except KeyError:
        if name not in {f"{n}_ref" for n in _BILD_POINT}:
            raise
        return np.full(size, np.nan)


def bild_designs(cases, section_point="reference", repeats=3, thrust=None, ideal_loading="paper"):
    """BILD designs of ``cases``: one batched run (failing cases isolated by bisection), then each alone, timed.

    Parameters
    ----------
    cases : list of Case
        Cases of one configuration (stations, blades, airfoil).
    section_point : {'reference', 'local'}
        BILDGroup's ``section_point``.
    repeats : int
        Timed passes of single-design runs (:func:`_time_singles`).
    thrust : ndarray, optional
        Thrust (N) to design for instead of the case's c_ref (``thrust_target=True``).
    ideal_loading : {'paper', 'exact'}
        BILDGroup's ``ideal_loading``.

    Returns
    -------
    MethodDesigns
        ``extra``: ``thrust`` (N), ``ref_chord`` (m) and the reference station's ``alpha_star, cl_star, cd_star``
        (NaN for the Reynolds-aware exact loading with ``thrust``: it has no reference station then).
    """
    num_radial, num_blades, airfoil = _configuration(cases)
    out = _empty(len(cases), num_radial, ("thrust",) + _BILD_POINT + ("ref_chord",))
    names = ("thrust",) + tuple(f"{n}_ref" if section_point == "local" else n for n in _BILD_POINT) + ("ref_chord",)
    mode = {"section_point": section_point, "ideal_loading": ideal_loading}
    if thrust is not None:
        mode["thrust_target"] = True
    usable = np.arange(len(cases)) if thrust is None else np.flatnonzero(np.isfinite(thrust))

    def run(part):
        prob = bild_problem(len(part), num_radial, num_blades, airfoil, **mode)
        _set_bild_inputs(prob, [cases[i] for i in part], None if thrust is None else thrust[part])
        start = time.perf_counter()
        prob.run_model()
        return (time.perf_counter() - start, [_value_or_nan(prob, name, part.size) for name in names],
                prob.get_val("chord", units="m").copy(), prob.get_val("twist", units="rad").copy())

    out.errors.update({int(i): "no thrust target" for i in np.setdiff1d(np.arange(len(cases)), usable)})
    if usable.size == 0:
        return out
    with contextlib.suppress(*CASE_ERRORS):  # set-up, first-run costs untimed; rolled: no case starts at its answer
        run(np.roll(usable, 1))
    successes, failures = isolate_failures(run, usable, CASE_ERRORS)
    # Model runs of the batches that succeeded (set-ups and failed runs of the bisection excluded).
    out.batch_time_per_design = sum(r[0] for _, r in successes) / max(sum(p.size for p, _ in successes), 1)
    for i, exc in failures:
        out.errors[i] = f"BILD ({section_point}, {ideal_loading}) failed: {' '.join(str(exc).split())}"
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
    args = {key: column(cases, key) for key in ("v_axial", "rpm", "radius", "hub_radius", "altitude")}
    args.update({name: bild.extra[name] for name in _BILD_POINT}, thrust=bild.extra["thrust"])
    usable = np.flatnonzero(bild.converged)

    def design(part):
        return design_mil(num_blades=num_blades, num_radial=num_radial, **{k: v[part] for k, v in args.items()})

    out.errors.update({int(i): "no BILD design (thrust and airfoil point)" for i in np.flatnonzero(~bild.converged)})
    if usable.size:
        isolate_failures(design, usable, CASE_ERRORS)  # sets up the models untimed (the solve is stateless)
        start = time.perf_counter()
        successes, failures = isolate_failures(design, usable, CASE_ERRORS)
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

