"""``bild-mdo verify``: options, the printed Table 3 reproduction, figures, and the paper's sweep at three levels."""
import argparse
import io
import re
import sys
import time

import pytest

from bild_mdo.cli.verify import add_verify_arguments, run_verify
from bild_mdo.verification.cases import SweepSpec
from bild_mdo.verification.statistics import table3
from bild_mdo.verification.store import ResultsStore, StoreError
from tests.cli.runner import run
from tests.verification import standins

# Mean relative errors of BILD against the BEM optimum that the three-level sweep must meet; the paper's
# Table 3 (Ruh & Hwang 2023) reports 0.161, 0.161, 0.156 and 0.288 % for C_Q, C_P, eta and FM and 11.966 % for E.
MAX_ERROR_PCT = {
    "torque_coefficient": 0.3,
    "power_coefficient": 0.3,
    "efficiency": 0.3,
    "figure_of_merit": 0.3,
    "energy_loss": 3.0,
}


def _args(argv):
    return add_verify_arguments(argparse.ArgumentParser(prog="bild-mdo verify")).parse_args(argv)


def test_options_and_defaults():
    args = _args([])
    assert (args.levels, args.optimizer, args.db, args.figures, args.no_progress) == (10, "slsqp", None, None, False)
    with pytest.raises(SystemExit):
        _args(["--optimizer", "cobyla"])


def test_prints_table3_and_writes_figures(tmp_path):
    pytest.importorskip("matplotlib")
    args = _args(["--levels", "2", "--workers", "1", "--db", str(tmp_path / "v.sqlite"),
                  "--figures", str(tmp_path / "figs"), "--no-progress", "--optimizer", "ipopt"])
    out = io.StringIO()
    assert run_verify(args, out, standins.bild_batch, standins.optimize) == 0
    text = out.getvalue()
    assert text.startswith(f"Sweep of 16 cases in {tmp_path / 'v.sqlite'}: 0 resumed, 16 computed in ")
    assert "Table 3 reproduction: 16 cases, 12 with both methods converged" in text
    # The paper's Table 3 column is printed beside ours.
    for paper_value in ("6.337e-10", "11.966", "12.406", "86.810", "2.130"):
        assert paper_value in text
    assert (tmp_path / "figs" / "fig4_run_time.png").stat().st_size > 10_000
    assert (tmp_path / "figs" / "fig5_parity.png").stat().st_size > 10_000
    # The optimiser choice is part of the sweep: the same file refuses another optimiser.
    args.optimizer = "slsqp"
    with pytest.raises(StoreError, match="different sweep"):
        run_verify(args, out, standins.bild_batch, standins.optimize)


@pytest.mark.slow
def test_verify_levels3_end_to_end(tmp_path):
    # 3^4 cases of the paper's Sec. 5.1 sweep, real BILD and SLSQP optimisations on two workers (about a minute).
    db, figures = tmp_path / "x.sqlite", tmp_path / "figs"
    args = _args(["--levels", "3", "--workers", "2", "--optimizer", "slsqp", "--db", str(db),
                  "--figures", str(figures), "--no-progress"])
    out = io.StringIO()
    start = time.perf_counter()
    assert run_verify(args, out) == 0
    print(f"verify --levels 3 took {time.perf_counter() - start:.1f} s")
    text = out.getvalue()

    assert "Table 3 reproduction: 81 cases, 81 with both methods converged" in text
    assert re.search(r"^Percent converged\s+100\.000\s+100\.000\s", text, re.MULTILINE)
    for name in ("fig4_run_time.png", "fig5_parity.png"):
        assert (figures / name).stat().st_size > 10_000
    # The optimum is an optimum: none is lossier than BILD's geometry trimmed to the same thrust (+0.01 %).
    assert "Optimum is an optimum: 0 of 81 cases have E_opt > E_BILD,trimmed (1 + 0.0001)" in text

    with ResultsStore(db, SweepSpec(levels=3, optimizer="slsqp")) as store:
        rows = store.rows()
    table = table3(rows)
    assert (table.num_cases, table.num_converged) == (81, 81)
    assert table.percent_converged_bild == table.percent_converged_opt == 100.0
    for key, limit in MAX_ERROR_PCT.items():
        assert table.quantities[key].mean_relative_error_pct <= limit, key
    # Same thrust by construction: the optimisation's equality constraint is T = T_BILD (|T/T* - 1| <= 1e-6).
    assert table.quantities["thrust_coefficient"].mean_relative_error_pct < 1e-4


def _never_called(*args):
    raise AssertionError("no case may be computed when the options are wrong")


@pytest.mark.parametrize("argv, message", [
    (["--workers", "0"], "workers must be an integer >= 1"),
    (["--workers", "-3"], "workers must be an integer >= 1"),
    (["--levels", "1000"], r"levels=1000 is too large: 1,000,000,000,000 cases: about 80 PB of memory and "
                           r"1.58e\+04 CPU-years of BEM optimisation; levels <= 15"),
])
def test_bad_options_stop_before_any_work(tmp_path, argv, message):
    db = tmp_path / "v.sqlite"
    with pytest.raises(ValueError, match=message):
        run_verify(_args(argv + ["--db", str(db), "--no-progress"]), io.StringIO(), _never_called, _never_called)
    assert not db.exists()


def test_missing_optimizer_package_stops_at_once_with_an_install_hint(tmp_path, monkeypatch):
    # None in sys.modules makes `import pyoptsparse` fail, whether or not it is installed here.
    monkeypatch.setitem(sys.modules, "pyoptsparse", None)
    db = tmp_path / "v.sqlite"
    with pytest.raises(ImportError, match=r"^--optimizer snopt needs pyOptSparse built with SNOPT .* not importable "
                                          r"here: build pyOptSparse \(https://github.com/mdolab/pyoptsparse\)"):
        run_verify(_args(["--optimizer", "snopt", "--db", str(db)]), io.StringIO(), _never_called, _never_called)
    assert not db.exists()


