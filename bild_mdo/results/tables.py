"""Text tables of the result objects: design summaries, station tables, off-design sweeps.

The functions read a result's quantities by name, so they serve
:class:`~bild_mdo.results.design.DesignResult` and
:class:`~bild_mdo.results.off_design.OffDesignResult` alike.  Column titles
and display scales of the performance metrics come from the registry
:data:`~bild_mdo.bem.metrics.METRICS`.

The efficiency and the figure of merit are printed only where they mean
something (:data:`PROPULSIVE_ONLY`, :func:`meaningful`): both need ``T > 0``
and ``P > 0`` (not a windmill, a brake or a rotor that absorbs no power), the
efficiency ``V_x T / P`` forward flight (``V_x > 0``; it is 0 in hover) and
the figure of merit hover (``V_x = 0``; in climb or cruise it compares the
rotor with a hovering actuator disk it is not).  Elsewhere the cell reads
"n/a", although the result objects keep the formulas' values.  Designs or points
that are infeasible or failed (``result.feasible`` / ``result.status``) print
their reason instead of numbers.
"""
from __future__ import annotations

import numpy as np

from bild_mdo.bem.metrics import METRICS_BY_NAME
from bild_mdo.results.design_analysis import analysis_reason

#: Operating-point and sizing columns: name -> title (SI units; rpm in rpm).
INPUT_TITLES = {"advance_ratio": "J [-]", "v_axial": "V [m/s]", "rpm": "rpm", "radius": "R [m]",
                "ref_chord": "c_ref [m]", "altitude": "alt [m]", "collective_pitch_deg": "pitch [deg]"}

#: Columns of a batch of designs: inputs, then metrics.
DESIGN_BATCH_COLUMNS = ("advance_ratio", "v_axial", "rpm", "radius", "ref_chord", "altitude", "thrust",
                        "torque", "power", "efficiency", "figure_of_merit", "thrust_coefficient", "solidity")

#: Operating-point columns of an off-design sweep (printed for failed points too).
POINT_TITLES = ("advance_ratio", "v_axial", "rpm", "collective_pitch_deg")

#: Columns of an off-design sweep and their number formats (the pitch only where some point has one).
SWEEP_COLUMNS = {"advance_ratio": ".4f", "v_axial": ".3f", "rpm": ".1f", "collective_pitch_deg": ".3f",
                 "thrust": ".5g", "torque": ".5g",
                 "power": ".5g", "efficiency": ".4f", "figure_of_merit": ".4f", "thrust_coefficient": ".5f",
                 "torque_coefficient": ".6f", "power_coefficient": ".5f"}

#: Metrics printed only where they mean something (:func:`meaningful`; else "n/a").
PROPULSIVE_ONLY = ("efficiency", "figure_of_merit")


def propulsive(result):
    """Boolean array: T > 0 and P > 0 (where eta and FM are efficiencies), per design or point."""
    return (np.asarray(result.thrust) > 0.0) & (np.asarray(result.power) > 0.0)


def meaningful(result):
    """Where each metric of :data:`PROPULSIVE_ONLY` means something, per design or point: the efficiency in
    forward flight (``V_x > 0``), the figure of merit in hover (``V_x = 0``), both only with T > 0 and P > 0."""
    both = propulsive(result)
    hover = np.asarray(result.v_axial) == 0.0
    return {"efficiency": both & ~hover, "figure_of_merit": both & hover}


def not_meaningful_reason(result, name):
    """Why a metric of :data:`PROPULSIVE_ONLY` of one design or point is "n/a" (its table note)."""
    if not bool(propulsive(result)):
        return "needs T > 0 and P > 0"
    return "hover: see FM" if name == "efficiency" else "not in hover: see eta"


def metric_cell(result, name, index, scale=1.0, fmt=None, width=11, useful=None):
    """A table cell of quantity ``name`` at ``index``: "n/a" for eta and FM where they mean nothing
    (``useful``: :func:`meaningful` of the result, computed here if not given)."""
    if name in PROPULSIVE_ONLY:
        ok = (meaningful(result) if useful is None else useful)[name]
        if not np.ndim(ok) == 0:
            ok = ok[index]
        if not ok:
            return f"{'n/a':>{width}s}"
    value = np.asarray(getattr(result, name))
    value = float(value if value.ndim == 0 else value[index]) * scale
    return format_cell(value, width) if fmt is None else f"{value:>{width}{fmt}}"


