"""The figure canvas shared by the plots: a PNG file without pyplot, or a pyplot figure for display.

matplotlib is imported only when a figure is made (extra ``bild-mdo[plot]``).
With a ``path`` the figure is drawn on a ``matplotlib.figure.Figure`` with the
Agg canvas and written as PNG (no display, no pyplot state); without one it is
a pyplot figure, ready for ``plt.show()`` or a notebook.
"""
from __future__ import annotations

PLOT_MISSING = "plots need matplotlib: pip install bild-mdo[plot]"


def new_figure(path, **kwargs):
    """A constrained-layout figure: on the Agg canvas when ``path`` is given, else from pyplot.

    Raises
    ------
    ImportError
        Without matplotlib (the message names the extra to install).
    """
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


def finish(fig, path):
    """Write ``fig`` as a 150-dpi PNG when ``path`` is given; return the figure."""
    if path is not None:
        fig.savefig(path, dpi=150)
    return fig
