"""SpeedRatioComp: partials against complex step; hover is rejected (A&L's method is for forward flight)."""
import openmdao.api as om
import pytest

from bild_mdo.mil.speed_ratio import SpeedRatioComp
from bild_mdo.utils.testing import check_component_partials

from .conftest import NN, NR, station_values


def test_speed_ratio_partials():
    values = station_values()
    values.update(radii=values["radius_fraction"] * values["radius"][:, None],
                  dr=values["width_fraction"] * values["radius"][:, None])
    check_component_partials(SpeedRatioComp(num_nodes=NN, num_radial=NR), values)


def test_speed_ratio_rejects_hover():
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("comp", SpeedRatioComp(num_nodes=2, num_radial=3), promotes=["*"])
    prob.setup()
    prob.set_val("v_axial", [30.0, 0.0])
    with pytest.raises(om.AnalysisError, match="v_axial must be positive.*forward flight"):
        prob.run_model()
