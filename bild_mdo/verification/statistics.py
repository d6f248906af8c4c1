"""Table 3 of the paper from the rows of a results store.

Definitions (the paper does not spell them out; these are ours):

- Ranges, mean relative errors and mean run times use the *converged* cases
  only: BILD and the optimisation both converged.  An unconverged optimum is
  not a reference to measure BILD against.  The percent converged of each
  method counts every stored case.
- Efficiency eta = T V_x / P is zero in hover, so it uses only the cases with
  J > 0; the figure of merit is a hover metric, so it uses only J == 0.
- Relative error of a scalar: ``|x_bild - x_opt| / |x_opt|``; of a chord or
  twist distribution: ``||x_bild - x_opt||_2 / ||x_opt||_2``.  Means are in
  percent.  A case whose value is missing (NULL/NaN) for either method, or
  whose optimum is zero, is left out of that quantity; ``num_cases`` of each
  quantity says how many were used.
- Energy loss E is stored in W and shown in kW, as in the paper (the
  registry's display scale, :data:`bild_mdo.bem.metrics.METRICS`).
- The scalar rows are the registry's verified metrics
  (:data:`~bild_mdo.bem.metrics.VERIFIED_METRICS`); a metric the paper does
  not report shows "-" in the paper's columns.
"""
import math
from dataclasses import dataclass

import numpy as np

from bild_mdo.bem.metrics import METRICS_BY_NAME, VERIFIED_METRICS

# Row labels of the paper's Table 3; a verified metric without one is labelled from the registry.
TABLE3_LABELS = {
    "thrust_coefficient": "Thrust coefficient C_T [min, max]",
    "torque_coefficient": "Torque coefficient C_Q [min, max]",
    "power_coefficient": "Power coefficient C_P [min, max]",
    "efficiency": "Efficiency eta [min, max] (J > 0)",
    "figure_of_merit": "Figure of merit FM [min, max] (J = 0)",
    "energy_loss": "Rate of energy loss (kW) [min, max]",
}
# Metrics defined in one flight regime only: eta is zero in hover, FM a hover metric.
REGIMES = {"efficiency": "forward", "figure_of_merit": "hover"}
#: (result key, row label, display scale) of the scalar rows, one per verified metric of the registry.
SCALARS = tuple(
    (name, TABLE3_LABELS.get(name, f"{METRICS_BY_NAME[name].label} [min, max]"),
     METRICS_BY_NAME[name].display_scale)
    for name in VERIFIED_METRICS
)
NORMS = (
    ("twist_norm", "Blade twist distribution (norm)", "twist"),
    ("chord_norm", "Blade chord distribution (norm)", "chord"),
)

# Ruh & Hwang (2023), Table 3: BILD [min, max], BEM optimisation [min, max], mean relative error (%).
PAPER_TABLE3 = {
    "thrust_coefficient": ((0.046, 0.645), (0.046, 0.645), 6.337e-10),
    "torque_coefficient": ((0.001, 0.440), (0.001, 0.440), 0.161),
    "power_coefficient": ((0.009, 2.766), (0.009, 2.766), 0.161),
    "efficiency": ((0.412, 0.932), (0.410, 0.933), 0.156),
    "figure_of_merit": ((0.691, 0.770), (0.693, 0.770), 0.288),
    "energy_loss": ((0.087, 90.287), (0.104, 116.932), 11.966),
    "twist_norm": (None, None, 3.583),
    "chord_norm": (None, None, 12.406),
}
PAPER_PERCENT_CONVERGED = (100.0, 86.810)
PAPER_RUN_TIME = (0.009, 2.130)


@dataclass
class QuantityStats:
    """Statistics of one Table 3 quantity.

    Attributes
    ----------
    key : str
        Result key (``'efficiency'``, ``'chord_norm'``, ...).
    label : str
        Row label of the table.
    bild_range, opt_range : tuple of float or None
        ``(min, max)`` over the cases used (in the table's unit); None for the norms
        or when no case was usable.
    mean_relative_error_pct : float
        Mean relative error in percent; NaN when no case was usable.
    num_cases : int
        Cases used.
    """

    key: str
    label: str
    bild_range: tuple
    opt_range: tuple
    mean_relative_error_pct: float
    num_cases: int


