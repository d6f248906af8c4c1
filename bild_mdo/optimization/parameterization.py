"""ParameterizationComp: chord and twist distributions from the optimiser's design variables.

Two parameterisations of the blade (paper Sec. 5.1):

``'stations'``
    One chord and one twist value per radial station (30 + 30 design variables
    for the paper's 30 stations, the setup Sec. 5.1 states).
``'bspline'``
    Clamped uniform B-spline control points (default 10 + 10 of order 4, what
    the authors' published scripts use).  The spline's parameter is the
    normalised span ``x = (r - r_hub) / (R - r_hub)`` in [0, 1], so its basis
    at the stations is a constant matrix and the component is linear in the
    control points.

The chord design variables are the chord divided by the tip radius, ``c/R``.
That makes their bounds and scaling the same for rotors of every size, so one
optimisation problem, set up once, serves every case of a sweep.
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.utils.options import declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_node

PARAMETERIZATIONS = ("stations", "bspline")


def station_fractions(num_radial):
    """Normalised span ``x = (r - r_hub)/(R - r_hub)`` of the stations: midpoints of equal annuli.

    Matches the default stations of :class:`~bild_mdo.bem.stations.StationsComp`.

    Parameters
    ----------
    num_radial : int
        Number of stations.

    Returns
    -------
    ndarray, shape (num_radial,)
    """
    return (np.arange(num_radial) + 0.5) / num_radial


def _clamped_knots(num_cp, order):
    """Clamped uniform knot vector on [0, 1] (``num_cp + order`` knots)."""
    if order < 1 or num_cp < order:
        raise ValueError(f"a B-spline of order {order} needs order >= 1 and at least {order} control points, "
                         f"got num_cp={num_cp}")
    interior = np.linspace(0.0, 1.0, num_cp - order + 2)[1:-1]
    return np.concatenate([np.zeros(order), interior, np.ones(order)])


def bspline_matrix(num_cp, num_radial, order=4):
    """Basis of a clamped uniform B-spline evaluated at the stations.

    Parameters
    ----------
    num_cp : int
        Number of control points (``>= order``).
    num_radial : int
        Number of stations.
    order : int
        Spline order (degree + 1); 4 is cubic.

    Returns
    -------
    ndarray, shape (num_radial, num_cp)
        ``values_at_stations = matrix @ control_points``.  Rows sum to one
        (partition of unity) and each row has at most ``order`` non-zeros.

    Raises
    ------
    ValueError
        If ``num_cp < order`` or ``order < 1``.
    """
    # Imported here: scipy.interpolate costs tens of ms, and only the 'bspline' parameterisation needs it.
    from scipy.interpolate import BSpline

    return BSpline.design_matrix(station_fractions(num_radial), _clamped_knots(num_cp, order), order - 1).toarray()


def parameterization_matrix(parameterization, num_radial, num_cp=10, order=4):
    """Matrix ``M`` with ``distribution[nr] = M @ design_values[ncp]``.

    Parameters
    ----------
    parameterization : {'stations', 'bspline'}
        Per-station values (``M`` is the identity) or B-spline control points.
    num_radial : int
        Number of stations.
    num_cp : int
        Number of control points (``'bspline'`` only).
    order : int
        B-spline order (``'bspline'`` only).

    Returns
    -------
    ndarray, shape (num_radial, ncp)
    """
    if parameterization == "stations":
        return np.eye(num_radial)
    if parameterization == "bspline":
        return bspline_matrix(num_cp, num_radial, order)
    raise ValueError(f"parameterization must be one of {PARAMETERIZATIONS}, got {parameterization!r}")


def design_value_fractions(parameterization, num_radial, num_cp=10, order=4):
    """Normalised span position that each design value stands for.

    The station positions for ``'stations'``; the Greville abscissae (knot
    averages) of the control points for ``'bspline'``, where a B-spline takes
    roughly the value of its control point.  Used for position-dependent bounds.

    Returns
    -------
    ndarray, shape (ncp,)
    """
    if parameterization == "stations":
        return station_fractions(num_radial)
    if parameterization != "bspline":
        raise ValueError(f"parameterization must be one of {PARAMETERIZATIONS}, got {parameterization!r}")
    knots = _clamped_knots(num_cp, order)
    # Greville abscissa i: mean of knots i+1 ... i+order-1, as a moving sum.
    sums = np.convolve(knots, np.ones(order - 1), mode="valid")
    return sums[1:num_cp + 1] / (order - 1)


def fit_design_values(matrix, distribution):
    """Least-squares design values that best reproduce given distributions (warm starts).

    Parameters
    ----------
    matrix : ndarray, shape (nr, ncp)
        From :func:`parameterization_matrix`.
    distribution : array_like, shape (nr,) or (nn, nr)
        Target values at the stations.

    Returns
    -------
    ndarray, shape (ncp,) or (nn, ncp)
    """
    dist = np.asarray(distribution, dtype=float)
    sol, *_ = np.linalg.lstsq(matrix, np.atleast_2d(dist).T, rcond=None)
    return sol.T.reshape(dist.shape[:-1] + (matrix.shape[1],))


class ParameterizationComp(om.ExplicitComponent):
    """Chord and twist at the stations from per-station values or B-spline control points.

    ``chord = R * (M @ chord_ratio_cp)`` and ``twist = M @ twist_cp`` node by node,
    with the constant matrix ``M`` of :func:`parameterization_matrix`.  The
    twist partials are constant (declared with ``val=``); the chord partials
    scale with ``R``.

    Options
    -------
    num_nodes, num_radial : int
        Designs (axis 0) and radial stations (axis 1).
    parameterization : {'stations', 'bspline'}
        Design variables per station or B-spline control points.
    num_cp : int
        Number of B-spline control points (ignored for ``'stations'``).
    order : int
        B-spline order, 4 = cubic (ignored for ``'stations'``).

    Inputs
    ------
    chord_ratio_cp[nn, ncp] (-)
        Chord design values divided by the tip radius, c/R.
    twist_cp[nn, ncp] (rad)
        Twist design values.
    radius[nn] (m)
        Rotor tip radius R.

    Outputs
    -------
    chord[nn, nr] (m)
        Chord at the stations.
    twist[nn, nr] (rad)
        Twist at the stations.

    ``ncp`` is ``num_radial`` for ``'stations'`` and ``num_cp`` for ``'bspline'``.
    """

    def initialize(self):
        declare_size_options(self.options)
        self.options.declare("parameterization", default="stations", values=PARAMETERIZATIONS,
                             desc="'stations': one design value per station; 'bspline': B-spline control points")
        self.options.declare("num_cp", types=int, default=10, desc="number of B-spline control points")
        self.options.declare("order", types=int, default=4, desc="B-spline order (degree + 1)")

    @property
    def num_design_values(self):
        """Design values per distribution and node (``ncp``)."""
        if self.options["parameterization"] == "stations":
            return self.options["num_radial"]
        return self.options["num_cp"]

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        ncp = self.num_design_values
        self._matrix = parameterization_matrix(self.options["parameterization"], nr, self.options["num_cp"],
                                               self.options["order"])
        self.add_input("chord_ratio_cp", val=np.full((nn, ncp), 0.1), units=None,
                       desc="chord design values divided by the tip radius, c/R")
        self.add_input("twist_cp", val=np.full((nn, ncp), 0.3), units="rad", desc="twist design values")
        self.add_input("radius", val=np.ones(nn), units="m", desc="rotor tip radius R")
        self.add_output("chord", val=np.full((nn, nr), 0.1), units="m", desc="blade chord at the stations")
        self.add_output("twist", val=np.full((nn, nr), 0.3), units="rad", desc="blade twist at the stations")

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        ncp = self.num_design_values
        # Block-diagonal kron(I_nn, M): only the non-zeros of M, repeated per node.
        row_s, col_c = np.nonzero(self._matrix)
        offsets_r = np.repeat(np.arange(nn) * nr, row_s.size)
        offsets_c = np.repeat(np.arange(nn) * ncp, row_s.size)
        rows = np.tile(row_s, nn) + offsets_r
        cols = np.tile(col_c, nn) + offsets_c
        self._nz_values = self._matrix[row_s, col_c]
        self._nz_rows = row_s
        self.declare_partials("twist", "twist_cp", rows=rows, cols=cols, val=np.tile(self._nz_values, nn))
        self.declare_partials("chord", "chord_ratio_cp", rows=rows, cols=cols)
        rows_n, cols_n = dist_wrt_node(nn, nr)
        self.declare_partials("chord", "radius", rows=rows_n, cols=cols_n)

    def compute(self, inputs, outputs):
        matrix = self._matrix
        outputs["chord"] = inputs["radius"][:, None] * (inputs["chord_ratio_cp"] @ matrix.T)
        outputs["twist"] = inputs["twist_cp"] @ matrix.T

    def compute_partials(self, inputs, partials):
        partials["chord", "chord_ratio_cp"] = np.outer(inputs["radius"], self._nz_values).ravel()
        partials["chord", "radius"] = (inputs["chord_ratio_cp"] @ self._matrix.T).ravel()
