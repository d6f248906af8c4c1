"""Local Mach number of the ideal blade, ``M = W / a`` at every station."""
import numpy as np
import openmdao.api as om

from bild_mdo.utils.options import add_inputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node


class LocalMachComp(om.ExplicitComponent):
    """Local Mach number ``M = W / a`` of every blade element.

    ``W`` is the inflow speed with induction of the ideal rotor (Eq. (7)),
    ``a`` the speed of sound of the atmosphere.  The tip Mach number
    ``sqrt(V_x**2 + (Omega R)**2) / a`` is a per-design metric of
    :class:`~bild_mdo.bem.performance.RotorPerformanceComp` (``tip_mach``).

    Options: the sizes ``num_nodes`` and ``num_radial``.

    Inputs
    ------
    inflow_speed[nn, nr] (m/s)
        Resultant inflow speed W.
    speed_of_sound[nn] (m/s)
        Speed of sound a.

    Outputs
    -------
    mach[nn, nr] (-)
        Local Mach number.
    """

    def initialize(self):
        declare_size_options(self.options)

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        add_inputs(self, ("inflow_speed",))
        add_inputs(self, ("speed_of_sound",))
        self.add_output("mach", val=np.full((nn, nr), 0.2), units=None, desc="local Mach number W / a")

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = dist_wrt_dist(nn, nr)
        self.declare_partials("mach", "inflow_speed", rows=rows, cols=cols)
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials("mach", "speed_of_sound", rows=rows, cols=cols)

    def compute(self, inputs, outputs):
        outputs["mach"] = inputs["inflow_speed"] / inputs["speed_of_sound"][:, None]

    def compute_partials(self, inputs, partials):
        a = inputs["speed_of_sound"][:, None]
        partials["mach", "inflow_speed"] = np.broadcast_to(1.0 / a, inputs["inflow_speed"].shape).ravel()
        partials["mach", "speed_of_sound"] = (-inputs["inflow_speed"] / a ** 2).ravel()
