"""``bild-mdo verify --ideal-loading paper|exact``: BILD's ideal loading of the sweep, part of its fingerprint."""
import argparse
import io

import pytest

from bild_mdo.bild.problem import bild_problem
from bild_mdo.cli.verify import add_verify_arguments, run_verify
from bild_mdo.verification import case_functions
from bild_mdo.verification.cases import SweepSpec
from bild_mdo.verification.optimality import OptimalityCheck, optimality_check
from bild_mdo.verification.report import default_db_path
from bild_mdo.verification.statistics import table3
from bild_mdo.verification.store import ResultsStore, StoreError
from tests.cli.runner import run
from tests.verification import standins

# The pinned fingerprint of the paper's sweep (tests/verification/test_cases.py): stores made before the option resume.
DEFAULT_FINGERPRINT = "a1c89e229d75513b"


def _args(argv):
    return add_verify_arguments(argparse.ArgumentParser(prog="bild-mdo verify")).parse_args(argv)


def test_bad_ideal_loading_exits_2_with_one_line_and_no_store(tmp_path, capsys):
    db = tmp_path / "v.sqlite"
    code, _out, err = run(capsys, "verify", "--levels", "2", "--db", str(db), "--no-progress",
                          "--ideal-loading", "betz")
    assert code == 2 and len(err.strip().splitlines()) == 1, err
    assert "argument --ideal-loading: invalid choice: 'betz'" in err
    assert not db.exists()
    # A namespace built without argparse's choices is refused before any file too.
    args = _args(["--db", str(db)])
    args.ideal_loading = "betz"
    with pytest.raises(ValueError, match=r"^--ideal-loading must be 'paper' or 'exact', got 'betz'$"):
        run_verify(args, io.StringIO(), standins.bild_batch, standins.optimize)
    assert not db.exists()


def test_ideal_loading_is_part_of_the_fingerprint_and_the_default_is_unchanged():
    assert _args([]).ideal_loading == "paper"
    assert SweepSpec().fingerprint() == SweepSpec(ideal_loading="paper").fingerprint() == DEFAULT_FINGERPRINT
    assert "ideal_loading" not in SweepSpec().to_dict()
    assert SweepSpec(ideal_loading="exact").to_dict()["ideal_loading"] == "exact"
    settings = [("reference", "paper"), ("reference", "exact"), ("local", "paper"), ("local", "exact")]
    prints = {SweepSpec(levels=3, section_point=point, starts=starts, ideal_loading=loading).fingerprint()
              for point, loading in settings for starts in (1, 2)}
    assert len(prints) == 8
    case = SweepSpec(levels=2, starts=2, ideal_loading="exact").case(3)
    assert (case.section_point, case.starts, case.ideal_loading) == ("reference", 2, "exact")
    with pytest.raises(ValueError, match="ideal loading must be one of paper, exact, got 'betz'"):
        SweepSpec(ideal_loading="betz")


def test_default_store_name_names_the_exact_ideal_loading():
    assert default_db_path(SweepSpec(levels=3)) == "bild-verify-L3-slsqp.sqlite"
    assert default_db_path(SweepSpec(levels=3, ideal_loading="exact")) == "bild-verify-L3-slsqp-exact.sqlite"
    assert (default_db_path(SweepSpec(levels=3, starts=2, ideal_loading="exact"))
            == "bild-verify-L3-slsqp-exact-starts2.sqlite")


def test_a_store_of_one_ideal_loading_is_never_resumed_as_the_other(tmp_path):
    db = tmp_path / "v.sqlite"
    base = ["--levels", "2", "--workers", "1", "--db", str(db), "--no-progress"]
    assert run_verify(_args(base + ["--ideal-loading", "exact"]), io.StringIO(), standins.bild_batch,
                      standins.optimize) == 0
    with ResultsStore(db, SweepSpec(levels=2, ideal_loading="exact"), writer=False) as store:
        assert len(store.rows()) == 16
    with pytest.raises(StoreError, match="different sweep"):
        run_verify(_args(base), io.StringIO(), standins.bild_batch, standins.optimize)


