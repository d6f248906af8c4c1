"""Text tables: columns titled from the metric registry, long batches elided in the middle."""
import pytest

from bild_mdo.bem.metrics import METRICS_BY_NAME
from bild_mdo.results import tables


def test_columns_come_from_the_registry():
    # Power is shown in kW: the registry's label and display scale (bild_mdo.bem.metrics).
    assert tables.column("power") == ("P [kW]", 1e-3)
    assert tables.column("thrust") == (METRICS_BY_NAME["thrust"].label, 1.0)
    assert tables.column("advance_ratio") == ("J [-]", 1.0)
    for name in tables.DESIGN_BATCH_COLUMNS + tuple(tables.SWEEP_COLUMNS):
        assert name in METRICS_BY_NAME or name in tables.INPUT_TITLES


@pytest.mark.parametrize("count, max_rows, expected", [
    (3, 20, [0, 1, 2]),
    (10, 4, [0, 1, None, 8, 9]),
    (10, 5, [0, 1, None, 7, 8, 9]),
])
def test_shown_rows(count, max_rows, expected):
    assert tables.shown_rows(count, max_rows) == expected


def test_format_cell():
    assert tables.format_cell(1234.5678) == "     1234.6"
    assert tables.format_cell("...", width=5) == "  ..."
