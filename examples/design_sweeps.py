"""The paper's parameter sweeps (Sec. 5.2, Figs. 6, 7 and 8), each one vectorised BILD run.

* Fig. 6: ideal chord (top-down view of the blade) and twist for advance
  ratios J = 0, 1, 2, 3 (rows) and reference chords c_ref = 0.1 ... 0.4 m
  (black to light grey) at r_ref = 0.5 R, without root-chord correction;
* Fig. 7: the same with the root-chord correction of Eq. (32);
* Fig. 8: thrust, torque, efficiency and figure of merit against c_ref for
  J = 0, 1, 2, 3 (rows) and several reference radii r_ref (curves).

Every figure is one ``BILDGroup`` evaluation with ``num_nodes`` = all its
designs (40, 40 and 280 at full size): BILD needs no iteration between
designs, so a whole sweep costs about as much as one design.

Settings (paper Sec. 5.2): R = 1.5 m, B = 3, 800 rpm, hub at 0.2 R (the
paper's verification sweep), NACA 4412 (the library's built-in polar), sea
level (ISA), 30 radial stations.  Ours, where the paper gives no number:

* root-chord correction ``k = 5`` on ``r/R`` (Eq. (32) with
  ``r`` nondimensional, see :class:`~bild_mdo.bild.root_chord_correction.RootChordCorrectionComp`):
  the reference chord has weight ``exp(-1) = 0.37`` at the hub and less
  than 0.1 outboard of ``r/R = 0.5``;
* reference radii for Fig. 8: ``r_ref/R = 0.35, 0.45, ..., 0.95`` (seven,
  as the paper's 280 = 4 x 7 x 10 rotors).  At ``r_ref = 0.3 R`` the design
  ``J = 3, c_ref = 0.4 m`` violates BILD's Assumption 3 (the tangential
  induction would exceed the blade speed at the reference station), so the
  set starts at 0.35 R.

Run ``python -m examples.design_sweeps`` from the repository root; the
figures go to ``--output-dir`` (default: the current directory).
"""
from __future__ import annotations

import argparse
import dataclasses
import os
import time

import numpy as np
import openmdao.api as om

from bild_mdo import BILDGroup, naca4412

RADIUS = 1.5  # m
NUM_BLADES = 3
RPM = 800.0
HUB_RADIUS_RATIO = 0.2
REF_RADIUS_RATIO = 0.5
ADVANCE_RATIOS = (0.0, 1.0, 2.0, 3.0)
REF_CHORD_RANGE = (0.1, 0.4)  # m
REF_RADIUS_RATIO_RANGE = (0.35, 0.95)
ROOT_CHORD_CORRECTION = 5.0  # k of Eq. (32), on r/R


@dataclasses.dataclass
class Sweep:
    """A grid of BILD designs: axes (advance ratio, reference radius, reference chord[, station]).

    Attributes
    ----------
    advance_ratios : ndarray, shape (nj,)
    ref_radius_ratios : ndarray, shape (nrr,)
        r_ref / R.
    ref_chords : ndarray, shape (nc,)
        m.
    radii : ndarray, shape (nj, nrr, nc, nr)
        Station radii (m).
    chord, chord_raw, twist : ndarray, shape (nj, nrr, nc, nr)
        Chord after and before the root-chord correction (m), twist (rad).
    thrust, torque, power, efficiency, figure_of_merit : ndarray, shape (nj, nrr, nc)
        N, N m, W, -, -.
    root_chord_correction : float or None
        ``k`` of Eq. (32).
    run_time : float
        Seconds of the one ``run_model`` of the sweep (set-up excluded).
    """

    advance_ratios: np.ndarray
    ref_radius_ratios: np.ndarray
    ref_chords: np.ndarray
    radii: np.ndarray
    chord: np.ndarray
    chord_raw: np.ndarray
    twist: np.ndarray
    thrust: np.ndarray
    torque: np.ndarray
    power: np.ndarray
    efficiency: np.ndarray
    figure_of_merit: np.ndarray
    root_chord_correction: float | None
    run_time: float

    @property
    def num_designs(self):
        """Number of designs in the sweep."""
        return self.thrust.size