def _statuses(result):
    """Per-row status strings of a batch result ('ok' where feasible)."""
    return np.broadcast_to(np.asarray(getattr(result, "status", "ok"), dtype=object), (len(result),))


def status_footer(result, noun):
    """Lines counting the rows that are not 'ok', by reason (empty if all are)."""
    status = _statuses(result)
    bad = status != "ok"
    if not np.any(bad):
        return []
    reasons, counts = np.unique(status[bad].astype(str), return_counts=True)
    lines = [f"{int(np.sum(bad))} of {len(result)} {noun} infeasible or failed (values NaN):"]
    lines += [f"  {count} x {reason}" for reason, count in zip(reasons, counts)]
    return lines


# The summary of one design: (label, quantity, display units); a quantity of None starts a section, a pair
# of quantities shares a row.  Quantities in kW are scaled by the metric's display_scale.
_SINGLE_DESIGN_ROWS = (
    ("operating point", None, None), ("axial velocity V_x", "v_axial", "m/s"),
    ("advance ratio J = V/(nD)", "advance_ratio", "-"), ("rotor speed", "rpm", "rpm"), ("altitude", "altitude", "m"),
    ("density rho", "rho", "kg/m^3"), ("dynamic viscosity mu", "mu", "Pa s"),
    ("geometry", None, None), ("tip radius R", "radius", "m"), ("hub radius", "hub_radius", "m"),
    ("reference radius r_ref", "ref_radius", "m"), ("reference chord c_ref", "ref_chord", "m"),
    ("solidity sigma_r", "solidity", "-"),
    ("reference airfoil point", None, None), ("Reynolds number Re_ref", "reynolds_ref", "-"),
    ("alpha*", "alpha_star_deg", "deg"), ("C_l*, C_d*", ("cl_star", "cd_star"), "-"),
    ("ideal-loading constant lambda", "ideal_loading_constant", "m/s"),
    ("performance", None, None), ("thrust T", "thrust", "N"), ("torque Q", "torque", "N m"), ("power P", "power", "kW"),
    ("energy loss E", "energy_loss", "kW"), ("efficiency eta", "efficiency", "-"),
    ("figure of merit FM", "figure_of_merit", "-"), ("C_T", "thrust_coefficient", "-"),
    ("C_Q", "torque_coefficient", "-"), ("C_P", "power_coefficient", "-"),
    ("blade loading C_T/sigma_r", "blade_loading", "-"), ("tip Mach number", "tip_mach", "-"),
)


def column(name):
    """``(title, scale)`` of a table column: a metric's label and display scale, or an input's title."""
    metric = METRICS_BY_NAME.get(name)
    if metric is not None:
        return metric.label, metric.display_scale
    return INPUT_TITLES[name], 1.0


def format_cell(value, width=11):
    """A right-aligned table cell: text as is, numbers to 5 significant digits."""
    if isinstance(value, str):
        return f"{value:>{width}s}"
    return f"{value:>{width}.5g}"


def shown_rows(count, max_rows):
    """Row indices to print, first and last ones, with None where the middle is elided."""
    if count <= max_rows:
        return list(range(count))
    head = max_rows // 2
    return list(range(head)) + [None] + list(range(count - (max_rows - head), count))


def design_configuration(result):
    """The first line of a design summary: airfoil, blades, stations, loss model, chord form."""
    correction = result.root_chord_correction
    return (f"BILD design: airfoil {result.airfoil}, B = {result.num_blades}, "
            f"{np.shape(result.radii)[-1]} stations, loss model {result.loss_model}, "
            f"chord from {result.chord_form}"
            + ("" if correction is None else f", root-chord correction k = {correction:g}"))


