"""The ``bild-mdo`` command: design rotors with BILD, analyse them off-design, run the verification sweep.

::

    bild-mdo demo                                    # the paper's rotor: tables, geometry files and PNGs
    bild-mdo design                                  # the paper's hover rotor (R = 1.5 m, B = 3, 800 rpm)
    bild-mdo design --advance-ratio 1.0 --csv blade.csv --qprop blade.prop --plot blade.png
    bild-mdo design --ref-chord 0.1 0.15 0.2         # a batch of three designs in one run
    bild-mdo analyze blade.csv --advance-ratio 0 2 21 --plot eta.png
    bild-mdo noise blade.csv --observer -150 0 0 --plot spectrum.png --directivity directivity.png
    bild-mdo verify --levels 3 --workers 2

Each subcommand lives in its own module (:mod:`bild_mdo.cli.design`,
:mod:`~bild_mdo.cli.analyze`, :mod:`~bild_mdo.cli.noise`, :mod:`~bild_mdo.cli.verify`,
:mod:`~bild_mdo.cli.demo`) with its ``HELP``, ``DESCRIPTION``, an
``add_<name>_arguments(parser)`` and a ``run_<name>(args, out)`` returning the
exit code.  Errors in the arguments or from the library (``ValueError``,
``openmdao.api.AnalysisError``, missing files) print one line on stderr and
exit with code 2; ``--debug`` shows the traceback.  An unexpected error (a bug)
is one line too, with exit code 1.  Warnings print as one line each
(``bild-mdo: warning: ...``), once per distinct message, without a source path.
:func:`main` returns the exit code.
"""
from __future__ import annotations

import argparse
import sys
import traceback
import warnings

import openmdao.api as om

from bild_mdo import __version__
from bild_mdo.cli import analyze, compare, demo, design, noise, verify

EXIT_USAGE = 2
#: Exit code of an unexpected error (a bug), reported as one line; ``--debug`` shows the traceback.
EXIT_INTERNAL = 1

#: Subcommand name -> (module, function adding its options, function running it).
COMMANDS = {
    "design": (design, design.add_design_arguments, design.run_design),
    "analyze": (analyze, analyze.add_analyze_arguments, analyze.run_analyze),
    "compare": (compare, compare.add_compare_arguments, compare.run_compare),
    "noise": (noise, noise.add_noise_arguments, noise.run_noise),
    "verify": (verify, verify.add_verify_arguments, verify.run_verify),
    "demo": (demo, demo.add_demo_arguments, demo.run_demo),
}


class UsageError(Exception):
    """A command-line argument error (reported as one line, exit code 2)."""

    def __init__(self, prog, message):
        super().__init__(message)
        self.prog = prog


class _Parser(argparse.ArgumentParser):
    """ArgumentParser that raises instead of printing the usage block and exiting."""

    def error(self, message):
        raise UsageError(self.prog, message)


class _HelpFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """Defaults in the help, except for options whose absence has a meaning the help text explains."""

    def _get_help_string(self, action):
        if action.default is None or isinstance(action.default, bool) or "default" in (action.help or ""):
            return action.help
        return super()._get_help_string(action)


def _add_debug(parser, top_level=False):
    # On subcommands the default is SUPPRESS so a --debug given before the subcommand survives.
    parser.add_argument("--debug", action="store_true", default=False if top_level else argparse.SUPPRESS,
                        help="show the full traceback when an error occurs")


def build_parser():
    """The ``bild-mdo`` argument parser (subcommands design, analyze, compare, noise, verify, demo).

    Returns
    -------
    argparse.ArgumentParser
    """
    parser = _Parser(prog="bild-mdo", formatter_class=_HelpFormatter,
                     description="BILD: fast ideal-loading design of rotors with BEM theory (Ruh & Hwang, "
                                 "AIAA J. 61(9), 2023).  SI units: m, m/s, N, W; rotor speed in rpm.")
    parser.add_argument("--version", action="version", version=f"bild-mdo {__version__}")
    _add_debug(parser, top_level=True)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", title="commands")
    for name, (module, add_arguments, run) in COMMANDS.items():
        command = sub.add_parser(name, formatter_class=_HelpFormatter, help=module.HELP,
                                 description=module.DESCRIPTION)
        add_arguments(command)
        _add_debug(command)
        command.set_defaults(handler=run)
    return parser


def _one_line(text):
    return " ".join(str(text).split())


class _WarningDisplay:
    """``warnings.showwarning`` of the command: one line per distinct message, no source path or code line."""

    def __init__(self):
        self.seen = set()

    def __call__(self, message, category, filename, lineno, file=None, line=None):
        text = _one_line(message)
        if text in self.seen:
            return
        self.seen.add(text)
        print(f"bild-mdo: warning: {text}", file=sys.stderr if file is None else file)


def main(argv=None):
    """Run the ``bild-mdo`` command.

    Parameters
    ----------
    argv : list of str, optional
        Arguments without the program name (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit code: 0 on success, 2 for bad arguments or a failed analysis, 1 for an unexpected
        error (a bug, reported as one line).
    """
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except UsageError as err:
        print(f"{err.prog}: error: {_one_line(err)} (see '{err.prog} --help')", file=sys.stderr)
        return EXIT_USAGE
    except SystemExit as done:  # --help and --version
        return done.code if isinstance(done.code, int) else 0
    if args.command is None:
        print("bild-mdo: error: give a command: design, analyze, verify or demo (see 'bild-mdo --help')",
              file=sys.stderr)
        return EXIT_USAGE
    debug = getattr(args, "debug", False)
    try:
        with warnings.catch_warnings():
            if not debug:
                warnings.showwarning = _WarningDisplay()
            return args.handler(args, sys.stdout)
    except (ValueError, om.AnalysisError, OSError, ImportError) as err:
        if debug:
            traceback.print_exc()
        print(f"bild-mdo {args.command}: error: {_one_line(err)}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        print("bild-mdo: interrupted", file=sys.stderr)
        return 130
    except MemoryError:
        if debug:
            traceback.print_exc()
        print(f"bild-mdo {args.command}: error: out of memory; use fewer designs, points or stations",
              file=sys.stderr)
        return EXIT_USAGE
    except Exception as err:  # noqa: BLE001 - a bug: still one line, the traceback with --debug
        if debug:
            raise
        print(f"bild-mdo {args.command}: internal error: {type(err).__name__}: {_one_line(err)} (rerun with "
              "--debug for the traceback and report it)", file=sys.stderr)
        return EXIT_INTERNAL


if __name__ == "__main__":
    sys.exit(main())
