"""The outcome of one BEM optimisation, and what every optimiser path shares to produce it."""
from __future__ import annotations

import contextlib
import dataclasses

import numpy as np

from bild_mdo.bem.flow_states import FLOW_STATE_NAMES, INVALID_STATES
from bild_mdo.bem.metrics import PERFORMANCE_OUTPUTS

#: Relative thrust-constraint violation above which a run counts as not converged.
THRUST_TOLERANCE = 1.0e-6

#: Performance quantities reported in :class:`OptimizationResult`.
RESULT_QUANTITIES = tuple(PERFORMANCE_OUTPUTS)

#: Start of the status of a run ended by a BEM analysis that failed (om.AnalysisError).
ANALYSIS_FAILED = "BEM analysis failed at a trial point"

_BLAS_THREADS = []


def single_threaded_blas():
    """Context limiting BLAS to one thread, when threadpoolctl is installed.

    SciPy's SLSQP calls BLAS on small dense matrices; OpenBLAS's extra threads
    then busy-wait and double the CPU time of every optimisation, which slows
    a sweep that already runs one process per core.

    Returns
    -------
    contextlib.AbstractContextManager
    """
    if not _BLAS_THREADS:
        try:
            from threadpoolctl import ThreadpoolController
        except ImportError:
            _BLAS_THREADS.append(None)
        else:
            _BLAS_THREADS.append(ThreadpoolController())
    controller = _BLAS_THREADS[0]
    if controller is None:
        return contextlib.nullcontext()
    return controller.limit(limits=1, user_api="blas")


@dataclasses.dataclass
class OptimizationResult:
    """Outcome of :func:`run_optimization` and :func:`optimize_rotor`.

    Attributes
    ----------
    converged : bool
        The optimiser reports success and ``|T/T* - 1| <= THRUST_TOLERANCE``.
    status : str
        The optimiser's exit message.
    iterations : int
        Major iterations of the optimiser.
    model_evaluations : int
        Model evaluations by the driver (OpenMDAO ``iter_count``).
    wall_time : float
        Time of the scaling step and the driver run (s), without set-up.
    setup_time : float
        Time to build and set up the problem (s); 0 when a problem was reused.
    chord, twist : ndarray, shape (nr,)
        Optimal geometry at the stations (m, rad).
    performance : dict
        Per-design BEM outputs at the optimum (float), one per entry of
        :data:`bild_mdo.bem.metrics.METRICS`: ``thrust`` (N), ``torque``
        (N m), ``power`` (W), ``efficiency``, ``energy_loss`` (W), ...
    thrust_error : float
        ``T/T* - 1`` at the optimum.
    optimizer : str
        Optimiser name.
    flow_state : ndarray of int, shape (nr,)
        Flow-state code of every station at the optimum (:mod:`bild_mdo.bem.flow_states`).
    invalid_stations : int
        Stations of the optimum in a flow state the momentum model does not
        represent (:data:`~bild_mdo.bem.flow_states.INVALID_STATES`).  The
        optimisation ignores such states at its trial points; a converged
        optimum with ``invalid_stations > 0`` is reported (``status`` says so)
        but not trusted by :attr:`flow_valid`.
    """

    converged: bool
    status: str
    iterations: int
    model_evaluations: int
    wall_time: float
    setup_time: float
    chord: np.ndarray
    twist: np.ndarray
    performance: dict
    thrust_error: float
    optimizer: str
    flow_state: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0, dtype=int))
    invalid_stations: int = 0

    @property
    def flow_valid(self):
        """True when every station of the optimum is in a valid flow state."""
        return self.invalid_stations == 0


def invalid_flow_text(flow_state):
    """One phrase on the stations of a design in an invalid flow state, e.g. ``'2 of 30 stations ... (4: ...)'``.

    Parameters
    ----------
    flow_state : array_like of int, shape (nr,)
        Flow-state codes of :mod:`bild_mdo.bem.flow_states`.

    Returns
    -------
    str
    """
    flow_state = np.asarray(flow_state, dtype=int)
    bad = np.flatnonzero(np.isin(flow_state, INVALID_STATES))
    names = sorted({FLOW_STATE_NAMES[int(code)] for code in flow_state[bad]})
    return (f"{bad.size} of {flow_state.size} stations in an invalid BEM flow state at the optimum "
            f"({', '.join(names)}; stations {bad.tolist()})")


def count_invalid(flow_state):
    """Stations of a design in an invalid flow state (:data:`~bild_mdo.bem.flow_states.INVALID_STATES`)."""
    return int(np.isin(flow_state, INVALID_STATES).sum())
