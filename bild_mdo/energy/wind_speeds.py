"""WindSpeedsComp: the wind speeds of the power curve, Gauss-Lobatto nodes of region 2 and region 3.

Region 2 runs from cut-in to the rated wind speed, region 3 from rated to cut-out.  Each region
gets the ``n`` nodes of the Gauss-Lobatto-Legendre rule on its interval, so its end points are
nodes: the power curve holds the cut-in, the rated and the cut-out wind speed, and the energy
integral of each region is exact for polynomials of degree ``2n - 3`` (Abramowitz & Stegun
25.4.32).  The nodes move with the rated wind speed, ``V = a + (b - a) t`` with fixed ``t`` in
``[0, 1]``, so their partials are constants.  The rated point is shared: the curve has
``num_wind_speeds = n2 + n3 - 1`` points, ``n2 = (num_wind_speeds + 1) // 2`` in region 2
(indices ``0 .. n2 - 1``, the last one rated) and the rest in region 3.

With option ``tip_speed_limit`` region 2 is split where the tip speed ``lambda V`` reaches
``max_tip_speed`` (region 2.5 beyond it: the rotor speed held at its limit, the power still below
rated), ``V_k = min(V_tip,max / lambda, V_r)``: the first ``n2a`` points are the Lobatto nodes of
``[V_in, V_k]``, the next ``n2b - 1`` those of ``[V_k, V_r]`` (``V_k`` shared), so neither
interval's integrand has the kink of the rotor speed inside it (:func:`region2_split`).
``n2a`` is the ``n2`` of the same number of points without the limit, so where the limit is not
reached below rated (``V_k = V_r``; the second interval has length zero, its points repeat the
rated point with no weight) region 2 is integrated on the same nodes as without the limit; region
3, whose energy is rated power's exact integral plus a trim residue, gives up the points.  ``V_k``
depends on ``max_tip_speed`` and ``lambda`` where the limit binds, on ``V_r`` where it does not (a
kink where ``V_tip,max = lambda V_r``).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
import openmdao.api as om

#: Fewest points of the curve: three per region (cut-in, one interior node, rated; rated, one, cut-out).
MIN_WIND_SPEEDS = 5
#: The wind speed where the tip speed reaches ``max_tip_speed`` (region 2.5 begins; at most the rated one).
TIP_SPEED_LIMIT_WIND_SPEED = "tip_speed_limit_wind_speed"


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


def region_sizes(num_wind_speeds, tip_speed_limit=False):
    """``(n2, n3)``: points of region 2 and of region 3 (the rated point counted in both); with
    ``tip_speed_limit`` region 2's two intervals together (:func:`region2_split`)."""
    if num_wind_speeds < MIN_WIND_SPEEDS:
        raise ValueError(f"num_wind_speeds must be at least {MIN_WIND_SPEEDS}, got {num_wind_speeds}")
    if tip_speed_limit:
        n2a, n2b, n3 = region2_split(num_wind_speeds)
        return n2a + n2b - 1, n3
    n2 = (num_wind_speeds + 1) // 2
    return n2, num_wind_speeds + 1 - n2


def region2_split(num_wind_speeds):
    """``(n2a, n2b, n3)``: Lobatto nodes of ``[V_in, V_k]``, of ``[V_k, V_r]`` and of region 3 with a tip-speed
    limit (``n2a + n2b + n3 - 2 = num_wind_speeds``): ``n2a`` is region 2's ``n2`` without the limit, the rest
    shared between the other two, at least 2 each."""
    n2a = (num_wind_speeds + 1) // 2
    rest = num_wind_speeds + 2 - n2a
    n2b = (rest + 1) // 2
    return n2a, n2b, rest - n2b


class Interval(NamedTuple):
    """One Lobatto rule of the curve: its limits (the names of the wind speeds at its ends), its points
    ``points`` (a slice of the curve, both ends included), their fractions ``t`` of the interval (0 ... 1) and
    their Lobatto weights on ``[-1, 1]``."""

    low: str
    high: str
    points: slice
    t: np.ndarray
    weights: np.ndarray


