"""ParameterizationComp: partials against complex step, B-spline basis properties, exactness."""
import numpy as np
import pytest

from bild_mdo.optimization.parameterization import (ParameterizationComp, bspline_matrix, fit_design_values,
                                                    parameterization_matrix, station_fractions)
from bild_mdo.utils.testing import check_component_partials

NN, NR = 3, 7


def _problem(parameterization, num_cp):
    comp = ParameterizationComp(num_nodes=NN, num_radial=NR, parameterization=parameterization, num_cp=num_cp)
    ncp = NR if parameterization == "stations" else num_cp
    rng = np.random.default_rng(3)
    values = {"chord_ratio_cp": 0.05 + 0.1 * rng.random((NN, ncp)), "twist_cp": 0.2 + rng.random((NN, ncp)),
              "radius": [0.5, 1.0, 1.5]}
    return check_component_partials(comp, values, atol=1e-12, rtol=1e-12)


@pytest.mark.parametrize("parameterization, num_cp", [("stations", 10), ("bspline", 5)])
def test_partials(parameterization, num_cp):
    _problem(parameterization, num_cp)


def test_stations_are_identity_times_radius():
    prob = _problem("stations", 10)
    # Hand derivation: chord = R * (c/R), twist = twist values, station by station.
    np.testing.assert_allclose(prob.get_val("chord"),
                               prob.get_val("radius")[:, None] * prob.get_val("chord_ratio_cp"), rtol=1e-15)
    np.testing.assert_array_equal(prob.get_val("twist"), prob.get_val("twist_cp"))


def test_bspline_basis_properties():
    matrix = bspline_matrix(10, 30, order=4)
    # B-spline invariants: partition of unity, non-negativity, local support of `order` functions.
    np.testing.assert_allclose(matrix.sum(axis=1), 1.0, rtol=0, atol=1e-14)
    assert matrix.min() >= 0.0
    assert np.count_nonzero(matrix, axis=1).max() <= 4
    # A cubic B-spline reproduces cubics exactly: fit x^3 - x and compare at the stations.
    x = station_fractions(30)
    target = x**3 - x
    np.testing.assert_allclose(matrix @ fit_design_values(matrix, target), target, atol=1e-13)


def test_bspline_needs_enough_control_points():
    with pytest.raises(ValueError, match="at least 4 control points"):
        bspline_matrix(3, 30, order=4)
    with pytest.raises(ValueError, match="parameterization must be one of"):
        parameterization_matrix("polynomial", 30)
