"""``bild-mdo design --turbine``: the parser options of bild_mdo.cli.design_turbine and its run."""
import argparse
import io

import numpy as np
import pytest

from bild_mdo.cli.design import add_design_arguments
from bild_mdo.cli.design_turbine import run_turbine


def _parser():
    """The design subcommand's own parser (its sizing options are shared with --turbine)."""
    return add_design_arguments(argparse.ArgumentParser())


def test_run_turbine_prints_the_summary():
    args = _parser().parse_args(["--turbine", "--wind-speed", "9", "--tip-speed-ratio", "6", "8",
                                 "--airfoil", "analytic", "--num-radial", "8"])
    out = io.StringIO()
    assert run_turbine(args, out) == 0
    text = out.getvalue()
    assert text.count("Turbine BILD design (maximum power)") == 2
    assert "radius                                 40" in text  # the turbine's default radius


def test_an_explicit_radius_is_kept_even_at_the_propeller_default():
    # --radius 1.5 (the propeller default, given by the user) designs a 1.5-m turbine, not the 40-m default.
    args = _parser().parse_args(["--turbine", "--radius", "1.5", "--airfoil", "analytic", "--num-radial", "8"])
    out = io.StringIO()
    assert run_turbine(args, out) == 0
    assert "radius                                1.5 m" in out.getvalue()


def test_rated_power_prints_each_designs_power_curve():
    args = _parser().parse_args(["--turbine", "--wind-speed", "9", "--tip-speed-ratio", "6", "8", "--airfoil",
                                 "analytic", "--num-radial", "8", "--rated-power", "1.5e6", "--max-tip-speed", "60"])
    out = io.StringIO()
    assert run_turbine(args, out) == 0
    text = out.getvalue()
    assert text.count("Power curve (turbine BEM") == 2 and text.count("annual energy") == 2
    # The limit is reached at 60 / 8 = 7.5 m/s (hand); at lambda = 6 only at 10 m/s, above rated (9.97 m/s).
    assert "60 m/s, reached at 7.5 m/s (region 2.5)" in text and "60 m/s, not reached below rated" in text


@pytest.mark.parametrize("argv, message", [
    (["--rated-power", "1e6"], "--rated-power belongs to a turbine's power curve"),
    (["--weibull-scale", "9"], "--weibull-scale belongs to a turbine's power curve"),
    (["--turbine", "--max-tip-speed", "60"], "--max-tip-speed belongs to the power curve"),
    (["--turbine", "--cut-out-speed", "20"], "--cut-out-speed belongs to the power curve"),
])
def test_power_curve_options_alone_exit_2_with_one_line(capsys, argv, message):
    from tests.cli.runner import run

    code, out, err = run(capsys, "design", *argv)
    assert code == 2 and message in err
    assert len(err.strip().splitlines()) == 1


def test_power_curve_files_from_the_command_line(tmp_path, capsys):
    from tests.cli.runner import run

    csv, png = tmp_path / "curve.csv", tmp_path / "curve.png"
    code, out, err = run(capsys, "design", "--turbine", "--airfoil", "analytic", "--num-radial", "8",
                         "--tip-speed-ratio", "6", "8", "--rated-power", "1.5e6", "--power-curve-csv", str(csv),
                         "--power-curve-plot", str(png))
    assert code == 0 and f"wrote {csv}" in out and png.stat().st_size > 10_000
    table = np.genfromtxt(csv, delimiter=",", comments="#", skip_header=2)
    assert set(table[:, 0]) == {0.0, 1.0} and table.shape[0] == 2 * 13
    code, out, err = run(capsys, "design", "--turbine", "--airfoil", "analytic", "--num-radial", "8",
                         "--power-curve-csv", str(csv))
    assert code == 2 and "give it with --rated-power" in err and len(err.strip().splitlines()) == 1
