"""``bild-mdo design --turbine``: design an ideal wind-turbine blade with the turbine BILD and print it.

The turbine shares the design subcommand's sizing options (``--radius``, ``--hub-radius-ratio``,
``--ref-radius-ratio``, ``--ref-chord``, ``--thrust``, ``--altitude``, ``--fluid``, ``--num-blades``,
``--airfoil``, ``--num-radial``, ``--loss-model``) and adds its own: ``--turbine``, ``--wind-speed`` and
``--tip-speed-ratio`` (or ``--turbine-rpm``).  Without ``--thrust`` or ``--ref-chord`` the design extracts the
most power at the tip-speed ratio.  With ``--rated-power`` each design's power curve and annual energy follow
(:meth:`~bild_mdo.results.turbine_design.TurbineDesign.power_curve`: ``--max-tip-speed``, ``--weibull-scale``,
``--weibull-shape``, ``--cut-in-speed``, ``--cut-out-speed``).
"""
from __future__ import annotations

import sys

from bild_mdo.cli.files import airfoil_polar, figure_file, output_file
from bild_mdo.fluid import fluid_from_text
from bild_mdo.results.turbine_design import design_turbine

#: Defaults of the shared options where the design subcommand's defaults (a propeller's) would not fit.
TURBINE_DEFAULTS = {"radius": 40.0, "hub_radius_ratio": 0.05, "ref_radius_ratio": 0.7}
#: Defaults of the power-curve options (those of :func:`~bild_mdo.results.power_curve.power_curve`).
CURVE_DEFAULTS = {"weibull_scale": 8.0, "weibull_shape": 2.0, "cut_in_speed": 3.0, "cut_out_speed": 25.0}
#: The options that need --rated-power (argparse's names).
CURVE_OPTIONS = ("max_tip_speed", *CURVE_DEFAULTS, "power_curve_csv", "power_curve_plot")


def add_turbine_arguments(parser):
    """Add the turbine options to the ``design`` parser (its sizing options are shared)."""
    group = parser.add_argument_group("wind turbine (--turbine)")
    group.add_argument("--turbine", action="store_true",
                       help="design a wind turbine for maximum power (or the member of --thrust / --ref-chord)")
    group.add_argument("--wind-speed", type=float, nargs="+", default=[10.0], metavar="V",
                       help="wind speed V [m/s] (with --turbine; default 10)")
    speed = group.add_mutually_exclusive_group()
    speed.add_argument("--tip-speed-ratio", type=float, nargs="+", default=None, metavar="LAMBDA",
                       help="tip-speed ratio Omega R / V [-] (with --turbine; default 7)")
    speed.add_argument("--turbine-rpm", type=float, nargs="+", default=None, metavar="RPM",
                       help="rotor speed [rpm] instead of --tip-speed-ratio (with --turbine)")
    curve = parser.add_argument_group("power curve and annual energy (--turbine --rated-power P)")
    curve.add_argument("--rated-power", type=float, default=None, metavar="P",
                       help="rated power [W]: print each design's power curve (pitch trimmed above rated) and AEP")
    curve.add_argument("--max-tip-speed", type=float, default=None, metavar="V",
                       help="largest tip speed [m/s] (region 2.5; default: no limit)")
    for option, text in (("--weibull-scale", "Weibull scale c of the wind [m/s]"),
                         ("--weibull-shape", "Weibull shape k [-] (2: Rayleigh)"),
                         ("--cut-in-speed", "cut-in wind speed [m/s]"),
                         ("--cut-out-speed", "cut-out wind speed [m/s]")):
        default = CURVE_DEFAULTS[option[2:].replace("-", "_")]
        # None when not given, so that an option without --rated-power is refused, not ignored.
        curve.add_argument(option, type=float, default=None, metavar="X", help=f"{text} (default {default:g})")
    curve.add_argument("--power-curve-csv", metavar="FILE.csv", default=None,
                       help="write the power curves as CSV (every design's rows; with --rated-power)")
    curve.add_argument("--power-curve-plot", metavar="FILE.png", default=None,
                       help="plot the first design's power curve (with --rated-power)")


def _value(values):
    if values is None:
        return None
    values = list(values) if isinstance(values, (list, tuple)) else [values]
    return values[0] if len(values) == 1 else values


def _shared(args, name):
    """A shared sizing option's value: the user's, else the turbine default (the design parser leaves it None)."""
    value = getattr(args, name, None)
    if value is None and name in TURBINE_DEFAULTS:
        return TURBINE_DEFAULTS[name]
    return _value(value)


def run_turbine(args, out=None):
    """Design the turbine(s) of parsed ``design --turbine`` options and print their summaries (each followed by
    its power curve and AEP with ``--rated-power``, written to ``--power-curve-csv`` / ``--power-curve-plot``).

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options (the design subcommand's and :func:`add_turbine_arguments`'s); a shared sizing option
        that is None (not given) takes the turbine's default (:data:`TURBINE_DEFAULTS`).
    out : file, optional
        Where to print (default ``sys.stdout``).

    Returns
    -------
    int
        Exit code, 0.
    """
    out = sys.stdout if out is None else out
    fluid = getattr(args, "fluid", None)
    rated_power = getattr(args, "rated_power", None)
    csv_file, plot_file = getattr(args, "power_curve_csv", None), getattr(args, "power_curve_plot", None)
    given = [name for name in CURVE_OPTIONS if getattr(args, name, None) is not None]
    if rated_power is None and given:
        raise ValueError(f"--{given[0].replace('_', '-')} belongs to the power curve: give it with --rated-power P [W]")
    curve_options = {name: CURVE_DEFAULTS[name] if getattr(args, name, None) is None else getattr(args, name)
                     for name in CURVE_DEFAULTS}
    csv_file = output_file("--power-curve-csv", csv_file)
    plot_file = figure_file("--power-curve-plot", plot_file)
    result = design_turbine(
        wind_speed=_value(args.wind_speed), tip_speed_ratio=_value(args.tip_speed_ratio),
        rpm=_value(args.turbine_rpm), radius=_shared(args, "radius"),
        hub_radius_ratio=_shared(args, "hub_radius_ratio"),
        ref_radius_ratio=_shared(args, "ref_radius_ratio"),
        num_blades=getattr(args, "num_blades", 3), airfoil=airfoil_polar("--airfoil", getattr(args, "airfoil",
                                                                                              "naca4412")),
        loss_model=getattr(args, "loss_model", "tip_hub"), num_radial=getattr(args, "num_radial", 30),
        thrust=_value(getattr(args, "thrust", None)), ref_chord=_value(getattr(args, "ref_chord", None)),
        altitude=_value(getattr(args, "altitude", 0.0)) or 0.0,
        fluid=None if fluid is None else fluid_from_text(fluid))
    designs = [result[i] for i in range(len(result))] if result.is_batch else [result]
    texts = [design.summary() for design in designs]
    if rated_power is not None:
        curves = result.power_curve(rated_power, max_tip_speed=args.max_tip_speed, **curve_options)
        one = [curves[i] for i in range(len(curves))] if curves.is_batch else [curves]
        texts = [text for pair in zip(texts, (curve.summary() for curve in one)) for text in pair]
    print("\n\n".join(texts), file=out)
    if csv_file:
        curves.to_csv(csv_file)
        print(f"wrote {csv_file}", file=out)
    if plot_file:
        from bild_mdo.plots import plot_power_curve

        plot_power_curve(curves, plot_file)
        print(f"wrote {plot_file}", file=out)
    return 0
