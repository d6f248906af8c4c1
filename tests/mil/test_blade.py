"""MILBladeComp: partials against complex step."""
import pytest

from bild_mdo.mil.blade import MILBladeComp
from bild_mdo.mil.kernel import LOSS_FORMS
from bild_mdo.utils.testing import check_component_partials

from .conftest import NN, NR, station_values


@pytest.mark.parametrize("loss_form", LOSS_FORMS)
def test_blade_partials(loss_form):
    check_component_partials(MILBladeComp(num_nodes=NN, num_radial=NR, num_blades=3, loss_form=loss_form),
                             station_values(1))
