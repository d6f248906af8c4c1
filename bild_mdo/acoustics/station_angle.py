"""StationAngleComp: a per-design angle of attack given to every station (BILD's one section point)."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.utils.options import declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_node


class StationAngleComp(om.ExplicitComponent):
    """``alpha[nn, nr] = alpha_star[nn]``: BILD places every station at the reference max-L/D point.

    With ``section_point='reference'`` and one airfoil, BILD's angle of attack is the same at every
    station (paper Assumption 2); the noise sources take it per station.

    Options
    -------
    num_nodes, num_radial : int

    Inputs
    ------
    alpha_star[nn] (rad)
        Angle of attack of the maximum lift-to-drag ratio.

    Outputs
    -------
    alpha[nn, nr] (rad)
        Angle of attack at every station.
    """

    def initialize(self):
        declare_size_options(self.options)

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        self.add_input("alpha_star", val=np.full(nn, 0.1), units="rad",
                       desc="angle of attack of maximum lift-to-drag ratio alpha*")
        self.add_output("alpha", val=np.full((nn, nr), 0.1), units="rad", desc="angle of attack at each station")
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials("alpha", "alpha_star", rows=rows, cols=cols, val=1.0)

    def compute(self, inputs, outputs):
        outputs["alpha"] = np.broadcast_to(inputs["alpha_star"][:, None], outputs["alpha"].shape)
