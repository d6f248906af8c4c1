"""Stall hysteresis: where the BEM residual has three roots in region 1, the attached-flow root is taken.

Case: the root station of levels-10 case 0 of the verification sweep (hover, R = 0.5 m, hub 0.1 m, 3 blades,
800 rpm, sea level, r = 0.10667 m) with a chord of 0.08 m and an analytic polar of sharp stall (a blend of
1 deg half width into Viterna's post-stall flow), whose residual has the S-curve of stall hysteresis for twists
between about 46.38 and 47.5 deg.  (The built-in NACA 4412 had it here too while it extrapolated below
Re = 5e4; its XFOIL data down to 1e4 stall gently, with one root.)  The references are
* a dense scan of the residual (20,001 angles over 0.5...60 deg) refined by scipy's brentq: the roots of
  ``R(phi) = 0`` themselves, independent of the package's solver;
* the rule of :mod:`bild_mdo.bem.attached_branch` (the root at the largest phi, i.e. the smallest angle
  of attack) and its consequence, a root that moves continuously with the twist along the attached branch.
"""
import numpy as np
import openmdao.api as om
import pytest
from scipy.optimize import brentq

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.bem.blade_element import residual_function
from bild_mdo.bem.inflow import InflowComp

STATION = dict(v_axial=0.0, rpm=800.0, radius=0.5, hub_radius=0.1, rho=1.225, mu=1.7894e-5,
               speed_of_sound=340.294, collective_pitch=0.0)
RADIUS, CHORD = 0.10666666666666667, 0.08
POLAR = AnalyticPolar(stall_half_width=np.radians(1.0))


def _scan_roots(twist):
    """All sign changes of the residual on a dense grid, refined by brentq (rad)."""
    grid = np.radians(np.linspace(0.5, 60.0, 20001))
    kernels = {k: np.full(grid.size, v) for k, v in STATION.items()}
    kernels.update(radii=np.full(grid.size, RADIUS), chord=np.full(grid.size, CHORD),
                   twist=np.full(grid.size, twist), num_blades=3, polar=POLAR, loss_model="tip_hub")
    residual = residual_function(**kernels)
    values = residual(grid, np.arange(grid.size))[0]
    change = np.flatnonzero(np.sign(values[:-1]) != np.sign(values[1:]))
    return [brentq(lambda x, k=k: residual(np.array([x]), np.array([k]))[0][0], grid[k], grid[k + 1], xtol=1e-14)
            for k in change]


def _solve(twists, warm_start=False, repeat=1):
    """InflowComp's roots at the station for each twist (one node per twist, two identical stations)."""
    twists = np.asarray(twists, dtype=float)
    n = twists.size
    prob = om.Problem()
    prob.model.add_subsystem("inflow", InflowComp(num_nodes=n, num_radial=2, num_blades=3, polar=POLAR,
                                                  warm_start=warm_start), promotes=["*"])
    prob.setup()
    for name, value in STATION.items():
        prob.set_val(name, np.full(n, value))
    prob.set_val("radii", np.full((n, 2), RADIUS))
    prob.set_val("chord", np.full((n, 2), CHORD))
    prob.set_val("twist", np.repeat(twists[:, None], 2, axis=1))
    for _ in range(repeat):
        prob.run_model()
    return prob.get_val("phi")[:, 0]


@pytest.mark.parametrize("twist_deg", [46.5, 47.0])
@pytest.mark.parametrize("warm_start", [False, True])
def test_three_roots_the_attached_one_is_taken(twist_deg, warm_start):
    roots = _scan_roots(np.radians(twist_deg))
    assert len(roots) == 3, np.degrees(roots)           # the S-curve: stalled, unstable, attached
    phi = _solve([np.radians(twist_deg)], warm_start=warm_start, repeat=2)
    np.testing.assert_allclose(phi, max(roots), atol=1e-10)


def test_one_root_below_the_fold_is_kept():
    roots = _scan_roots(np.radians(45.5))
    assert len(roots) == 1
    np.testing.assert_allclose(_solve([np.radians(45.5)]), roots[0], atol=1e-10)


def test_root_is_continuous_across_the_fold_where_the_stalled_pair_is_born():
    # Twist steps of 0.002 deg across the fold near 46.375 deg: the attached root moves by about 0.001 deg per
    # step (dphi/dtwist ~ 0.53 on this branch), while the stalled root is born 1.8 deg below it.
    twists = np.radians(np.linspace(46.32, 46.44, 61))
    phi = _solve(twists)
    assert len(_scan_roots(twists[-1])) == 3 and len(_scan_roots(twists[0])) == 1
    assert np.max(np.abs(np.diff(phi))) < np.radians(0.01)
    assert np.all(np.diff(phi) > 0.0)                    # the attached branch rises with the twist
