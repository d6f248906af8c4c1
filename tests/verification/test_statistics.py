import math

import numpy as np
import pytest

from bild_mdo.bem.metrics import METRICS_BY_NAME, VERIFIED_METRICS
from bild_mdo.verification import statistics
from bild_mdo.verification.statistics import PAPER_TABLE3, SCALARS, format_table3, table3


def _row(case_id, j, converged, **values):
    row = {"case_id": case_id, "advance_ratio": j, "bild_converged": True, "converged": converged,
           "bild_time": None, "opt_time": None}
    for method in ("bild", "opt"):
        for key in VERIFIED_METRICS + ("chord", "twist"):
            row[f"{method}_{key}"] = None
    row.update(values)
    return row


ROWS = [
    # Hover case: FM counts, eta does not.
    _row(0, 0.0, True, bild_thrust_coefficient=0.11, opt_thrust_coefficient=0.10,
         bild_figure_of_merit=0.72, opt_figure_of_merit=0.75, bild_efficiency=0.5, opt_efficiency=0.9,
         bild_energy_loss=1500.0, opt_energy_loss=1000.0,
         bild_chord=np.array([3.0, 5.0]), opt_chord=np.array([3.0, 4.0]),
         bild_twist=np.array([1.0, 0.1]), opt_twist=np.array([1.0, 0.0]),
         bild_time=0.01, opt_time=2.0),
    # Forward flight: eta counts, FM does not.
    _row(1, 1.0, True, bild_thrust_coefficient=0.2, opt_thrust_coefficient=0.2,
         bild_efficiency=0.81, opt_efficiency=0.9, bild_figure_of_merit=0.1, opt_figure_of_merit=0.9,
         bild_energy_loss=900.0, opt_energy_loss=1000.0,
         bild_chord=np.array([0.0, 2.0]), opt_chord=np.array([0.0, 2.0]),
         bild_twist=np.array([0.0, 0.5]), opt_twist=np.array([0.0, 0.5]),
         bild_time=0.03, opt_time=4.0),
    # Optimisation not converged: left out of every statistic but the percent converged.
    _row(2, 2.0, False, bild_thrust_coefficient=1.0, opt_thrust_coefficient=5.0, bild_efficiency=0.1,
         opt_efficiency=0.9, bild_time=0.5, opt_time=100.0),
]


def test_table3_against_hand_computed_values():
    t = table3(ROWS)
    q = t.quantities
    assert (t.num_cases, t.num_converged) == (3, 2)
    # C_T: |0.11-0.10|/0.10 = 10 %, |0.2-0.2|/0.2 = 0 % -> mean 5 %.
    assert q["thrust_coefficient"].mean_relative_error_pct == pytest.approx(5.0)
    assert q["thrust_coefficient"].bild_range == pytest.approx((0.11, 0.2))
    assert q["thrust_coefficient"].opt_range == pytest.approx((0.10, 0.2))
    assert q["thrust_coefficient"].num_cases == 2
    # eta over J > 0 only: |0.81-0.9|/0.9 = 10 %.
    assert q["efficiency"].mean_relative_error_pct == pytest.approx(10.0)
    assert q["efficiency"].num_cases == 1 and q["efficiency"].bild_range == pytest.approx((0.81, 0.81))
    # FM over J = 0 only: |0.72-0.75|/0.75 = 4 %.
    assert q["figure_of_merit"].mean_relative_error_pct == pytest.approx(4.0)
    assert q["figure_of_merit"].num_cases == 1
    # Energy loss: 50 % and 10 % -> 30 %; ranges in kW.
    assert q["energy_loss"].mean_relative_error_pct == pytest.approx(30.0)
    assert q["energy_loss"].bild_range == pytest.approx((0.9, 1.5))
    assert q["energy_loss"].opt_range == pytest.approx((1.0, 1.0))
    # Chord norm: ||(0,1)|| / ||(3,4)|| = 1/5 = 20 %, and 0 % -> 10 %.
    assert q["chord_norm"].mean_relative_error_pct == pytest.approx(10.0)
    # Twist norm: ||(0,0.1)|| / ||(1,0)|| = 10 %, and 0 % -> 5 %.
    assert q["twist_norm"].mean_relative_error_pct == pytest.approx(5.0)
    # Values missing for both methods (C_Q here) give no statistic rather than a fake zero.
    assert q["torque_coefficient"].num_cases == 0 and math.isnan(q["torque_coefficient"].mean_relative_error_pct)
    # Percent converged over all cases: BILD 3/3, optimisation 2/3.
    assert t.percent_converged_bild == pytest.approx(100.0)
    assert t.percent_converged_opt == pytest.approx(200.0 / 3.0)
    # Run times over converged cases: (0.01+0.03)/2 and (2+4)/2.
    assert t.mean_run_time_bild == pytest.approx(0.02)
    assert t.mean_run_time_opt == pytest.approx(3.0)
    assert t.speedup == pytest.approx(150.0)


