"""Verification sweep of the BILD method against BEM optimisation (paper Sec. 5.1, Table 3).

The sweep machinery (cases, results store, executors, statistics) is
independent of the science: :func:`run_sweep` takes the batched BILD function
and the per-case optimisation function as arguments
(:mod:`~bild_mdo.verification.case_functions` has the real ones).  The
sweep's airfoil is text (:attr:`SweepSpec.airfoil`) that :func:`sweep_polar`
resolves for both methods.  Figs. 4-5 are drawn by
:mod:`bild_mdo.plots.verification`; the ``bild-mdo verify`` command is
:mod:`bild_mdo.cli.verify`.

Importing the package costs nothing: the names below are loaded from their
modules on first use (PEP 562 module ``__getattr__``), so that a light module
such as :mod:`~bild_mdo.verification.statistics`, which every ``bild-mdo`` command
imports, does not pull in the sweep machinery (process pools, tqdm, the
optimisation problem): about 0.1 s of a cold start.
"""
import importlib

# Public name -> the module of this package that defines it.
_EXPORTS = {
    "Case": "cases",
    "CaseSetupError": "cases",
    "SweepSpec": "cases",
    "run_tasks": "executors",
    "BildTrim": "optimality",
    "OptimalityCheck": "optimality",
    "optimality_check": "optimality",
    "trimmed_bild_energy_loss": "optimality",
    "SweepResult": "runner",
    "default_db_path": "runner",
    "format_duration": "runner",
    "optimize_task": "runner",
    "run_sweep": "runner",
    "sweep_summary": "runner",
    "verification_table": "runner",
    "PAPER_TABLE3": "statistics",
    "QuantityStats": "statistics",
    "Table3": "statistics",
    "format_table3": "statistics",
    "table3": "statistics",
    "TurbineSweepSpec": "turbine_sweep",
    "optimize_turbine_cases": "turbine_sweep",
    "turbine_bild_batch": "turbine_sweep",
    "RESULT_KEYS": "store",
    "ResultsStore": "store",
    "StoreError": "store",
    "StoreBusyError": "store",
    "StoreFullError": "store",
}

__all__ = list(_EXPORTS)


def __getattr__(name):
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
