"""BladeBroadcastComp: one blade's geometry copied to every operating point of a multi-point analysis."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.utils.options import declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_station


class BladeBroadcastComp(om.ExplicitComponent):
    """The chord, twist, radius and hub radius of one blade, repeated for ``num_nodes`` operating points.

    ``chord[k, j] = blade_chord[j]``, ``twist[k, j] = blade_twist[j]``, ``radius[k] = blade_radius``
    (hub radius likewise).  Every partial is a constant 0/1 pattern (declared with ``val``).  The
    collective pitch of each operating point is not added here but by the BEM analysis (its input
    ``collective_pitch``), so the geometry stays that of the blade.

    Options
    -------
    num_nodes : int
        Operating points the blade is analysed at (axis 0 of the outputs).
    num_radial : int
        Radial stations.

    Inputs
    ------
    blade_chord[1, nr] (m), blade_twist[1, nr] (rad)
        The blade (one design, e.g. the output of a BILDGroup with ``num_nodes=1``).
    blade_radius[1] (m), blade_hub_radius[1] (m)
        Tip and hub radius of the blade.

    Outputs
    -------
    chord[nn, nr] (m), twist[nn, nr] (rad), radius[nn] (m), hub_radius[nn] (m)
    """

    def initialize(self):
        declare_size_options(self.options)

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        self.add_input("blade_chord", val=np.full((1, nr), 0.1), units="m", desc="chord of the blade")
        self.add_input("blade_twist", val=np.full((1, nr), 0.3), units="rad", desc="twist of the blade")
        self.add_input("blade_radius", val=1.0, shape=(1,), units="m", desc="tip radius of the blade")
        self.add_input("blade_hub_radius", val=0.1, shape=(1,), units="m", desc="hub radius of the blade")
        self.add_output("chord", val=np.full((nn, nr), 0.1), units="m", desc="blade chord at each operating point")
        self.add_output("twist", val=np.full((nn, nr), 0.3), units="rad", desc="blade twist at each operating point")
        self.add_output("radius", val=np.ones(nn), units="m", desc="tip radius at each operating point")
        self.add_output("hub_radius", val=np.full(nn, 0.1), units="m", desc="hub radius at each operating point")

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = dist_wrt_station(nn, nr)
        self.declare_partials("chord", "blade_chord", rows=rows, cols=cols, val=1.0)
        self.declare_partials("twist", "blade_twist", rows=rows, cols=cols, val=1.0)
        rows, cols = np.arange(nn), np.zeros(nn, dtype=int)
        self.declare_partials("radius", "blade_radius", rows=rows, cols=cols, val=1.0)
        self.declare_partials("hub_radius", "blade_hub_radius", rows=rows, cols=cols, val=1.0)

    def compute(self, inputs, outputs):
        nn = self.options["num_nodes"]
        outputs["chord"] = np.repeat(inputs["blade_chord"], nn, axis=0)
        outputs["twist"] = np.repeat(inputs["blade_twist"], nn, axis=0)
        outputs["radius"] = np.repeat(inputs["blade_radius"], nn)
        outputs["hub_radius"] = np.repeat(inputs["blade_hub_radius"], nn)