def test_format_puts_paper_values_beside_ours():
    text = format_table3(table3(ROWS))
    lines = text.splitlines()
    assert lines[0].startswith("Table 3 reproduction: 3 cases, 2 with both methods converged")
    ct = next(line for line in lines if line.startswith("Thrust coefficient"))
    # Ours: [0.110, 0.200] and 5 %; the paper's Table 3: [0.046, 0.645] and 6.337E-10 %.
    assert "[0.110, 0.200]" in ct and "5.000" in ct and "[0.046, 0.645]" in ct and ct.endswith("6.337e-10")
    energy = next(line for line in lines if line.startswith("Rate of energy loss"))
    assert "[0.900, 1.500]" in energy and "30.000" in energy and "[0.104, 116.932]" in energy
    assert next(line for line in lines if line.startswith("Percent converged")).split()[2:4] == ["100.000", "66.667"]
    run_time = next(line for line in lines if line.startswith("Average run time")).split()
    assert run_time[4:6] == ["0.020", "3.000"] and run_time[-3:-1] == ["0.009", "2.130"]
    assert PAPER_TABLE3["chord_norm"][2] == 12.406
    # All rows share one column layout.
    body = [line for line in lines[1:] if not line.startswith("-")]
    assert len({len(line) for line in body}) == 1


def test_no_converged_cases():
    t = table3([_row(0, 0.0, False)])
    assert t.num_converged == 0 and math.isnan(t.mean_run_time_opt) and math.isnan(t.speedup)
    assert t.quantities["chord_norm"].num_cases == 0
    assert "Table 3 reproduction: 1 cases, 0 with both methods converged" in format_table3(t)


def test_mismatched_distributions_are_an_error():
    rows = [_row(0, 1.0, True, bild_chord=np.ones(3), opt_chord=np.ones(4))]
    with pytest.raises(ValueError, match="different stations"):
        table3(rows)


def test_scalar_rows_are_the_verified_metrics_of_the_registry():
    assert [key for key, _, _ in SCALARS] == list(VERIFIED_METRICS)
    # Paper Table 3 shows the energy loss in kW: the registry's display scale.
    assert dict((key, scale) for key, _, scale in SCALARS)["energy_loss"] == METRICS_BY_NAME["energy_loss"].display_scale


def test_a_metric_the_paper_does_not_report_gets_a_row(monkeypatch):
    rows = [_row(0, 0.0, True, bild_solidity=0.11, opt_solidity=0.10, bild_time=0.01, opt_time=1.0)]
    monkeypatch.setattr(statistics, "SCALARS", SCALARS + (("solidity", "Solidity sigma [min, max]", 1.0),))
    text = format_table3(table3(rows))
    line = next(line for line in text.splitlines() if line.startswith("Solidity"))
    # Ours: 10 % error; the paper's columns are empty.
    assert line.split()[-4:] == ["1", "-", "-", "-"] and "10.000" in line