def design_batch_table(result, max_rows):
    """One row per design of a batch (the middle elided beyond ``max_rows``); infeasible rows say so."""
    columns = [(name, *column(name)) for name in DESIGN_BATCH_COLUMNS]
    lines = [f"{len(result)} designs", f"{'#':>6} " + " ".join(f"{title:>11}" for _, title, _ in columns)]
    useful, status = meaningful(result), _statuses(result)
    for i in shown_rows(len(result), max_rows):
        if i is None:
            lines.append(f"{'...':>6}")
            continue
        cells = [metric_cell(result, name, i, scale, useful=useful) for name, _, scale in columns
                 if name in INPUT_TITLES or status[i] == "ok"]
        lines.append(f"{i:>6d} " + " ".join(cells) + ("" if status[i] == "ok" else "  infeasible"))
    return lines + status_footer(result, "designs")


def single_design_table(design):
    """Label / value / units lines of one design's inputs, reference point and performance, then its notes
    (:func:`design_notes`)."""
    status = getattr(design, "status", "ok")
    lines = [] if status == "ok" else [f"INFEASIBLE (values NaN): {status}"]
    useful = {name: bool(mask) for name, mask in meaningful(design).items()}
    local = getattr(design, "section_point", "reference") == "local"
    for label, quantity, units in _SINGLE_DESIGN_ROWS:
        if quantity is None:
            lines.append(f"{label}:" if label != "reference airfoil point" else f"section point ({_method(design)}):")
        elif quantity == "altitude" and getattr(design, "fluid", None) is not None:
            lines.append(f"  {'fluid (instead of the ISA)':<32s} {design.fluid.name:>14s}")
        elif isinstance(quantity, tuple):
            cl_star, cd_star = (getattr(design, name) for name in quantity)
            text = f"{_number(cl_star, '.4f')}, {_number(cd_star, '.5f')}"
            lines.append(f"  {label:<32s} {text:>14s} {units}" + _per_station(cl_star, local))
        elif quantity in PROPULSIVE_ONLY and not useful[quantity]:
            lines.append(f"  {label:<32s} {'n/a':>14s} {units}  ({not_meaningful_reason(design, quantity)})")
        elif hasattr(design, quantity):  # tip_mach only where the model outputs it
            scale = METRICS_BY_NAME[quantity].display_scale if units == "kW" else 1.0
            value = np.asarray(getattr(design, quantity)) * scale
            lines.append(f"  {label:<32s} {_number(value, '.6g'):>14s} {units}" + _per_station(value, local))
    return lines + analysis_rows(design, useful) + design_notes(design)


def analysis_rows(design, useful):
    """The BEM analysis of one design's own blade beside the design's numbers, and why they can differ
    (empty without an analysis; :mod:`~bild_mdo.results.design_analysis`)."""
    if "bem_thrust" not in design.values or getattr(design, "status", "ok") != "ok":
        return []
    lines = ["BEM analysis of this blade (same polar and operating point; each station at its own Re):"]
    rows = [("thrust T", "thrust", "N", 1.0), ("power P", "power", "kW", 1e-3)]
    rows += [(label, name, "-", 1.0) for label, name in (("efficiency eta", "efficiency"),
                                                         ("figure of merit FM", "figure_of_merit"))
             if useful[name]]
    for label, name, units, scale in rows:
        analysed, designed = float(design.values["bem_" + name]), float(design.values[name])
        difference = round(100.0 * (analysed / designed - 1.0), 4) + 0.0  # no "-0.0000"
        lines.append(f"  {label:<32s} {analysed * scale:>14.6g} {units}  "
                     f"({difference:+.4f} % against the design's {designed * scale:.6g})")
    lines.append(f"  {analysis_reason(design)}")
    invalid = int(design.values.get("bem_invalid_stations", 0))
    if invalid:
        lines.append(f"  {invalid} station(s) outside the propeller flow state in the analysis "
                     "(bild_mdo.bem.flow_states)")
    return lines


def _method(design):
    if getattr(design, "section_point", "reference") == "local":
        return "each station at the least C_d/C_l of its own path of fixed load"
    if np.ndim(design.cl_star):
        return "max L/D at Re_ref of each station's airfoil"
    return "max L/D at Re_ref, every station (the paper's Assumption 2)"


