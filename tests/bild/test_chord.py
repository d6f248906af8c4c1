import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.bild.chord import ChordComp
from bild_mdo.bild.induced_velocity import InducedVelocityComp
from bild_mdo.bild.inflow_angle import InflowAngleComp
from bild_mdo.bild.momentum_loads import MomentumLoadsComp
from bild_mdo.utils.testing import check_component_partials
from tests.bild.conftest import NN, NR, state


def _consistent(kind):
    """Loads, inflow angle and speed of an ideal loading (Eqs. (24), (26), (30), (1), (2))."""
    values = state(kind)
    prob = om.Problem(reports=False)
    for name, comp in (("iv", InducedVelocityComp), ("ia", InflowAngleComp), ("sl", MomentumLoadsComp)):
        prob.model.add_subsystem(name, comp(num_nodes=NN, num_radial=NR), promotes=["*"])
    prob.setup()
    for name in ("eta2", "v_axial", "v_theta", "cl_star", "cd_star", "alpha_star", "radii", "rho", "rpm",
                 "radius", "hub_radius"):
        prob.set_val(name, values[name])
    prob.run_model()
    for name in ("phi", "inflow_speed", "dthrust_dr", "dtorque_dr"):
        values[name] = prob.get_val(name)
    return values


@pytest.mark.parametrize("form", ["thrust", "torque"])
def test_partials(kind, form):
    check_component_partials(ChordComp(num_nodes=NN, num_radial=NR, chord_form=form), _consistent(kind))


def test_thrust_and_torque_forms_agree(kind):
    # Eq. (25) holds for the ideal induced velocities, so Eq. (31) and the torque form of Eq. (6) agree.
    values = _consistent(kind)
    chords = [check_component_partials(ChordComp(num_nodes=NN, num_radial=NR, chord_form=form), values)
              .get_val("chord_raw") for form in ("thrust", "torque")]
    np.testing.assert_allclose(chords[0], chords[1], rtol=1e-11)
    assert np.all(chords[0] > 0.0)


def test_coefficients_and_zero_load():
    values = _consistent("hover")
    values["dthrust_dr"][:, 0] = 0.0
    prob = check_component_partials(ChordComp(num_nodes=NN, num_radial=NR), values)
    # An unloaded station gets zero chord, not NaN (Sec. 4.3 with dT = 0).
    np.testing.assert_array_equal(prob.get_val("chord_raw")[:, 0], 0.0)
    np.testing.assert_array_equal(prob.get_val("lift_coefficient"), np.repeat(values["cl_star"][:, None], NR, 1))
    np.testing.assert_array_equal(prob.get_val("drag_coefficient"), np.repeat(values["cd_star"][:, None], NR, 1))


@pytest.mark.parametrize("form, phi, rule", [("thrust", 1.6, r"phi < atan\(C_l/C_d\)"),
                                             ("torque", -0.5, r"phi > -atan\(C_d/C_l\)")])
def test_nonpositive_force_coefficient_names_node_and_station(form, phi, rule):
    # Thrust form: C_x = C_l cos(phi) - C_d sin(phi) < 0 beyond phi = atan(C_l/C_d) < pi/2 (1.6 rad is past it);
    # torque form: C_theta = C_l sin(phi) + C_d cos(phi) < 0 for phi < -atan(C_d/C_l) (~ -0.01 rad).
    values = _consistent("cruise")
    values["phi"] = values["phi"].copy()
    values["phi"][2, 5] = phi
    with pytest.raises(om.AnalysisError, match=rf"(?s)needs {rule}.*at 1 node\(s\): node 2, station 5 "):
        check_component_partials(ChordComp(num_nodes=NN, num_radial=NR, chord_form=form), values)
