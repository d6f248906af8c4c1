"""Noise figures (matplotlib, extra ``bild-mdo[plot]``): the spectrum at observers and the directivity on an arc.

:func:`plot_noise_spectrum` draws, for each observer of a
:class:`~bild_mdo.results.noise.NoiseResult`, the tonal lines (stems at the harmonic frequencies) and the
broadband one-third-octave band levels (steps, with each BPM mechanism thin);
:func:`plot_directivity` draws OASPL and A-weighted level against the polar angle from the rotor axis of
observers on an arc (:func:`arc_observers`).  With a ``path`` the figure is written as PNG
(:mod:`bild_mdo.plots.figure`).
"""
from __future__ import annotations

import numpy as np

from bild_mdo.acoustics.bands import band_edges
from bild_mdo.plots.figure import finish, new_figure

__all__ = ["arc_observers", "plot_directivity", "plot_noise_spectrum"]

# Observers drawn in one spectrum figure, at most.
_MAX_PANELS = 4
# Lowest level drawn (dB): the floor of silent sources is -100 dB.
_LOWEST_DB = 0.0


def arc_observers(distance, count=37, plane="xy"):
    """Observers on a half circle of ``distance`` (m) around the rotor centre, polar angle 0 ... 180 deg.

    The polar angle is measured from the rotor axis +x (the thrust direction); ``plane`` ``'xy'`` or
    ``'xz'`` holds the arc.  Returns an array of shape ``(count, 3)``.
    """
    theta = np.radians(np.linspace(0.0, 180.0, int(count)))
    positions = np.zeros((theta.size, 3))
    positions[:, 0] = distance * np.cos(theta)
    positions[:, 1 if plane == "xy" else 2] = distance * np.sin(theta)
    return positions


def _single(noise, design):
    if noise.is_batch:
        return (noise.tonal_frequency[design], noise.tonal_spl[design], noise.band_spl[design],
                {k: v[design] for k, v in noise.source_spl.items()}, noise.oaspl[design], noise.oaspl_dba[design])
    return (noise.tonal_frequency, noise.tonal_spl, noise.band_spl, noise.source_spl, noise.oaspl,
            noise.oaspl_dba)


def plot_noise_spectrum(noise, path=None, observers=None, design=0):
    """Spectrum of each observer: tonal lines and broadband band levels (dB re 20 uPa).

    Parameters
    ----------
    noise : NoiseResult
    path : str or path, optional
        PNG file to write.
    observers : sequence of int, optional
        Observers to draw (default: the first four).
    design : int
        Design of a batch.

    Returns
    -------
    matplotlib.figure.Figure
    """
    chosen = list(range(min(len(noise.observers), _MAX_PANELS))) if observers is None else list(observers)
    frequency, tonal, band, sources, oaspl, dba = _single(noise, design)
    fig = new_figure(path, figsize=(8.0, 2.6 * len(chosen) + 0.6))
    axes = np.atleast_1d(fig.subplots(len(chosen), 1, sharex=True, squeeze=False)[:, 0])
    lower, upper = band_edges(noise.band_frequencies)
    steps = np.concatenate([lower[:1], upper])
    for ax, k in zip(axes, chosen):
        has_band = np.any(band[k] > _LOWEST_DB)
        if has_band:
            ax.stairs(band[k], steps, color="C0", lw=1.6, label="broadband (1/3 octave)")
            for j, (name, level) in enumerate(sources.items()):
                if np.any(level[k] > _LOWEST_DB):
                    ax.stairs(level[k], steps, color=f"C{j + 2}", lw=0.8, alpha=0.8, label=name)
        shown = tonal[k] > _LOWEST_DB
        if np.any(shown):
            ax.vlines(frequency[shown], _LOWEST_DB, tonal[k][shown], color="C1", lw=1.8, label="tones (m B Omega)")
            ax.plot(frequency[shown], tonal[k][shown], "o", color="C1", ms=3)
        x, y, z = noise.observers[k]
        ax.set_title(f"observer {k} at ({x:.4g}, {y:.4g}, {z:.4g}) m: OASPL {oaspl[k]:.1f} dB, {dba[k]:.1f} dBA",
                     fontsize=9)
        ax.set_xscale("log")
        ax.set_ylabel("SPL [dB]")
        ax.set_ylim(bottom=_LOWEST_DB)
        ax.grid(True, which="both", lw=0.4, alpha=0.6)
    axes[0].legend(fontsize=7, ncol=2)
    axes[-1].set_xlabel("frequency [Hz]")
    return finish(fig, path)


def plot_directivity(noise, path=None, design=0):
    """OASPL and A-weighted level against the polar angle from the rotor axis (observers on an arc).

    Parameters
    ----------
    noise : NoiseResult
        Usually at :func:`arc_observers`; any observers are drawn at their polar angle.
    path : str or path, optional
        PNG file to write.
    design : int
        Design of a batch.

    Returns
    -------
    matplotlib.figure.Figure
    """
    *_, oaspl, dba = _single(noise, design)
    angle = noise.polar_angle
    order = np.argsort(angle)
    fig = new_figure(path, figsize=(7.0, 4.2))
    ax = fig.subplots()
    ax.plot(angle[order], oaspl[order], "-o", ms=3, label="OASPL [dB]")
    ax.plot(angle[order], dba[order], "-s", ms=3, label="A-weighted [dBA]")
    distance = noise.distance
    where = f"at {distance[0]:.4g} m" if np.ptp(distance) < 1e-9 * distance[0] else "at the observers"
    ax.set_title(f"Directivity {where} (0 deg: along the thrust, 90 deg: disc plane)", fontsize=10)
    ax.set_xlabel("polar angle from the rotor axis [deg]")
    ax.set_ylabel("level [dB]")
    ax.set_xlim(0.0, 180.0)
    ax.grid(True, lw=0.4, alpha=0.6)
    ax.legend()
    return finish(fig, path)
