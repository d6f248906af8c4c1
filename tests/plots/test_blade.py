"""plot_blade: PNG files are written, non-empty, with labelled axes in units."""
import pytest

from bild_mdo.plots import plot_blade
from bild_mdo.results.design import design_rotor

pytest.importorskip("matplotlib")

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
FAST = dict(airfoil="analytic", num_radial=12)


def _assert_png(path):
    data = path.read_bytes()
    assert data[:8] == PNG_SIGNATURE
    assert len(data) > 10_000  # a drawn 8 x 6 in figure at 150 dpi, not an empty canvas


def test_plot_blade_single_and_batch(tmp_path):
    fig = plot_blade(design_rotor(**FAST), tmp_path / "one.png")
    _assert_png(tmp_path / "one.png")
    labels = [ax.get_xlabel() + ax.get_ylabel() for ax in fig.axes]
    assert any("[m]" in text for text in labels) and any("[deg]" in text for text in labels)
    batch = design_rotor(advance_ratio=[0.0, 0.5, 1.0], **FAST)
    fig = plot_blade(batch, tmp_path / "batch.png")
    _assert_png(tmp_path / "batch.png")
    legend_text = [t.get_text() for t in fig.legends[0].get_texts()]
    assert legend_text[:3] == ["J = 0", "J = 0.5", "J = 1"]


def test_plot_blade_from_geometry(tmp_path):
    plot_blade(design_rotor(**FAST).geometry(), tmp_path / "geometry.png")
    _assert_png(tmp_path / "geometry.png")
