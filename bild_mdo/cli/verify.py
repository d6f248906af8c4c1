"""``bild-mdo verify``: the verification sweep of paper Sec. 5.1 and its Table 3.

:func:`add_verify_arguments` adds the options to the subcommand's parser and
:func:`run_verify` runs the sweep (or resumes it from its SQLite store),
prints the Table 3 reproduction and writes Figs. 4-5 on request.
"""
from __future__ import annotations

import os
import sys
import tempfile

from bild_mdo.cli.files import AIRFOIL_HELP
from bild_mdo.io.airfoil import airfoil_text
from bild_mdo.optimization.problem import OPTIMIZERS
from bild_mdo.plots.verification import require_matplotlib, save_figures
from bild_mdo.utils.cpus import available_cpus
from bild_mdo.airfoil.text import DEFAULT_AIRFOIL, sweep_polar
from bild_mdo.bild.annulus_stationarity import IDEAL_LOADINGS
from bild_mdo.verification.case_functions import bild_batch, optimize_case, optimize_cases, require_optimizer
from bild_mdo.verification.cases import START_KINDS, SweepSpec, check_workers
from bild_mdo.verification.executors import check_scheduler_address
from bild_mdo.verification.runner import (DEFAULT_CHUNK_SIZE, default_db_path, run_sweep, sweep_summary,
                                          verification_table)
from bild_mdo.verification.statistics import format_table3
from bild_mdo.verification.store import ResultsStore
from bild_mdo.verification.turbine_sweep import (TurbineSweepSpec, optimize_turbine_case, optimize_turbine_cases,
                                                 turbine_bild_batch)
from bild_mdo.verification.store_file import check_store_path

#: What the table's rows mean in a turbine sweep (:mod:`bild_mdo.verification.turbine_sweep`).
TURBINE_TABLE_NOTE = ("Turbine sweep: C_T = T/(rho A V^2/2), C_Q = Q/(rho A V^2 R/2), C_P = P/(rho A V^3/2), "
                      "eta = P/(V T), energy E = V T - P (both methods minimise it at the thrust: the most power); "
                      "FM is not defined.")

#: What each optimiser beyond SciPy's SLSQP needs, and how to get it.
INSTALL_HINTS = {
    "ipopt": ("cyipopt", "pip install cyipopt (or conda install -c conda-forge cyipopt)"),
    "snopt": ("pyOptSparse built with SNOPT (a commercial licence)",
              "build pyOptSparse (https://github.com/mdolab/pyoptsparse) with your licensed SNOPT source"),
}

#: One-line help of the subcommand.
HELP = "verification sweep against BEM optimisation (paper Table 3)"
#: Description of the subcommand.
DESCRIPTION = (
    "Reproduce the paper's verification (Sec. 5.1, Table 3): a full-factorial sweep of advance ratio J "
    "(0 ... 3) [-], tip radius (0.5 ... 1.5 m), altitude (0 ... 3000 m) and reference chord (0.08 ... 0.22 m) "
    "at 800 rpm and r_ref/R = 0.5, designing every case with BILD in one batch and optimising each with BEM; "
    "prints the Table 3 statistics.  Results go to an SQLite store that a rerun resumes.")