def _fractions(design, stations):
    return ", ".join(f"{design.radial_fractions[i]:.3f}" for i in stations)


def reference_mismatches(values):
    """Per design of ``values`` (a result's arrays), whether the blade has not ``ref_chord`` at ``r_ref`` (None
    without the local section point): the reference state's sheet (``section_branch_ref``) is not the one a
    station at ``r_ref`` takes at the design's lambda (``station_branch_ref``, the Reynolds-aware exact loading),
    or, with the paper loading, not the sheet of either station next to ``r_ref``; the blade there then carries
    another load and chord.  A reference state in the Reynolds gap (sheet -1) is not checked."""
    ref_sheet = values.get("section_branch_ref")
    if ref_sheet is None:
        return None
    ref_sheet = np.atleast_1d(ref_sheet)
    station_sheet = values.get("station_branch_ref")
    if station_sheet is not None:
        station_sheet = np.atleast_1d(station_sheet)
        return (ref_sheet >= 0) & (station_sheet >= -1) & (station_sheet != ref_sheet)
    return (ref_sheet >= 0) & ~np.any(_sheets_next_to_reference(values) == ref_sheet[:, None], axis=1)


def _sheets_next_to_reference(values):
    """``[nn, 2]``: the sheets of the two stations next to ``r_ref`` (the outermost one inward of it and the
    next one out, clipped to the blade)."""
    branch, radii = np.atleast_2d(values["section_branch"]), np.atleast_2d(values["radii"])
    after = np.sum(radii < np.atleast_1d(values["ref_radius"])[:, None], axis=1)
    near = np.clip(after[:, None] + np.array([-1, 0]), 0, branch.shape[1] - 1)
    return branch[np.arange(branch.shape[0])[:, None], near]


def reference_mismatch(design):
    """The note for a design whose blade has not ``ref_chord`` at ``r_ref`` (:func:`reference_mismatches`), or
    None."""
    mismatch = reference_mismatches(design.values)
    if mismatch is None or not mismatch[0]:
        return None
    ref_sheet, station_sheet = int(design.values["section_branch_ref"]), design.values.get("station_branch_ref")
    if station_sheet is not None:
        taken = ("a station at r_ref leaves it unloaded" if station_sheet < 0
                 else f"a station at r_ref takes sheet {int(station_sheet)}, of lower F (e - lambda t)")
        taken += ("; no other state with c_ref there is taken by a station at its own lambda: c_ref lies in a jump "
                  "of the optimal blades' chord at r_ref")
    else:
        sheets = np.unique(_sheets_next_to_reference(design.values))
        taken = "the stations next to r_ref take sheet(s) " + ", ".join(str(int(b)) for b in sheets)
    chord = float(np.interp(design.ref_radius, design.radii, design.chord))
    return (f"  ref_chord is not the blade's chord at r_ref: the reference state (c_ref {design.ref_chord:.4g} m, "
            f"Re_ref {design.reynolds_ref:.3g}, sheet {ref_sheet}) is not the state the blade has there at this "
            f"lambda ({taken}); the blade there has a chord of about {chord:.4g} m (interpolated). It is the "
            f"blade of its own thrust; for a blade with c_ref at r_ref ask for a thrust (thrust=) or another ref_chord")


