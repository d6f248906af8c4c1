"""Deterministic stand-ins for the BILD model and the BEM optimisation.

Module-level (picklable) so they run in worker processes and on Dask workers.
The numbers are simple functions of the case inputs; only their determinism
and their failure pattern matter to the tests:

- ``optimize`` raises for ``case_id % 11 == 4`` and reports not converged for
  ``case_id % 7 == 3``;
- ``optimize_crashing`` kills its own worker process for the ids it is given.
"""
import os
import time

import numpy as np

RAISE_MOD, RAISE_REM = 11, 4
NOT_CONVERGED_MOD, NOT_CONVERGED_REM = 7, 3


def bild_batch(cases):
    """Vectorised stand-in BILD: one dict per case."""
    j = np.array([c.inputs["advance_ratio"] for c in cases])
    radius = np.array([c.inputs["radius"] for c in cases])
    chord_ref = np.array([c.inputs["reference_chord"] for c in cases])
    nr = cases[0].inputs["num_radial"] if cases else 0
    ct = 0.05 + 0.1 * j + chord_ref / radius
    cp = ct * (1.0 + j) + 0.01
    cq = cp / (2.0 * np.pi)  # C_Q = C_P / (2 pi)
    energy_loss = 1000.0 * (1.0 + radius) * (1.0 + j)
    shape = np.linspace(1.2, 0.6, nr)
    out = []
    for k, case in enumerate(cases):
        hover = j[k] == 0.0
        out.append({
            "thrust_coefficient": ct[k],
            "torque_coefficient": cq[k],
            "power_coefficient": cp[k],
            "efficiency": None if hover else j[k] * ct[k] / cp[k],  # eta = J C_T / C_P
            "figure_of_merit": ct[k] ** 1.5 / (np.sqrt(2.0) * cp[k]) if hover else None,
            "energy_loss": energy_loss[k],
            "chord": chord_ref[k] * shape,
            "twist": np.linspace(0.6, 0.1, nr) * (1.0 + 0.1 * j[k]),
            "thrust_target": ct[k],
        })
    return out


def optimize(case, bild_result, sleep=0.0):
    """Stand-in optimisation: BILD values perturbed by a case-dependent amount."""
    if sleep:
        time.sleep(sleep)
    cid = case.case_id
    if cid % RAISE_MOD == RAISE_REM:
        raise ValueError(f"stand-in failure in case {cid}")
    factor = 1.0 + 0.001 * (cid % 5)
    result = {}
    for key in ("thrust_coefficient", "torque_coefficient", "power_coefficient", "efficiency",
                "figure_of_merit", "energy_loss"):
        value = bild_result[key]
        result[key] = None if value is None else value * factor
    result["thrust_coefficient"] = bild_result["thrust_target"]
    result["chord"] = np.asarray(bild_result["chord"]) * factor
    result["twist"] = np.asarray(bild_result["twist"]) / factor
    converged = cid % NOT_CONVERGED_MOD != NOT_CONVERGED_REM
    result.update(converged=converged, status="optimal" if converged else "stand-in: iteration limit",
                  iterations=10 + cid % 13)
    return result


def optimize_crashing(case, bild_result, crash_ids=()):
    """Like ``optimize`` but the worker process dies (as in a segfault) for ``crash_ids``."""
    if case.case_id in crash_ids:
        os._exit(3)
    return optimize(case, bild_result)


def sleep_echo(task):
    """``task = (value, seconds)``: sleep, then return the value."""
    time.sleep(task[1])
    return task[0]


def thread_setting(task):
    """The worker's ``BILD_MDO_NUM_THREADS`` (None where unset)."""
    return os.environ.get("BILD_MDO_NUM_THREADS")


def echo_after_file(task):
    """``task = (value, wait_for, create)``: wait until file ``wait_for`` exists (if given), create
    file ``create`` (if given), then return the value.  Orders two workers without timing assumptions."""
    value, wait_for, create = task
    if wait_for is not None:
        deadline = time.monotonic() + 60.0
        while not os.path.exists(wait_for):
            if time.monotonic() > deadline:
                raise TimeoutError(f"{wait_for} never appeared")
            time.sleep(0.01)
    if create is not None:
        open(create, "w").close()
    return value


def optimize_warning(case, bild_result):
    """Like ``optimize`` but warns first, as the polar's Reynolds clamp does, with numbers that vary by case."""
    import warnings

    warnings.warn(f"stand-in clamp (seen {case.case_id}..{case.case_id + 0.5})", UserWarning)
    return optimize(case, bild_result)


def optimize_setup_error(case, bild_result, missing_ids=()):
    """Like ``optimize`` but the optimiser's package is missing for ``missing_ids``."""
    if case.case_id in missing_ids:
        raise ImportError("stand-in optimiser package is not installed")
    return optimize(case, bild_result)


def optimize_chunk(payloads, missing_ids=()):
    """Chunk stand-in: ``optimize`` per case, its exception (or ImportError for ``missing_ids``) in its place."""
    out = []
    for case, bild_result in payloads:
        try:
            out.append(optimize_setup_error(case, bild_result, missing_ids))
        except Exception as exc:
            out.append(exc)
    return out
