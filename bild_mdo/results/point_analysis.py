"""The points of an off-design sweep analysed together, the failing ones isolated and reported by reason."""
from __future__ import annotations

import re
import warnings

import numpy as np
import openmdao.api as om

from bild_mdo.bem.flow_states import INVALID_STATES, PROPELLER, BEMStateWarning, describe_invalid
from bild_mdo.bem.metrics import METRICS
from bild_mdo.utils.batches import isolate_failures


def _one_line(message):
    """An error text as one line, without OpenMDAO's component prefix or the sub-run's node number."""
    message = re.sub(r"^'[^']*' <class \w+>: Error calling \w+\(\), ", "", " ".join(str(message).split()))
    return message.replace("node 0, ", "")


def analyze_points(run, count, on_invalid, r_over_r):
    """Analyse every point in one run; isolate points that raise by bisection.

    Returns ``(bem or None, performance, stations, status)``, ``stations`` the
    per-station ``flow_state`` (-1 at failed points) and ``mach`` (NaN there),
    shape ``(count, nr)``.  Stations in invalid flow states are found from
    ``flow_state`` (one run with ``on_invalid='ignore'``): one warning for
    ``'warn'``, failed points for ``'raise'``.
    """
    status = np.full(count, "ok", dtype=object)
    performance = {metric.name: np.full(count, np.nan) for metric in METRICS}
    stations = {"flow_state": np.full((count, r_over_r.shape[1]), -1, dtype=int),
                "mach": np.full((count, r_over_r.shape[1]), np.nan)}
    bem = None
    successes, failures = isolate_failures(lambda points: run(points, "ignore"), np.arange(count), om.AnalysisError)
    for point, err in failures:
        status[point] = _one_line(err)
    for points, result in successes:
        for name, values in stations.items():
            values[points] = np.atleast_2d(getattr(result, name))
        for name, values in performance.items():
            values[points] = getattr(result, name)
        bem = result if points.size == count else None
    flow_state = stations["flow_state"]
    if on_invalid != "ignore":
        invalid = np.flatnonzero(np.any(np.isin(flow_state, INVALID_STATES), axis=1))
        if on_invalid == "warn" and invalid.size:
            warnings.warn(describe_invalid(np.where(flow_state < 0, PROPELLER, flow_state), r_over_r),
                          BEMStateWarning, stacklevel=3)
        elif invalid.size:
            for i in invalid:  # messages only; the analysis ran once for all points
                status[i] = _one_line(describe_invalid(flow_state[i:i + 1], r_over_r[i:i + 1]))
            for values in performance.values():
                values[invalid] = np.nan
            stations["mach"][invalid] = np.nan
            bem = None
    return bem, performance, stations, status
