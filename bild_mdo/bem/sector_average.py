"""SectorAverageComp: the sectional loads along the shaft, averaged over the azimuth sectors."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.bem.sectors import declare_sector_option, sector_wrt_station
from bild_mdo.bem.wind_components import add_geometry_inputs
from bild_mdo.utils.options import VARIABLES, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_node

#: Averaged loads: output name -> the per-sector input it averages.
AVERAGED_LOADS = {"dthrust_dr": "sector_dthrust_dr", "dtorque_dr": "sector_dtorque_dr"}


class SectorAverageComp(om.ExplicitComponent):
    """Azimuth-averaged sectional thrust and torque of a coned rotor in inclined flow.

    Each sector's blade elements give ``dT/dr`` normal to the coned blade and ``dQ/dr`` with the arm
    ``r`` along the blade (per unit blade length, all blades).  Along the shaft the force is
    ``dT/dr cos(precone)`` and the arm of the tangential force is ``r cos(precone)``; the rotor's loads
    are the mean over the ``ns`` equally spaced sectors (CCBlade's azimuthal average)::

        dthrust_dr = cos(precone) / ns  sum_k  sector_dthrust_dr[k]
        dtorque_dr = cos(precone) / ns  sum_k  sector_dtorque_dr[k]

    (per unit blade length; ``sum(dthrust_dr dr)`` is the thrust).  With one sector and no precone
    the outputs equal the inputs exactly.

    Options
    -------
    num_nodes, num_radial, num_sectors : int

    Inputs
    ------
    sector_dthrust_dr[nn, ns*nr] (N/m), sector_dtorque_dr[nn, ns*nr] (N*m/m), precone[nn] (rad)

    Outputs
    -------
    dthrust_dr[nn, nr] (N/m), dtorque_dr[nn, nr] (N*m/m)
    """

    def initialize(self):
        declare_size_options(self.options)
        declare_sector_option(self.options)

    def setup(self):
        nn, nr, ns = self.options["num_nodes"], self.options["num_radial"], self.options["num_sectors"]
        for out, name in AVERAGED_LOADS.items():
            _, _, units, desc = VARIABLES[out]
            self.add_input(name, val=np.ones((nn, ns * nr)), units=units, desc=f"{desc}, in each sector")
            self.add_output(out, val=np.ones((nn, nr)), units=units, desc=f"{desc}, along the shaft, sector mean")
        add_geometry_inputs(self, ("precone",))

    def setup_partials(self):
        nn, nr, ns = self.options["num_nodes"], self.options["num_radial"], self.options["num_sectors"]
        rows, cols = sector_wrt_station(nn, ns, nr)
        rows_n, cols_n = dist_wrt_node(nn, nr)
        for out, name in AVERAGED_LOADS.items():
            # d out[i, j] / d in[i, k, j]: the (row, col) pairs of the copy pattern, transposed.
            self.declare_partials(out, name, rows=cols, cols=rows)
            self.declare_partials(out, "precone", rows=rows_n, cols=cols_n)

    def _mean(self, inputs, name):
        nn, nr, ns = self.options["num_nodes"], self.options["num_radial"], self.options["num_sectors"]
        return np.sum(inputs[name].reshape(nn, ns, nr), axis=1) / ns

    def compute(self, inputs, outputs):
        cone = np.cos(inputs["precone"])[:, None]
        for out, name in AVERAGED_LOADS.items():
            outputs[out] = cone * self._mean(inputs, name)

    def compute_partials(self, inputs, partials):
        nr, ns = self.options["num_radial"], self.options["num_sectors"]
        cone = np.real(np.cos(inputs["precone"]))
        for out, name in AVERAGED_LOADS.items():
            partials[out, name] = np.repeat(cone / ns, ns * nr)
            partials[out, "precone"] = (-np.real(np.sin(inputs["precone"]))[:, None]
                                        * np.real(self._mean(inputs, name))).ravel()
