"""Is the optimum an optimum?  The BEM optimum against the BILD geometry trimmed to the same thrust.

BILD's reported energy loss is a momentum-theory value with the airfoil's
maximum-L/D point at the reference Reynolds number; evaluated in the full BEM
model (local Reynolds numbers, Prandtl losses) the BILD geometry produces a
slightly different thrust (up to about 2 % over the sweep).  So BILD's reported
E is not a feasible point of the optimisation, and comparing the optimum with
it says nothing about optimality.  The fair comparison, and the paper's intent
(the optimiser solves the same problem, Sec. 5.1), is:

1. take BILD's chord and twist;
2. trim them in the BEM model to the optimisation's thrust target
   ``T* = T_BILD`` with one collective-pitch offset per case (a uniform twist
   change), which is a feasible design of the optimisation problem;
3. the optimum's energy loss must not exceed that design's, within a
   relative tolerance.

:func:`trimmed_bild_energy_loss` does step 2 for all cases in one vectorised
BEM analysis per iteration; :func:`optimality_check` does step 3 and sums up.
The BEM set-up is the one the optimisation uses (``loss_model='tip_hub'``,
ISA at the case's altitude, the polar the case's airfoil text names:
:func:`~bild_mdo.airfoil.text.sweep_polar`) at the
stations BILD designs at: the midpoints of ``num_radial`` equal annuli from hub
to tip, which are also :func:`~bild_mdo.bem.analyze.analyze_rotor`'s default
stations.

The optimum meets its thrust constraint to ``|T/T* - 1| <= 1e-6``
(:data:`~bild_mdo.optimization.problem.THRUST_TOLERANCE`); E changes by at most
about twice that relative amount, far below the default tolerance of 1e-4.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from .cases import bild_setting
from .thrust_trim import CASE_KEYS, MODEL_KEYS, trim_batch

#: Default relative tolerance of the optimality check (0.01 %, the acceptance criterion).
DEFAULT_TOLERANCE = 1.0e-4



@dataclasses.dataclass
class BildTrim:
    """BILD geometries trimmed to their own thrust in the BEM model (:func:`trimmed_bild_energy_loss`).

    All arrays have shape ``(n,)``, one entry per row, in the order of the rows.

    Attributes
    ----------
    case_ids : ndarray of int
        Case ids of the rows.
    energy_loss : ndarray
        BEM rate of energy loss of the trimmed BILD design (W).
    thrust_residual : ndarray
        ``T/T* - 1`` of the trimmed design (-).
    pitch_offset : ndarray
        Collective-pitch offset added to BILD's twist (rad).
    untrimmed_thrust_error : ndarray
        ``T/T* - 1`` of BILD's geometry as designed, in the BEM model (-).
    converged : ndarray of bool
        ``|thrust_residual| <= tol``.
    iterations : int
        BEM analyses per configuration batch after the first (the largest batch count).
    invalid_stations : ndarray of int
        Stations of the trimmed design in an invalid BEM flow state
        (:data:`~bild_mdo.bem.flow_states.INVALID_STATES`), where its loads are not reliable.
    twist : list of ndarray
        Per row, the twist as last analysed (rad): BILD's plus the pitch offset (at a zero chord: the
        twist of least loss plus the offset).
    """

    case_ids: np.ndarray
    energy_loss: np.ndarray
    thrust_residual: np.ndarray
    pitch_offset: np.ndarray
    untrimmed_thrust_error: np.ndarray
    converged: np.ndarray
    iterations: int
    invalid_stations: np.ndarray = None
    twist: list = None


def _row_text(row):
    return f"case {row.get('case_id')}"


def _check_rows(rows):
    for row in rows:
        missing = [k for k in ("bild_chord", "bild_twist", "bild_thrust_coefficient") + CASE_KEYS + MODEL_KEYS
                   if row.get(k) is None]
        if missing:
            raise ValueError(f"{_row_text(row)}: the BILD trim needs {missing}; pass only cases whose BILD "
                             "design converged (bild_converged)")
        nr = int(row["num_radial"])
        for name in ("bild_chord", "bild_twist"):
            values = np.asarray(row[name], dtype=float)
            if values.shape != (nr,) or not np.all(np.isfinite(values)):
                raise ValueError(f"{_row_text(row)}: {name} must be {nr} finite values at the sweep's stations "
                                 f"(num_radial = {nr}), got shape {values.shape}")
        c_t = float(row["bild_thrust_coefficient"])
        if not (math.isfinite(c_t) and c_t > 0.0):
            raise ValueError(f"{_row_text(row)}: BILD's thrust coefficient must be positive, got {c_t!r}")


def trimmed_bild_energy_loss(rows, tol=1.0e-10, max_iter=30, first_step=1.0e-3, max_step=np.radians(2.0),
                             rotor_type="propeller"):
    """Trim every row's BILD geometry to its own thrust in the BEM model; return the BEM energy loss.

    For each case the twist is shifted uniformly (collective pitch) until
    the BEM thrust equals ``T* = T_BILD = C_T rho n^2 D^4`` (C_T as BILD
    reported it, rho from the ISA at the case's altitude, n = rpm / 60,
    D = 2 R): the optimisation's thrust target.  A chord below the
    optimisation's lower bound (``c/R = CHORD_RATIO_BOUNDS[0]``, 1e-4) is
    raised to it, as in the optimiser's BILD start: BILD gives a zero chord
    where its ideal load vanishes (an annulus whose profile loss per thrust
    at zero load exceeds lambda, e.g. at the hub in fast forward flight with
    the exact loading), which the BEM analysis refuses; at the bound it is a
    feasible design of the same problem.  BILD gives no twist there (no
    blade), so the trim gives such a station the twist of least energy loss
    (:func:`~bild_mdo.verification.feathering.least_loss_twist`), as the
    optimiser from its BILD start may.  All cases of one
    configuration (stations, blades, airfoil; the sweep has one) are solved
    together: every iteration is one vectorised
    :func:`~bild_mdo.bem.analyze.analyze_rotor` call with ``num_nodes`` equal to
    the number of cases, and the pitch offsets follow a secant iteration per
    case (a probe step of ``first_step`` first), with each step limited to
    ``max_step`` and the last positive slope kept where a secant is not.

    Parameters
    ----------
    rows : list of dict
        Results-store rows (:meth:`~bild_mdo.verification.store.ResultsStore.rows`)
        with BILD's design: ``bild_chord`` and ``bild_twist`` (``num_radial``
        values, m and rad, at the midpoints of equal annuli),
        ``bild_thrust_coefficient`` and the case inputs.
    tol : float
        Tolerance on ``|T/T* - 1|``.
    max_iter : int
        BEM analyses after the first.  Cases not trimmed by then are returned
        with ``converged`` False (no exception).
    first_step, max_step : float
        Probe step and largest step of the pitch offset (rad).
    rotor_type : {'propeller', 'turbine'}
        Rows of a turbine sweep (:mod:`~bild_mdo.verification.turbine_sweep`): T* from the turbine's ``C_T``.

    Returns
    -------
    BildTrim
        In the order of ``rows``.

    Raises
    ------
    ValueError
        If a row lacks BILD's design or it is not at ``num_radial`` stations.
    openmdao.api.AnalysisError
        If a BEM inflow solve fails (outside the valid domain).
    """
    rows = list(rows)
    _check_rows(rows)
    size = len(rows)
    out = {name: np.full(size, np.nan) for name in ("energy_loss", "thrust_residual", "pitch_offset",
                                                    "untrimmed_thrust_error")}
    out["invalid_stations"], converged = np.zeros(size, dtype=int), np.zeros(size, dtype=bool)
    twist, iterations, groups = {}, 0, {}
    for index, row in enumerate(rows):
        groups.setdefault(tuple(row[k] for k in MODEL_KEYS), []).append(index)
    for indices in groups.values():
        batch = trim_batch([rows[i] for i in indices], tol, max_iter, first_step, max_step, rotor_type)
        for name in out:
            out[name][indices] = batch[name]
        converged[indices] = batch["converged"]
        twist.update(zip(indices, batch["twist"]))
        iterations = max(iterations, batch["iterations"])
    return BildTrim(case_ids=np.array([int(row["case_id"]) for row in rows], dtype=int), converged=converged,
                    iterations=iterations, twist=[twist[i] for i in range(size)], **out)


@dataclasses.dataclass
class OptimalityCheck:
    """Summary of :func:`optimality_check`.

    Relative margins are ``(E_opt - E_trim) / E_trim`` with ``E_trim`` the BEM
    energy loss of BILD's geometry trimmed to ``T*``: negative where the
    optimum is better, as it must be.

    Attributes
    ----------
    tolerance : float
        Relative tolerance of the check.
    num_cases : int
        Cases compared (BILD and optimisation converged, trim converged).
    num_skipped : int
        Rows left out because BILD or the optimisation did not converge.
    trim_failed_ids : list of int
        Cases whose trim did not converge (not compared).
    violations : list of tuple
        ``(case_id, margin)`` where ``margin > tolerance``, worst first.
    max_margin, mean_margin : float
        Largest and mean relative margin (-); NaN without cases.
    worst_case_id : int or None
        Case of ``max_margin``.
    bild_reported_mean_abs, bild_reported_max_abs : float
        Mean and largest ``|E_BILD - E_trim| / E_trim``: BILD's reported
        (momentum-theory) E against its own geometry's trimmed BEM E (-).
    max_untrimmed_thrust_error : float
        Largest ``|T/T* - 1|`` of BILD's geometry in the BEM model before trimming (-).
    max_pitch_offset : float
        Largest ``|offset|`` of the trim (rad).
    max_trim_residual : float
        Largest ``|T/T* - 1|`` after the trim over the compared cases (-).
    invalid_flow_ids : list of int
        Compared cases whose trimmed BILD design has stations in an invalid
        BEM flow state (its E_trim is less reliable there).
    mean_excess, max_excess : float
        Mean and largest energy excess of the trimmed BILD design over the
        optimum, ``(E_trim - E_opt) / E_opt`` (-); NaN without cases.
    max_excess_case_id : int or None
        Case of ``max_excess``.
    section_point : str or None
        BILD's section point of the rows; when given, :meth:`summary` adds
        the excess line for it.
    ideal_loading : str
        BILD's ideal loading of the rows; the excess line names it when it is not the paper's.
    """

    tolerance: float
    num_cases: int
    num_skipped: int
    trim_failed_ids: list
    violations: list
    max_margin: float
    mean_margin: float
    worst_case_id: object
    bild_reported_mean_abs: float
    bild_reported_max_abs: float
    max_untrimmed_thrust_error: float
    max_pitch_offset: float
    max_trim_residual: float
    invalid_flow_ids: list = dataclasses.field(default_factory=list)
    mean_excess: float = math.nan
    max_excess: float = math.nan
    max_excess_case_id: object = None
    section_point: str = None
    ideal_loading: str = "paper"

    @property
    def num_violations(self):
        """Number of cases where the optimum is worse than the trimmed BILD design beyond the tolerance."""
        return len(self.violations)

    @property
    def passed(self):
        """True when no case violates the check and every trim converged."""
        return not self.violations and not self.trim_failed_ids

    def summary(self):
        """Text for the verification report (two to four lines)."""
        if self.num_cases == 0:
            return (f"Optimum is an optimum: no case to check ({self.num_skipped} without both methods converged, "
                    f"{len(self.trim_failed_ids)} trims failed).")
        lines = [
            f"Optimum is an optimum: {self.num_violations} of {self.num_cases} cases have E_opt > E_BILD,trimmed "
            f"(1 + {self.tolerance:g}); (E_opt - E_BILD,trimmed)/E_BILD,trimmed worst "
            f"{100.0 * self.max_margin:+.4f} % (case {self.worst_case_id}), mean {100.0 * self.mean_margin:+.4f} %.",
            f"  E_BILD,trimmed: BILD's chord and twist in the BEM model, collective pitch trimmed to T* = T_BILD "
            f"(|offset| <= {np.degrees(self.max_pitch_offset):.3f} deg, |T/T* - 1| before "
            f"<= {100.0 * self.max_untrimmed_thrust_error:.3f} %, after <= {self.max_trim_residual:.1e}).",
            f"  BILD's reported E vs E_BILD,trimmed: mean |diff| {100.0 * self.bild_reported_mean_abs:.3f} %, "
            f"max {100.0 * self.bild_reported_max_abs:.3f} %.",
        ]
        if self.section_point is not None:
            lines.append(f"  BILD ({bild_setting(self.section_point, self.ideal_loading)}) trimmed to T*: energy "
                         f"excess over the optimum "
                         f"(E_BILD,trimmed - E_opt)/E_opt mean {100.0 * self.mean_excess:+.3f} %, worst "
                         f"{100.0 * self.max_excess:+.3f} % (case {self.max_excess_case_id}).")
        if self.violations:
            shown = ", ".join(f"{cid} ({100.0 * m:+.4f} %)" for cid, m in self.violations[:10])
            more = "" if len(self.violations) <= 10 else f" and {len(self.violations) - 10} more"
            lines.append(f"  Violations (case, margin): {shown}{more}.")
        if self.invalid_flow_ids:
            lines.append(f"  Trimmed BILD designs with stations in an invalid BEM flow state: cases "
                         f"{self.invalid_flow_ids[:10]}{'' if len(self.invalid_flow_ids) <= 10 else ' ...'}.")
        if self.trim_failed_ids:
            lines.append(f"  Trim did not converge (not compared): cases {self.trim_failed_ids[:10]}"
                         f"{'' if len(self.trim_failed_ids) <= 10 else ' ...'}.")
        return "\n".join(lines)


def optimality_check(rows, tolerance=DEFAULT_TOLERANCE, trim=None, section_point=None, ideal_loading="paper",
                     rotor_type="propeller"):
    """Check that no optimum has a higher energy loss than BILD's design trimmed to the same thrust.

    Parameters
    ----------
    rows : list of dict
        Results-store rows; only cases where BILD and the optimisation both
        converged are compared.
    tolerance : float
        Relative tolerance: a case violates the check when
        ``E_opt > E_trim (1 + tolerance)``.  Default 1e-4 (0.01 %).
    trim : BildTrim, optional
        The trim of exactly the compared rows, to reuse one already computed;
        computed with :func:`trimmed_bild_energy_loss` when omitted.
    section_point : str, optional
        BILD's section point of the rows (``'reference'`` or ``'local'``):
        the summary then reports the trimmed design's energy excess for it.
    ideal_loading : str
        BILD's ideal loading of the rows (``'paper'`` or ``'exact'``), named by that line when not the paper's.
    rotor_type : {'propeller', 'turbine'}
        As for :func:`trimmed_bild_energy_loss`.

    Returns
    -------
    OptimalityCheck

    Raises
    ------
    ValueError
        If a compared row lacks its optimum's energy loss or BILD's design.
    openmdao.api.AnalysisError
        If a BEM inflow solve of the trim fails.
    """
    rows = list(rows)
    compared = [row for row in rows if row["converged"] and row["bild_converged"]]
    for row in compared:
        value = row.get("opt_energy_loss")
        if value is None or not math.isfinite(float(value)):
            raise ValueError(f"{_row_text(row)}: converged optimum without a finite energy loss")
    if trim is None:
        trim = trimmed_bild_energy_loss(compared, rotor_type=rotor_type)
    elif len(trim.case_ids) != len(compared) or any(
            int(a) != int(b["case_id"]) for a, b in zip(trim.case_ids, compared)):
        raise ValueError("trim must belong to the converged rows, in the same order")
    ok = np.asarray(trim.converged, dtype=bool)
    ids = np.asarray(trim.case_ids, dtype=int)
    e_opt = np.array([row["opt_energy_loss"] for row in compared], dtype=float)[ok]
    e_bild = np.array([math.nan if row["bild_energy_loss"] is None else row["bild_energy_loss"]
                       for row in compared], dtype=float)[ok]
    e_trim = trim.energy_loss[ok]
    margin = (e_opt - e_trim) / e_trim
    excess = (e_trim - e_opt) / e_opt
    reported = np.abs(e_bild - e_trim) / e_trim
    reported = reported[np.isfinite(reported)]
    bad = margin > tolerance
    order = np.argsort(-margin[bad])
    violations = [(int(cid), float(m)) for cid, m in zip(ids[ok][bad][order], margin[bad][order])]
    num = int(ok.sum())

    def stat(fn, values):
        return float(fn(values)) if values.size else math.nan

    return OptimalityCheck(
        tolerance=float(tolerance),
        num_cases=num,
        num_skipped=len(rows) - len(compared),
        trim_failed_ids=[int(cid) for cid in ids[~ok]],
        violations=violations,
        max_margin=stat(np.max, margin),
        mean_margin=stat(np.mean, margin),
        worst_case_id=int(ids[ok][np.argmax(margin)]) if num else None,
        bild_reported_mean_abs=stat(np.mean, reported),
        bild_reported_max_abs=stat(np.max, reported),
        max_untrimmed_thrust_error=stat(np.max, np.abs(trim.untrimmed_thrust_error[ok])),
        max_pitch_offset=stat(np.max, np.abs(trim.pitch_offset[ok])),
        max_trim_residual=stat(np.max, np.abs(trim.thrust_residual[ok])),
        invalid_flow_ids=[] if trim.invalid_stations is None else
        [int(cid) for cid in ids[ok][np.asarray(trim.invalid_stations)[ok] > 0]],
        mean_excess=stat(np.mean, excess),
        max_excess=stat(np.max, excess),
        max_excess_case_id=int(ids[ok][np.argmax(excess)]) if num else None,
        section_point=section_point,
        ideal_loading=ideal_loading,
    )
