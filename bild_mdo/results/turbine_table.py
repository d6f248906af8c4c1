"""Text table of a wind-turbine BEM analysis (:class:`~bild_mdo.bem.analyze_inclined.TurbineBEMResult`).

Turbine-signed columns (:data:`~bild_mdo.bem.metrics.TURBINE_METRICS`): power extracted, C_P, thrust
downwind, C_T, driving torque, C_Q and the tip-speed ratio, one row per operating point, with the
titles and display scales of the registry (kW, kN, kN m).
"""
from __future__ import annotations

import numpy as np

from bild_mdo.bem.metrics import TURBINE_METRICS

#: Columns of the turbine table, in order: metric name -> number format.
TURBINE_COLUMNS = {"tip_speed_ratio": ".3f", "power": ".6g", "power_coefficient": ".4f", "thrust": ".6g",
                   "thrust_coefficient": ".4f", "torque": ".6g", "torque_coefficient": ".5f"}
_BY_NAME = {metric.name: metric for metric in TURBINE_METRICS}


def turbine_table(result, width=12):
    """The operating points of a turbine analysis as a fixed-width text table.

    Parameters
    ----------
    result : TurbineBEMResult
        From ``analyze_rotor(..., rotor_type='turbine')`` (one point or a batch).
    width : int
        Column width (characters).

    Returns
    -------
    str
        A header line and one line per operating point.
    """
    if not all(hasattr(result, name) for name in TURBINE_COLUMNS):
        raise ValueError("turbine_table needs a turbine result: analyze_rotor(..., rotor_type='turbine')")
    columns = {name: np.atleast_1d(np.asarray(getattr(result, name), dtype=float)) * _BY_NAME[name].display_scale
               for name in TURBINE_COLUMNS}
    lines = ["".join(f"{_BY_NAME[name].label:>{width}}" for name in TURBINE_COLUMNS)]
    for row in range(next(iter(columns.values())).size):
        lines.append("".join(f"{columns[name][row]:>{width}{fmt}}" for name, fmt in TURBINE_COLUMNS.items()))
    return "\n".join(lines)
