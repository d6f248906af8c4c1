import numpy as np
import pytest

from bild_mdo.bild.sectional_loads import SectionalLoadsComp
from tests.bild.conftest import NN, NR, check_component, state


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip", "none"])
def test_partials(kind, loss_model):
    check_component(SectionalLoadsComp(num_nodes=NN, num_radial=NR, loss_model=loss_model), state(kind))


def test_energy_loss_matches_eq13(kind):
    # Without loss factor, dE/dr = Omega dQ/dr - V_x dT/dr must equal the closed form of Eq. (13).
    values = state(kind)
    prob = check_component(SectionalLoadsComp(num_nodes=NN, num_radial=NR, loss_model="none"), values)
    r, u_x, u_t = values["radii"], values["u_x"], values["u_theta"]
    v_x, rho = values["v_axial"][:, None], values["rho"][:, None]
    eq13 = 2 * np.pi * r * rho * (values["v_theta"] * u_x * u_t - 2 * v_x * u_x ** 2 + 2 * v_x ** 2 * u_x)
    np.testing.assert_allclose(prob.get_val("denergy_loss_dr", units="W/m"), eq13, rtol=1e-12)
    # Eq. (1): dT/dr = 4 pi rho u_x (u_x - V_x) r.
    np.testing.assert_allclose(prob.get_val("dthrust_dr"), 4 * np.pi * rho * u_x * (u_x - v_x) * r, rtol=1e-14)


def test_loss_factor_scales_both_loads(kind):
    values = state(kind)
    with_loss = check_component(SectionalLoadsComp(num_nodes=NN, num_radial=NR), values)
    without = check_component(SectionalLoadsComp(num_nodes=NN, num_radial=NR, loss_model="none"), values)
    f = with_loss.get_val("loss_factor")
    # Prandtl: 0 < F <= 1, smallest at the outermost station.
    assert np.all((f > 0) & (f <= 1)) and np.all(np.argmin(f, axis=1) == NR - 1)
    for name in ("dthrust_dr", "dtorque_dr"):
        np.testing.assert_allclose(with_loss.get_val(name), f * without.get_val(name), rtol=1e-14)
