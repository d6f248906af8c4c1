import numpy as np
import pytest

from bild_mdo.bem.inflow_residual import force_coefficients
from bild_mdo.bem.prandtl import prandtl_loss
from bild_mdo.bild.reference_induced_velocity import ReferenceInducedVelocityComp
from bild_mdo.bild.variants.reference_point.reference_station import ReferenceStationComp
from bild_mdo.utils.testing import check_component_partials
from tests.bild.conftest import NN, state


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip", "none"])
def test_partials_and_bem_balance(kind, loss_model):
    values = state(kind)
    values["phi_ref"] = check_component_partials(
        ReferenceStationComp(num_nodes=NN, loss_model=loss_model), values).get_val("phi_ref")
    prob = check_component_partials(ReferenceInducedVelocityComp(num_nodes=NN, loss_model=loss_model),
                           values)
    u_axial, u_t = prob.get_val("u_axial_ref"), prob.get_val("u_theta_ref")
    phi, r, c = values["phi_ref"], values["ref_radius"], values["ref_chord"]
    v_t = values["v_theta_ref"] - 0.5 * u_t
    # At the solved angle the inflow geometry closes: tan(phi) = u_axial / (V_theta - u_theta/2) (Fig. 1b).
    np.testing.assert_allclose(np.tan(phi), u_axial / v_t, rtol=1e-12)
    # Momentum thrust (Eq. 1, with F) equals blade-element thrust (Eq. 5) for the reference chord.
    f = prandtl_loss(phi, r, values["radius"], values["hub_radius"], 3, loss_model).F
    c_x, c_theta = force_coefficients(phi, values["cl_star"], values["cd_star"])
    w2 = u_axial ** 2 + v_t ** 2
    momentum = 4 * np.pi * values["rho"] * u_axial * (u_axial - values["v_axial"]) * r * f
    blade = 0.5 * c_x * values["rho"] * w2 * 3 * c
    np.testing.assert_allclose(momentum, blade, rtol=1e-11)
    # ... and the torques (Eq. 2 with F against Eq. 6).
    np.testing.assert_allclose(2 * np.pi * values["rho"] * u_axial * u_t * r ** 2 * f,
                               0.5 * c_theta * values["rho"] * w2 * 3 * c * r, rtol=1e-11)


def test_one_design_matches_the_batch(kind):
    # Designs do not interact: one design (run on NumPy scalars) has the velocities it has in a batch.
    values = state(kind)
    values["phi_ref"] = check_component_partials(ReferenceStationComp(num_nodes=NN), values).get_val("phi_ref")
    batch = check_component_partials(ReferenceInducedVelocityComp(num_nodes=NN), values)
    for k in range(NN):
        one = check_component_partials(ReferenceInducedVelocityComp(num_nodes=1),
                                       {name: np.atleast_1d(value)[[k]] for name, value in values.items()})
        for name in ("u_axial_ref", "u_theta_ref"):
            np.testing.assert_allclose(one.get_val(name), batch.get_val(name)[[k]], rtol=1e-14)
