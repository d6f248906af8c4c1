"""NormalizedResponsesComp: O(1) objective and thrust constraint of the energy-loss minimisation."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.utils.options import declare_size_options
from bild_mdo.utils.sparsity import node_wrt_node


class NormalizedResponsesComp(om.ExplicitComponent):
    """Objective and constraint of the rotor energy-loss minimisation (paper Problem 1, Eq. 10).

    ``energy_loss_ratio = E / E_ref`` and ``thrust_residual = T / T* - 1``.
    Dividing by per-case references keeps both responses of order one for
    rotors from 0.5 m hover to 1.5 m fast cruise, so one set of optimiser
    tolerances fits every case, and ``T = T*`` holds to the relative
    tolerance the optimiser enforces on ``thrust_residual``.

    Options
    -------
    num_nodes : int
        Number of designs / operating points (axis 0).

    Inputs
    ------
    thrust[nn] (N)
        Rotor thrust T.
    energy_loss[nn] (W)
        Rate of energy loss E = Omega Q - V_x T (Eq. 12 integrated).
    thrust_target[nn] (N)
        Required thrust T* (from BILD in the verification), > 0.
    energy_loss_ref[nn] (W)
        Reference energy loss of the case, > 0 (e.g. the ideal induced loss).

    Outputs
    -------
    energy_loss_ratio[nn] (-)
        E / E_ref, the objective.
    thrust_residual[nn] (-)
        T / T* - 1, constrained to zero.
    """

    def initialize(self):
        declare_size_options(self.options, radial=False)

    def setup(self):
        ones = np.ones(self.options["num_nodes"])
        for name, units, desc in (("thrust", "N", "rotor thrust T"),
                                  ("energy_loss", "W", "rate of energy loss E = Omega Q - V_x T"),
                                  ("thrust_target", "N", "required thrust T*"),
                                  ("energy_loss_ref", "W", "reference energy loss E_ref")):
            self.add_input(name, val=ones, units=units, desc=desc)
        self.add_output("energy_loss_ratio", val=ones, units=None, desc="objective E / E_ref")
        self.add_output("thrust_residual", val=0.0 * ones, units=None, desc="thrust constraint T / T* - 1")

    def setup_partials(self):
        rows, cols = node_wrt_node(self.options["num_nodes"])
        self.declare_partials("energy_loss_ratio", ["energy_loss", "energy_loss_ref"], rows=rows, cols=cols)
        self.declare_partials("thrust_residual", ["thrust", "thrust_target"], rows=rows, cols=cols)

    def compute(self, inputs, outputs):
        outputs["energy_loss_ratio"] = inputs["energy_loss"] / inputs["energy_loss_ref"]
        outputs["thrust_residual"] = inputs["thrust"] / inputs["thrust_target"] - 1.0

    def compute_partials(self, inputs, partials):
        e_ref = inputs["energy_loss_ref"]
        t_star = inputs["thrust_target"]
        partials["energy_loss_ratio", "energy_loss"] = 1.0 / e_ref
        partials["energy_loss_ratio", "energy_loss_ref"] = -inputs["energy_loss"] / e_ref**2
        partials["thrust_residual", "thrust"] = 1.0 / t_star
        partials["thrust_residual", "thrust_target"] = -inputs["thrust"] / t_star**2


class ResponseSumsComp(om.ExplicitComponent):
    """Sums over the designs of the objective and the thrust constraint, for one reverse solve per response.

    The designs of a batch do not interact, so ``d(sum_k f_k)/dx_i = df_i/dx_i``
    for the design values ``x_i`` of design ``i``: the total derivative of
    each sum, one reverse linear solve, gives every design's gradient of that
    response (:mod:`bild_mdo.optimization.lockstep`).

    Options
    -------
    num_nodes : int
        Number of designs / operating points (axis 0).

    Inputs
    ------
    energy_loss_ratio[nn] (-), thrust_residual[nn] (-)
        Objective ``E / E_ref`` and constraint ``T / T* - 1`` of every design.

    Outputs
    -------
    energy_loss_ratio_sum (-), thrust_residual_sum (-)
        Their sums over the designs.
    """

    def initialize(self):
        declare_size_options(self.options, radial=False)

    def setup(self):
        nn = self.options["num_nodes"]
        for name, desc in (("energy_loss_ratio", "objective E / E_ref"),
                           ("thrust_residual", "thrust constraint T / T* - 1")):
            self.add_input(name, val=np.zeros(nn), units=None, desc=f"{desc} of every design")
            self.add_output(f"{name}_sum", val=0.0, units=None, desc=f"sum over the designs of the {desc}")

    def setup_partials(self):
        nn = self.options["num_nodes"]
        for name in ("energy_loss_ratio", "thrust_residual"):
            self.declare_partials(f"{name}_sum", name, rows=np.zeros(nn, dtype=int), cols=np.arange(nn),
                                  val=np.ones(nn))

    def compute(self, inputs, outputs):
        outputs["energy_loss_ratio_sum"] = np.sum(inputs["energy_loss_ratio"])
        outputs["thrust_residual_sum"] = np.sum(inputs["thrust_residual"])
