"""Verification sweep of the BILD method against BEM optimisation (paper Sec. 5.1, Table 3, Figs. 4-5).

The sweep machinery (cases, results store, executors, statistics, figures) is
independent of the science: :func:`run_sweep` takes the batched BILD function
and the per-case optimisation function as arguments.
"""
from .cases import Case, SweepSpec
from .executors import run_tasks
from .optimality import BildTrim, OptimalityCheck, optimality_check, trimmed_bild_energy_loss
from .progress import ProgressBar
from .runner import (
    SweepResult,
    add_verify_arguments,
    default_db_path,
    optimize_task,
    run_sweep,
    run_verify_from_args,
)
from .statistics import PAPER_TABLE3, QuantityStats, Table3, format_table3, table3
from .store import RESULT_KEYS, ResultsStore, StoreError

__all__ = [
    "Case",
    "SweepSpec",
    "run_tasks",
    "BildTrim",
    "OptimalityCheck",
    "optimality_check",
    "trimmed_bild_energy_loss",
    "ProgressBar",
    "SweepResult",
    "add_verify_arguments",
    "default_db_path",
    "optimize_task",
    "run_sweep",
    "run_verify_from_args",
    "PAPER_TABLE3",
    "QuantityStats",
    "Table3",
    "format_table3",
    "table3",
    "RESULT_KEYS",
    "ResultsStore",
    "StoreError",
]
