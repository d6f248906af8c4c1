"""Prandtl tip/hub loss factor: hand values, limits and partial derivatives."""
import math
import warnings

import numpy as np
import pytest

from bild_mdo.bem.prandtl import prandtl_loss, prandtl_loss_and_dphi


def _hand_F(phi, r, R, rh, B, hub=True):
    """Prandtl's formula written out with the math module (paper Sec. 3 uses it for all results)."""
    s = abs(math.sin(phi))
    ft = 2.0 / math.pi * math.acos(math.exp(-B * (R - r) / (2.0 * r * s)))
    fh = 2.0 / math.pi * math.acos(math.exp(-B * (r - rh) / (2.0 * rh * s))) if hub else 1.0
    return ft * fh


@pytest.mark.parametrize("phi, r", [(0.3, 0.8), (-0.2, 0.5), (2.5, 0.95), (0.05, 0.25)])
def test_matches_hand_formula(phi, r):
    R, rh, B = 1.0, 0.2, 3
    assert prandtl_loss(phi, r, R, rh, B, "tip_hub").F == pytest.approx(_hand_F(phi, r, R, rh, B), rel=1e-14)
    assert prandtl_loss(phi, r, R, rh, B, "tip").F == pytest.approx(_hand_F(phi, r, R, rh, B, hub=False),
                                                                    rel=1e-14)
    assert prandtl_loss(phi, r, R, rh, B, "none").F == 1.0


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip", "none"])
def test_partials_match_complex_step(loss_model):
    rng = np.random.default_rng(3)
    n = 200
    args = [rng.uniform(-0.78, 3.1, n), rng.uniform(0.22, 0.999, n), rng.uniform(1.0, 1.1, n),
            rng.uniform(0.1, 0.2, n)]
    loss = prandtl_loss(*args, 4, loss_model)
    step = 1e-30
    for i, name in enumerate(["dF_dphi", "dF_dr", "dF_dradius", "dF_dhub_radius"]):
        perturbed = list(args)
        perturbed[i] = perturbed[i] + 1j * step
        cs = np.imag(prandtl_loss(*perturbed, 4, loss_model).F) / step
        np.testing.assert_allclose(getattr(loss, name), cs, rtol=1e-12, atol=1e-14, err_msg=name)


def test_limits_are_finite_and_physical():
    # phi -> 0: the exponent blows up, F -> 1 exactly (no 0/0); r -> R: F -> 0 (no load at the tip).
    phi = np.array([0.0, 1e-300, -1e-300, np.pi, 0.3, 0.3, 0.3])
    r = np.array([0.5, 0.5, 0.5, 0.5, 1.0, 0.2, 0.999999])
    with np.errstate(all="raise"):
        loss = prandtl_loss(phi, r, 1.0, 0.2, 3, "tip_hub")
    for field in loss:
        assert np.all(np.isfinite(field))
    np.testing.assert_array_equal(loss.F[:4], 1.0)
    assert loss.F[4] < 1e-4 and loss.F[5] < 1e-4
    assert 0.0 < loss.F[6] < 0.01
    # F in (0, 1] over the whole circle of inflow angles.
    phis = np.linspace(-np.pi, np.pi, 721)
    F = prandtl_loss(phis, 0.7, 1.0, 0.2, 3, "tip_hub").F
    assert np.all((F > 0.0) & (F <= 1.0))


def test_invalid_arguments():
    with pytest.raises(ValueError, match="hub_radius"):
        prandtl_loss(0.3, 0.5, 1.0, 0.0, 3, "tip_hub")
    with pytest.raises(ValueError, match="loss_model"):
        prandtl_loss(0.3, 0.5, 1.0, 0.1, 3, "glauert")


@pytest.mark.parametrize("loss_model", ["tip_hub", "tip", "none"])
def test_fast_path_matches_full_function(loss_model):
    rng = np.random.default_rng(8)
    args = (rng.uniform(-0.78, 3.1, 300), rng.uniform(0.2, 1.0, 300), 1.0, 0.2, 3, loss_model)
    full = prandtl_loss(*args)
    F, dF_dphi = prandtl_loss_and_dphi(*args)
    np.testing.assert_allclose(F, full.F, rtol=1e-15)
    np.testing.assert_allclose(dF_dphi, full.dF_dphi, rtol=1e-13, atol=1e-300)


def test_tiny_hub_radius_gives_the_tip_factor_without_overflow():
    # f_hub = B (r - r_hub) / (2 r_hub |sin phi|) -> infinity as r_hub -> 0, so F_hub -> 1 (Prandtl's
    # factor of a vanishing hub); the capped exponent gives that limit with finite partials.
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        both = prandtl_loss(0.3, 0.5, 1.0, 1e-300, 3, "tip_hub")
        tip = prandtl_loss(0.3, 0.5, 1.0, 1e-300, 3, "tip")
        F, dF_dphi = prandtl_loss_and_dphi(0.3, 0.5, 1.0, 1e-300, 3, "tip_hub")
    assert both.F == tip.F and F == tip.F and dF_dphi == tip.dF_dphi
    assert all(np.isfinite(x) for x in both)