def curve_intervals(num_wind_speeds, tip_speed_limit=False):
    """The Lobatto rules of the curve in order (module docstring): region 2 (one, or two split at
    :data:`TIP_SPEED_LIMIT_WIND_SPEED` with ``tip_speed_limit``), then region 3; consecutive rules share their
    end point."""
    if tip_speed_limit:
        sizes = region2_split(num_wind_speeds)
        limits = ("cut_in_speed", TIP_SPEED_LIMIT_WIND_SPEED, "rated_wind_speed", "cut_out_speed")
    else:
        sizes = region_sizes(num_wind_speeds)
        limits = ("cut_in_speed", "rated_wind_speed", "cut_out_speed")
    intervals, start = [], 0
    for low, high, n in zip(limits[:-1], limits[1:], sizes):
        x, weights = lobatto(n)
        intervals.append(Interval(low, high, slice(start, start + n), 0.5 * (x + 1.0), weights))
        start += n - 1
    return intervals


def declare_wind_speed_option(options):
    """Declare ``num_wind_speeds`` (points of the power curve, cut-in to cut-out)."""
    options.declare("num_wind_speeds", types=int, default=13, lower=MIN_WIND_SPEEDS,
                    desc="points of the power curve from cut-in to cut-out (Gauss-Lobatto nodes of regions 2 and 3)")


def declare_tip_speed_limit_option(options):
    """Declare ``tip_speed_limit`` (hold the rotor speed at ``max_tip_speed``: region 2.5)."""
    options.declare("tip_speed_limit", types=bool, default=False,
                    desc="hold the rotor speed where the tip speed reaches input max_tip_speed (region 2.5)")


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
            f"{where}: at its design tip-speed ratio (up to any tip-speed limit) with zero pitch the rotor's BEM "
            "power reaches the rated power "
            f"at {v_rated[i]:.6g} m/s, which {side} (cut-in {v_in[i]:.6g} m/s, cut-out {v_out[i]:.6g} m/s; "
            f"rotor {i}): {fix}")


_KNEE = TIP_SPEED_LIMIT_WIND_SPEED