@dataclass
class Table3:
    """Our reproduction of the paper's Table 3.

    Attributes
    ----------
    quantities : dict of str to QuantityStats
        The verified scalar metrics then ``twist_norm`` and ``chord_norm``, in table order.
    num_cases : int
        Stored cases.
    num_converged : int
        Cases where BILD and the optimisation both converged (the statistics' basis).
    percent_converged_bild, percent_converged_opt : float
        Converged cases of each method over all stored cases (%).
    mean_run_time_bild, mean_run_time_opt : float
        Mean run time per case over the converged cases (s); NaN without any.
    optimality : OptimalityCheck or None
        The check that no optimum is worse than BILD's geometry trimmed to the
        same thrust (:func:`~bild_mdo.verification.optimality.optimality_check`);
        not computed by :func:`table3` (it runs BEM analyses), set by the caller.
        When set, :func:`format_table3` prints its summary under the table.
    start_spread : dict or None
        With several optimiser starts (``verify --starts``): ``num_cases``
        (converged cases with at least two converged starts), ``num_single``
        (those with only one), ``best_start`` (cases per
        best start, from 1) and, for ``twist``, ``chord`` and ``energy``,
        ``(mean, max)`` of the spread between the starts in percent
        (:mod:`~bild_mdo.verification.starts`); None with one start.
    """

    quantities: dict
    num_cases: int
    num_converged: int
    percent_converged_bild: float
    percent_converged_opt: float
    mean_run_time_bild: float
    mean_run_time_opt: float
    optimality: object = None
    start_spread: dict = None

    @property
    def speedup(self):
        """Mean optimisation time over mean BILD time (converged cases)."""
        if not self.mean_run_time_bild > 0:
            return math.nan
        return self.mean_run_time_opt / self.mean_run_time_bild


def _value(x):
    return math.nan if x is None else float(x)


def _scalar_stats(rows, key, label, scale):
    bild = np.array([_value(r[f"bild_{key}"]) for r in rows], dtype=float)
    opt = np.array([_value(r[f"opt_{key}"]) for r in rows], dtype=float)
    usable = np.isfinite(bild) & np.isfinite(opt) & (opt != 0.0)
    bild, opt = bild[usable], opt[usable]
    if bild.size == 0:
        return QuantityStats(key, label, None, None, math.nan, 0)
    error = np.abs(bild - opt) / np.abs(opt)
    return QuantityStats(
        key,
        label,
        (float(bild.min() * scale), float(bild.max() * scale)),
        (float(opt.min() * scale), float(opt.max() * scale)),
        float(100.0 * error.mean()),
        int(bild.size),
    )


def _norm_stats(rows, key, label, array):
    errors = []
    for row in rows:
        bild, opt = row[f"bild_{array}"], row[f"opt_{array}"]
        if bild is None or opt is None:
            continue
        bild, opt = np.asarray(bild, dtype=float), np.asarray(opt, dtype=float)
        if bild.shape != opt.shape:
            raise ValueError(
                f"case {row['case_id']}: BILD and optimum {array} have different stations "
                f"({bild.shape} vs {opt.shape}); both must use the sweep's num_radial"
            )
        denominator = np.linalg.norm(opt)
        if not (np.all(np.isfinite(bild)) and np.all(np.isfinite(opt))) or denominator == 0.0:
            continue
        errors.append(np.linalg.norm(bild - opt) / denominator)
    mean = float(100.0 * np.mean(errors)) if errors else math.nan
    return QuantityStats(key, label, None, None, mean, len(errors))


def defined_cases(rows, key):
    """The rows in whose flight regime the metric ``key`` is defined.

    Parameters
    ----------
    rows : list of dict
        Results-store rows.
    key : str
        A verified metric.

    Returns
    -------
    list of dict
        J > 0 for the efficiency, J = 0 for the figure of merit, every row otherwise.
    """
    regime = REGIMES.get(key)
    if regime == "hover":
        return [r for r in rows if r["advance_ratio"] == 0.0]
    if regime == "forward":
        return [r for r in rows if r["advance_ratio"] > 0.0]
    return list(rows)


def table3(rows):
    """Compute the Table 3 statistics from results-store rows.

    Parameters
    ----------
    rows : list of dict
        As returned by :meth:`ResultsStore.rows`.

    Returns
    -------
    Table3
    """
    rows = list(rows)
    converged = [r for r in rows if r["converged"] and r["bild_converged"]]
    quantities = {}
    for key, label, scale in SCALARS:
        quantities[key] = _scalar_stats(defined_cases(converged, key), key, label, scale)
    for key, label, array in NORMS:
        quantities[key] = _norm_stats(converged, key, label, array)
    num = len(rows)

    def percent(count):
        return 100.0 * count / num if num else math.nan

    def mean_time(column):
        times = [r[column] for r in converged if r[column] is not None]
        return float(np.mean(times)) if times else math.nan

    return Table3(
        start_spread=_start_spread(converged),
        quantities=quantities,
        num_cases=num,
        num_converged=len(converged),
        percent_converged_bild=percent(sum(bool(r["bild_converged"]) for r in rows)),
        percent_converged_opt=percent(sum(bool(r["converged"]) for r in rows)),
        mean_run_time_bild=mean_time("bild_time"),
        mean_run_time_opt=mean_time("opt_time"),
    )


