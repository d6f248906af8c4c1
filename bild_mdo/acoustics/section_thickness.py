"""SectionThicknessComp: the section thickness ratio t/c at every station, from the blade's airfoil."""
from __future__ import annotations

import warnings

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.builtin import resolve_polar
from bild_mdo.airfoil.thickness import ThicknessWarning, section_thickness_ratio
from bild_mdo.utils.options import add_inputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node


class SectionThicknessComp(om.ExplicitComponent):
    """Thickness ratio ``t/c`` of the airfoil at each station (:mod:`bild_mdo.airfoil.thickness`).

    One airfoil gives one constant ratio; a spanwise set of airfoils blends its members' ratios in
    ``r/R`` with the smooth step of its coefficients, so the ratio moves with ``radii / radius``.  An
    airfoil without a ratio gets 0.12 and one :class:`~bild_mdo.airfoil.thickness.ThicknessWarning`
    at setup.

    Options
    -------
    num_nodes, num_radial : int
        Designs (axis 0) and stations (axis 1).
    polar : Polar or None
        The blade's airfoil; None is the built-in NACA 4412 (t/c = 0.12).

    Inputs
    ------
    radii[nn, nr] (m), radius[nn] (m)
        Station radii and tip radius (used by a spanwise set only).

    Outputs
    -------
    thickness_ratio[nn, nr] (-)
        Section thickness over chord.
    """

    def initialize(self):
        declare_size_options(self.options)
        self.options.declare("polar", default=None, allow_none=True, recordable=False,
                             desc="airfoil Polar; None selects the built-in NACA 4412")

    def _polar(self):
        return resolve_polar("naca4412") if self.options["polar"] is None else self.options["polar"]

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        add_inputs(self, ["radii", "radius"])
        # The warning for an airfoil without a thickness ratio, once here rather than on every run.
        ratio, _ = section_thickness_ratio(self._polar(), np.linspace(0.0, 1.0, nr))
        self.add_output("thickness_ratio", val=np.broadcast_to(ratio, (nn, nr)).copy(), units=None,
                        desc="section thickness over chord t/c")

    def setup_partials(self):
        if self._polar().varies_along_span:
            nn, nr = self.options["num_nodes"], self.options["num_radial"]
            rows, cols = dist_wrt_dist(nn, nr)
            self.declare_partials("thickness_ratio", "radii", rows=rows, cols=cols)
            rows, cols = dist_wrt_node(nn, nr)
            self.declare_partials("thickness_ratio", "radius", rows=rows, cols=cols)

    def _ratio(self, inputs):
        radius = inputs["radius"][:, None]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ThicknessWarning)
            ratio, slope = section_thickness_ratio(self._polar(), inputs["radii"] / radius)
        return ratio, slope, radius

    def compute(self, inputs, outputs):
        outputs["thickness_ratio"] = self._ratio(inputs)[0]

    def compute_partials(self, inputs, partials):
        if not self._polar().varies_along_span:
            return
        _, slope, radius = self._ratio(inputs)
        partials["thickness_ratio", "radii"] = (slope / radius).ravel()
        partials["thickness_ratio", "radius"] = (-slope * inputs["radii"] / radius ** 2).ravel()
