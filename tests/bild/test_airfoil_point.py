"""The airfoil point per station (a polar that varies along the span) in the four BILD components that read it."""
import numpy as np
import pytest

from bild_mdo.bild.chord import ChordComp
from bild_mdo.bild.variants.paper.eta2 import Eta2Comp
from bild_mdo.bild.induced_velocity import InducedVelocityComp
from bild_mdo.bild.inflow_angle import InflowAngleComp
from bild_mdo.utils.testing import check_component_partials
from tests.bild.conftest import NN, NR, state
from tests.bild.test_chord import _consistent
from tests.bild.variants.paper.test_eta2 import component_values

COMPONENTS = {
    "eta2": (Eta2Comp, {}, component_values, ("eta2",)),
    "induced_velocity": (InducedVelocityComp, {}, state, ("u_axial", "u_theta")),
    "inflow_angle": (InflowAngleComp, {}, state, ("phi", "inflow_speed", "twist")),
    "chord_thrust": (ChordComp, {"chord_form": "thrust"}, _consistent, ("chord_raw", "lift_coefficient")),
    "chord_torque": (ChordComp, {"chord_form": "torque"}, _consistent, ("chord_raw", "drag_coefficient")),
}


def _per_station(values):
    """The per-design point spread to every station, then varied along the span by up to +-10 %."""
    spread = np.linspace(-0.1, 0.1, NR)[None, :]
    out = dict(values)
    for name in ("alpha_star", "cl_star", "cd_star"):
        out[name] = values[name][:, None] * (1.0 + (spread if name != "cd_star" else -spread))
    return out


@pytest.mark.parametrize("name", sorted(COMPONENTS))
def test_partials_per_station(kind, name):
    comp, options, values, _ = COMPONENTS[name]
    check_component_partials(comp(num_nodes=NN, num_radial=NR, varies_along_span=True, **options),
                             _per_station(values(kind)))


@pytest.mark.parametrize("name", sorted(COMPONENTS))
def test_uniform_point_per_station_equals_per_design(kind, name):
    # The same point at every station is the per-design case: the shapes change, the numbers do not.
    comp, options, values, outputs = COMPONENTS[name]
    per_design = values(kind)
    per_station = dict(per_design)
    for point in ("alpha_star", "cl_star", "cd_star"):
        per_station[point] = np.repeat(per_design[point][:, None], NR, axis=1)
    a = check_component_partials(comp(num_nodes=NN, num_radial=NR, **options), per_design)
    b = check_component_partials(comp(num_nodes=NN, num_radial=NR, varies_along_span=True, **options),
                                 per_station)
    for output in outputs:
        np.testing.assert_array_equal(b.get_val(output), a.get_val(output))