class WindSpeedsComp(om.ExplicitComponent):
    """The power curve's wind speeds: Gauss-Lobatto nodes on [cut-in, rated] and [rated, cut-out] (module docstring).

    Options
    -------
    num_nodes : int
        Rotors (axis 0).
    num_wind_speeds : int
        Points of the curve (at least 5).
    tip_speed_limit : bool
        False (default); True: region 2 in two intervals split where the tip speed reaches ``max_tip_speed``.

    Inputs
    ------
    cut_in_speed[nn] (m/s), rated_wind_speed[nn] (m/s), cut_out_speed[nn] (m/s);
    max_tip_speed[nn] (m/s), tip_speed_ratio[nn] (-) (``tip_speed_limit``)

    Outputs
    -------
    wind_speed[nn, nw] (m/s)
        Ascending; ``wind_speed[:, 0]`` cut-in, ``[:, n2 - 1]`` rated, ``[:, -1]`` cut-out.
    tip_speed_limit_wind_speed[nn] (m/s) (``tip_speed_limit``)
        ``V_k = min(max_tip_speed / tip_speed_ratio, rated_wind_speed)``: where region 2.5 begins (the rated
        wind speed where the limit is not reached below it); ``wind_speed[:, n2a - 1]``
        (:func:`region2_split`).

    Raises
    ------
    openmdao.api.AnalysisError
        Unless ``cut_in_speed < rated_wind_speed < cut_out_speed``, and, with the limit, unless the tip speed
        reaches it above cut-in.
    """

    def initialize(self):
        self.options.declare("num_nodes", types=int, default=1, lower=1, desc="rotors (axis 0)")
        declare_wind_speed_option(self.options)
        declare_tip_speed_limit_option(self.options)

    def setup(self):
        nn, nw = self.options["num_nodes"], self.options["num_wind_speeds"]
        limited = self.options["tip_speed_limit"]
        for name, val in (("cut_in_speed", 3.0), ("rated_wind_speed", 11.0), ("cut_out_speed", 25.0)):
            self.add_input(name, val=np.full(nn, val), units="m/s")
        self.add_output("wind_speed", val=np.ones((nn, nw)), units="m/s", desc="wind speeds of the power curve")
        # d V / d (each limit) at each point, the same for every rotor: a point shared by two rules is the first
        # one's (the end of one rule, the start of the next).
        self._weights = {}
        for k, interval in enumerate(curve_intervals(nw, limited)):
            first = 0 if k == 0 else 1
            owned = np.arange(interval.points.start + first, interval.points.stop)
            t = interval.t[first:]
            for name, share in ((interval.low, 1.0 - t), (interval.high, t)):
                self._weights.setdefault(name, np.zeros(nw))[owned] += share
        rows, cols = np.arange(nn * nw), np.repeat(np.arange(nn), nw)
        if limited:
            self.add_input("max_tip_speed", val=np.full(nn, 80.0), units="m/s", desc="largest tip speed Omega R")
            self.add_input("tip_speed_ratio", val=np.full(nn, 7.0), units=None, desc="design tip-speed ratio")
            self.add_output(_KNEE, val=np.full(nn, 11.0), units="m/s",
                            desc="wind speed where the tip speed reaches max_tip_speed (at most the rated one)")
            node = np.arange(nn)
            self.declare_partials(_KNEE, ["max_tip_speed", "tip_speed_ratio", "rated_wind_speed"], rows=node, cols=node)
            for name in ("cut_in_speed", "cut_out_speed"):
                self.declare_partials("wind_speed", name, rows=rows, cols=cols, val=np.tile(self._weights[name], nn))
            self.declare_partials("wind_speed", "rated_wind_speed", rows=rows, cols=cols)
            # Only the points of region 2 move with V_k.
            self._knee_points = np.flatnonzero(self._weights[_KNEE])
            knee_rows = (np.arange(nn)[:, None] * nw + self._knee_points[None, :]).ravel()
            self.declare_partials("wind_speed", ["max_tip_speed", "tip_speed_ratio"], rows=knee_rows,
                                  cols=np.repeat(np.arange(nn), self._knee_points.size))
        else:
            for name, value in self._weights.items():
                self.declare_partials("wind_speed", name, rows=rows, cols=cols, val=np.tile(value, nn))

    def _knee(self, inputs):
        """``V_k`` and whether the limit binds (real parts); AnalysisError where it binds at or below cut-in."""
        reached = inputs["max_tip_speed"] / inputs["tip_speed_ratio"]
        binds = np.real(reached) < np.real(inputs["rated_wind_speed"])
        early = ~(np.real(reached) > np.real(inputs["cut_in_speed"]))
        if np.any(early):
            i = int(np.flatnonzero(early)[0])
            raise om.AnalysisError(
                f"{self.msginfo}: the tip speed reaches max_tip_speed {np.real(inputs['max_tip_speed'][i]):.6g} m/s "
                f"at {np.real(reached[i]):.6g} m/s, not above the cut-in speed "
                f"{np.real(inputs['cut_in_speed'][i]):.6g} m/s (rotor {i}): raise max_tip_speed or lower the "
                "tip-speed ratio")
        return np.where(binds, reached, inputs["rated_wind_speed"]), binds

    def compute(self, inputs, outputs):
        check_rated_inside(inputs["cut_in_speed"], inputs["rated_wind_speed"], inputs["cut_out_speed"], self.msginfo)
        limits = {name: inputs[name] for name in ("cut_in_speed", "rated_wind_speed", "cut_out_speed")}
        if self.options["tip_speed_limit"]:
            limits[_KNEE], _ = self._knee(inputs)
            outputs[_KNEE] = limits[_KNEE]
        outputs["wind_speed"] = sum(limits[name][:, None] * value[None, :] for name, value in self._weights.items())

    def compute_partials(self, inputs, partials):
        if not self.options["tip_speed_limit"]:
            return
        _, binds = self._knee(inputs)
        tsr = inputs["tip_speed_ratio"]
        d_knee = {"max_tip_speed": np.where(binds, 1.0 / tsr, 0.0),
                  "tip_speed_ratio": np.where(binds, -inputs["max_tip_speed"] / tsr ** 2, 0.0),
                  "rated_wind_speed": np.where(binds, 0.0, 1.0)}
        for name, value in d_knee.items():
            partials[_KNEE, name] = value
            if name == "rated_wind_speed":
                partials["wind_speed", name] = (self._weights["rated_wind_speed"][None, :]
                                                + value[:, None] * self._weights[_KNEE][None, :]).ravel()
            else:
                partials["wind_speed", name] = (value[:, None] * self._weights[_KNEE][None, self._knee_points]).ravel()
