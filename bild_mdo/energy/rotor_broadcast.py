"""RotorBroadcastComp: each rotor's blade and fluid copied to every wind speed of its power curve."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.utils.options import VARIABLES, add_inputs, declare_size_options

#: Per-rotor inputs copied to every point: the blade's distributions, then its scalars and the fluid.
BROADCAST_DISTRIBUTIONS = ("chord", "twist")
BROADCAST_SCALARS = ("radius", "hub_radius", "rho", "mu", "speed_of_sound")


class RotorBroadcastComp(om.ExplicitComponent):
    """``point_<name>[i * np + p] = <name>[i]``: rotor ``i`` at its ``np`` wind speeds (flat BEM node axis).

    Every partial is a constant 0/1 pattern (declared with ``val``).

    Options
    -------
    num_nodes, num_radial : int
        Rotors and blade stations.
    num_points : int
        Wind speeds per rotor ``np``.

    Inputs
    ------
    chord[nn, nr] (m), twist[nn, nr] (rad), radius[nn] (m), hub_radius[nn] (m), rho[nn] (kg/m**3), mu[nn] (Pa*s),
    speed_of_sound[nn] (m/s)

    Outputs
    -------
    point_chord[nn*np, nr] (m), point_twist[nn*np, nr] (rad), point_radius[nn*np] (m), point_hub_radius[nn*np] (m),
    point_rho[nn*np] (kg/m**3), point_mu[nn*np] (Pa*s), point_speed_of_sound[nn*np] (m/s)
    """

    def initialize(self):
        declare_size_options(self.options)
        self.options.declare("num_points", types=int, default=1, lower=1, desc="wind speeds per rotor")

    def setup(self):
        nn, nr, npt = self.options["num_nodes"], self.options["num_radial"], self.options["num_points"]
        add_inputs(self, BROADCAST_DISTRIBUTIONS + BROADCAST_SCALARS)
        for name in BROADCAST_DISTRIBUTIONS + BROADCAST_SCALARS:
            _, default, units, desc = VARIABLES[name]
            shape = (nn * npt, nr) if name in BROADCAST_DISTRIBUTIONS else (nn * npt,)
            self.add_output(f"point_{name}", val=np.full(shape, default), units=units,
                            desc=f"{desc}, at every wind speed of the curve")

    def setup_partials(self):
        nn, nr, npt = self.options["num_nodes"], self.options["num_radial"], self.options["num_points"]
        rows = np.arange(nn * npt * nr)
        cols = (np.repeat(np.arange(nn), npt)[:, None] * nr + np.arange(nr)[None, :]).ravel()
        for name in BROADCAST_DISTRIBUTIONS:
            self.declare_partials(f"point_{name}", name, rows=rows, cols=cols, val=1.0)
        rows, cols = np.arange(nn * npt), np.repeat(np.arange(nn), npt)
        for name in BROADCAST_SCALARS:
            self.declare_partials(f"point_{name}", name, rows=rows, cols=cols, val=1.0)

    def compute(self, inputs, outputs):
        npt = self.options["num_points"]
        for name in BROADCAST_DISTRIBUTIONS + BROADCAST_SCALARS:
            outputs[f"point_{name}"] = np.repeat(inputs[name], npt, axis=0)
