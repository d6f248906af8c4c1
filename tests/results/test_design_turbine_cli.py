"""``bild-mdo design --turbine``: the parser options of bild_mdo.cli.design_turbine and its run."""
import argparse
import io

from bild_mdo.cli.design_turbine import add_turbine_arguments, run_turbine


def _parser():
    parser = argparse.ArgumentParser()
    for option, default in (("--radius", 1.5), ("--hub-radius-ratio", 0.2), ("--ref-radius-ratio", 0.5),
                            ("--ref-chord", None), ("--thrust", None), ("--altitude", 0.0)):
        parser.add_argument(option, type=float, nargs="+", default=default)
    parser.add_argument("--num-blades", type=int, default=3)
    parser.add_argument("--airfoil", default="naca4412")
    parser.add_argument("--num-radial", type=int, default=30)
    parser.add_argument("--loss-model", default="tip_hub")
    parser.add_argument("--fluid", default=None)
    add_turbine_arguments(parser)
    return parser


def test_run_turbine_prints_the_summary():
    args = _parser().parse_args(["--turbine", "--wind-speed", "9", "--tip-speed-ratio", "6", "8",
                                 "--airfoil", "analytic", "--num-radial", "8"])
    out = io.StringIO()
    assert run_turbine(args, out) == 0
    text = out.getvalue()
    assert text.count("Turbine BILD design (maximum power)") == 2
    assert "radius                                 40" in text  # the turbine's default radius
