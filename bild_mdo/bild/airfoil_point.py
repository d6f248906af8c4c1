"""The airfoil point ``alpha*, C_l*, C_d*`` of the BILD chain: one per design, or one per station.

With one airfoil along the span the maximum-L/D point is a per-design value,
shape ``(nn,)`` (paper Assumption 2).  With a polar that varies along the span
(:class:`~bild_mdo.airfoil.spanwise.SpanwisePolar`) every station has its own
point, shape ``(nn, nr)``, taken at the reference station's Reynolds and Mach
numbers (Assumption 2 per station).  The components that read the point
(:class:`~bild_mdo.bild.variants.paper.eta2.Eta2Comp`,
:class:`~bild_mdo.bild.induced_velocity.InducedVelocityComp`,
:class:`~bild_mdo.bild.inflow_angle.InflowAngleComp`,
:class:`~bild_mdo.bild.chord.ChordComp`) declare the option
``varies_along_span`` and use the helpers below, so the per-design case keeps
its shapes, arithmetic and sparsity exactly.
"""
import numpy as np

from bild_mdo.utils.options import VARIABLES, add_inputs
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node

#: The names of the maximum-L/D point.
AIRFOIL_POINT = ("alpha_star", "cl_star", "cd_star")


def declare_spanwise_option(options):
    """Declare ``varies_along_span``: whether the airfoil point is given per station ``(nn, nr)``."""
    options.declare("varies_along_span", types=bool, default=False,
                    desc="alpha_star, cl_star, cd_star per station [nn, nr] (a polar that varies along the span) "
                         "instead of per design [nn]")


def add_airfoil_point_inputs(component, names):
    """Declare the airfoil-point inputs ``names`` with shape ``(nn, nr)`` or ``(nn,)`` (the option)."""
    if not component.options["varies_along_span"]:
        add_inputs(component, names)
        return
    shape = (component.options["num_nodes"], component.options["num_radial"])
    for name in names:
        _, default, units, desc = VARIABLES[name]
        component.add_input(name, val=np.full(shape, default), units=units, desc=f"{desc}, per station")


def airfoil_point_pattern(component):
    """``rows, cols`` of the partial of a ``(nn, nr)`` output with respect to the airfoil point."""
    nn, nr = component.options["num_nodes"], component.options["num_radial"]
    return dist_wrt_dist(nn, nr) if component.options["varies_along_span"] else dist_wrt_node(nn, nr)


def per_station(value):
    """A per-design value as an ``(nn, 1)`` column that broadcasts over stations; an ``(nn, nr)`` value as is."""
    return value if value.ndim == 2 else value[:, None]