def test_unwritable_figures_folder_stops_at_once(tmp_path):
    (tmp_path / "plain").write_text("x")
    db = tmp_path / "v.sqlite"
    for folder, message in ((tmp_path / "plain", "it is a file, not a folder"),
                            (tmp_path / "plain" / "figs", "cannot write figures there")):
        with pytest.raises(ValueError, match=message):
            run_verify(_args(["--figures", str(folder), "--db", str(db)]), io.StringIO(), _never_called,
                       _never_called)
    assert not db.exists()


def test_bad_db_paths_stop_at_once(tmp_path):
    for db, message in ((tmp_path / "missing" / "v.sqlite", "does not exist; create it"),
                        (tmp_path, "is a folder")):
        with pytest.raises(StoreError, match=message):
            run_verify(_args(["--db", str(db)]), io.StringIO(), _never_called, _never_called)


def test_airfoil_option(tmp_path):
    assert _args([]).airfoil == "naca4412"
    db = tmp_path / "v.sqlite"
    with pytest.raises(ValueError, match=r"^--airfoil: unknown airfoil 'no_such_airfoil'"):
        run_verify(_args(["--airfoil", "no_such_airfoil", "--db", str(db), "--no-progress"]), io.StringIO(),
                   _never_called, _never_called)
    assert not db.exists()
    # A spanwise set written with commas is stored in the one form the sweep reads (r/R:AIRFOIL;...).
    args = _args(["--levels", "2", "--workers", "1", "--db", str(db), "--no-progress", "--airfoil",
                  "0:analytic,1:analytic"])
    assert run_verify(args, io.StringIO(), standins.bild_batch, standins.optimize) == 0
    spec = SweepSpec(levels=2, airfoil="0:analytic;1:analytic")
    with ResultsStore(db, spec, writer=False) as store:
        assert {row["airfoil"] for row in store.rows()} == {"0:analytic;1:analytic"}


def test_bad_scheduler_address_stops_before_the_store_exists(tmp_path):
    db = tmp_path / "v.sqlite"
    with pytest.raises(ValueError, match="scheduler must be an address like 'tcp://host:8786', got 'notaurl'"):
        run_verify(_args(["--scheduler", "notaurl", "--db", str(db)]), io.StringIO(), _never_called, _never_called)
    assert not db.exists()


@pytest.mark.parametrize("argv, message", [
    (["--section-point", "middle"], "argument --section-point: invalid choice: 'middle'"),
    (["--starts", "0"], "--starts must be an integer from 1 to 3 (bild, other_bild, linear), got 0"),
    (["--starts", "4"], "--starts must be an integer from 1 to 3"),
    (["--starts", "two"], "argument --starts: invalid int value: 'two'"),
])
def test_bad_section_point_or_starts_exit_2_with_one_line(tmp_path, capsys, argv, message):
    db = tmp_path / "v.sqlite"
    code, out, err = run(capsys, "verify", "--levels", "2", "--db", str(db), "--no-progress", *argv)
    assert code == 2 and len(err.strip().splitlines()) == 1 and message in err, err
    assert not db.exists()


def test_section_point_and_starts_are_part_of_the_sweep(tmp_path):
    args = _args([])
    assert (args.section_point, args.starts) == ("reference", 1)
    db = tmp_path / "v.sqlite"
    base = ["--levels", "2", "--workers", "1", "--db", str(db), "--no-progress"]
    assert run_verify(_args(base), io.StringIO(), standins.bild_batch, standins.optimize) == 0
    # A store of one setting is never resumed as another.
    for extra in (["--section-point", "local"], ["--starts", "2"]):
        with pytest.raises(StoreError, match="different sweep"):
            run_verify(_args(base + extra), io.StringIO(), standins.bild_batch, standins.optimize)


@pytest.mark.slow
def test_two_starts_keep_the_lower_energy_optimum(tmp_path):
    # 16 cases of the paper's sweep, real BILD and SLSQP, once with one start and once with two (BILD at the
    # reference point, BILD at the local point).  Invariant: the reference optimum of two starts is the better of
    # them, so its energy loss never exceeds the one-start optimum's (same thrust target T_BILD), and equals it
    # when the first start wins; spreads are distances, >= 0.
    rows = {}
    for starts in (1, 2):
        db = tmp_path / f"s{starts}.sqlite"
        out = io.StringIO()
        assert run_verify(_args(["--levels", "2", "--workers", "1", "--db", str(db), "--no-progress",
                                 "--starts", str(starts)]), out) == 0
        with ResultsStore(db, SweepSpec(levels=2, starts=starts), writer=False) as store:
            rows[starts] = store.rows()
    text = out.getvalue()
    assert "Start spread (mean over the" in text
    assert "BILD (reference section point) trimmed to T*: energy excess over the optimum" in text
    compared = 0
    for one, two in zip(rows[1], rows[2]):
        if not (one["converged"] and two["converged"]):
            continue
        compared += 1
        assert two["starts_converged"] >= 1 and two["best_start"] in (1, 2)
        assert two["opt_energy_loss"] <= one["opt_energy_loss"] * (1.0 + 1e-9)
        if two["best_start"] == 1:
            assert two["opt_energy_loss"] == pytest.approx(one["opt_energy_loss"], rel=1e-9)
        for key in ("start_spread_twist", "start_spread_chord", "start_spread_energy"):
            assert two[key] >= 0.0
    assert compared >= 12
