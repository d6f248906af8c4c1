import numpy as np
import pytest

from bild_mdo.bild.momentum_loads import MomentumLoadsComp
from bild_mdo.utils.testing import check_component_partials
from tests.bild.conftest import NN, NR, state


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip", "none"])
def test_partials(kind, loss_model):
    check_component_partials(MomentumLoadsComp(num_nodes=NN, num_radial=NR, loss_model=loss_model), state(kind))


def test_energy_loss_matches_eq13(kind):
    # Without loss factor, dE/dr = Omega dQ/dr - V_x dT/dr must equal the closed form of Eq. (13).
    values = state(kind)
    prob = check_component_partials(MomentumLoadsComp(num_nodes=NN, num_radial=NR, loss_model="none"), values)
    r, u_axial, u_t = values["radii"], values["u_axial"], values["u_theta"]
    v_x, rho = values["v_axial"][:, None], values["rho"][:, None]
    eq13 = 2 * np.pi * r * rho * (values["v_theta"] * u_axial * u_t - 2 * v_x * u_axial ** 2 + 2 * v_x ** 2 * u_axial)
    np.testing.assert_allclose(prob.get_val("denergy_loss_dr", units="W/m"), eq13, rtol=1e-12)
    # Eq. (1): dT/dr = 4 pi rho u_axial (u_axial - V_x) r.
    np.testing.assert_allclose(prob.get_val("dthrust_dr"), 4 * np.pi * rho * u_axial * (u_axial - v_x) * r, rtol=1e-14)


def test_loss_factor_scales_both_loads(kind):
    values = state(kind)
    with_loss = check_component_partials(MomentumLoadsComp(num_nodes=NN, num_radial=NR), values)
    without = check_component_partials(MomentumLoadsComp(num_nodes=NN, num_radial=NR, loss_model="none"), values)
    f = with_loss.get_val("loss_factor")
    # Prandtl: 0 < F <= 1, smallest at the outermost station.
    assert np.all((f > 0) & (f <= 1)) and np.all(np.argmin(f, axis=1) == NR - 1)
    for name in ("dthrust_dr", "dtorque_dr"):
        np.testing.assert_allclose(with_loss.get_val(name), f * without.get_val(name), rtol=1e-14)
