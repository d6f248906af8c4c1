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

import warnings

import numpy as np
import openmdao.api as om

from bild_mdo import validation
from bild_mdo.airfoil.load_path_table import data_reynolds_range
from bild_mdo.atmosphere import MAX_ALTITUDE, isa
from bild_mdo.bem.metrics import warn_supersonic_tip
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.bild.annulus_stationarity import IDEAL_LOADINGS
from bild_mdo.bild.chord import CHORD_FORMS
from bild_mdo.bild.variants import SECTION_POINTS
from bild_mdo.bild.problem import bild_problem
from bild_mdo.constants import RPM_TO_REV_PER_S
from bild_mdo.fluid import fluid_arrays, resolve_fluid
from bild_mdo.io.airfoil import resolve_airfoil
from bild_mdo.results import tables
from bild_mdo.results.design_analysis import analyze_designs
from bild_mdo.results.design_result import (DISTRIBUTION_UNITS, DISTRIBUTIONS, INPUT_UNITS, NODE_OUTPUT_UNITS,
                                            ON_INFEASIBLE, OPTIONAL_OUTPUTS, DesignResult)

__all__ = ["DesignResult", "ReferenceChordWarning", "UnloadedStationsWarning", "design_rotor"]

#: Largest helical tip Mach number a design is attempted at: far past the sonic tip, where the blade-element
#: polar and momentum theory already fail (a warning from 1 on); beyond it the inputs are a mistake (rpm in rad/s?).
MAX_TIP_MACH = 3.0


class UnloadedStationsWarning(UserWarning):
    """A design leaves stations unloaded (zero chord): its ideal loading carries nothing there."""


class ReferenceChordWarning(UserWarning):
    """A local-point design whose blade has not ``ref_chord`` at ``r_ref``: the reference state's sheet is not the
    one the blade has there at the design's lambda (:func:`bild_mdo.results.tables.reference_mismatch`)."""


def _warn_reference(result, is_batch):
    """One :class:`ReferenceChordWarning` naming the designs whose blade has not ``ref_chord`` at ``r_ref``."""
    mismatch = tables.reference_mismatches(result.values)
    designs = [] if mismatch is None else np.flatnonzero(mismatch & result.feasible)
    if len(designs):
        which = f"{len(designs)} design(s) (the first: design {designs[0]})" if is_batch else "the design"
        warnings.warn(f"{which}: the blade has not ref_chord at r_ref (the blade there is on another branch of the "
                      "section point at this lambda; it is the blade of its own thrust): ask for a thrust or another "
                      "ref_chord; result.summary() says more", ReferenceChordWarning, stacklevel=3)


def _check_tip_mach(values, input_mode, fluid=None):
    """ValueError if the helical tip Mach number of some design exceeds :data:`MAX_TIP_MACH`."""
    omega_r = values["rpm"] * (RPM_TO_REV_PER_S * 2.0 * np.pi) * values["radius"]
    speed = values[input_mode] * (values["rpm"] * RPM_TO_REV_PER_S * 2.0 * values["radius"]
                                  if input_mode == "advance_ratio" else 1.0)
    sound = isa(values["altitude"], derivatives=False).speed_of_sound if fluid is None else fluid.speed_of_sound
    tip_mach = np.hypot(speed, omega_r) / sound
    bad = np.flatnonzero(tip_mach > MAX_TIP_MACH)
    if bad.size:
        where = f" (design {int(bad[0])})" if tip_mach.size > 1 else ""
        raise ValueError(f"tip Mach number {tip_mach[bad[0]]:.3g}{where} from rpm, radius and speed is far beyond "
                         f"any rotor (BILD refuses above {MAX_TIP_MACH:g}; polars and momentum theory fail past 1): "
                         "check rpm [rpm] and radius [m]")


def _fraction_range(fractions):
    return f"{fractions[0]:.3f}" if fractions.size == 1 else f"{fractions[0]:.3f}..{fractions[-1]:.3f}"


def _warn_unloaded(chord, feasible, radial_fractions, is_batch):
    """One :class:`UnloadedStationsWarning` naming the designs that leave stations at zero chord."""
    unloaded = (chord <= 0.0) & feasible[:, None]
    designs = np.flatnonzero(np.any(unloaded, axis=1))
    if designs.size == 0:
        return
    first = int(designs[0])
    stations = np.flatnonzero(unloaded[first])
    where = f"{stations.size} of {chord.shape[1]} stations at r/R {_fraction_range(radial_fractions[first, stations])}"
    label = (f"{designs.size} design(s) leave stations unloaded (zero chord), design {first}: {where}" if is_batch
             else f"the design leaves {where} unloaded (zero chord)")
    warnings.warn(f"{label}: the ideal loading carries nothing there (a light loading: raise ref_chord or the "
                  "thrust if that is not meant); result.summary() lists them", UnloadedStationsWarning, stacklevel=3)


