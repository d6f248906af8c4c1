"""StationsComp: radial stations (radii and widths) of the blade-element discretisation."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.utils.sparsity import dist_wrt_node


def _fraction_array(value, name, nn, nr):
    arr = np.asarray(value, dtype=float)
    if arr.shape == (nr,):
        arr = np.broadcast_to(arr, (nn, nr))
    if arr.shape != (nn, nr):
        raise ValueError(f"{name} must have shape ({nr},) or ({nn}, {nr}), got {arr.shape}")
    return np.array(arr)


class StationsComp(om.ExplicitComponent):
    """Radii and widths of the radial stations; integrals are ``sum(f * dr)``.

    By default the span from hub to tip is cut into ``num_radial`` equal annuli
    and each station sits at the midpoint of its annulus (midpoint rule):
    ``dr = (R - r_hub)/nr``, ``r_j = r_hub + (j + 1/2) dr``.  Alternatively the
    user gives station radii and widths as fractions of the tip radius
    (options ``radial_fractions`` and ``width_fractions``, shape (nr,) or
    (nn, nr)); then ``r = radial_fractions * R`` and ``dr = width_fractions * R``.

    Options
    -------
    num_nodes, num_radial : int
        Designs (axis 0) and stations (axis 1).
    radial_fractions : array_like or None
        Station radii r/R; None for equal annuli.
    width_fractions : array_like or None
        Station widths dr/R; required with ``radial_fractions``.

    Inputs
    ------
    radius[nn] (m), hub_radius[nn] (m)
        Tip and hub radius.

    Outputs
    -------
    radii[nn, nr] (m), dr[nn, nr] (m)
        Station radii and widths.
    """

    def initialize(self):
        self.options.declare("num_nodes", types=int, default=1, desc="number of designs / operating points (axis 0)")
        self.options.declare("num_radial", types=int, default=10, desc="number of radial stations (axis 1)")
        self.options.declare("radial_fractions", default=None, allow_none=True,
                             desc="station radii as fractions of the tip radius, shape (nr,) or (nn, nr); "
                                  "None for midpoints of equal annuli")
        self.options.declare("width_fractions", default=None, allow_none=True,
                             desc="station widths as fractions of the tip radius (with radial_fractions)")

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        self.add_input("radius", val=np.ones(nn), units="m", desc="rotor tip radius R")
        self.add_input("hub_radius", val=np.full(nn, 0.1), units="m", desc="hub radius")
        self.add_output("radii", val=np.tile(np.linspace(0.2, 0.95, nr), (nn, 1)), units="m",
                        desc="radius of each station")
        self.add_output("dr", val=np.full((nn, nr), 0.1), units="m", desc="radial width of each station")
        rf, wf = self.options["radial_fractions"], self.options["width_fractions"]
        if (rf is None) != (wf is None):
            raise ValueError("give both radial_fractions and width_fractions, or neither")
        if rf is None:
            self._user = None
        else:
            self._user = (_fraction_array(rf, "radial_fractions", nn, nr),
                          _fraction_array(wf, "width_fractions", nn, nr))

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = dist_wrt_node(nn, nr)
        if self._user is None:
            # r_j = r_hub + (j + 1/2)(R - r_hub)/nr, dr = (R - r_hub)/nr: constant partials.
            frac = np.tile((np.arange(nr) + 0.5) / nr, nn)
            self.declare_partials("radii", "radius", rows=rows, cols=cols, val=frac)
            self.declare_partials("radii", "hub_radius", rows=rows, cols=cols, val=1.0 - frac)
            self.declare_partials("dr", "radius", rows=rows, cols=cols, val=np.full(nn * nr, 1.0 / nr))
            self.declare_partials("dr", "hub_radius", rows=rows, cols=cols, val=np.full(nn * nr, -1.0 / nr))
        else:
            rf, wf = self._user
            self.declare_partials("radii", "radius", rows=rows, cols=cols, val=rf.ravel())
            self.declare_partials("dr", "radius", rows=rows, cols=cols, val=wf.ravel())

    def compute(self, inputs, outputs):
        nr = self.options["num_radial"]
        R = inputs["radius"][:, None]
        if self._user is None:
            rh = inputs["hub_radius"][:, None]
            width = (R - rh) / nr
            outputs["radii"] = rh + (np.arange(nr) + 0.5) * width
            outputs["dr"] = width * np.ones(nr)
        else:
            rf, wf = self._user
            outputs["radii"] = rf * R
            outputs["dr"] = wf * R
