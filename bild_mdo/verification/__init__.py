"""Verification sweep of the BILD method against BEM optimisation (paper Sec. 5.1, Table 3).

The sweep machinery (cases, results store, executors, statistics) is
independent of the science: :func:`run_sweep` takes the batched BILD function
and the per-case optimisation function as arguments
(:mod:`~bild_mdo.verification.case_functions` has the real ones).  Figs. 4-5
are drawn by :mod:`bild_mdo.plots.verification`; the ``bild-mdo verify``
command is :mod:`bild_mdo.cli.verify`.
"""
from .cases import Case, CaseSetupError, SweepSpec
from .executors import run_tasks
from .optimality import BildTrim, OptimalityCheck, optimality_check, trimmed_bild_energy_loss
from .runner import (
    SweepResult,
    default_db_path,
    format_duration,
    optimize_task,
    run_sweep,
    sweep_summary,
    verification_table,
)
from .statistics import PAPER_TABLE3, QuantityStats, Table3, format_table3, table3
from .store import RESULT_KEYS, ResultsStore, StoreBusyError, StoreError, StoreFullError

__all__ = [
    "Case",
    "CaseSetupError",
    "SweepSpec",
    "run_tasks",
    "BildTrim",
    "OptimalityCheck",
    "optimality_check",
    "trimmed_bild_energy_loss",
    "SweepResult",
    "default_db_path",
    "format_duration",
    "optimize_task",
    "run_sweep",
    "sweep_summary",
    "verification_table",
    "PAPER_TABLE3",
    "QuantityStats",
    "Table3",
    "format_table3",
    "table3",
    "RESULT_KEYS",
    "ResultsStore",
    "StoreError",
    "StoreBusyError",
    "StoreFullError",
]