def test_bild_batch_designs_every_start_with_the_sweeps_ideal_loading(monkeypatch):
    # Start 2 is BILD at the other section point with the same ideal loading (at the local point the exact loading is
    # the Reynolds-aware one).  The recorded models are built at the reference point (fast); only the options the
    # sweep asks for are checked.
    calls = []

    def recording(*args, section_point="reference", ideal_loading="paper"):
        calls.append((section_point, ideal_loading))
        return bild_problem(*args, section_point="reference", ideal_loading=ideal_loading)

    monkeypatch.setattr(case_functions, "bild_problem", recording)
    spec = SweepSpec(levels=2, starts=2, ideal_loading="exact", num_radial=8)
    rows = case_functions.bild_batch(spec.cases([0, 15]))
    assert calls == [("reference", "exact"), ("local", "exact")]
    assert all(row["converged"] and row["other_chord"] is not None for row in rows)


def test_bild_batch_keeps_the_ideal_loadings_apart(monkeypatch):
    calls = []

    def failing(*args, section_point="reference", ideal_loading="paper"):
        calls.append((section_point, ideal_loading))
        raise ValueError("no model")

    monkeypatch.setattr(case_functions, "bild_problem", failing)
    exact = SweepSpec(levels=2, ideal_loading="exact").case(0)
    with pytest.raises(case_functions.CaseSetupError,
                       match=r"the BILD model \(reference section point, exact ideal loading\) cannot be set up"):
        case_functions.bild_batch([exact, SweepSpec(levels=2).case(1)])
    assert calls == [("reference", "exact")]


def test_excess_line_names_the_ideal_loading_off_the_paper():
    check = OptimalityCheck(tolerance=1e-4, num_cases=1, num_skipped=0, trim_failed_ids=[], violations=[],
                            max_margin=0.0, mean_margin=0.0, worst_case_id=0, bild_reported_mean_abs=0.0,
                            bild_reported_max_abs=0.0, max_untrimmed_thrust_error=0.0, max_pitch_offset=0.0,
                            max_trim_residual=0.0, mean_excess=0.0, max_excess=0.0, max_excess_case_id=0,
                            section_point="local")
    assert "  BILD (local section point) trimmed to T*: energy excess" in check.summary()
    check = OptimalityCheck(**{**check.__dict__, "ideal_loading": "exact"})
    assert "  BILD (local section point, exact ideal loading) trimmed to T*: energy excess" in check.summary()


@pytest.mark.slow
def test_exact_ideal_loading_is_the_bem_optimum_for_a_reynolds_independent_polar(tmp_path):
    # Hand-derivable invariant (bild_mdo/bild/annulus_stationarity.py, module docstring): the exact ideal loading
    # makes E - lambda T stationary annulus by annulus with Prandtl's F kept, at the max-L/D point of a polar that
    # does not depend on the Reynolds number; that is the optimality condition of the full BEM model at the thrust
    # T_BILD.  So BILD's design trimmed to T_BILD loses no more energy than the optimum: excess <= 0.01 % (the
    # check's tolerance).  Three starts make the optimum independent of BILD: the linear cold start (start 3)
    # finds it on its own, and the reference is the lowest-energy start.
    db = tmp_path / "exact.sqlite"
    out = io.StringIO()
    assert run_verify(_args(["--levels", "2", "--workers", "1", "--airfoil", "naca4412@re=1e6", "--ideal-loading",
                             "exact", "--starts", "3", "--db", str(db), "--no-progress"]), out) == 0
    text = out.getvalue()
    print(text)
    assert "Table 3 reproduction: 16 cases, 16 with both methods converged" in text
    assert "BILD (reference section point, exact ideal loading) trimmed to T*: energy excess over the optimum" in text
    spec = SweepSpec(levels=2, airfoil="naca4412@re=1e6", ideal_loading="exact", starts=3)
    with ResultsStore(db, spec, writer=False) as store:
        rows = store.rows()
    assert sum(row["starts_converged"] == 3 for row in rows) == 16
    check = optimality_check(rows, section_point="reference", ideal_loading="exact")
    assert check.num_cases == 16 and check.passed
    assert check.max_excess <= 1.0e-4
    table = table3(rows)
    # The printed errors of Table 3 against the optimum: FM and E within the same 0.01 %.
    for key in ("figure_of_merit", "energy_loss", "power_coefficient", "efficiency"):
        assert table.quantities[key].mean_relative_error_pct <= 0.01, key
