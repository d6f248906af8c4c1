"""SpeedRatioComp: the nondimensional operating point of minimum-induced-loss design."""
import numpy as np
import openmdao.api as om

from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.utils.options import add_inputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node, node_wrt_node


class SpeedRatioComp(om.ExplicitComponent):
    """Speed ratio ``lambda = V/(Omega R)`` and the stations as fractions of the tip radius.

    Adkins & Liebeck (1994) write the whole design in the speed ratio
    ``lambda`` (their nomenclature; ``lambda = J/pi`` with the advance ratio
    ``J = V/(n D)``) and the nondimensional radius ``xi = r/R``.  The method is
    for forward flight only: ``lambda -> 0`` (hover) makes the
    nondimensional coefficients ``T_c = 2T/(rho V^2 pi R^2)`` infinite, so
    ``v_axial <= 0`` raises :class:`openmdao.api.AnalysisError`.

    Options
    -------
    num_nodes, num_radial : int
        Designs (axis 0) and stations (axis 1).

    Inputs
    ------
    v_axial[nn] (m/s), rpm[nn] (rpm), radius[nn] (m)
        Flight speed (> 0), rotor speed (> 0) and tip radius.
    radii[nn, nr] (m), dr[nn, nr] (m)
        Station radii and widths.

    Outputs
    -------
    speed_ratio[nn] (-)
        ``lambda = V/(Omega R)``.
    radius_fraction[nn, nr] (-), width_fraction[nn, nr] (-)
        ``xi = r/R`` and ``dxi = dr/R``.
    """

    def initialize(self):
        declare_size_options(self.options)

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        add_inputs(self, ("v_axial", "rpm", "radius", "radii", "dr"), v_axial=50.0, rpm=2400.0)
        self.add_output("speed_ratio", val=np.full(nn, 0.2), units=None, desc="speed ratio lambda = V/(Omega R)")
        self.add_output("radius_fraction", val=np.full((nn, nr), 0.5), units=None, desc="station radius xi = r/R")
        self.add_output("width_fraction", val=np.full((nn, nr), 0.05), units=None, desc="station width dr/R")

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = node_wrt_node(nn)
        self.declare_partials("speed_ratio", ["v_axial", "rpm", "radius"], rows=rows, cols=cols)
        rows, cols = dist_wrt_dist(nn, nr)
        self.declare_partials("radius_fraction", "radii", rows=rows, cols=cols)
        self.declare_partials("width_fraction", "dr", rows=rows, cols=cols)
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials("radius_fraction", "radius", rows=rows, cols=cols)
        self.declare_partials("width_fraction", "radius", rows=rows, cols=cols)

    def _check(self, inputs):
        for name, hint in (("v_axial", "minimum-induced-loss design is for forward flight (J > 0)"),
                           ("rpm", "give a positive rotor speed"), ("radius", "give a positive tip radius")):
            value = np.real(inputs[name])
            bad = ~(value > 0.0)
            if np.any(bad):
                node = int(np.flatnonzero(bad)[0])
                raise om.AnalysisError(f"{self.msginfo}: {name} must be positive, got {value[node]!r} at node "
                                       f"{node}: {hint}")

    def compute(self, inputs, outputs):
        self._check(inputs)
        radius = inputs["radius"]
        outputs["speed_ratio"] = inputs["v_axial"] / (inputs["rpm"] * RPM_TO_RAD_PER_S * radius)
        outputs["radius_fraction"] = inputs["radii"] / radius[:, None]
        outputs["width_fraction"] = inputs["dr"] / radius[:, None]

    def compute_partials(self, inputs, partials):
        v, rpm, radius = inputs["v_axial"], inputs["rpm"], inputs["radius"]
        lam = v / (rpm * RPM_TO_RAD_PER_S * radius)
        partials["speed_ratio", "v_axial"] = lam / v
        partials["speed_ratio", "rpm"] = -lam / rpm
        partials["speed_ratio", "radius"] = -lam / radius
        nr = self.options["num_radial"]
        partials["radius_fraction", "radii"] = np.repeat(1.0 / radius, nr)
        partials["width_fraction", "dr"] = np.repeat(1.0 / radius, nr)
        partials["radius_fraction", "radius"] = (-inputs["radii"] / radius[:, None] ** 2).ravel()
        partials["width_fraction", "radius"] = (-inputs["dr"] / radius[:, None] ** 2).ravel()
