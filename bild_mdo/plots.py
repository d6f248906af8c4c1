"""Figures of blade designs and off-design performance (matplotlib, extra ``bild-mdo[plot]``).

matplotlib is imported only when a figure is made.  With a ``path`` the
figure is drawn on a ``matplotlib.figure.Figure`` with the Agg canvas and
written as PNG (no display, no pyplot state); without one it is a pyplot
figure, ready for ``plt.show()`` or a notebook.

:func:`plot_blade`
    Planform seen from above and twist distribution of one design or a batch.
    The planform is drawn about a straight quarter-chord line (the pitch
    axis): leading edge ``c/4`` ahead of it, trailing edge ``3c/4`` behind.
    The chordwise scale is stretched relative to the span so the chord
    distribution is readable; the axis labels give both in metres.
:func:`plot_performance_curves`
    Thrust, power, efficiency (or figure of merit) and the coefficients of an
    :class:`~bild_mdo.off_design.OffDesignResult` against J or rpm.
:func:`plot_run_times`, :func:`plot_parity`
    The verification sweep's timing scatter (paper Fig. 4) and parity plots
    (Fig. 5), from :mod:`bild_mdo.verification.figures`.
"""
from __future__ import annotations

import numpy as np

from bild_mdo.verification.figures import plot_parity, plot_run_times  # re-exported: one place for all figures

PLOT_MISSING = "plots need matplotlib: pip install bild-mdo[plot]"

# Inputs that label the curves of a batch, in order of preference: (field, label, format).
_LABEL_FIELDS = (("advance_ratio", "J", ".3g"), ("v_axial", "V", ".3g m/s"), ("ref_chord", "c_ref", ".3g m"),
                 ("ref_radius_ratio", "r_ref/R", ".3g"), ("rpm", "rpm", ".4g"), ("radius", "R", ".3g m"),
                 ("altitude", "alt", ".4g m"), ("hub_radius_ratio", "r_hub/R", ".3g"))
_MAX_LEGEND_ENTRIES = 12


def _new_figure(path, **kwargs):
    try:
        if path is None:
            import matplotlib.pyplot as plt

            return plt.figure(layout="constrained", **kwargs)
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError as exc:
        raise ImportError(PLOT_MISSING) from exc
    fig = Figure(layout="constrained", **kwargs)
    FigureCanvasAgg(fig)
    return fig


def _finish(fig, path):
    if path is not None:
        fig.savefig(path, dpi=150)
    return fig


def _fmt(value, spec):
    number, _, unit = spec.partition(" ")
    return f"{value:{number}}" + (f" {unit}" if unit else "")


def _designs(result):
    """Geometries, curve labels, title and the colour key for a DesignResult, RotorGeometry or a list of them.

    The colour key is ``(values, axis label)``: the first input that varies over a batch, or the design
    index.
    """
    from bild_mdo.design import DesignResult
    from bild_mdo.geometry_io import as_geometry

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
    fig = _new_figure(path, figsize=(8.0, 6.4))
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
    return _finish(fig, path)


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