def _model_outputs(prob):
    """``(name, value)`` of every output the result copies; the optional ones only where the model has them (the
    model's promoted outputs looked up once per problem: a failed ``get_val`` costs about a millisecond)."""
    present = getattr(prob, "_bild_mdo_outputs", None)
    if present is None:
        meta = prob.model.get_io_metadata(iotypes="output", metadata_keys=[])
        present = prob._bild_mdo_outputs = {value["prom_name"] for value in meta.values()}
    for name, units in {**DISTRIBUTION_UNITS, **NODE_OUTPUT_UNITS}.items():
        if name in present or name not in OPTIONAL_OUTPUTS:
            yield name, np.array(prob.get_val(name, units=units))


def station_reynolds(outputs, values, polar):
    """The chord Reynolds number of every station and whether it lies outside the polar's data
    (:data:`~bild_mdo.results.design_result.DERIVED_DISTRIBUTIONS`)."""
    omega = values["rpm"][:, None] * (RPM_TO_REV_PER_S * 2.0 * np.pi)
    w0 = np.hypot(values["v_axial"][:, None], omega * outputs["radii"])
    reynolds = outputs["rho"][:, None] * w0 * outputs["chord"] / outputs["mu"][:, None]
    return {"reynolds": reynolds, "reynolds_outside_data": reynolds_outside_data(reynolds, outputs["chord"], polar)}


def reynolds_outside_data(reynolds, chord, polar):
    """1.0 where a loaded station's chord Reynolds number lies outside the polar's data (which extrapolates
    there), else 0.0 (all 0.0 for a polar without a data range)."""
    data = data_reynolds_range(polar)
    if data is None:
        return np.zeros(reynolds.shape)
    with np.errstate(invalid="ignore"):
        return ((chord > 0.0) & ((reynolds < data[0]) | (reynolds > data[1]))).astype(float)


def _checked_inputs(input_mode, speed, rpm, radius, hub_radius_ratio, ref_radius_ratio, ref_chord, altitude,
                    thrust=None):
    """The per-design inputs as float arrays (0-d or 1-D), each checked; ValueError names the first bad one.

    With ``thrust`` the thrust target (N) replaces the reference chord.
    """
    values = {input_mode: validation.non_negative(input_mode, speed, units=INPUT_UNITS[input_mode],
                                                  hint="axial inflow from ahead; 0 is hover"),
              "rpm": validation.positive("rpm", rpm, units="rpm"),
              "radius": validation.positive("radius", radius, units="m")}
    for name, value in (("hub_radius_ratio", hub_radius_ratio), ("ref_radius_ratio", ref_radius_ratio)):
        values[name] = validation.in_range(name, value, 0.0, 1.0, open_low=True, open_high=True)
    validation.smaller("hub_radius_ratio", values["hub_radius_ratio"], "ref_radius_ratio",
                       values["ref_radius_ratio"], hint="the reference station lies on the blade")
    if thrust is None:
        values["ref_chord"] = validation.positive("ref_chord", ref_chord, units="m")
    else:
        values["thrust_target"] = validation.positive("thrust", thrust, units="N")
    values["altitude"] = validation.in_range("altitude", altitude, 0.0, MAX_ALTITUDE, units="m", hint="ISA")
    return values


