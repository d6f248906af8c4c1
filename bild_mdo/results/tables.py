"""Text tables of the result objects: design summaries, station tables, off-design sweeps.

The functions read a result's quantities by name, so they serve
:class:`~bild_mdo.results.design.DesignResult` and
:class:`~bild_mdo.results.off_design.OffDesignResult` alike.  Column titles
and display scales of the performance metrics come from the registry
:data:`~bild_mdo.bem.metrics.METRICS`.
"""
from __future__ import annotations

import numpy as np

from bild_mdo.bem.metrics import METRICS_BY_NAME

#: Operating-point and sizing columns: name -> title (SI units; rpm in rpm).
INPUT_TITLES = {"advance_ratio": "J [-]", "v_axial": "V [m/s]", "rpm": "rpm", "radius": "R [m]",
                "ref_chord": "c_ref [m]", "altitude": "alt [m]"}

#: Columns of a batch of designs: inputs, then metrics.
DESIGN_BATCH_COLUMNS = ("advance_ratio", "v_axial", "rpm", "radius", "ref_chord", "altitude", "thrust",
                        "torque", "power", "efficiency", "figure_of_merit", "thrust_coefficient", "solidity")

#: Columns of an off-design sweep and their number formats.
SWEEP_COLUMNS = {"advance_ratio": ".4f", "v_axial": ".3f", "rpm": ".1f", "thrust": ".5g", "torque": ".5g",
                 "power": ".5g", "efficiency": ".4f", "figure_of_merit": ".4f", "thrust_coefficient": ".5f",
                 "torque_coefficient": ".6f", "power_coefficient": ".5f"}

# The summary of one design: (label, quantity, display units); a quantity of None starts a section, a pair
# of quantities shares a row.  Quantities in kW are scaled by the metric's display_scale.
_SINGLE_DESIGN_ROWS = (
    ("operating point", None, None), ("axial velocity V_x", "v_axial", "m/s"),
    ("advance ratio J = V/(nD)", "advance_ratio", "-"), ("rotor speed", "rpm", "rpm"), ("altitude", "altitude", "m"),
    ("air density rho", "rho", "kg/m^3"),
    ("geometry", None, None), ("tip radius R", "radius", "m"), ("hub radius", "hub_radius", "m"),
    ("reference radius r_ref", "ref_radius", "m"), ("reference chord c_ref", "ref_chord", "m"),
    ("solidity sigma_r", "solidity", "-"),
    ("reference airfoil point", None, None), ("Reynolds number Re_ref", "reynolds_ref", "-"),
    ("alpha* (max L/D)", "alpha_star_deg", "deg"), ("C_l*, C_d*", ("cl_star", "cd_star"), "-"),
    ("ideal-loading constant lambda", "ideal_loading_constant", "m/s"),
    ("performance", None, None), ("thrust T", "thrust", "N"), ("torque Q", "torque", "N m"), ("power P", "power", "kW"),
    ("energy loss E", "energy_loss", "kW"), ("efficiency eta", "efficiency", "-"),
    ("figure of merit FM", "figure_of_merit", "-"), ("C_T", "thrust_coefficient", "-"),
    ("C_Q", "torque_coefficient", "-"), ("C_P", "power_coefficient", "-"),
    ("blade loading C_T/sigma_r", "blade_loading", "-"),
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
    """One row per design of a batch (the middle elided beyond ``max_rows``)."""
    columns = [(name, *column(name)) for name in DESIGN_BATCH_COLUMNS]
    lines = [f"{len(result)} designs", f"{'#':>6} " + " ".join(f"{title:>11}" for _, title, _ in columns)]
    for i in shown_rows(len(result), max_rows):
        if i is None:
            lines.append(f"{'...':>6}")
            continue
        lines.append(f"{i:>6d} " + " ".join(format_cell(getattr(result, name)[i] * scale)
                                             for name, _, scale in columns))
    return lines


def single_design_table(design):
    """Label / value / units lines of one design's inputs, reference point and performance."""
    lines = []
    for label, quantity, units in _SINGLE_DESIGN_ROWS:
        if quantity is None:
            lines.append(f"{label}:")
        elif isinstance(quantity, tuple):
            cl_star, cd_star = (getattr(design, name) for name in quantity)
            lines.append(f"  {label:<32s} {f'{cl_star:.4f}, {cd_star:.5f}':>14s} {units}")
        else:
            scale = METRICS_BY_NAME[quantity].display_scale if units == "kW" else 1.0
            lines.append(f"  {label:<32s} {getattr(design, quantity) * scale:>14.6g} {units}")
    return lines


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
    columns = [(name, *column(name), fmt) for name, fmt in SWEEP_COLUMNS.items()]
    lines = [" ".join(f"{title:>10}" for _, title, _, _ in columns)]
    for i in range(len(result)):
        lines.append(" ".join(f"{getattr(result, name)[i] * scale:>10{fmt}}" for name, _, scale, fmt in columns))
    return lines
