"""Minimum-induced-loss designs at BILD's thrust on the forward-flight cases of the verification grid.

Run:  .venv/bin/python benchmarks/mil_grid.py [levels]   (default 3: the 54 J > 0 cases of ``--levels 3``)

For the paper's Sec. 5.1 grid (J 0 ... 3, R 0.5 ... 1.5 m, altitude 0 ... 3000 m,
c_ref 0.08 ... 0.22 m, 800 rpm, hub 0.2 R, reference station 0.5 R, 3 blades,
built-in NACA 4412, 20 stations) without its hover cases, BILD designs each
case; then, per Prandtl form of :class:`~bild_mdo.mil.MILGroup`, a MIL design
is made for BILD's thrust at BILD's airfoil point (alpha*, C_l*, C_d*) and
analysed by :func:`bild_mdo.bem.analyze.analyze_rotor` (tip loss only, the same
polar).  Prints:

* the range of the thrust coefficient T_c = 2T/(rho V^2 pi R^2) of the grid and
  how many MIL designs exist (A&L's relations reach a largest T_c that falls
  with the speed ratio);
* the time per MIL design (one batched run);
* the relative difference between the BEM analysis of the MIL blade and its
  design thrust and power (mean, worst): with ``loss_form='local'`` only the
  polar's Reynolds dependence separates them (A&L's exact agreement of design
  and analysis), with A&L's own tip factor and with QMIL's (``'qmil'``) the two
  loss models differ as well.

Nothing is asserted.
"""
import sys
import time
import warnings

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.builtin import resolve_polar
from bild_mdo.bem.analyze import analyze_rotor
from bild_mdo.bild import BILDGroup
from bild_mdo.mil import design_mil
from bild_mdo.mil.kernel import LOSS_FORMS

NUM_RADIAL, NUM_BLADES, RPM = 20, 3, 800.0


def grid(levels):
    j, radius, altitude, ref_chord = np.meshgrid(np.linspace(0.0, 3.0, levels), np.linspace(0.5, 1.5, levels),
                                                 np.linspace(0.0, 3000.0, levels), np.linspace(0.08, 0.22, levels),
                                                 indexing="ij")
    keep = j.ravel() > 0.0
    j, radius = j.ravel()[keep], radius.ravel()[keep]
    return {"v_axial": j * RPM / 60.0 * 2.0 * radius, "rpm": np.full(j.size, RPM), "radius": radius,
            "hub_radius_ratio": np.full(j.size, 0.2), "ref_radius_ratio": np.full(j.size, 0.5),
            "ref_chord": ref_chord.ravel()[keep], "altitude": altitude.ravel()[keep]}


def main(levels=3):
    warnings.simplefilter("ignore", UserWarning)  # Reynolds numbers clamped to the polar's table
    cases = grid(levels)
    nn = cases["rpm"].size
    prob = om.Problem(BILDGroup(num_nodes=nn, num_radial=NUM_RADIAL, num_blades=NUM_BLADES), reports=False)
    prob.setup()
    for name, value in cases.items():
        prob.set_val(name, value)
    prob.run_model()
    bild = {name: prob.get_val(name) for name in ("thrust", "rho", "mu", "alpha_star", "cl_star", "cd_star")}
    v, radius = cases["v_axial"], cases["radius"]
    t_c = 2.0 * bild["thrust"] / (bild["rho"] * v ** 2 * np.pi * radius ** 2)
    print(f"{nn} forward-flight cases (levels = {levels}); BILD's T_c from {t_c.min():.3f} to {t_c.max():.3f}")
    polar = resolve_polar("naca4412")
    for form in LOSS_FORMS:
        kwargs = dict(v_axial=v, rpm=RPM, radius=radius, hub_radius=0.2 * radius, altitude=cases["altitude"],
                      alpha_star=bild["alpha_star"], cl_star=bild["cl_star"], cd_star=bild["cd_star"],
                      num_blades=NUM_BLADES, num_radial=NUM_RADIAL, loss_form=form)
        start = time.perf_counter()
        try:
            design = design_mil(bild["thrust"], **kwargs)
        except om.AnalysisError as err:
            print(f"{form}: no batch design: {err}")
            continue
        per_design = (time.perf_counter() - start) / nn
        width = np.broadcast_to((0.8 * radius / NUM_RADIAL)[:, None], design.radii.shape)
        bem = analyze_rotor(design.chord, design.twist, radius, 0.2 * radius, RPM, v, NUM_BLADES, polar,
                            loss_model="tip", radii=design.radii, dr=width, rho=bild["rho"], mu=bild["mu"])
        d_thrust = np.abs(bem.thrust / design.thrust - 1.0)
        d_power = np.abs(bem.power / design.power - 1.0)
        print(f"{form:15s} {nn}/{nn} designs, {per_design * 1e3:.2f} ms per design (batched, first run); "
              f"BEM vs design: thrust mean {d_thrust.mean():.2%} worst {d_thrust.max():.2%}, "
              f"power mean {d_power.mean():.2%} worst {d_power.max():.2%}; MIL eta {design.efficiency.min():.3f}"
              f" ... {design.efficiency.max():.3f}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3)
