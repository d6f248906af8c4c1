"""CurveAssemblyComp: the power curve of each rotor from its region-2 and region-3 BEM analyses."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.energy.wind_speeds import declare_tip_speed_limit_option, declare_wind_speed_option, region_sizes

#: Curves assembled from both regions: name -> (units, description).
CURVE_OUTPUTS = {"power": ("W", "power extracted at each wind speed of the curve"),
                 "thrust": ("N", "rotor thrust (downwind) at each wind speed of the curve"),
                 "torque": ("N*m", "aerodynamic torque at each wind speed of the curve"),
                 "power_coefficient": (None, "power coefficient C_P at each wind speed of the curve"),
                 "thrust_coefficient": (None, "thrust coefficient C_T at each wind speed of the curve")}


class CurveAssemblyComp(om.ExplicitComponent):
    """Region 2 (``n2`` points, pitch 0) and region 3 (``n3 - 1`` points, trimmed pitch) side by side per rotor.

    ``<name>[i, :n2] = region2_<name>[i*n2 : (i+1)*n2]`` and ``<name>[i, n2:] = region3_<name>[...]``
    (flat BEM node axes of :class:`~bild_mdo.energy.rotor_broadcast.RotorBroadcastComp`); the pitch is
    zero in region 2.  Constant 0/1 partials.

    Options
    -------
    num_nodes : int
        Rotors.
    num_wind_speeds : int
        Points of the curve ``nw = n2 + n3 - 1`` (:func:`~bild_mdo.energy.wind_speeds.region_sizes`).
    tip_speed_limit : bool
        The layout of a curve with a tip-speed limit (region 2 with more points, region 3 with fewer).

    Inputs
    ------
    region2_<name>[nn*n2], region3_<name>[nn*(n3-1)] for every name of :data:`CURVE_OUTPUTS`;
    region3_collective_pitch[nn*(n3-1)] (rad)

    Outputs
    -------
    power[nn, nw] (W), thrust[nn, nw] (N), torque[nn, nw] (N*m), power_coefficient[nn, nw],
    thrust_coefficient[nn, nw], collective_pitch[nn, nw] (rad)
    """

    def initialize(self):
        self.options.declare("num_nodes", types=int, default=1, lower=1, desc="rotors (axis 0)")
        declare_wind_speed_option(self.options)
        declare_tip_speed_limit_option(self.options)

    def setup(self):
        nn, nw = self.options["num_nodes"], self.options["num_wind_speeds"]
        n2, n3 = region_sizes(nw, self.options["tip_speed_limit"])
        index = np.arange(nn * nw).reshape(nn, nw)
        self._slots = {"region2": index[:, :n2].ravel(), "region3": index[:, n2:].ravel()}
        sizes = {"region2": nn * n2, "region3": nn * (n3 - 1)}
        for name, (units, desc) in CURVE_OUTPUTS.items():
            self.add_output(name, val=np.ones((nn, nw)), units=units, desc=desc)
            for region, size in sizes.items():
                self.add_input(f"{region}_{name}", val=np.ones(size), units=units, desc=f"{desc} ({region})")
                self.declare_partials(name, f"{region}_{name}", rows=self._slots[region], cols=np.arange(size),
                                      val=1.0)
        self.add_input("region3_collective_pitch", val=np.zeros(sizes["region3"]), units="rad",
                       desc="trimmed collective pitch in region 3")
        self.add_output("collective_pitch", val=np.zeros((nn, nw)), units="rad",
                        desc="collective pitch at each wind speed of the curve (0 in region 2, to feather > 0)")
        self.declare_partials("collective_pitch", "region3_collective_pitch", rows=self._slots["region3"],
                              cols=np.arange(sizes["region3"]), val=1.0)

    def compute(self, inputs, outputs):
        for name in list(CURVE_OUTPUTS) + ["collective_pitch"]:
            flat = np.zeros(outputs[name].size, dtype=outputs[name].dtype)
            for region, slots in self._slots.items():
                key = f"{region}_{name}"
                if key in inputs:
                    flat[slots] = inputs[key]
            outputs[name] = flat.reshape(outputs[name].shape)