def add_verify_arguments(parser):
    """Add the ``verify`` options to an argparse parser.

    Options: ``--levels``, ``--workers``, ``--scheduler``, ``--db``,
    ``--optimizer``, ``--airfoil``, ``--section-point``, ``--ideal-loading``,
    ``--starts``, ``--turbine``, ``--figures``, ``--no-progress``, ``--chunk-size``.

    Parameters
    ----------
    parser : argparse.ArgumentParser

    Returns
    -------
    argparse.ArgumentParser
        The same parser.
    """
    parser.add_argument("--levels", type=int, default=10,
                        help="levels per swept axis (J, R, altitude, c_ref), 2 to 15; 10 gives the paper's 10,000 cases")
    parser.add_argument("--workers", type=int, default=available_cpus(),
                        help="local worker processes for the optimisations (1 = in this process; default: the CPUs "
                             "this process may use)")
    parser.add_argument("--scheduler", metavar="ADDR", default=None,
                        help="Dask scheduler address, e.g. tcp://host:8786 (needs bild-mdo[dask]); overrides --workers")
    parser.add_argument("--db", metavar="FILE", default=None,
                        help="SQLite results store; an existing store of the same sweep is resumed (damaged rows "
                             "are recomputed); one sweep writes to a file at a time "
                             "(default: bild-verify-L<levels>-<optimizer>.sqlite)")
    parser.add_argument("--optimizer", choices=OPTIMIZERS, default="slsqp",
                        help="optimiser of the reference BEM optimisation (default: slsqp)")
    parser.add_argument("--airfoil", default=DEFAULT_AIRFOIL, metavar="AIRFOIL",
                        help=AIRFOIL_HELP.replace(", a polar file written next to a geometry file (NAME.polar.json)",
                                                  "")
                        + "; stored as written and part of the sweep's fingerprint (a relative path: rerun from "
                          "the same folder); the default is the paper's NACA 4412")
    parser.add_argument("--section-point", default="reference", choices=("reference", "local"),
                        help="BILD's section point: 'reference' (the paper's: the max-L/D point at the reference "
                             "station everywhere) or 'local' (each station's own point for its Reynolds number, "
                             "from the airfoil's load-path table); part of the sweep's fingerprint "
                             "(default: reference)")
    parser.add_argument("--ideal-loading", default="paper", choices=IDEAL_LOADINGS,
                        help="BILD's ideal loading: 'paper' (Eq. (22), without the derivative of Prandtl's F) or "
                             "'exact' (each annulus makes E - lambda T stationary with Prandtl's F kept: the BEM "
                             "optimum for a Reynolds-independent polar; with --section-point local each station's "
                             "cd/cl follows its own load too); part of the sweep's fingerprint (default: paper)")
    parser.add_argument("--starts", type=int, default=1, metavar="N",
                        help=f"optimiser starts per case, 1 to {len(START_KINDS)}: BILD at the section point, BILD at "
                             "the other section point (same ideal loading), a linear "
                             "chord/twist; the lowest-energy converged optimum is the reference and the spread "
                             "between the starts is reported; part of the sweep's fingerprint (default: 1)")
    parser.add_argument("--turbine", action="store_true",
                        help="the turbine verification: the turbine BILD against the full-BEM optimum of the most "
                             "power at its thrust, over tip-speed ratio (4 ... 10), radius (2 ... 8 m), altitude "
                             "(0 ... 3000 m) and thrust coefficient (0.4 ... 0.75) at 8 m/s; --starts 1 or 2 "
                             "(BILD, a linear cold start); not with --section-point or --ideal-loading")
    parser.add_argument("--figures", metavar="DIR", default=None,
                        help="write Fig. 4 and Fig. 5 as PNG files into DIR (needs bild-mdo[plot])")
    parser.add_argument("--no-progress", action="store_true", help="no progress report on stderr")
    parser.add_argument("--chunk-size", type=int, default=DEFAULT_CHUNK_SIZE, metavar="N",
                        help="cases per worker task, optimised together in lockstep (one vectorised BEM model; "
                             f"each case as if alone); stored when the task ends (default: {DEFAULT_CHUNK_SIZE})")
    return parser


