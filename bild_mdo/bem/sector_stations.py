"""SectorStationsComp: the blade's station distributions repeated for every azimuth sector."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.bem.sectors import declare_sector_option, sector_wrt_station
from bild_mdo.utils.options import VARIABLES, add_inputs, declare_size_options

#: Distributions the blade elements of every sector read: input name -> output name.
SECTOR_COPIES = {"radii": "sector_radii", "chord": "sector_chord", "twist": "sector_twist"}


class SectorStationsComp(om.ExplicitComponent):
    """Copies ``radii``, ``chord`` and ``twist`` to every azimuth sector (:mod:`bild_mdo.bem.sectors`).

    The blade is the same in every sector; the inflow differs
    (:class:`~bild_mdo.bem.wind_components.WindComponentsComp`).  With one sector the outputs equal
    the inputs exactly.

    Options
    -------
    num_nodes, num_radial, num_sectors : int

    Inputs
    ------
    radii[nn, nr] (m), chord[nn, nr] (m), twist[nn, nr] (rad)

    Outputs
    -------
    sector_radii[nn, ns*nr] (m), sector_chord[nn, ns*nr] (m), sector_twist[nn, ns*nr] (rad)
        Sector-major: ``output.reshape(nn, ns, nr)[:, k] == input`` for every sector ``k``.
    """

    def initialize(self):
        declare_size_options(self.options)
        declare_sector_option(self.options)

    def setup(self):
        nn, nr, ns = self.options["num_nodes"], self.options["num_radial"], self.options["num_sectors"]
        add_inputs(self, tuple(SECTOR_COPIES))
        for name, out in SECTOR_COPIES.items():
            _, default, units, desc = VARIABLES[name]
            self.add_output(out, val=np.full((nn, ns * nr), default), units=units, desc=f"{desc}, every sector")

    def setup_partials(self):
        rows, cols = sector_wrt_station(self.options["num_nodes"], self.options["num_sectors"],
                                        self.options["num_radial"])
        for name, out in SECTOR_COPIES.items():
            self.declare_partials(out, name, rows=rows, cols=cols, val=1.0)

    def compute(self, inputs, outputs):
        ns = self.options["num_sectors"]
        for name, out in SECTOR_COPIES.items():
            outputs[out] = np.tile(inputs[name], (1, ns))
