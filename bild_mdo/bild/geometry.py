"""Hub and reference radii from the rotor radius and two radius ratios."""
import numpy as np
import openmdao.api as om

from bild_mdo.utils.options import add_inputs, add_outputs, declare_size_options
from bild_mdo.utils.sparsity import node_wrt_node


class GeometryComp(om.ExplicitComponent):
    """Hub radius and reference radius of a BILD design.

    ``hub_radius = hub_radius_ratio * radius`` and
    ``ref_radius = ref_radius_ratio * radius``.  The reference station, where
    the user fixes the chord (paper Sec. 4, Algorithm 1, step 1), must lie on
    the blade: ``0 < hub_radius_ratio < ref_radius_ratio < 1``.

    Options: the size ``num_nodes`` (:func:`~bild_mdo.utils.options.declare_size_options`).

    Inputs
    ------
    radius[nn] (m)
        Rotor (tip) radius R.
    hub_radius_ratio[nn] (-)
        Hub radius over tip radius.
    ref_radius_ratio[nn] (-)
        Reference radius over tip radius.

    Outputs
    -------
    hub_radius[nn] (m)
    ref_radius[nn] (m)

    Raises
    ------
    openmdao.api.AnalysisError
        When the ratios do not satisfy ``0 < hub < ref < 1``.
    """

    def initialize(self):
        declare_size_options(self.options, radial=False)

    def setup(self):
        nn = self.options["num_nodes"]
        add_inputs(self, ("radius",))
        self.add_input("hub_radius_ratio", val=0.2 * np.ones(nn), units=None,
                       desc="hub radius divided by the tip radius")
        self.add_input("ref_radius_ratio", val=0.5 * np.ones(nn), units=None,
                       desc="reference-station radius divided by the tip radius")
        add_outputs(self, ("hub_radius", "ref_radius"))

    def setup_partials(self):
        rows, cols = node_wrt_node(self.options["num_nodes"])
        self.declare_partials("hub_radius", ["radius", "hub_radius_ratio"], rows=rows, cols=cols)
        self.declare_partials("ref_radius", ["radius", "ref_radius_ratio"], rows=rows, cols=cols)

    def compute(self, inputs, outputs):
        hub = inputs["hub_radius_ratio"]
        ref = inputs["ref_radius_ratio"]
        radius = inputs["radius"]
        hub_r, ref_r, rad_r = np.real(hub), np.real(ref), np.real(radius)
        # Written as ~(x > 0) so that NaN fails the checks too.
        if np.any(~(rad_r > 0.0) | ~np.isfinite(rad_r)):
            raise om.AnalysisError(f"{self.msginfo}: radius must be positive and finite, got {rad_r}")
        for name, value in (("hub_radius_ratio", hub_r), ("ref_radius_ratio", ref_r)):
            if not np.all(np.isfinite(value)):
                raise om.AnalysisError(f"{self.msginfo}: {name} must be finite, got {value}")
        if np.any(~(hub_r > 0.0) | ~(ref_r < 1.0) | ~(hub_r < ref_r)):
            raise om.AnalysisError(
                f"{self.msginfo}: the radius ratios must satisfy 0 < hub_radius_ratio < "
                f"ref_radius_ratio < 1; got hub_radius_ratio={hub_r}, ref_radius_ratio={ref_r}")
        outputs["hub_radius"] = hub * radius
        outputs["ref_radius"] = ref * radius

    def compute_partials(self, inputs, partials):
        partials["hub_radius", "radius"] = inputs["hub_radius_ratio"]
        partials["hub_radius", "hub_radius_ratio"] = inputs["radius"]
        partials["ref_radius", "radius"] = inputs["ref_radius_ratio"]
        partials["ref_radius", "ref_radius_ratio"] = inputs["radius"]
