"""``bild-mdo verify --turbine``: the turbine BILD against the full-BEM optimum of the most power at its thrust."""
import argparse
import io
import re

import numpy as np
import pytest

from bild_mdo.cli.verify import add_verify_arguments, run_verify
from bild_mdo.verification.cases import SweepSpec
from bild_mdo.verification.statistics import table3
from bild_mdo.verification.store import ResultsStore
from bild_mdo.verification.turbine_sweep import TurbineSweepSpec
from tests.cli.runner import run


def _args(argv):
    return add_verify_arguments(argparse.ArgumentParser(prog="bild-mdo verify")).parse_args(argv)


def test_verify_turbine_levels3_end_to_end(tmp_path):
    # 3^4 turbine cases with the Reynolds-dependent NACA 4412 table, real turbine BILD and SLSQP in lockstep.
    db = tmp_path / "t.sqlite"
    out = io.StringIO()
    assert run_verify(_args(["--turbine", "--levels", "3", "--workers", "1", "--db", str(db), "--no-progress"]),
                      out) == 0
    text = out.getvalue()
    assert "Turbine sweep: C_T = T/(rho A V^2/2)" in text
    assert "Table 3 reproduction: 81 cases, 81 with both methods converged" in text
    assert re.search(r"^Percent converged\s+100\.000\s+100\.000\s", text, re.MULTILINE)
    # The optimum is an optimum (physical invariant): no optimum extracts less power than BILD's blade trimmed
    # by collective pitch to the same thrust, a feasible design of the same problem.
    match = re.search(r"Optimum is an optimum: 0 of (\d+) cases have E_opt > E_BILD,trimmed", text)
    assert match and int(match.group(1)) >= 79, text
    with ResultsStore(db, TurbineSweepSpec(levels=3)) as store:
        rows = store.rows()
    table = table3(rows)
    # Same thrust by construction: the optimisation's equality constraint is T = T_BILD (|T/T* - 1| <= 1e-6).
    assert table.quantities["thrust_coefficient"].mean_relative_error_pct < 1e-4
    for row in rows:
        # Stored quantities of a turbine (module docstring of turbine_sweep): E = V T - P, eta = P / (V T) and
        # C_P / C_T = P / (V T) by the definitions C_P = P / (rho A V^3 / 2), C_T = T / (rho A V^2 / 2).
        for method in ("bild", "opt"):
            ratio = row[f"{method}_power_coefficient"] / row[f"{method}_thrust_coefficient"]
            assert row[f"{method}_efficiency"] == pytest.approx(ratio, rel=1e-12)
            assert row[f"{method}_figure_of_merit"] is None
        assert row["advance_ratio"] * row["rpm"] * np.pi / 30.0 * row["radius"] / row["v_axial"] == \
            pytest.approx(np.pi, rel=1e-12)  # J = V / (n D) = pi / lambda
        assert row["reference_chord"] is None


def test_frozen_polar_bild_is_the_bem_optimum(tmp_path):
    # With a polar frozen at one Reynolds number the turbine BILD loading is the BEM optimum (its derivation in
    # bild_mdo.bild.variants.turbine: the annulus stationarity of E - mu T with Prandtl's F, as the paper's
    # Sec. 3 for propellers); both starts, the BILD blade and the linear cold start, must end there.
    db = tmp_path / "f.sqlite"
    out = io.StringIO()
    assert run_verify(_args(["--turbine", "--levels", "2", "--starts", "2", "--airfoil", "naca4412@re=1e6",
                             "--workers", "1", "--db", str(db), "--no-progress"]), out) == 0
    with ResultsStore(db, TurbineSweepSpec(levels=2, starts=2, airfoil="naca4412@re=1e6")) as store:
        rows = store.rows()
    assert len(rows) == 16 and all(row["converged"] and row["bild_converged"] for row in rows)
    for row in rows:
        assert row["bild_power_coefficient"] == pytest.approx(row["opt_power_coefficient"], rel=1e-5)
        for name in ("chord", "twist"):
            gap = np.linalg.norm(row[f"bild_{name}"] - row[f"opt_{name}"]) / np.linalg.norm(row[f"opt_{name}"])
            assert gap < 2e-3, (row["case_id"], name, gap)
        assert row["start_spread_energy"] < 1e-6


@pytest.mark.parametrize("argv, message", [
    (["--section-point", "local"], "--turbine designs with the turbine BILD: leave out --section-point"),
    (["--ideal-loading", "exact"], "--turbine designs with the turbine BILD: leave out --section-point"),
    (["--starts", "3"], "--starts must be 1 or 2 with --turbine (BILD, a linear cold start), got 3"),
])
def test_bad_turbine_options_exit_2_with_one_line(tmp_path, capsys, argv, message):
    db = tmp_path / "v.sqlite"
    code, out, err = run(capsys, "verify", "--turbine", "--levels", "2", "--db", str(db), "--no-progress", *argv)
    assert code == 2 and len(err.strip().splitlines()) == 1 and message in err, err
    assert not db.exists()


def test_turbine_sweep_is_its_own_sweep():
    spec = TurbineSweepSpec(levels=3)
    assert spec.fingerprint() != SweepSpec(levels=3).fingerprint()
    assert spec.fingerprint() != TurbineSweepSpec(levels=3, airfoil="naca4412@re=1e6").fingerprint()
    case = spec.case(80)  # the last: every axis at its upper end
    assert (case.inputs["tip_speed_ratio"], case.inputs["radius"], case.inputs["altitude"],
            case.inputs["thrust_coefficient"]) == (10.0, 8.0, 3000.0, 0.75)
    with pytest.raises(ValueError, match="starts must be 1 or 2"):
        TurbineSweepSpec(levels=3, starts=3)
    with pytest.raises(ValueError, match="below Betz's 8/9"):
        TurbineSweepSpec(levels=3, thrust_coefficient_range=(0.4, 0.9))
