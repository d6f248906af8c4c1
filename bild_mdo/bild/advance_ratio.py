"""Axial velocity from the advance ratio, V_x = J n D (paper Table 2 notation)."""
import numpy as np
import openmdao.api as om

from bild_mdo.constants import RPM_TO_REV_PER_S
from bild_mdo.utils.options import add_inputs, add_outputs, declare_size_options
from bild_mdo.utils.sparsity import node_wrt_node


class AdvanceRatioComp(om.ExplicitComponent):
    """Axial free-stream velocity from the advance ratio ``J = V_x / (n D)``.

    ``n`` is the rotor speed in rev/s and ``D = 2R`` the diameter (Table 2),
    so ``V_x = J (rpm/60) 2R``.  The paper specifies BILD designs by advance
    ratio (Algorithm 1, step 1); ``BILDGroup(input_mode='advance_ratio')``
    puts this component in front of the chain.

    Options: the size ``num_nodes`` (:func:`~bild_mdo.utils.options.declare_size_options`).

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
        declare_size_options(self.options, radial=False)

    def setup(self):
        nn = self.options["num_nodes"]
        self.add_input("advance_ratio", val=np.zeros(nn), units=None, desc="advance ratio J = V_x/(n D)")
        add_inputs(self, ("rpm", "radius"))
        add_outputs(self, ("v_axial",))

    def setup_partials(self):
        rows, cols = node_wrt_node(self.options["num_nodes"])
        self.declare_partials("v_axial", ["advance_ratio", "rpm", "radius"], rows=rows, cols=cols)

    def compute(self, inputs, outputs):
        outputs["v_axial"] = inputs["advance_ratio"] * inputs["rpm"] * RPM_TO_REV_PER_S * 2.0 * inputs["radius"]

    def compute_partials(self, inputs, partials):
        j, rpm, radius = inputs["advance_ratio"], inputs["rpm"], inputs["radius"]
        # d/dx of V_x = J n D with n = rpm RPM_TO_REV_PER_S and D = 2 R.
        two_n_per_rpm = 2.0 * RPM_TO_REV_PER_S
        partials["v_axial", "advance_ratio"] = two_n_per_rpm * rpm * radius
        partials["v_axial", "rpm"] = two_n_per_rpm * j * radius
        partials["v_axial", "radius"] = two_n_per_rpm * j * rpm
