"""Shared inputs of the BILD component tests (partials are checked by bild_mdo.utils.testing).

Two operating states are used throughout, at num_nodes=3 (three designs that
differ in rpm and radius) and num_radial=7 (nn != nr so a transposed sparsity
pattern fails):

* ``hover``: V_x = 0, the case the paper treats separately (Remark 4);
* ``cruise``: V_x = 20..40 m/s, advance ratios J ~ 0.5..1.
"""
import numpy as np
import pytest

NN = 3
NR = 7


def state(kind):
    """Plausible, mutually consistent inputs of the BILD chain for ``kind`` in {'hover', 'cruise'}."""
    rng = np.random.default_rng(0 if kind == "hover" else 1)
    radius = np.array([1.5, 1.2, 0.9])
    rpm = np.array([800.0, 1000.0, 1300.0])
    hub_ratio = np.array([0.2, 0.15, 0.25])
    ref_ratio = np.array([0.5, 0.6, 0.45])
    frac = (np.arange(NR) + 0.5) / NR
    radii = radius[:, None] * (hub_ratio[:, None] + (1.0 - hub_ratio[:, None]) * frac[None, :])
    omega = rpm * 2.0 * np.pi / 60.0
    v_theta = omega[:, None] * radii
    v_axial = np.zeros(NN) if kind == "hover" else np.array([20.0, 30.0, 40.0])
    eta2 = 0.90 + 0.08 * rng.random((NN, NR))
    u_theta = 2.0 * v_theta * (1.0 - eta2)
    u_axial = v_axial[:, None] + 8.0 + 4.0 * rng.random((NN, NR))
    return dict(
        radius=radius, rpm=rpm, hub_radius_ratio=hub_ratio, ref_radius_ratio=ref_ratio,
        hub_radius=hub_ratio * radius, ref_radius=ref_ratio * radius, radii=radii,
        v_theta=v_theta, v_theta_ref=omega * ref_ratio * radius, v_axial=v_axial,
        eta2=eta2, u_theta=u_theta, u_axial=u_axial,
        phi=np.arctan2(u_axial, v_theta - 0.5 * u_theta),
        rho=np.array([1.225, 1.1, 0.95]), mu=np.array([1.81e-5, 1.78e-5, 1.75e-5]),
        ref_chord=np.array([0.15, 0.1, 0.2]),
        cl_star=np.array([1.1, 1.0, 0.95]), cd_star=np.array([0.011, 0.012, 0.010]),
        alpha_star=np.radians([6.0, 5.5, 5.0]),
    )


@pytest.fixture(params=["hover", "cruise"])
def kind(request):
    return request.param
