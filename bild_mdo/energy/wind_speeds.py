"""WindSpeedsComp: the wind speeds of the power curve, Gauss-Lobatto nodes of region 2 and region 3.

Region 2 runs from cut-in to the rated wind speed, region 3 from rated to cut-out.  Each region
gets the ``n`` nodes of the Gauss-Lobatto-Legendre rule on its interval, so its end points are
nodes: the power curve holds the cut-in, the rated and the cut-out wind speed, and the energy
integral of each region is exact for polynomials of degree ``2n - 3`` (Abramowitz & Stegun
25.4.32).  The nodes move with the rated wind speed, ``V = a + (b - a) t`` with fixed ``t`` in
``[0, 1]``, so their partials are constants.  The rated point is shared: the curve has
``num_wind_speeds = n2 + n3 - 1`` points, ``n2 = (num_wind_speeds + 1) // 2`` in region 2
(indices ``0 .. n2 - 1``, the last one rated) and the rest in region 3.
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

#: Fewest points of the curve: three per region (cut-in, one interior node, rated; rated, one, cut-out).
MIN_WIND_SPEEDS = 5


def lobatto(n):
    """Gauss-Lobatto-Legendre nodes ``x`` (ascending, ``x[0] = -1``, ``x[-1] = 1``) and weights on ``[-1, 1]``.

    The interior nodes are the roots of ``P'_{n-1}``; the weights are ``2 / (n (n - 1) P_{n-1}(x)**2)``
    (Abramowitz & Stegun 25.4.32).
    """
    if n < 2:
        raise ValueError(f"a Gauss-Lobatto rule needs at least 2 nodes, got {n}")
    basis = np.polynomial.legendre.Legendre.basis(n - 1)
    interior = np.sort(np.real(basis.deriv().roots())) if n > 2 else np.zeros(0)
    x = np.concatenate(([-1.0], interior, [1.0]))
    weights = 2.0 / (n * (n - 1) * basis(x) ** 2)
    return x, weights


def region_sizes(num_wind_speeds):
    """``(n2, n3)``: Lobatto nodes of region 2 and of region 3 (the rated point counted in both)."""
    if num_wind_speeds < MIN_WIND_SPEEDS:
        raise ValueError(f"num_wind_speeds must be at least {MIN_WIND_SPEEDS}, got {num_wind_speeds}")
    n2 = (num_wind_speeds + 1) // 2
    return n2, num_wind_speeds + 1 - n2


def declare_wind_speed_option(options):
    """Declare ``num_wind_speeds`` (points of the power curve, cut-in to cut-out)."""
    options.declare("num_wind_speeds", types=int, default=13, lower=MIN_WIND_SPEEDS,
                    desc="points of the power curve from cut-in to cut-out (Gauss-Lobatto nodes of regions 2 and 3)")


def check_rated_inside(v_in, v_rated, v_out, where):
    """om.AnalysisError unless ``cut_in < rated < cut_out`` at every rotor (real parts)."""
    v_in, v_rated, v_out = (np.real(np.asarray(v)) for v in (v_in, v_rated, v_out))
    limits = ~(v_in < v_out)
    if np.any(limits):
        i = int(np.flatnonzero(limits)[0])
        raise om.AnalysisError(f"{where}: the cut-in speed {v_in[i]:.6g} m/s must be below the cut-out speed "
                               f"{v_out[i]:.6g} m/s (rotor {i})")
    bad = ~((v_in < v_rated) & (v_rated < v_out))
    if np.any(bad):
        i = int(np.flatnonzero(bad)[0])
        above = not v_rated[i] < v_out[i]
        side, fix = (("is not reached below the cut-out speed", "lower the rated power or enlarge the rotor") if above
                     else ("is reached below the cut-in speed", "raise the rated power or shrink the rotor"))
        raise om.AnalysisError(
            f"{where}: at its design tip-speed ratio with zero pitch the rotor's BEM power reaches the rated power "
            f"at {v_rated[i]:.6g} m/s, which {side} (cut-in {v_in[i]:.6g} m/s, cut-out {v_out[i]:.6g} m/s; "
            f"rotor {i}): {fix}")


class WindSpeedsComp(om.ExplicitComponent):
    """The power curve's wind speeds: Gauss-Lobatto nodes on [cut-in, rated] and [rated, cut-out] (module docstring).

    Options
    -------
    num_nodes : int
        Rotors (axis 0).
    num_wind_speeds : int
        Points of the curve (at least 5).

    Inputs
    ------
    cut_in_speed[nn] (m/s), rated_wind_speed[nn] (m/s), cut_out_speed[nn] (m/s)

    Outputs
    -------
    wind_speed[nn, nw] (m/s)
        Ascending; ``wind_speed[:, 0]`` cut-in, ``[:, n2 - 1]`` rated, ``[:, -1]`` cut-out.

    Raises
    ------
    openmdao.api.AnalysisError
        Unless ``cut_in_speed < rated_wind_speed < cut_out_speed``.
    """

    def initialize(self):
        self.options.declare("num_nodes", types=int, default=1, lower=1, desc="rotors (axis 0)")
        declare_wind_speed_option(self.options)

    def setup(self):
        nn, nw = self.options["num_nodes"], self.options["num_wind_speeds"]
        n2, n3 = region_sizes(nw)
        for name, val in (("cut_in_speed", 3.0), ("rated_wind_speed", 11.0), ("cut_out_speed", 25.0)):
            self.add_input(name, val=np.full(nn, val), units="m/s")
        self.add_output("wind_speed", val=np.ones((nn, nw)), units="m/s", desc="wind speeds of the power curve")
        t2 = 0.5 * (lobatto(n2)[0] + 1.0)
        t3 = 0.5 * (lobatto(n3)[0][1:] + 1.0)
        # d V / d (cut-in, rated, cut-out) at each point, the same for every rotor.
        self._weights = {"cut_in_speed": np.concatenate((1.0 - t2, np.zeros(n3 - 1))),
                         "rated_wind_speed": np.concatenate((t2, 1.0 - t3)),
                         "cut_out_speed": np.concatenate((np.zeros(n2), t3))}
        rows, cols = np.arange(nn * nw), np.repeat(np.arange(nn), nw)
        for name, value in self._weights.items():
            self.declare_partials("wind_speed", name, rows=rows, cols=cols, val=np.tile(value, nn))

    def compute(self, inputs, outputs):
        check_rated_inside(inputs["cut_in_speed"], inputs["rated_wind_speed"], inputs["cut_out_speed"], self.msginfo)
        outputs["wind_speed"] = sum(inputs[name][:, None] * value[None, :] for name, value in self._weights.items())