def bild_sweep(advance_ratios, ref_chords, ref_radius_ratios=(REF_RADIUS_RATIO,), num_radial=30,
               root_chord_correction=None):
    """All combinations of advance ratio, reference radius and reference chord in one BILD run.

    Parameters
    ----------
    advance_ratios : array_like
        J values.
    ref_chords : array_like
        Reference chords (m).
    ref_radius_ratios : array_like
        r_ref / R values.
    num_radial : int
        Radial stations.
    root_chord_correction : float or None
        ``k`` of Eq. (32); ``None`` for none.

    Returns
    -------
    Sweep
    """
    j_values = np.asarray(advance_ratios, dtype=float)
    rr_values = np.asarray(ref_radius_ratios, dtype=float)
    c_values = np.asarray(ref_chords, dtype=float)
    grid = np.meshgrid(j_values, rr_values, c_values, indexing="ij")
    shape = grid[0].shape
    nn = grid[0].size
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("bild", BILDGroup(num_nodes=nn, num_radial=num_radial, num_blades=NUM_BLADES,
                                               input_mode="advance_ratio",
                                               root_chord_correction=root_chord_correction),
                             promotes=["*"])
    prob.setup()
    prob.set_val("advance_ratio", grid[0].ravel())
    prob.set_val("ref_radius_ratio", grid[1].ravel())
    prob.set_val("ref_chord", grid[2].ravel(), units="m")
    prob.set_val("rpm", np.full(nn, RPM), units="rpm")
    prob.set_val("radius", np.full(nn, RADIUS), units="m")
    prob.set_val("hub_radius_ratio", np.full(nn, HUB_RADIUS_RATIO))
    prob.set_val("altitude", np.zeros(nn), units="m")
    start = time.perf_counter()
    prob.run_model()
    run_time = time.perf_counter() - start

    def dist(name, units):
        return prob.get_val(name, units=units).reshape(shape + (num_radial,)).copy()

    def node(name, units):
        return prob.get_val(name, units=units).reshape(shape).copy()

    return Sweep(advance_ratios=j_values, ref_radius_ratios=rr_values, ref_chords=c_values,
                 radii=dist("radii", "m"), chord=dist("chord", "m"), chord_raw=dist("chord_raw", "m"),
                 twist=dist("twist", "rad"), thrust=node("thrust", "N"), torque=node("torque", "N*m"),
                 power=node("power", "W"), efficiency=node("efficiency", None),
                 figure_of_merit=node("figure_of_merit", None), root_chord_correction=root_chord_correction,
                 run_time=run_time)


def _grey_colors(n):
    """Black (smallest c_ref) to light grey (largest), as in the paper's Figs. 6 and 7."""
    from matplotlib import colormaps

    return colormaps["gray"](np.linspace(0.0, 0.75, n))


def plot_shapes(sweep, path, title):
    """Blade planform (top-down) and twist for every J (rows) and c_ref (grey level): paper Figs. 6 and 7.

    The planform is drawn about the quarter-chord line: leading edge at
    ``+c/4``, trailing edge at ``-3c/4``.

    Parameters
    ----------
    sweep : Sweep
        With one reference radius.
    path : str or path-like
        PNG to write.
    title : str
        Figure title.

    Returns
    -------
    str
        ``path``.
    """
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import LinearSegmentedColormap, Normalize
    from matplotlib.figure import Figure

    nj, nc = sweep.advance_ratios.size, sweep.ref_chords.size
    colors = _grey_colors(nc)
    fig = Figure(figsize=(11, 2.3 * nj + 1.2), layout="constrained")
    axes = fig.subplots(nj, 2, sharex=True, squeeze=False, gridspec_kw={"width_ratios": [1.3, 1.0]})
    c_max = sweep.chord.max()
    for i, j_value in enumerate(sweep.advance_ratios):
        ax_c, ax_t = axes[i]
        for k in range(nc):
            x = sweep.radii[i, 0, k] / RADIUS
            c = sweep.chord[i, 0, k]
            ax_c.plot(x, 0.25 * c, color=colors[k], lw=1.2)
            ax_c.plot(x, -0.75 * c, color=colors[k], lw=1.2)
            ax_t.plot(x, np.degrees(sweep.twist[i, 0, k]), color=colors[k], lw=1.2)
        ax_c.set_ylim(-0.8 * c_max, 0.3 * c_max)
        ax_c.set_ylabel(f"J = {j_value:g}\nchordwise position (m)")
        ax_t.set_ylabel("twist (deg)")
        for ax in (ax_c, ax_t):
            ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("$r/R$")
    axes[-1, 1].set_xlabel("$r/R$")
    axes[0, 0].set_title("blade planform (leading edge up, $c/4$ line at 0)")
    axes[0, 1].set_title("twist")
    cmap = LinearSegmentedColormap.from_list("c_ref", _grey_colors(256))
    mappable = ScalarMappable(norm=Normalize(sweep.ref_chords[0], sweep.ref_chords[-1]), cmap=cmap)
    fig.colorbar(mappable, ax=axes[:, 1], label="reference chord $c_{ref}$ (m)", shrink=0.6)
    fig.suptitle(title)
    fig.savefig(path, dpi=110)
    return str(path)


