"""MILPerformanceComp: partials against complex step."""
import pytest

from bild_mdo.mil.kernel import LOSS_FORMS
from bild_mdo.mil.performance import MILPerformanceComp
from bild_mdo.utils.testing import check_component_partials

from .conftest import NN, NR, station_values


@pytest.mark.parametrize("loss_form", LOSS_FORMS)
def test_performance_partials(loss_form):
    check_component_partials(MILPerformanceComp(num_nodes=NN, num_radial=NR, num_blades=2, loss_form=loss_form),
                             station_values(2))