def plot_performance_curves(off_design_result, path=None):
    """Thrust, power, efficiency (or FM) and coefficients of an off-design sweep.

    Efficiency is drawn only where it means something (positive thrust and
    power, forward speed); the maximum-efficiency point (star) and, when the
    sweep contains it, the design point (circle) are marked, as in the
    paper's Fig. 9.  An rpm sweep in hover shows the figure of merit instead.

    Parameters
    ----------
    off_design_result : OffDesignResult
    path : str or path, optional
        PNG file to write.

    Returns
    -------
    matplotlib.figure.Figure
    """
    res = off_design_result
    if res.sweep == "advance_ratio":
        x, xlabel = res.advance_ratio, "advance ratio J = V/(nD) [-]"
    else:
        x, xlabel = res.rpm, "rotor speed [rpm]"
    fig = _new_figure(path, figsize=(9.0, 6.6))
    (ax_t, ax_p), (ax_e, ax_c) = fig.subplots(2, 2, sharex=True)
    ax_t.plot(x, res.thrust, color="tab:blue", marker="o", ms=3)
    ax_t.axhline(0.0, color="0.5", lw=0.7)
    ax_t.set_ylabel("thrust T [N]")
    ax_t.set_title("Thrust")
    ax_p.plot(x, res.power / 1e3, color="tab:red", marker="o", ms=3)
    ax_p.axhline(0.0, color="0.5", lw=0.7)
    ax_p.set_ylabel("shaft power P [kW]")
    ax_p.set_title("Power")

    hover = np.all(res.v_axial == 0.0)
    if hover:
        ax_e.plot(x, res.figure_of_merit, color="tab:green", marker="o", ms=3, label="figure of merit")
        design = _design_index(res)
        if design is not None:
            ax_e.plot(x[design], res.figure_of_merit[design], marker="o", ms=9, ls="none", mfc="none",
                      mec="k", mew=1.5, label="design point")
        ax_e.set_ylabel("figure of merit FM [-]")
        ax_e.set_title("Figure of merit (hover)")
    else:
        useful = (res.thrust > 0.0) & (res.power > 0.0) & (res.v_axial > 0.0)
        eta = np.where(useful, res.efficiency, np.nan)
        ax_e.plot(x, eta, color="tab:green", marker="o", ms=3, label=r"efficiency $\eta$")
        best = res.max_efficiency_index
        if best is not None:
            ax_e.plot(x[best], res.efficiency[best], marker="*", ms=14, ls="none", color="tab:orange",
                      label=f"max. efficiency {res.efficiency[best]:.3f}")
        design = _design_index(res)
        if design is not None and useful[design]:
            ax_e.plot(x[design], res.efficiency[design], marker="o", ms=9, ls="none", mfc="none",
                      mec="k", mew=1.5, label="design point")
        ax_e.set_ylabel(r"efficiency $\eta$ [-]")
        ax_e.set_title(r"Propulsive efficiency $\eta = VT/P$ (T > 0, P > 0)")
        ax_e.set_ylim(0.0, 1.05)
    ax_c.plot(x, res.thrust_coefficient, color="tab:blue", marker="o", ms=3, label=r"$C_T$")
    ax_c.plot(x, res.power_coefficient, color="tab:red", marker="s", ms=3, label=r"$C_P$")
    ax_c.axhline(0.0, color="0.5", lw=0.7)
    ax_c.set_ylabel("coefficient [-]")
    ax_c.set_title(r"$C_T = T/(\rho n^2 D^4)$, $C_P = P/(\rho n^3 D^5)$")
    for ax in (ax_t, ax_p, ax_e, ax_c):
        ax.grid(True, lw=0.4, alpha=0.6)
    for ax in (ax_e, ax_c):
        ax.set_xlabel(xlabel)
    handles, names = [], []
    for ax in (ax_e, ax_c):
        h, n = ax.get_legend_handles_labels()
        handles += h
        names += n
    fig.legend(handles, names, loc="outside lower center", ncols=min(5, len(names)), fontsize="small",
               frameon=False)
    geom = res.geometry
    fig.suptitle(f"Off-design BEM analysis: B = {geom.num_blades}, R = {geom.radius:.3g} m, "
                 f"altitude {res.altitude:.4g} m"
                 + (f", {res.rpm[0]:.4g} rpm" if res.sweep == "advance_ratio" else
                    f", V = {res.v_axial[0]:.3g} m/s"))
    return _finish(fig, path)


def _design_index(res):
    """Index of the sweep point at the geometry's design point, if the sweep contains it."""
    point = res.geometry.design_point
    if res.sweep == "advance_ratio" and res.design_advance_ratio is not None:
        hits = np.flatnonzero(np.isclose(res.advance_ratio, res.design_advance_ratio, rtol=1e-9, atol=1e-12)
                              & np.isclose(res.rpm, point.get("rpm", np.nan), rtol=1e-9))
    elif res.sweep == "rpm" and "rpm" in point:
        hits = np.flatnonzero(np.isclose(res.rpm, point["rpm"], rtol=1e-9)
                              & np.isclose(res.v_axial, point.get("v_axial", np.nan), rtol=1e-9, atol=1e-12))
    else:
        return None
    return int(hits[0]) if hits.size else None