def plot_performance(sweep, path):
    """T, Q, eta and FM against c_ref for every J (rows) and r_ref (curves): paper Fig. 8.

    Parameters
    ----------
    sweep : Sweep
    path : str or path-like
        PNG to write.

    Returns
    -------
    str
        ``path``.
    """
    from matplotlib import colormaps
    from matplotlib.figure import Figure

    nj, nrr = sweep.advance_ratios.size, sweep.ref_radius_ratios.size
    colors = colormaps["viridis"](np.linspace(0.0, 0.9, nrr))
    columns = (("thrust", "thrust $T$ (kN)", 1e-3), ("torque", "torque $Q$ (kN m)", 1e-3),
               ("efficiency", r"efficiency $\eta$", 1.0), ("figure_of_merit", "figure of merit FM", 1.0))
    fig = Figure(figsize=(14, 2.6 * nj + 1.0), layout="constrained")
    axes = fig.subplots(nj, 4, sharex=True, squeeze=False)
    for i, j_value in enumerate(sweep.advance_ratios):
        for col, (name, label, scale) in enumerate(columns):
            ax = axes[i, col]
            values = getattr(sweep, name)[i]
            for k in range(nrr):
                ax.plot(sweep.ref_chords, values[k] * scale, "o-", ms=2.5, color=colors[k],
                        label=f"{sweep.ref_radius_ratios[k]:.2f}")
            ax.grid(alpha=0.3)
            if name == "efficiency" and j_value == 0.0:
                ax.text(0.5, 0.75, r"$\eta = V_x T / P = 0$ in hover", transform=ax.transAxes, ha="center",
                        va="center", fontsize=10, color="0.3")
            if i == 0:
                ax.set_title(label)
            if col == 0:
                ax.set_ylabel(f"J = {j_value:g}")
    for ax in axes[-1]:
        ax.set_xlabel("reference chord $c_{ref}$ (m)")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, title="$r_{ref}/R$", loc="outside right center")
    fig.suptitle(f"Performance of {sweep.num_designs} BILD rotors (R = {RADIUS} m, B = {NUM_BLADES}, "
                 f"{RPM:.0f} rpm, NACA 4412)")
    fig.savefig(path, dpi=110)
    return str(path)


