import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.bild.geometry import GeometryComp
from bild_mdo.utils.testing import check_component_partials
from tests.bild.conftest import NN, state


def test_partials(kind):
    check_component_partials(GeometryComp(num_nodes=NN), state(kind))


def test_values():
    # Hand derivation: hub = 0.2 * 1.5 m, ref = 0.5 * 1.5 m.
    prob = check_component_partials(GeometryComp(num_nodes=1),
                           dict(radius=[1.5], hub_radius_ratio=[0.2], ref_radius_ratio=[0.5]))
    assert prob.get_val("hub_radius", units="m")[0] == pytest.approx(0.3, rel=1e-15)
    assert prob.get_val("ref_radius", units="m")[0] == pytest.approx(0.75, rel=1e-15)


@pytest.mark.parametrize("hub, ref", [(0.0, 0.5), (0.5, 0.5), (0.6, 0.5), (0.2, 1.0)])
def test_invalid_ratios_raise(hub, ref):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("geometry", GeometryComp(num_nodes=1), promotes=["*"])
    prob.setup()
    prob.set_val("hub_radius_ratio", hub)
    prob.set_val("ref_radius_ratio", ref)
    with pytest.raises(om.AnalysisError, match="0 < hub_radius_ratio < ref_radius_ratio < 1"):
        prob.run_model()


@pytest.mark.parametrize("name, match", [
    ("radius", "radius must be positive and finite"),
    ("hub_radius_ratio", "hub_radius_ratio must be finite"),
    ("ref_radius_ratio", "ref_radius_ratio must be finite"),
])
def test_nan_inputs_raise_naming_the_input(name, match):
    # NaN compares False with everything, so "x <= 0" checks let it through; the message must name the input.
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("geometry", GeometryComp(num_nodes=2), promotes=["*"])
    prob.setup()
    prob.set_val(name, [prob.get_val(name)[0], np.nan])
    with pytest.raises(om.AnalysisError, match=match):
        prob.run_model()