def run_verify(args, out=None, bild_batch_fn=bild_batch, optimize_fn=optimize_case, optimize_chunk_fn=None):
    """Run the sweep from parsed ``verify`` options and print the Table 3 reproduction.

    Parameters
    ----------
    args : argparse.Namespace
        From a parser set up with :func:`add_verify_arguments`.
    out : file-like, optional
        Where the table goes (stdout by default); progress goes to stderr.
    bild_batch_fn, optimize_fn : callable
        The science of the sweep (see :func:`~bild_mdo.verification.runner.run_sweep`);
        the batched BILD design and the BEM optimisation of
        :mod:`~bild_mdo.verification.case_functions` by default.
    optimize_chunk_fn : callable, optional
        Optimises chunks of cases (``run_sweep``'s ``optimize_chunk_fn``);
        with the default ``optimize_fn``, the lockstep
        :func:`~bild_mdo.verification.case_functions.optimize_cases`.

    Returns
    -------
    int
        Exit code, 0.

    Raises
    ------
    ValueError
        Before any work and before the store file exists: ``--levels``
        outside 2 ... 15 (the message gives the estimated memory and time),
        ``--workers`` below 1, an ``--airfoil`` that names no airfoil, a
        ``--section-point`` other than reference/local, an ``--ideal-loading``
        other than paper/exact, ``--starts`` outside 1 ... 3, a
        ``--figures`` folder that cannot be written,
        a ``--db`` path that cannot hold a store (``StoreError``).  During the
        sweep: a full disk (``StoreFullError``; the stored rows stay, rerun to
        resume), another sweep writing to the file (``StoreBusyError``), cases
        that could not be set up (``CaseSetupError``; not stored).
    ImportError
        Before any work: the optimiser's package, or matplotlib with ``--figures``, is missing.
    """
    out = sys.stdout if out is None else out
    airfoil = airfoil_text(getattr(args, "airfoil", DEFAULT_AIRFOIL))
    spec = _sweep_spec(args, airfoil)
    turbine = isinstance(spec, TurbineSweepSpec)
    if turbine and bild_batch_fn is bild_batch:
        bild_batch_fn, optimize_fn = turbine_bild_batch, optimize_turbine_case
    if getattr(args, "chunk_size", 1) < 1:
        raise ValueError(f"--chunk-size must be >= 1, got {args.chunk_size}")
    if args.scheduler is None:
        check_workers(args.workers)
    else:
        check_scheduler_address(args.scheduler)
    _require_optimizer(args.optimizer)
    try:
        sweep_polar(airfoil)  # an unknown airfoil stops here, before any file (XFOIL runs once if needed)
    except ValueError as err:
        raise ValueError(f"--airfoil: {err}") from None
    db_path = args.db or default_db_path(spec)
    if args.figures:
        # Fail before hours of computing, not after.
        require_matplotlib()
        _check_figures_folder(args.figures)
    check_store_path(db_path)
    if optimize_chunk_fn is None and optimize_fn in (optimize_case, optimize_turbine_case):
        optimize_chunk_fn = optimize_cases if optimize_fn is optimize_case else optimize_turbine_cases
    run = run_sweep(spec, db_path, bild_batch_fn, optimize_fn, workers=args.workers, scheduler=args.scheduler,
                    progress=not args.no_progress, optimize_chunk_fn=optimize_chunk_fn,
                    chunk_size=getattr(args, "chunk_size", DEFAULT_CHUNK_SIZE))
    with ResultsStore(db_path, spec, writer=False) as store:
        rows = store.rows()
    # The excess line is printed for the settings beyond the paper's, so the paper's output stays as it was.
    beyond_paper = spec.section_point != "reference" or spec.starts > 1 or spec.ideal_loading != "paper"
    table, optimality_error = verification_table(rows, spec.section_point if beyond_paper else None,
                                                 spec.ideal_loading, "turbine" if turbine else "propeller")
    print(sweep_summary(spec, db_path, run), file=out)
    if turbine:
        print(TURBINE_TABLE_NOTE, file=out)
    print(format_table3(table, paper=not turbine), file=out)
    if optimality_error is not None:
        print(f"Optimum is an optimum: not checked, the BEM trim of the BILD designs failed: {optimality_error}",
              file=out)
    if args.figures:
        for path in save_figures(rows, args.figures):
            print(f"wrote {path}", file=out)
    return 0


def _sweep_spec(args, airfoil):
    """The sweep of the options; a bad ``--section-point``, ``--ideal-loading`` or ``--starts`` raises one
    ValueError naming the option."""
    section_point = getattr(args, "section_point", "reference")
    ideal_loading = getattr(args, "ideal_loading", "paper")
    starts = getattr(args, "starts", 1)
    if getattr(args, "turbine", False):
        if section_point != "reference" or ideal_loading != "paper":
            raise ValueError("--turbine designs with the turbine BILD: leave out --section-point and --ideal-loading")
        if starts not in (1, 2):
            raise ValueError(f"--starts must be 1 or 2 with --turbine (BILD, a linear cold start), got {starts}")
        return TurbineSweepSpec(levels=args.levels, optimizer=args.optimizer, airfoil=airfoil, starts=starts)
    if section_point not in ("reference", "local"):
        raise ValueError(f"--section-point must be 'reference' or 'local', got {section_point!r}")
    if ideal_loading not in IDEAL_LOADINGS:
        raise ValueError(f"--ideal-loading must be 'paper' or 'exact', got {ideal_loading!r}")
    if not 1 <= starts <= len(START_KINDS):
        raise ValueError(f"--starts must be an integer from 1 to {len(START_KINDS)} ({', '.join(START_KINDS)}), "
                         f"got {starts}")
    return SweepSpec(levels=args.levels, optimizer=args.optimizer, airfoil=airfoil, section_point=section_point,
                     starts=starts, ideal_loading=ideal_loading)


def _require_optimizer(optimizer):
    try:
        require_optimizer(optimizer)
    except ImportError as exc:
        needs, hint = INSTALL_HINTS.get(optimizer, (str(exc), "install it"))
        raise ImportError(f"--optimizer {optimizer} needs {needs}, which is not importable here: {hint}, "
                          "or use --optimizer slsqp (SciPy, always available)") from None


def _check_figures_folder(folder):
    """Raise ValueError unless ``folder`` is, or can be made as, a folder this process can write in."""
    if os.path.exists(folder) and not os.path.isdir(folder):
        raise ValueError(f"--figures {folder}: it is a file, not a folder")
    try:
        os.makedirs(folder, exist_ok=True)
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError as exc:
        raise ValueError(f"--figures {folder}: cannot write figures there ({exc.strerror or exc})") from None
