"""Shared inputs of the MIL component tests: seeded, away from singular points (0.15 <= xi <= 0.97)."""
import numpy as np

NN, NR = 3, 5


def station_values(seed=0):
    rng = np.random.default_rng(seed)
    xi = np.sort(rng.uniform(0.15, 0.97, (NN, NR)), axis=1)
    return dict(speed_ratio=rng.uniform(0.1, 0.4, NN), radius_fraction=xi,
                width_fraction=rng.uniform(0.05, 0.2, (NN, NR)), zeta=rng.uniform(0.05, 0.4, NN),
                cl_star=rng.uniform(0.5, 1.1, NN), cd_star=rng.uniform(0.005, 0.03, NN),
                alpha_star=rng.uniform(0.02, 0.1, NN), rho=rng.uniform(0.9, 1.3, NN),
                v_axial=rng.uniform(20.0, 80.0, NN), radius=rng.uniform(0.5, 1.5, NN),
                rpm=rng.uniform(1500.0, 3000.0, NN))
