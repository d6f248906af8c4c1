"""plot_performance_curves: PNG files of off-design sweeps, with labelled axes and marked points."""
import numpy as np
import pytest

from bild_mdo.plots import plot_performance_curves
from bild_mdo.results.design import design_rotor
from bild_mdo.results.off_design import off_design_sweep
from tests.plots.test_blade import FAST, _assert_png

pytest.importorskip("matplotlib")


def test_plot_performance_curves(tmp_path):
    rotor = design_rotor(advance_ratio=1.0, **FAST)
    sweep = off_design_sweep(rotor, advance_ratios=np.linspace(0.0, 2.0, 21))
    fig = plot_performance_curves(sweep, tmp_path / "j.png")
    _assert_png(tmp_path / "j.png")
    assert all(ax.get_ylabel() for ax in fig.axes)
    assert "design point" in [t.get_text() for t in fig.legends[0].get_texts()]
    hover = off_design_sweep(design_rotor(**FAST), rpms=np.linspace(500.0, 1100.0, 7))
    fig = plot_performance_curves(hover, tmp_path / "rpm.png")
    _assert_png(tmp_path / "rpm.png")
    assert "rotor speed [rpm]" in {ax.get_xlabel() for ax in fig.axes}