def design_notes(design):
    """What a reader of one design should know beyond its numbers (empty when there is nothing):

    * stations whose chord Reynolds number lies outside the polar's data (the polar extrapolates there);
    * with the local section point, jumps: adjacent loaded stations on different sheets of the load-path table
      (the two minima of C_d/C_l along the path are nearly equal there, and the lower is taken), where chord
      and twist change by more than the ideal loading's smooth variation;
    * unloaded stations (zero chord) between loaded ones;
    * a local-point design whose blade has not ``ref_chord`` at ``r_ref`` (:func:`reference_mismatch`).
    """
    if getattr(design, "status", "ok") != "ok":
        return []
    notes = []
    outside = np.flatnonzero(np.asarray(design.values.get("reynolds_outside_data", 0.0)) > 0.0)
    if outside.size:
        re = design.reynolds[outside]
        notes.append(f"  {outside.size} station(s) outside the polar's Reynolds-number data, extrapolated there "
                     f"(Re {np.min(re):.3g}..{np.max(re):.3g}) at r/R {_fractions(design, outside)}")
    chord = np.asarray(design.chord)
    loaded = chord > 0.0
    if loaded.any() and not loaded.all():
        unloaded = np.flatnonzero(~loaded)
        first, last = np.flatnonzero(loaded)[[0, -1]]
        inner = (unloaded > first) & (unloaded < last)
        where = ("between loaded ones" if inner.all() else "at the tip" if np.all(unloaded > last)
                 else "at the hub" if np.all(unloaded < first) else "at the hub, the tip or between loaded ones")
        notes.append(f"  {unloaded.size} unloaded station(s) (zero chord) {where}, at r/R "
                     f"{_fractions(design, unloaded)}: the ideal loading carries nothing there at this lambda")
    mismatch = reference_mismatch(design)
    if mismatch is not None:
        notes.append(mismatch)
    branch = design.values.get("section_branch")
    if branch is not None:
        both = loaded[:-1] & loaded[1:]
        switch = np.flatnonzero(both & (branch[:-1] != branch[1:]))
        for i in switch:
            notes.append(f"  jump between r/R {design.radial_fractions[i]:.3f} and {design.radial_fractions[i + 1]:.3f}"
                         f": the section point changes branch (sheet {int(branch[i])} -> {int(branch[i + 1])}, "
                         f"alpha {np.degrees(design.alpha_star[i]):.2f} -> {np.degrees(design.alpha_star[i + 1]):.2f} "
                         f"deg); chord {chord[i]:.4g} -> {chord[i + 1]:.4g} m, twist "
                         f"{design.twist_deg[i]:.2f} -> {design.twist_deg[i + 1]:.2f} deg")
    return ["notes:"] + notes if notes else []


def _number(value, fmt):
    """A number, or the range ``lo..hi`` of a per-station array (several airfoils, or the local section point)."""
    value = np.asarray(value)
    if value.ndim == 0:
        return f"{float(value):{fmt}}"
    return f"{np.min(value):{fmt}}..{np.max(value):{fmt}}"


def _per_station(value, local=False):
    if not np.ndim(value):
        return ""
    return "  (per station: its own section point)" if local else "  (per station: several airfoils along the span)"


def station_table(design):
    """Stations of one design: r [m], r/R, chord [m], twist [deg], C_l, C_d."""
    lines = [f"{'r [m]':>10} {'r/R [-]':>9} {'chord [m]':>10} {'twist [deg]':>11} {'C_l [-]':>8} "
             f"{'C_d [-]':>8}"]
    for row in zip(design.radii, design.radial_fractions, design.chord, design.twist_deg,
                   design.lift_coefficient, design.drag_coefficient):
        lines.append(f"{row[0]:>10.4f} {row[1]:>9.4f} {row[2]:>10.5f} {row[3]:>11.3f} {row[4]:>8.4f} "
                     f"{row[5]:>8.5f}")
    return "\n".join(lines)


def sweep_table(result):
    """One row per operating point of an off-design sweep."""
    pitched = np.any(np.asarray(getattr(result, "collective_pitch", 0.0)) != 0.0)
    columns = [(name, *column(name), fmt) for name, fmt in SWEEP_COLUMNS.items()
               if pitched or name != "collective_pitch_deg"]
    lines = [" ".join(f"{title:>10}" for _, title, _, _ in columns)]
    useful, status = meaningful(result), _statuses(result)
    for i in range(len(result)):
        cells = [metric_cell(result, name, i, scale, fmt, width=10, useful=useful)
                 for name, _, scale, fmt in columns if name in POINT_TITLES or status[i] == "ok"]
        lines.append(" ".join(cells) + ("" if status[i] == "ok" else f"  failed: {status[i]}"))
    return lines
