"""Optional root-chord correction of the back-computed chord (paper Eq. (32), Sec. 5.2.2)."""
import numbers

import numpy as np
import openmdao.api as om

from bild_mdo.utils.options import add_inputs, add_outputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node


def _check_constant(name, value):
    if value is None:
        return
    if not isinstance(value, numbers.Real) or isinstance(value, bool) or not value > 0.0:
        raise ValueError(f"{name} must be None (no correction) or a positive number, got {value!r}")


class RootChordCorrectionComp(om.ExplicitComponent):
    """Blend the reference chord into the back-computed chord near the root.

    Designs for forward flight get an infeasibly small root chord (paper
    Sec. 5.2.1, Fig. 6).  Eq. (32) takes a weighted average::

        c = exp(-k r/R) c_ref + (1 - exp(-k r/R)) c_bc

    The paper writes ``exp(-k r)`` without stating the unit of ``r``; here
    ``r`` is the *nondimensional* radius ``r/R``, so that one ``k`` means the
    same blending for rotors of any size (``k = 10`` gives the reference chord
    a weight ``exp(-2) = 0.14`` at ``r/R = 0.2``).  The correction only changes
    the chord, never the twist or the ideal loads.

    With ``correction_constant=None`` (the default) the component passes the
    chord through unchanged, so ``chord`` is always the chord to use.

    Options
    -------
    num_nodes, num_radial : int
        Designs / operating points (axis 0) and radial stations (axis 1).
    correction_constant : float or None
        ``k`` of Eq. (32) (on ``r/R``); ``None`` switches the correction off.

    Inputs
    ------
    chord_raw[nn, nr] (m)
        Back-computed chord ``c_bc``.
    ref_chord[nn] (m)
        Reference chord ``c_ref``.
    radii[nn, nr] (m)
        Station radii.
    radius[nn] (m)
        Rotor tip radius.

    Outputs
    -------
    chord[nn, nr] (m)
        Corrected chord (equal to ``chord_raw`` when the correction is off).
    """

    def initialize(self):
        declare_size_options(self.options)
        self.options.declare("correction_constant", default=None, allow_none=True,
                             check_valid=_check_constant,
                             desc="k of Eq. (32), applied to r/R; None switches the correction off")

    def setup(self):
        add_inputs(self, ("chord_raw", "ref_chord", "radii", "radius"))
        add_outputs(self, ("chord",))

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = dist_wrt_dist(nn, nr)
        if self.options["correction_constant"] is None:
            self.declare_partials("chord", "chord_raw", rows=rows, cols=cols, val=1.0)
            return
        self.declare_partials("chord", ["chord_raw", "radii"], rows=rows, cols=cols)
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials("chord", ["ref_chord", "radius"], rows=rows, cols=cols)

    def _weight(self, inputs):
        k = self.options["correction_constant"]
        radius = inputs["radius"][:, None]
        return k, radius, np.exp(-k * inputs["radii"] / radius)

    def compute(self, inputs, outputs):
        if self.options["correction_constant"] is None:
            outputs["chord"] = inputs["chord_raw"]
            return
        _, _, weight = self._weight(inputs)
        outputs["chord"] = weight * inputs["ref_chord"][:, None] + (1.0 - weight) * inputs["chord_raw"]

    def compute_partials(self, inputs, partials):
        if self.options["correction_constant"] is None:
            return
        k, radius, weight = self._weight(inputs)
        gap = inputs["ref_chord"][:, None] - inputs["chord_raw"]
        dweight_dr = -k / radius * weight
        partials["chord", "chord_raw"] = (1.0 - weight).ravel()
        partials["chord", "ref_chord"] = weight.ravel()
        partials["chord", "radii"] = (dweight_dr * gap).ravel()
        partials["chord", "radius"] = (-dweight_dr * inputs["radii"] / radius * gap).ravel()