def main(num_radial=30, num_ref_chords=10, num_ref_radii=7, output_dir=".",
         root_chord_correction=ROOT_CHORD_CORRECTION, plot=True, verbose=True):
    """Run the sweeps of Figs. 6, 7 and 8 and plot them.

    Parameters
    ----------
    num_radial : int
        Radial stations (30 at full size).
    num_ref_chords : int
        Reference chords from 0.1 to 0.4 m (10 at full size).
    num_ref_radii : int
        Reference radii for Fig. 8 (7 at full size).
    output_dir : str or path-like
        Directory of the PNGs.
    root_chord_correction : float
        ``k`` of Eq. (32) for Fig. 7.
    plot : bool
        Write the figures.
    verbose : bool
        Print a summary.

    Returns
    -------
    dict
        ``'fig6'``, ``'fig7'``, ``'fig8'``: :class:`Sweep`; ``'figures'``: name -> path;
        ``'setup_time'``: seconds to build and set up the three problems; ``'polar_time'``: seconds to
        build the NACA 4412 surrogate (once per process).
    """
    ref_chords = np.linspace(*REF_CHORD_RANGE, num_ref_chords)
    ref_radii = np.linspace(*REF_RADIUS_RATIO_RANGE, num_ref_radii)
    start = time.perf_counter()
    naca4412()  # built once per process and cached: timed apart from the sweeps
    polar_time = time.perf_counter() - start
    start = time.perf_counter()
    sweeps = {
        "fig6": bild_sweep(ADVANCE_RATIOS, ref_chords, num_radial=num_radial),
        "fig7": bild_sweep(ADVANCE_RATIOS, ref_chords, num_radial=num_radial,
                           root_chord_correction=root_chord_correction),
        "fig8": bild_sweep(ADVANCE_RATIOS, ref_chords, ref_radii, num_radial=num_radial),
    }
    total_time = time.perf_counter() - start
    figures = {}
    if plot:
        os.makedirs(output_dir, exist_ok=True)
        figures["fig6"] = plot_shapes(sweeps["fig6"], os.path.join(output_dir, "fig6_shapes.png"),
                                      f"Ideal blades without root-chord correction (r_ref = {REF_RADIUS_RATIO} R, "
                                      f"R = {RADIUS} m, B = {NUM_BLADES}, {RPM:.0f} rpm)")
        figures["fig7"] = plot_shapes(sweeps["fig7"], os.path.join(output_dir, "fig7_shapes_corrected.png"),
                                      "Ideal blades with root-chord correction, Eq. (32), "
                                      f"k = {root_chord_correction:g} on r/R (r_ref = {REF_RADIUS_RATIO} R)")
        figures["fig8"] = plot_performance(sweeps["fig8"], os.path.join(output_dir, "fig8_performance.png"))
    result = dict(sweeps, figures=figures, polar_time=polar_time,
                  setup_time=total_time - sum(s.run_time for s in sweeps.values()))
    if verbose:
        print_summary(result)
    return result


def print_summary(result):
    """Print what the sweeps show (the trends of paper Sec. 5.2)."""
    print(f"Design sweeps (R = {RADIUS} m, B = {NUM_BLADES}, {RPM:.0f} rpm); set-up of the three problems "
          f"{result['setup_time']:.2f} s, polar surrogate {result['polar_time']:.2f} s")
    for key in ("fig6", "fig7", "fig8"):
        s = result[key]
        print(f"  {key}: {s.num_designs} designs in one BILD run, {s.run_time * 1e3:.1f} ms "
              f"({s.run_time / s.num_designs * 1e6:.0f} us per design)")
    s6, s7 = result["fig6"], result["fig7"]
    print(f"  {'J':>4s}{'max-chord r/R':>16s}{'root c/c_ref':>15s}{'corrected':>12s}{'tip twist deg':>16s}")
    for i, j_value in enumerate(s6.advance_ratios):
        x_max = s6.radii[i, 0, np.arange(s6.ref_chords.size), np.argmax(s6.chord[i, 0], axis=1)] / RADIUS
        root = s6.chord[i, 0, :, 0] / s6.ref_chords
        root_corrected = s7.chord[i, 0, :, 0] / s7.ref_chords
        tip_twist = np.degrees(s6.twist[i, 0, :, -1])
        print(f"  {j_value:4g}{x_max.min():8.2f}-{x_max.max():.2f}{root.min():8.3f}-{root.max():.3f}"
              f"{root_corrected.min():6.3f}-{root_corrected.max():.3f}{tip_twist.min():9.1f}-{tip_twist.max():.1f}")
    s8 = result["fig8"]
    print(f"  fig8: T from {s8.thrust.min():.0f} to {s8.thrust.max():.0f} N; eta (J > 0) from "
          f"{s8.efficiency[1:].min():.3f} to {s8.efficiency[1:].max():.3f}; FM (J = 0) from "
          f"{s8.figure_of_merit[0].min():.3f} to {s8.figure_of_merit[0].max():.3f}")
    for name, path in result["figures"].items():
        print(f"  {name}: {path}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output-dir", default=".", help="directory of the PNGs")
    parser.add_argument("--num-radial", type=int, default=30, help="radial stations")
    args = parser.parse_args()
    main(num_radial=args.num_radial, output_dir=args.output_dir)