def _start_spread(rows):
    """Mean and largest spread between the optimiser's starts (%), or None when no row compared starts."""
    with_starts = [r for r in rows if r.get("starts_converged") is not None]
    if not with_starts:
        return None
    compared = [r for r in with_starts if r["starts_converged"] >= 2]
    out = {"num_cases": len(compared), "num_single": len(with_starts) - len(compared),
           "best_start": {k: sum(r.get("best_start") == k for r in compared)
                          for k in sorted({r.get("best_start") for r in compared} - {None})}}
    for name in ("twist", "chord", "energy"):
        values = 100.0 * np.array([float(r[f"start_spread_{name}"]) for r in compared])
        out[name] = (float(values.mean()), float(values.max())) if values.size else (math.nan, math.nan)
    return out


def format_start_spread(spread):
    """One line on the spread between the optimiser's starts (:attr:`Table3.start_spread`)."""
    parts = ", ".join(f"{name} {spread[name][0]:.3f} % (max {spread[name][1]:.3f} %)"
                      for name in ("twist", "chord", "energy"))
    best = ", ".join(f"start {k} in {n}" for k, n in spread["best_start"].items())
    return (f"Start spread (mean over the {spread['num_cases']} cases with >= 2 converged starts; largest distance "
            f"between them relative to the best, the Table 3 reference): {parts}; best: {best or '-'}; "
            f"{spread['num_single']} cases with one converged start.")


def _fmt_range(rng):
    return "-" if rng is None else f"[{rng[0]:.3f}, {rng[1]:.3f}]"


def _fmt_number(value, digits=3):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if value != 0.0 and abs(value) < 10.0 ** (-digits):
        return f"{value:.{digits}e}"
    return f"{value:.{digits}f}"


def format_table3(table, paper=True):
    """Format a :class:`Table3` as text, the paper's values beside ours.

    Parameters
    ----------
    table : Table3
    paper : bool
        Print the paper's columns (its propeller sweep); False for another sweep (the turbines').

    Returns
    -------
    str
        A fixed-width table with columns: quantity, BILD, optimum, mean relative
        error (%) and n for this sweep, then the paper's BILD, optimum and error.
    """
    header = ("Quantity", "BILD", "Optimum", "Err. (%)", "n", "Paper BILD", "Paper optimum", "Paper err. (%)")
    lines = []
    for key, stats in table.quantities.items():
        paper_bild, paper_opt, paper_error = PAPER_TABLE3.get(key, (None, None, None))
        lines.append((
            stats.label, _fmt_range(stats.bild_range), _fmt_range(stats.opt_range),
            _fmt_number(stats.mean_relative_error_pct), str(stats.num_cases),
            _fmt_range(paper_bild), _fmt_range(paper_opt), _fmt_number(paper_error),
        ))
    lines.append((
        "Percent converged", _fmt_number(table.percent_converged_bild), _fmt_number(table.percent_converged_opt),
        "-", str(table.num_cases), _fmt_number(PAPER_PERCENT_CONVERGED[0]), _fmt_number(PAPER_PERCENT_CONVERGED[1]),
        "-",
    ))
    lines.append((
        "Average run time (s)", _fmt_number(table.mean_run_time_bild), _fmt_number(table.mean_run_time_opt),
        "-", str(table.num_converged), _fmt_number(PAPER_RUN_TIME[0]), _fmt_number(PAPER_RUN_TIME[1]), "-",
    ))
    widths = [max(len(row[i]) for row in [header] + lines) for i in range(len(header))]

    def render(cells):
        first = cells[0].ljust(widths[0])
        rest = "  ".join(cell.rjust(width) for cell, width in zip(cells[1:], widths[1:]))
        return f"{first}  {rest}"

    rule = "-" * len(render(header))
    title = (
        f"Table 3 reproduction: {table.num_cases} cases, {table.num_converged} with both methods converged "
        f"(statistics over those; eta over J > 0, FM over J = 0); speed-up {_fmt_number(table.speedup, 1)}x"
    )
    footer = [] if table.start_spread is None else [format_start_spread(table.start_spread)]
    footer += [] if table.optimality is None else [table.optimality.summary()]
    if not paper:
        header, lines = header[:5], [line[:5] for line in lines]
        widths = widths[:5]
        rule = "-" * len(render(header))
    return "\n".join([title, rule, render(header), rule] + [render(line) for line in lines] + [rule] + footer)
