"""Axial velocity from the advance ratio, V_x = J n D (paper Table 2 notation)."""
import numpy as np
import openmdao.api as om

from bild_mdo.utils.sparsity import node_wrt_node


class AdvanceRatioComp(om.ExplicitComponent):
    """Axial free-stream velocity from the advance ratio ``J = V_x / (n D)``.

    ``n`` is the rotor speed in rev/s and ``D = 2R`` the diameter (Table 2),
    so ``V_x = J (rpm/60) 2R``.  The paper specifies BILD designs by advance
    ratio (Algorithm 1, step 1); ``BILDGroup(input_mode='advance_ratio')``
    puts this component in front of the chain.

    Options
    -------
    num_nodes : int
        Number of designs / operating points.
    num_radial : int
        Number of radial stations (unused here).

    Inputs
    ------
    advance_ratio[nn] (-)
        Advance ratio J.
    rpm[nn] (rpm)
        Rotor speed.
    radius[nn] (m)
        Rotor tip radius.

    Outputs
    -------
    v_axial[nn] (m/s)
        Axial free-stream velocity.
    """

    def initialize(self):
        self.options.declare("num_nodes", types=int, default=1, desc="number of designs / operating points")
        self.options.declare("num_radial", types=int, default=1, desc="number of radial stations (unused)")

    def setup(self):
        nn = self.options["num_nodes"]
        self.add_input("advance_ratio", val=np.zeros(nn), units=None, desc="advance ratio J = V_x/(n D)")
        self.add_input("rpm", val=np.full(nn, 1000.0), units="rpm", desc="rotor speed")
        self.add_input("radius", val=np.ones(nn), units="m", desc="rotor tip radius")
        self.add_output("v_axial", val=np.zeros(nn), units="m/s", desc="axial free-stream velocity")

    def setup_partials(self):
        rows, cols = node_wrt_node(self.options["num_nodes"])
        self.declare_partials("v_axial", ["advance_ratio", "rpm", "radius"], rows=rows, cols=cols)

    def compute(self, inputs, outputs):
        outputs["v_axial"] = inputs["advance_ratio"] * inputs["rpm"] / 60.0 * 2.0 * inputs["radius"]

    def compute_partials(self, inputs, partials):
        j, rpm, radius = inputs["advance_ratio"], inputs["rpm"], inputs["radius"]
        partials["v_axial", "advance_ratio"] = rpm * radius / 30.0
        partials["v_axial", "rpm"] = j * radius / 30.0
        partials["v_axial", "radius"] = j * rpm / 30.0