def design_rotor(v_axial=None, advance_ratio=None, rpm=800.0, radius=1.5, hub_radius_ratio=0.2,
                 ref_radius_ratio=0.5, ref_chord=None, altitude=0.0, num_blades=3, airfoil="naca4412",
                 num_radial=30, loss_model="tip_hub", chord_form="thrust", root_chord_correction=None,
                 on_infeasible="raise", thrust=None, section_point="reference", ideal_loading="paper",
                 bem_analysis=True, fluid=None):
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
    ref_chord : float or array_like, optional
        Chord at the reference station c_ref (m), > 0.  Default 0.15
        (unless ``thrust`` is given).
    altitude : float or array_like
        Geometric altitude for the ISA (m), 0 ... 11,000.  Default 0.
    num_blades : int
        Number of blades B.  Default 3.
    airfoil : str or Polar
        ``'naca4412'`` (built-in XFOIL surrogate, default), ``'analytic'``,
        any :class:`~bild_mdo.airfoil.Polar` (e.g. a spanwise set from
        :func:`~bild_mdo.airfoil.spanwise_polar`) or any text
        :func:`~bild_mdo.io.airfoil.resolve_airfoil` accepts (a NACA
        designation, polar files or a folder of them, a spanwise set
        ``'0.2:naca4415;1:naca4412'``, ...).
    num_radial : int
        Radial stations (midpoints of equal annuli from hub to tip).  Default 30.
    loss_model : {'tip_hub', 'tip', 'none'}
        Prandtl loss factor.
    chord_form : {'thrust', 'torque'}
        Back-compute the chord from the thrust (Eq. (31)) or the torque balance.
    root_chord_correction : float, optional
        ``k`` of the root-chord correction, Eq. (32); None (default) for none.
    section_point : {'reference', 'local'}
        ``'reference'`` (default, the paper): every station at the maximum-L/D
        point of the reference station's Reynolds number.  ``'local'``: each
        station minimises its ``cd/cl`` at its fixed load, with the chord (and so
        the Reynolds number) following from the load
        (:mod:`bild_mdo.bild.variants.local_point`; a polar that varies with the
        Reynolds number only).
    ideal_loading : {'paper', 'exact'}
        ``'paper'`` (default): lambda of Eq. (22) and eta2 of the quartic (27).
        ``'exact'``: every annulus makes ``E - lambda T`` stationary with the
        Prandtl factor differentiated too
        (:mod:`bild_mdo.bild.annulus_stationarity`); with a fixed airfoil point
        this is the optimum of the BEM model.  With ``section_point='local'``
        the Reynolds-aware exact loading: each station's section point follows
        its own load (:mod:`bild_mdo.bild.variants.reynolds_exact`).
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
    thrust : float or array_like, optional
        Thrust target T* (N), > 0, instead of ``ref_chord``: the reference
        chord is solved for it inside the BILD model
        (:class:`~bild_mdo.bild.BILDGroup` with ``thrust_target=True``); the
        result's ``ref_chord`` is the solved chord.
    bem_analysis : bool
        Also analyse every design's own blade with the BEM model and the same
        polar at its operating point (default True; one vectorised run of a
        cached problem, :mod:`bild_mdo.results.design_analysis`): the result's
        ``bem_thrust``, ``bem_torque``, ``bem_power``, ``bem_efficiency`` and
        ``bem_figure_of_merit``, shown by :meth:`DesignResult.summary` beside
        the design's own numbers with the difference and why they can differ.
        False leaves them out (a sizing loop that needs only the design).
    fluid : Fluid, str or (rho, mu, speed_of_sound), optional
        Any fluid instead of the ISA at ``altitude`` (:mod:`bild_mdo.fluid`:
        ``'water'``, ``'seawater'``, ``'air'`` or your own; then ``altitude``
        must stay 0).  The result keeps it (``result.fluid``) and so do its
        geometry files, whose analysis then runs in the same fluid.

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
    if thrust is not None and ref_chord is not None:
        raise ValueError("give either ref_chord [m] or thrust [N] (the reference chord is then solved for it), "
                         "not both")
    ref_chord = 0.15 if ref_chord is None and thrust is None else ref_chord
    input_mode = "advance_ratio" if advance_ratio is not None else "v_axial"
    speed = advance_ratio if advance_ratio is not None else (0.0 if v_axial is None else v_axial)
    num_blades = validation.integer("num_blades", num_blades)
    num_radial = validation.integer("num_radial", num_radial)
    validation.choice("loss_model", loss_model, LOSS_MODELS)
    validation.choice("chord_form", chord_form, CHORD_FORMS)
    validation.choice("on_infeasible", on_infeasible, ON_INFEASIBLE)
    validation.choice("section_point", section_point, SECTION_POINTS)
    validation.choice("ideal_loading", ideal_loading, IDEAL_LOADINGS)
    if root_chord_correction is not None:
        root_chord_correction = float(validation.positive("root_chord_correction", root_chord_correction,
                                                          hint="k of Eq. (32), or None", ndim=(0,)))
    if fluid is not None:
        fluid = resolve_fluid(fluid)
        if np.any(np.asarray(altitude, dtype=float) != 0.0):
            raise ValueError("give either altitude [m] (the ISA) or fluid, not both")
    values = _checked_inputs(input_mode, speed, rpm, radius, hub_radius_ratio, ref_radius_ratio, ref_chord,
                             altitude, thrust)
    is_batch = any(arr.ndim == 1 for arr in values.values())
    nn = validation.batch_size({name: arr.size for name, arr in values.items() if arr.ndim == 1})
    values = {name: np.broadcast_to(arr, (nn,)).astype(float) for name, arr in values.items()}
    _check_tip_mach(values, input_mode, fluid)
    validation.memory_bound("designs", nn, num_radial, hint="design in smaller batches or with fewer stations")

    config = dict(num_nodes=nn, num_radial=num_radial, num_blades=num_blades, loss_model=loss_model,
                  chord_form=chord_form, root_chord_correction=root_chord_correction, input_mode=input_mode,
                  on_infeasible="flag", section_point=section_point)
    # resolve_airfoil gives one polar object per airfoil text in a process, so bild_problem (keyed by the
    # polar) reuses the set-up problem on repeated calls.
    polar = resolve_airfoil(airfoil)
    prob = bild_problem(airfoil=polar, thrust_target=thrust is not None, ideal_loading=ideal_loading,
                        use_atmosphere=fluid is None, **config)
    polar = prob.model.options["polar"]
    for name, arr in values.items():
        if name == "altitude" and fluid is not None:
            continue
        prob.set_val(name, arr, units="N" if name == "thrust_target" else INPUT_UNITS[name])
    if fluid is not None:
        for name, arr in fluid_arrays(fluid, nn).items():
            prob.set_val(name, arr)
    prob.run_model()

    infeasible = prob.model.feasibility.infeasible
    if thrust is not None:  # the solved reference chord is the design's (NaN where infeasible)
        del values["thrust_target"]
        values["ref_chord"] = np.where(infeasible, np.nan, prob.get_val("ref_chord", units="m"))
    if on_infeasible == "raise" and np.any(infeasible):
        raise om.AnalysisError(f"BILD: {prob.model.feasibility.message(noun='design', limit=10)}\n  "
                               "(design_rotor(..., on_infeasible='skip') returns the whole batch with "
                               "result.feasible and result.status)")
    # Infeasible designs hold placeholder values in the model: NaN in the result.
    outputs = {name: np.where(infeasible if np.ndim(value) == 1 else infeasible[:, None], np.nan, value)
               for name, value in _model_outputs(prob)}
    for name in ("thrust", "torque", "chord", "twist"):
        bad = ~np.isfinite(outputs[name]) & (~infeasible if outputs[name].ndim == 1 else ~infeasible[:, None])
        if np.any(bad):
            designs = np.unique(np.nonzero(bad)[0])
            raise om.AnalysisError(f"BILD returned non-finite {name} for design(s) {designs[:10].tolist()}")
    if "tip_mach" in outputs:
        warn_supersonic_tip(outputs["tip_mach"])
    if input_mode == "v_axial":
        values["advance_ratio"] = values["v_axial"] / (values["rpm"] * RPM_TO_REV_PER_S * 2.0 * values["radius"])
    else:
        values["v_axial"] = np.array(prob.get_val("v_axial", units="m/s"))
    outputs["radial_fractions"] = outputs["radii"] / values["radius"][:, None]
    _warn_unloaded(outputs["chord"], ~infeasible, outputs["radial_fractions"], is_batch)
    outputs.update(station_reynolds(outputs, values, polar))
    ordered = {name: outputs[name] for name in DISTRIBUTIONS if name in outputs}
    ordered.update({name: values[name] for name in INPUT_UNITS})
    ordered.update({name: outputs[name] for name in NODE_OUTPUT_UNITS if name in outputs})
    if bem_analysis:
        analysis, invalid = analyze_designs(values, outputs, ~infeasible, num_blades, polar, loss_model, fluid)
        ordered.update(analysis)
        ordered["bem_invalid_stations"] = np.where(infeasible, np.nan, invalid.astype(float))
    result = DesignResult(values=ordered, num_blades=num_blades, airfoil=getattr(polar, "name", type(polar).__name__),
                          loss_model=loss_model, chord_form=chord_form,
                          root_chord_correction=root_chord_correction, polar=polar, is_batch=True,
                          feasible=~infeasible, status=prob.model.feasibility.status(),
                          section_point=section_point, ideal_loading=ideal_loading, fluid=fluid)
    _warn_reference(result, is_batch)
    return result if is_batch else result[0]
