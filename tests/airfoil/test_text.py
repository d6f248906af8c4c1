"""The sweep's airfoil text: resolution to a polar, the Reynolds-independent polar, spanwise sets, store names."""
import subprocess
import sys
import warnings

import numpy as np
import pytest

from bild_mdo import verification
from bild_mdo.airfoil import SpanwisePolar, naca4412, resolve_polar
from bild_mdo.airfoil.text import (REYNOLDS_INDEPENDENT_AIRFOIL, FixedReynoldsPolar,
                                            sweep_polar)
from bild_mdo.verification.case_functions import bild_batch, optimize_case
from bild_mdo.verification.cases import SweepSpec
from bild_mdo.verification.optimality import optimality_check
from bild_mdo.verification.runner import default_db_path, run_sweep
from bild_mdo.verification.store import ResultsStore

ALPHA = np.radians(np.linspace(-4.0, 14.0, 7))
# Inside and outside the built-in table (5e4 ... 2e6): a frozen polar has no range to leave.
REYNOLDS = np.array([1.0e4, 5.0e4, 2.0e5, 1.0e6, 2.0e6, 5.0e6, 3.0e7])


def test_builtin_names_resolve_to_the_builtin_polar():
    assert sweep_polar("naca4412") is naca4412()
    assert sweep_polar(" NACA4412 ") is naca4412()


def test_fixed_reynolds_polar_is_the_base_polar_at_that_reynolds_number():
    polar = sweep_polar(REYNOLDS_INDEPENDENT_AIRFOIL)
    assert isinstance(polar, FixedReynoldsPolar) and polar.reynolds == 1.0e6
    # One object per text in a process: the set-up models are cached per polar object.
    assert polar is sweep_polar(f" {REYNOLDS_INDEPENDENT_AIRFOIL} ")
    assert sweep_polar("naca4412 @ Re = 2e5").reynolds == 2.0e5
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no Reynolds-clamp warning: the polar has no Reynolds range
        values = polar.evaluate(ALPHA, REYNOLDS)
        second = polar.second_derivatives(ALPHA, REYNOLDS)
    base = naca4412().evaluate(ALPHA, 1.0e6)
    np.testing.assert_array_equal(values.cl, base.cl)
    np.testing.assert_array_equal(values.cd, base.cd)
    np.testing.assert_array_equal(values.dcl_dalpha, base.dcl_dalpha)
    for field in ("dcl_dre", "dcd_dre"):
        np.testing.assert_array_equal(getattr(values, field), 0.0)
    for field in ("d2cl_dalpha_dre", "d2cd_dalpha_dre", "d2cl_dre2", "d2cd_dre2"):
        np.testing.assert_array_equal(getattr(second, field), 0.0)


def test_fixed_reynolds_max_lift_to_drag_point_is_one_point():
    # BILD's airfoil point (paper Assumption 2) at any Reynolds number is the base polar's point at Re_0.
    point = sweep_polar(REYNOLDS_INDEPENDENT_AIRFOIL).max_lift_to_drag(REYNOLDS)
    reference = naca4412().max_lift_to_drag(np.array([1.0e6]))
    np.testing.assert_allclose(point.alpha, reference.alpha[0], rtol=0.0, atol=1e-12)
    np.testing.assert_allclose(point.cl / point.cd, reference.cl[0] / reference.cd[0], rtol=1e-12)
    np.testing.assert_array_equal(point.dalpha_dre, 0.0)


def test_complex_step_carries_alpha_and_not_reynolds():
    polar = sweep_polar(REYNOLDS_INDEPENDENT_AIRFOIL)
    h = 1e-30
    values = polar.evaluate(ALPHA + 1j * h, REYNOLDS + 1j * h * 1e6)
    real = polar.evaluate(ALPHA, REYNOLDS)
    np.testing.assert_allclose(values.cl.imag / h, real.dcl_dalpha, rtol=1e-12)
    np.testing.assert_allclose(values.cd.imag / h, real.dcd_dalpha, rtol=1e-12)


def test_spanwise_set_blends_its_members():
    polar = sweep_polar("0.2:naca4412@re=1e6; 1:analytic")
    assert isinstance(polar, SpanwisePolar) and polar.varies_along_span
    np.testing.assert_array_equal(polar.radial_fractions, [0.2, 1.0])
    # At a station the blend is exactly that station's airfoil (smooth step s(0) = 0, s(1) = 1).
    root = polar.evaluate(ALPHA, 3.0e5, radial_fraction=0.2)
    tip = polar.evaluate(ALPHA, 3.0e5, radial_fraction=1.0)
    np.testing.assert_allclose(root.cl, naca4412().evaluate(ALPHA, 1.0e6).cl, rtol=1e-14)
    np.testing.assert_allclose(tip.cl, sweep_polar("analytic").evaluate(ALPHA, 3.0e5).cl, rtol=1e-14)


