import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.bem.inflow_residual import inflow_residual_value
from bild_mdo.bem.prandtl import prandtl_loss
from bild_mdo.bild.variants.reference_point.reference_station import ReferenceStationComp
from bild_mdo.utils.testing import assert_totals_match, check_component_partials
from tests.bild.conftest import NN, state

WRT = ["v_axial", "v_theta_ref", "ref_radius", "ref_chord", "radius", "hub_radius", "cl_star", "cd_star"]


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip", "none"])
def test_partials_solve_and_totals(kind, loss_model):
    values = state(kind)
    prob = check_component_partials(ReferenceStationComp(num_nodes=NN, loss_model=loss_model), values)
    phi = prob.get_val("phi_ref")
    # The state solves Eq. (9) with F at the reference station (fixed cl*, cd*).
    sigma = 3 * values["ref_chord"] / (2 * np.pi * values["ref_radius"])
    loss = prandtl_loss(phi, values["ref_radius"], values["radius"], values["hub_radius"], 3, loss_model)
    res = inflow_residual_value(phi, values["v_axial"], values["v_theta_ref"], sigma, values["cl_star"],
                                values["cd_star"], loss.F)
    assert np.max(np.abs(res)) < 1e-13
    # A thrust-producing root: 0 < phi < pi/2.
    assert np.all((phi > 0) & (phi < 0.5 * np.pi))
    # Totals through solve_linear against complex step through the complex Newton update.
    data = prob.check_totals(of=["phi_ref"], wrt=WRT, method="cs", out_stream=None)
    assert_totals_match(data, atol=1e-10, rtol=1e-10)


def test_negative_axial_velocity_raises():
    values = state("cruise")
    values["v_axial"] = -values["v_axial"]
    with pytest.raises(om.AnalysisError, match="v_axial >= 0"):
        check_component_partials(ReferenceStationComp(num_nodes=NN), values)


def test_one_design_and_the_bracketed_search_give_the_batch_root(kind, monkeypatch):
    # Designs do not interact: one design (run on NumPy scalars) has the root and partials it has in a
    # batch; and the bracketed search, which takes every node the Newton start does not accept, finds the
    # same root (one root in region 1, ReferenceStationComp._solve_region_one).
    from bild_mdo.bild.variants.reference_point import reference_station

    values = state(kind)
    batch = check_component_partials(ReferenceStationComp(num_nodes=NN), values)
    phi = batch.get_val("phi_ref")
    for k in range(NN):
        one = check_component_partials(ReferenceStationComp(num_nodes=1),
                                       {name: np.atleast_1d(value)[[k]] for name, value in values.items()})
        np.testing.assert_allclose(one.get_val("phi_ref"), phi[[k]], rtol=1e-14)
    monkeypatch.setattr(reference_station, "_MAX_PASSES", 0)
    bracketed = check_component_partials(ReferenceStationComp(num_nodes=NN), values)
    np.testing.assert_allclose(bracketed.get_val("phi_ref"), phi, rtol=1e-12)
