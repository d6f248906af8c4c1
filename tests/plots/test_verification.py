import sys

import pytest

from bild_mdo.plots.verification import PLOT_MISSING, plot_parity, plot_run_times, save_figures
from bild_mdo.verification import ResultsStore, SweepSpec, run_sweep
from tests.verification import standins

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def rows(tmp_path_factory):
    pytest.importorskip("matplotlib")
    db = tmp_path_factory.mktemp("fig") / "s.sqlite"
    spec = SweepSpec(levels=2)
    run_sweep(spec, db, standins.bild_batch, standins.optimize, progress=False)
    with ResultsStore(db, spec) as store:
        return store.rows()


def test_figures_are_written(rows, tmp_path):
    paths = save_figures(rows, tmp_path / "out")
    assert [p.rsplit("/", 1)[1] for p in paths] == ["fig4_run_time.png", "fig5_parity.png"]
    from matplotlib.image import imread

    for path in paths:
        with open(path, "rb") as handle:
            assert handle.read(8) == PNG_SIGNATURE
        image = imread(path)
        # Not a blank canvas: the plot put ink on a good share of pixels.
        assert (image[..., :3] < 0.9).any(axis=-1).mean() > 0.01


def test_parity_axes_are_labelled_with_units(rows, tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    saved = []
    monkeypatch.setattr(Figure, "savefig", lambda self, *a, **k: saved.append(self))
    plot_parity(rows, tmp_path / "p.png")
    plot_run_times(rows, tmp_path / "t.png")
    parity, times = saved
    labels = [(ax.get_xlabel(), ax.get_ylabel()) for ax in parity.axes]
    assert labels[0] == (r"optimum efficiency $\eta$ (-), J > 0", r"BILD efficiency $\eta$ (-), J > 0")
    assert all(x.startswith("optimum ") and y.startswith("BILD ") for x, y in labels)
    assert parity.get_layout_engine() is not None
    (ax,) = times.axes
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("BILD run time per case (s)", "BEM optimisation run time per case (s)")
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    # Stand-in sweep of 16 cases: 4 not converged (ids 3, 4, 10, 15).
    assert legend[0].startswith("optimisation converged (12), mean speed-up ") and legend[0].endswith("x")
    assert legend[1] == "optimisation not converged (4)"


def test_parity_panels_of_other_verified_metrics(rows, tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    saved = []
    monkeypatch.setattr(Figure, "savefig", lambda self, *a, **k: saved.append(self))
    plot_parity(rows, tmp_path / "p.png", quantities=("figure_of_merit", "energy_loss", "efficiency"))
    (fig,) = saved
    visible = [ax for ax in fig.axes if ax.get_visible()]
    # Three panels on a 2 x 2 grid, labelled from the metrics registry; the figure of merit is a
    # hover metric, so its panel holds only the converged cases at J = 0.
    assert len(visible) == 3
    assert visible[0].get_xlabel() == "optimum FM [-]" and visible[1].get_xlabel() == "optimum E [kW]"
    hover = [r for r in rows if r["converged"] and r["bild_converged"] and r["advance_ratio"] == 0.0]
    assert 0 < len(hover) < len(rows)
    assert visible[0].get_title() == f"FM [-] ({len(hover)} cases)"


def test_missing_matplotlib_names_the_extra(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "matplotlib.figure", None)
    with pytest.raises(ImportError, match=r"pip install bild-mdo\[plot\]") as info:
        save_figures([], tmp_path)
    assert str(info.value) == PLOT_MISSING