@pytest.mark.parametrize("text, message", [
    ("nacax", "unknown airfoil"),
    ("naca4412@re=abc", "not a number"),
    ("naca4412@re=-1", "finite and > 0"),
    ("0.2:naca4412;analytic", "spanwise set is"),
    ("0.5:naca4412;0.5:analytic", "same r/R"),
    ("", "non-empty"),
])
def test_bad_airfoil_text_is_one_clear_line(text, message):
    with pytest.raises(ValueError, match=message) as info:
        sweep_polar(text)
    assert "\n" not in str(info.value)


def test_airfoil_is_part_of_the_fingerprint_and_the_default_file_name():
    default, other = SweepSpec(levels=2), SweepSpec(levels=2, airfoil=REYNOLDS_INDEPENDENT_AIRFOIL)
    assert default.fingerprint() != other.fingerprint()
    assert other.case(3).inputs["airfoil"] == REYNOLDS_INDEPENDENT_AIRFOIL
    assert default_db_path(default) == "bild-verify-L2-slsqp.sqlite"
    assert default_db_path(other) == "bild-verify-L2-slsqp-naca4412-re=1e6.sqlite"
    assert default_db_path(SweepSpec(levels=2, airfoil="0.2:/data/n4415;1:naca4412")) == \
        "bild-verify-L2-slsqp-0.2-data-n4415-1-naca4412.sqlite"
    with pytest.raises(ValueError, match="non-empty string"):
        SweepSpec(airfoil=" ")


def test_sweep_with_a_reynolds_independent_polar(tmp_path):
    # levels=2 cases 0 (hover, R = 0.5 m, c_ref = 0.08 m) and 9 (J = 3, c_ref = 0.22 m), both methods
    # on NACA 4412 at Re = 1e6 only.
    spec = SweepSpec(levels=2, airfoil=REYNOLDS_INDEPENDENT_AIRFOIL)
    db = tmp_path / "sweep.sqlite"
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # neither the Reynolds clamp nor BEM flow-state warnings
        result = run_sweep(spec, db, bild_batch, optimize_case, workers=1, progress=False, case_ids=[0, 9])
    assert result.num_failed == 0 and result.warnings == []
    with ResultsStore(db, spec) as store:
        rows = store.rows()
    default = bild_batch(SweepSpec(levels=2).cases([0, 9]))
    for row, other in zip(rows, default):
        assert row["airfoil"] == REYNOLDS_INDEPENDENT_AIRFOIL
        assert row["converged"] and row["bild_converged"], row["status"]
        assert abs(row["opt_thrust_coefficient"] / row["bild_thrust_coefficient"] - 1.0) < 1e-6
        # The polar reaches the designs: the case at low Reynolds numbers (c_ref = 0.08 m) differs.
        if row["case_id"] == 0:
            assert abs(row["bild_energy_loss"] / other["energy_loss"] - 1.0) > 1e-3
    # The optimality check analyses BILD's geometry with the same frozen polar: no optimum is worse.
    check = optimality_check(rows)
    assert check.num_cases == 2 and check.passed and check.invalid_flow_ids == []


def test_airfoil_text_does_not_load_the_sweep_machinery():
    # Every bild-mdo command resolves its --airfoil here; the package's names load on first use.
    code = ("import sys, bild_mdo.airfoil.text\n"
            "print(sorted(m for m in ('bild_mdo.verification.runner', 'bild_mdo.verification.executors', 'tqdm',"
            " 'bild_mdo.verification.optimality') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True)
    assert out.stdout.strip() == "[]"
    assert verification.SweepSpec is SweepSpec and "run_sweep" in dir(verification)


def test_spanwise_set_with_a_frozen_reynolds_member_is_named_by_its_text():
    # A geometry file stores the polar's name: it must read back to the same polar.
    text = "0.2:naca4412;1:naca4412@re=1e6"
    polar = sweep_polar(text)
    assert polar.name == text
    assert sweep_polar(polar.name) is polar


def test_spaced_naca_designation_of_a_built_in_airfoil_is_the_built_in():
    assert resolve_polar("NACA 4412") is resolve_polar("naca4412")
