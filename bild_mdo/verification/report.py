"""What a sweep reports: its store's default name, durations, the one-line summary, Table 3 and the progress bar."""
import os
import re
import sys

import openmdao.api as om

from bild_mdo.airfoil.text import DEFAULT_AIRFOIL
from .optimality import optimality_check
from .statistics import table3


def progress_bar(total, stream):
    """A tqdm bar of the optimisations: redrawn on a terminal, a plain line every 30 s in a log."""
    # Imported here: the command line imports this module for every subcommand, and only a sweep draws a bar.
    from tqdm import tqdm

    stream = sys.stderr if stream is None else stream
    isatty = getattr(stream, "isatty", None)
    tty = bool(isatty and isatty())
    return tqdm(total=total, desc="optimise", unit="case", file=stream, mininterval=0.1 if tty else 30.0,
                ascii=not tty, dynamic_ncols=tty)


def default_db_path(spec):
    """Default results file name of a sweep, in the working directory.

    ``bild-verify-L{levels}-{optimizer}.sqlite`` for the default airfoil,
    ``bild-verify-L{levels}-{optimizer}-{airfoil}.sqlite`` for another one
    (the airfoil text with every run of other characters than letters,
    digits, ``.`` and ``=`` replaced by ``-``, at most 40 characters), so
    that sweeps of different airfoils do not meet in one file; then
    ``-local`` for the local section point, ``-exact`` for the exact ideal
    loading and ``-starts{N}`` for several starts.
    """
    name = f"bild-verify-L{spec.levels}-{spec.optimizer}"
    if spec.airfoil.strip().lower() != DEFAULT_AIRFOIL:
        slug = re.sub(r"[^a-z0-9.=]+", "-", spec.airfoil.strip().lower()).strip("-.")[:40].strip("-.")
        name += f"-{slug or 'airfoil'}"
    if getattr(spec, "section_point", "reference") != "reference":
        name += f"-{spec.section_point}"
    if getattr(spec, "ideal_loading", "paper") != "paper":
        name += f"-{spec.ideal_loading}"
    if getattr(spec, "starts", 1) > 1:
        name += f"-starts{spec.starts}"
    return f"{name}.sqlite"


def format_duration(seconds):
    """Format seconds as ``'42s'``, ``'3m05s'`` or ``'2h07m'``; ``'?'`` when unknown."""
    if seconds is None or seconds != seconds or seconds == float("inf"):
        return "?"
    seconds = int(round(seconds))
    if seconds < 60:
        return f"{seconds}s"
    if seconds < 3600:
        return f"{seconds // 60}m{seconds % 60:02d}s"
    return f"{seconds // 3600}h{(seconds % 3600) // 60:02d}m"


def sweep_summary(spec, db_path, run):
    """One line on what :func:`run_sweep` did: cases resumed, computed, their wall time and failures.

    Parameters
    ----------
    spec : SweepSpec
    db_path : str or os.PathLike
    run : SweepResult

    Returns
    -------
    str
    """
    return (f"Sweep of {spec.num_cases} cases in {os.fspath(db_path)}: {run.num_skipped} resumed, "
            f"{len(run.computed_ids)} computed in {format_duration(run.wall_time)} ({run.num_failed} not converged).")


def verification_table(rows, section_point=None, ideal_loading="paper", rotor_type="propeller"):
    """Table 3 of a results store, with the check that every optimum is an optimum.

    A failed optimality check must not cost the figures of a finished sweep,
    so analysis errors are returned instead of raised.

    Parameters
    ----------
    rows : list of dict
        :meth:`ResultsStore.rows`.
    section_point : str, optional
        BILD's section point of the sweep; when given, the check reports
        BILD's trimmed energy excess over the optimum for it.
    ideal_loading : str
        BILD's ideal loading of the sweep, named in that report when not the paper's.
    rotor_type : {'propeller', 'turbine'}
        The sweep's rotors (a turbine sweep: :mod:`~bild_mdo.verification.turbine_sweep`).

    Returns
    -------
    table : Table3
        With ``table.optimality`` set when the check ran
        (:func:`~bild_mdo.verification.optimality.optimality_check`).
    error : str or None
        Why the check failed, if it did.
    """
    table = table3(rows)
    try:
        table.optimality = optimality_check(rows, section_point=section_point, ideal_loading=ideal_loading,
                                            rotor_type=rotor_type)
    except (om.AnalysisError, ValueError, ArithmeticError) as exc:
        return table, str(exc)
    return table, None
