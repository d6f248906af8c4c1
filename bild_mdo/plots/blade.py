"""Planform and twist of blade designs (matplotlib, extra ``bild-mdo[plot]``).

:func:`plot_blade` draws one design or a batch: the planform seen from above
and the twist distribution.  The planform is drawn about a straight
quarter-chord line (the pitch axis): leading edge ``c/4`` ahead of it,
trailing edge ``3c/4`` behind.  The chordwise scale is stretched relative to
the span so the chord distribution is readable; the axis labels give both in
metres.  With a ``path`` the figure is written as PNG (see
:mod:`bild_mdo.plots.figure`).
"""
from __future__ import annotations

import numpy as np

from bild_mdo.io.geometry import as_geometry
from bild_mdo.plots.figure import PLOT_MISSING, finish, new_figure
from bild_mdo.results.design import DesignResult

# Inputs that label the curves of a batch, in order of preference: (field, label, format).
_LABEL_FIELDS = (("advance_ratio", "J", ".3g"), ("v_axial", "V", ".3g m/s"), ("ref_chord", "c_ref", ".3g m"),
                 ("ref_radius_ratio", "r_ref/R", ".3g"), ("rpm", "rpm", ".4g"), ("radius", "R", ".3g m"),
                 ("altitude", "alt", ".4g m"), ("hub_radius_ratio", "r_hub/R", ".3g"))
_MAX_LEGEND_ENTRIES = 12


def _fmt(value, spec):
    number, _, unit = spec.partition(" ")
    return f"{value:{number}}" + (f" {unit}" if unit else "")


def _designs(result):
    """Geometries, curve labels, title and the colour key for a DesignResult, RotorGeometry or a list of them.

    The colour key is ``(values, axis label)``: the first input that varies over a batch, or the design
    index.
    """
    if isinstance(result, DesignResult):
        designs = list(result)
        varying = [(field, label, spec) for field, label, spec in _LABEL_FIELDS
                   if len(designs) > 1 and np.ptp(np.atleast_1d(getattr(result, field))) > 0.0]
        # V follows from J (or J from V) at fixed rpm and R: one of the two is enough.
        if {f for f, _, _ in varying} >= {"advance_ratio", "v_axial"}:
            varying = [v for v in varying if v[0] != "v_axial"]
        if not varying:
            varying = [_LABEL_FIELDS[0]] if designs[0].advance_ratio > 0 else [("rpm", "rpm", ".4g")]
        labels = [", ".join(f"{label} = {_fmt(getattr(d, field), spec)}" for field, label, spec in varying[:3])
                  for d in designs]
        title = f"BILD blade{'s' if len(designs) > 1 else ''}: {result.airfoil}, B = {result.num_blades}"
        if np.ptp(np.atleast_1d(result.radius)) == 0.0:
            title += f", R = {_fmt(designs[0].radius, '.3g m')}"
        if len(designs) > _MAX_LEGEND_ENTRIES:
            title += f" ({len(designs)} designs)"
        field, label, spec = varying[0]
        unit = spec.partition(" ")[2] or "-"
        key = (np.atleast_1d(getattr(result, field)).astype(float), f"{label} [{unit}]")
        return [d.geometry() for d in designs], labels, title, key
    items = result if isinstance(result, (list, tuple)) else [result]
    geometries = [as_geometry(item) for item in items]
    labels = [g.name for g in geometries]
    key = (np.arange(len(geometries), dtype=float), "design [-]")
    return geometries, labels, "Rotor blade" + ("s" if len(geometries) > 1 else ""), key


def plot_blade(result, path=None):
    """Planform (seen from above, about the quarter-chord line) and twist distribution of one or more blades.

    Parameters
    ----------
    result : DesignResult, RotorGeometry or list of RotorGeometry
        A single design or a batch (one curve per design; the legend names
        the inputs that vary, up to 12 entries).
    path : str or path, optional
        PNG file to write.

    Returns
    -------
    matplotlib.figure.Figure
    """
    geometries, labels, title, (key_values, key_label) = _designs(result)
    fig = new_figure(path, figsize=(8.0, 6.4))
    ax_plan, ax_twist = fig.subplots(2, 1, sharex=True, height_ratios=[1.0, 1.0])
    colors, mappable = _colors(key_values)
    show_legend = 1 < len(geometries) <= _MAX_LEGEND_ENTRIES
    for geom, label, color in zip(geometries, labels, colors):
        r = np.concatenate([[geom.hub_radius], geom.radii, [geom.radius]])
        # The chord at hub and tip is continued flat from the end stations so the outline closes.
        c = np.concatenate([[geom.chord[0]], geom.chord, [geom.chord[-1]]])
        leading, trailing = 0.25 * c, -0.75 * c
        ax_plan.plot(r, leading, color=color, lw=1.6, label=label if show_legend else None)
        ax_plan.plot(r, trailing, color=color, lw=1.6)
        ax_plan.plot([r[-1], r[-1]], [trailing[-1], leading[-1]], color=color, lw=1.6)
        ax_plan.plot([r[0], r[0]], [trailing[0], leading[0]], color=color, lw=1.6)
        if len(geometries) == 1:
            ax_plan.fill_between(r, trailing, leading, color=color, alpha=0.15, lw=0)
        ax_twist.plot(geom.radii, geom.twist_deg, color=color, lw=1.6, marker="o", ms=2.5)
    ax_plan.axhline(0.0, color="0.3", lw=0.8, ls="--", label="quarter-chord line (pitch axis)")
    ax_plan.set_ylabel("chordwise position [m]\n(leading edge up)")
    ax_plan.set_title("Planform seen from above (chord about the quarter-chord line)")
    ax_twist.set_xlabel("radius r [m]")
    ax_twist.set_ylabel("twist [deg]")
    ax_twist.set_title("Twist (pitch) distribution")
    for ax in (ax_plan, ax_twist):
        ax.grid(True, lw=0.4, alpha=0.6)
    ax_plan.margins(y=0.12)
    # Legends outside the axes never cover a curve.
    if len(geometries) > _MAX_LEGEND_ENTRIES:
        fig.colorbar(mappable, ax=[ax_plan, ax_twist], label=key_label, shrink=0.8)
    handles, names = ax_plan.get_legend_handles_labels()
    fig.legend(handles, names, loc="outside lower center", ncols=min(3, len(names)), fontsize="small",
               frameon=False)
    fig.suptitle(title)
    return finish(fig, path)


def _colors(values):
    """Line colours by value on a truncated viridis map, and the ScalarMappable for a colour bar."""
    if len(values) == 1:
        return ["tab:blue"], None
    try:
        from matplotlib import colormaps
        from matplotlib.cm import ScalarMappable
        from matplotlib.colors import ListedColormap, Normalize
    except ImportError as exc:
        raise ImportError(PLOT_MISSING) from exc
    # The yellow end of viridis is hard to see on white.
    cmap = ListedColormap(colormaps["viridis"](np.linspace(0.0, 0.9, 256)))
    low, high = float(np.min(values)), float(np.max(values))
    norm = Normalize(low, high if high > low else low + 1.0)
    return [cmap(norm(v)) for v in values], ScalarMappable(norm=norm, cmap=cmap)
