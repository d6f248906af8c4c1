"""Text tables: columns titled from the metric registry, long batches elided in the middle."""
import numpy as np
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


class _Rows:
    """Two operating points as a table reads them: a propeller and a windmill (T < 0, P < 0)."""

    def __init__(self, status=("ok", "ok")):
        # Windmill row: eta = T V / P = (-400 N)(72 m/s)/(-19.7 kW) = 1.46 by the formula, not an efficiency.
        self.advance_ratio = np.array([1.0, 1.8])
        self.v_axial = np.array([40.0, 72.0])
        self.rpm = np.array([800.0, 800.0])
        self.thrust = np.array([1711.9, -400.0])
        self.power = np.array([77790.0, -19726.0])
        self.efficiency = self.thrust * self.v_axial / self.power
        self.figure_of_merit = np.array([0.2188, 0.31])
        for name in ("torque", "thrust_coefficient", "torque_coefficient", "power_coefficient"):
            setattr(self, name, np.array([1.0, -1.0]))
        self.status = np.array(status, dtype=object)

    def __len__(self):
        return 2


def test_efficiency_and_figure_of_merit_only_where_thrust_and_power_are_positive():
    rows = _Rows()
    assert rows.efficiency[1] == pytest.approx(1.46, abs=0.01)
    propeller, windmill = tables.sweep_table(rows)[1:]
    # Forward flight: eta = V T / P = 40 * 1711.9 / 77790 = 0.8803; the hover figure of merit means nothing there.
    assert propeller.split()[6:8] == ["0.8803", "n/a"] and "0.2188" not in propeller
    assert windmill.split()[6:8] == ["n/a", "n/a"] and "1.46" not in windmill


def test_figure_of_merit_only_in_hover_and_efficiency_only_in_forward_flight():
    # FM = T^1.5 / (P sqrt(2 rho A)) compares with the ideal HOVER power; eta = V T / P is 0 at V = 0 (Table 2).
    rows = _Rows()
    rows.v_axial = np.array([0.0, 40.0])
    rows.power = np.array([77790.0, 77790.0])
    rows.thrust = np.array([1711.9, 1711.9])
    useful = tables.meaningful(rows)
    assert useful["figure_of_merit"].tolist() == [True, False]
    assert useful["efficiency"].tolist() == [False, True]
    hover, cruise = tables.sweep_table(rows)[1:]
    assert hover.split()[6:8] == ["n/a", "0.2188"]
    assert cruise.split()[7] == "n/a"


def test_failed_point_prints_its_reason():
    rows = _Rows(status=("ok", "BEM analysis: 4 station(s) outside the momentum model's valid flow states"))
    lines = tables.sweep_table(rows)
    assert lines[2].split()[:3] == ["1.8000", "72.000", "800.0"]
    assert "failed: BEM analysis: 4 station(s)" in lines[2] and "-400" not in lines[2]
    assert tables.status_footer(rows, "points")[0] == "1 of 2 points infeasible or failed (values NaN):"
