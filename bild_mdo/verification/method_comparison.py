"""BILD, minimum-induced-loss design and the full-BEM optimum, compared at the same thrust (issue 12).

Per forward-flight case (J > 0) of a verification sweep: BILD with the paper's reference section point
(``bild_reference``, for the case's ``c_ref``), with each station's own point (``bild_local``, for the same
thrust) and with the Reynolds-aware exact ideal loading (``bild_local_exact``: the local point with
``ideal_loading='exact'``, for the same thrust); the minimum-induced-loss design (``mil``: Adkins & Liebeck
1994, A&L's tip factor) for the same thrust at BILD's operating and reference airfoil point; the full-BEM
optimum (``optimum``) for the same thrust, the lowest converged run from the BILD starts (it is not unique
with a Reynolds-dependent polar).  Each is trimmed by collective pitch to the optimum's thrust in the
optimisation's BEM model by the optimality check's trim (:mod:`~bild_mdo.verification.optimality`, which
gives a zero-chord station of an unloaded annulus the optimiser's least chord and the twist of least loss)
and compared with the optimum: energy loss, and geometry as the verification measures it
(``||x - x_opt||_2 / ||x_opt||_2``, the twist as trimmed).
"""
from __future__ import annotations

import dataclasses

import numpy as np

from bild_mdo.atmosphere import isa
from bild_mdo.constants import RPM_TO_REV_PER_S

from .method_designs import bild_designs, column, mil_designs, optimum_designs
from .optimality import trimmed_bild_energy_loss

#: BILD's variants: method name -> (section_point, ideal_loading) of BILDGroup.
BILD_VARIANTS = {"bild_reference": ("reference", "paper"), "bild_local": ("local", "paper"),
                 "bild_local_exact": ("local", "exact")}
#: The compared methods, in table order; the optimum is the reference.
METHODS = tuple(BILD_VARIANTS) + ("mil", "optimum")
#: Names for tables and figures.
METHOD_LABELS = {"bild_reference": "BILD (reference point)", "bild_local": "BILD (local point)",
                 "bild_local_exact": "BILD (local, exact loading)", "mil": "MIL (Adkins & Liebeck)",
                 "optimum": "BEM optimum"}
_FIELDS = ("energy_loss", "energy_excess", "efficiency", "twist_error", "chord_error", "pitch_offset",
           "thrust_residual")


def forward_flight_cases(spec):
    """The cases (list of Case) of ``spec`` (SweepSpec) with J > 0, in case-id order (54 at levels 3)."""
    return [case for case in spec.cases() if case.inputs["advance_ratio"] > 0.0]


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


def _design_all(cases, variants, repeats, restarts, notes):
    unknown = sorted(set(variants) - set(BILD_VARIANTS))
    if unknown or "bild_reference" not in variants:
        raise ValueError(f"variants must include 'bild_reference' and be among {sorted(BILD_VARIANTS)}, "
                         f"got {list(variants)}")
    designs = {"bild_reference": bild_designs(cases, "reference", repeats)}
    thrust = designs["bild_reference"].extra["thrust"]
    for method in (m for m in BILD_VARIANTS if m in variants and m != "bild_reference"):
        # At the reference design's thrust (its reference chord follows), so that one optimum serves all.
        section_point, ideal_loading = BILD_VARIANTS[method]
        designs[method] = bild_designs(cases, section_point, repeats, thrust=thrust, ideal_loading=ideal_loading)
    designs["mil"] = mil_designs(cases, designs["bild_reference"], repeats)
    designs["optimum"] = optimum_designs(cases, {name: designs[name] for name in BILD_VARIANTS if name in designs},
                                         restarts)
    for method, d in designs.items():
        for what, errors in (("without a design", d.errors), ("failed alone (untimed)", d.timing_failures)):
            notes += [f"{METHOD_LABELS[method]}: {len(errors)} of {len(cases)} cases {what}; first: "
                      f"{next(iter(errors.values()))[:200]}"] if errors else []
    return designs


def compare_methods(cases, variants=tuple(BILD_VARIANTS), repeats=3, restarts=1):
    """Design every case by each method, trim all to the optimum's thrust and compare (see the module doc).

    Parameters
    ----------
    cases : list of Case
        Forward-flight cases of one configuration (:func:`forward_flight_cases`).
    variants : sequence of str
        BILD's variants to design (keys of :data:`BILD_VARIANTS`; default all), each also a start of the
        optimiser; ``'bild_reference'`` must be one (its thrust is the common target).
    repeats, restarts : int
        Timed passes of single-design runs (BILD, MIL; 0: untimed); optimiser restarts.

    Returns
    -------
    MethodComparison

    Raises
    ------
    ValueError
        For a hover case (J = 0: MIL has no hover form), cases of different configurations or an unknown
        variant.
    """
    cases, notes = list(cases), []
    if any(case.inputs["v_axial"] <= 0.0 for case in cases):
        raise ValueError("the comparison is for forward flight (J > 0): MIL design has no hover form")
    designs = _design_all(cases, variants, repeats, restarts, notes)
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
        twist_trimmed[method][ok] = np.array(trim.twist)[done]
    useful = thrust * column(cases, "v_axial")
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
