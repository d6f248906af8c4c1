"""BladeBroadcastComp: the blade at every operating point, exact (constant) partials."""
import numpy as np

from bild_mdo.multipoint import BladeBroadcastComp
from bild_mdo.utils.testing import check_component_partials

NN, NR = 3, 7


def _values():
    rng = np.random.default_rng(13)
    return dict(blade_chord=0.05 + 0.1 * rng.random((1, NR)), blade_twist=0.1 + 0.4 * rng.random((1, NR)),
                blade_radius=[0.8], blade_hub_radius=[0.15])


def test_partials_complex_step():
    check_component_partials(BladeBroadcastComp(num_nodes=NN, num_radial=NR), _values(), atol=1e-12, rtol=1e-12)


def test_every_point_gets_the_blade():
    values = _values()
    prob = check_component_partials(BladeBroadcastComp(num_nodes=NN, num_radial=NR), values)
    np.testing.assert_array_equal(prob.get_val("twist"), np.repeat(values["blade_twist"], NN, axis=0))
    np.testing.assert_array_equal(prob.get_val("chord"), np.repeat(values["blade_chord"], NN, axis=0))
    np.testing.assert_array_equal(prob.get_val("radius"), np.full(NN, 0.8))
    np.testing.assert_array_equal(prob.get_val("hub_radius"), np.full(NN, 0.15))
