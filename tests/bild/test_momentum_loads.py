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


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip", "none"])
def test_loss_factor_of_compute_is_prandtls(loss_model):
    # compute evaluates F alone (_loss_factor); it is the F of bild_mdo.bem.prandtl.prandtl_loss (same floor and
    # clips) to round-off, over inflow angles of both signs, near zero (floored) and stations at hub and tip.
    from bild_mdo.bem.prandtl import prandtl_loss
    from bild_mdo.bild.momentum_loads import _loss_factor

    rng = np.random.default_rng(3)
    phi = np.concatenate([rng.uniform(-1.5, 1.5, 2000), [0.0, 1e-14, -1e-14, 1e-6]])
    radius, hub = 1.2, 0.2
    r = np.concatenate([rng.uniform(hub, radius, 2000), [hub, radius, 0.5 * (hub + radius), radius * (1 - 1e-12)]])
    value = _loss_factor(phi, r, radius, hub, 3, loss_model, np.empty(phi.size))
    np.testing.assert_allclose(value, prandtl_loss(phi, r, radius, hub, 3, loss_model).F, rtol=4e-16, atol=0.0)
