"""Figures 4 and 5 of the paper from the rows of a verification results store (PNG via matplotlib).

matplotlib is imported only when a figure is made (extra ``bild-mdo[plot]``).
The figures are drawn on ``matplotlib.figure.Figure`` objects with the Agg
canvas, never through pyplot, so no display or global state is involved.
"""
import math
import os

from bild_mdo.bem.metrics import METRICS_BY_NAME
from bild_mdo.plots.figure import PLOT_MISSING, finish, new_figure
from bild_mdo.verification.statistics import defined_cases

CONVERGED_COLOR = "tab:blue"
FAILED_COLOR = "tab:orange"

#: The verified metrics of the Fig. 5 panels, in the paper's order.
PARITY_QUANTITIES = ("efficiency", "thrust_coefficient", "power_coefficient", "torque_coefficient")
# Axis labels of the paper's panels; any other verified metric is labelled from the registry.
PARITY_LABELS = {
    "efficiency": r"efficiency $\eta$ (-), J > 0",
    "thrust_coefficient": r"thrust coefficient $C_T$ (-)",
    "power_coefficient": r"power coefficient $C_P$ (-)",
    "torque_coefficient": r"torque coefficient $C_Q$ (-)",
}


def require_matplotlib():
    """Import matplotlib's object API or raise ImportError naming the extra to install.

    Returns
    -------
    tuple
        ``(Figure, FigureCanvasAgg)`` classes.
    """
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError as exc:
        raise ImportError(PLOT_MISSING) from exc
    return Figure, FigureCanvasAgg


def _finite(*values):
    return all(v is not None and math.isfinite(v) for v in values)


def _save(fig, path):
    finish(fig, path)
    return path


def plot_run_times(rows, path):
    """Fig. 4: optimisation time vs BILD time per case, converged and not converged.

    Parameters
    ----------
    rows : list of dict
        Results-store rows (:meth:`~bild_mdo.verification.store.ResultsStore.rows`).
    path : str or os.PathLike
        PNG file to write.

    Returns
    -------
    str
        The path written.
    """
    fig = new_figure(os.fspath(path), figsize=(6.4, 4.8))
    ax = fig.add_subplot()
    both = [r for r in rows if r["converged"] and r["bild_converged"]]
    times = [(r["bild_time"], r["opt_time"]) for r in both if _finite(r["bild_time"], r["opt_time"])]
    speedup = ""
    if times and sum(b for b, _ in times) > 0:
        # Ratio of the mean times over converged cases, as Table 3's run times.
        speedup = f", mean speed-up {sum(o for _, o in times) / sum(b for b, _ in times):.0f}x"
    groups = (
        ("optimisation converged", speedup, CONVERGED_COLOR, [r for r in rows if r["converged"]]),
        ("optimisation not converged", "", FAILED_COLOR, [r for r in rows if not r["converged"]]),
    )
    all_times = []
    for label, suffix, color, group in groups:
        points = [(r["bild_time"], r["opt_time"]) for r in group if _finite(r["bild_time"], r["opt_time"])]
        points = [(b, o) for b, o in points if b > 0 and o > 0]
        if not points:
            continue
        bild, opt = zip(*points)
        all_times.extend(bild + opt)
        ax.scatter(bild, opt, s=6, alpha=0.6, color=color, edgecolors="none",
                   label=f"{label} ({len(points)}){suffix}")
    if all_times:
        low, high = min(all_times), max(all_times)
        ax.plot([low, high], [low, high], color="0.4", linestyle="--", linewidth=1.0, label="equal time")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("BILD run time per case (s)")
    ax.set_ylabel("BEM optimisation run time per case (s)")
    ax.set_title("Run time: BEM optimisation vs BILD (cf. paper Fig. 4)")
    ax.grid(True, which="major", alpha=0.3)
    if all_times:
        ax.legend(loc="best", fontsize="small", markerscale=2)
    return _save(fig, os.fspath(path))


def _parity_label(key):
    return PARITY_LABELS.get(key, METRICS_BY_NAME[key].label)


def plot_parity(rows, path, quantities=PARITY_QUANTITIES):
    """Fig. 5: BILD vs optimum of verified metrics over converged cases.

    Parameters
    ----------
    rows : list of dict
        Results-store rows, with columns ``bild_<key>`` and ``opt_<key>``.
    path : str or os.PathLike
        PNG file to write.
    quantities : sequence of str
        Verified metrics, one panel each, two panels a row; the paper's eta
        (J > 0 only), C_T, C_P and C_Q by default.

    Returns
    -------
    str
        The path written.
    """
    fig = new_figure(os.fspath(path), figsize=(8.0, 3.5 * math.ceil(len(quantities) / 2)))
    axes = fig.subplots(math.ceil(len(quantities) / 2), 2, squeeze=False)
    converged = [r for r in rows if r["converged"] and r["bild_converged"]]
    for ax in axes.flat[len(quantities):]:
        ax.set_visible(False)
    for ax, key in zip(axes.flat, quantities):
        label = _parity_label(key)
        group = defined_cases(converged, key)
        points = [(r[f"opt_{key}"], r[f"bild_{key}"]) for r in group if _finite(r[f"opt_{key}"], r[f"bild_{key}"])]
        if points:
            opt, bild = zip(*points)
            ax.scatter(opt, bild, s=5, alpha=0.5, color=CONVERGED_COLOR, edgecolors="none")
            low, high = min(opt + bild), max(opt + bild)
            ax.plot([low, high], [low, high], color="0.3", linestyle="--", linewidth=1.0)
        else:
            ax.text(0.5, 0.5, "no converged cases", ha="center", va="center", transform=ax.transAxes)
        ax.set_xlabel(f"optimum {label}")
        ax.set_ylabel(f"BILD {label}")
        ax.set_title(f"{label.split(' (')[0]} ({len(points)} cases)", fontsize="medium")
        ax.grid(True, alpha=0.3)
    fig.suptitle("BILD vs BEM optimisation, converged cases (cf. paper Fig. 5); dashed: y = x")
    return _save(fig, os.fspath(path))


def save_figures(rows, directory):
    """Write ``fig4_run_time.png`` and ``fig5_parity.png`` into ``directory`` (created if needed).

    Parameters
    ----------
    rows : list of dict
        Results-store rows.
    directory : str or os.PathLike

    Returns
    -------
    list of str
        The paths written.
    """
    require_matplotlib()
    directory = os.fspath(directory)
    os.makedirs(directory, exist_ok=True)
    return [
        plot_run_times(rows, os.path.join(directory, "fig4_run_time.png")),
        plot_parity(rows, os.path.join(directory, "fig5_parity.png")),
    ]
