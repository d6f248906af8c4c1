"""The size options and the shared input declarations of every vectorised component, written once.

``num_nodes`` counts designs or operating points (axis 0) and ``num_radial``
counts radial stations (axis 1).  A component declares only the sizes it uses:
a per-design component (reference station, advance ratio) has no ``num_radial``.
Inputs that several components share (``v_axial``, ``radii``, ``cl_star`` ...)
are declared from one catalogue, :data:`VARIABLES`, so their units and
descriptions cannot drift apart.
"""
import numpy as np

#: Default number of designs or operating points.
DEFAULT_NUM_NODES = 1
#: Default number of radial stations, the same for every component and group.
DEFAULT_NUM_RADIAL = 20


def declare_size_options(options, radial=True):
    """Declare ``num_nodes`` (and, unless ``radial`` is False, ``num_radial``) on an options dictionary.

    Parameters
    ----------
    options : openmdao.utils.options_dictionary.OptionsDictionary
        The component's or group's ``self.options``.
    radial : bool
        Whether the component has radial distributions (axis 1).
    """
    options.declare("num_nodes", types=int, default=DEFAULT_NUM_NODES, lower=1,
                    desc="number of designs or operating points (axis 0), >= 1")
    if radial:
        options.declare("num_radial", types=int, default=DEFAULT_NUM_RADIAL, lower=1,
                        desc="number of radial stations (axis 1), >= 1")


def sizes(options):
    """``{'num_nodes': nn, 'num_radial': nr}`` of a group's options, to pass to radial children."""
    return {"num_nodes": options["num_nodes"], "num_radial": options["num_radial"]}


#: Variables that several components declare, one declaration each: name -> (axes, default, units, description).
#: ``axes`` is ``'node'`` for a per-design scalar, shape ``(nn,)``, or ``'dist'`` for a radial distribution,
#: shape ``(nn, nr)``.  BEM and BILD use the same name for the same quantity.
VARIABLES = {
    "v_axial": ("node", 0.0, "m/s", "axial free-stream velocity V_x (>= 0)"),
    "rpm": ("node", 1000.0, "rpm", "rotor speed"),
    "radius": ("node", 1.0, "m", "rotor tip radius R"),
    "hub_radius": ("node", 0.1, "m", "hub radius"),
    "rho": ("node", 1.225, "kg/m**3", "density of the fluid (air: ISA)"),
    "mu": ("node", 1.789e-5, "Pa*s", "dynamic viscosity of the fluid (air: ISA)"),
    "ref_radius": ("node", 0.5, "m", "radius of the reference station r_ref"),
    "ref_chord": ("node", 0.1, "m", "chord at the reference station c_ref"),
    "v_theta_ref": ("node", 50.0, "m/s", "rotational speed Omega*r_ref at the reference station"),
    "cl_star": ("node", 1.0, None, "lift coefficient at the maximum lift-to-drag ratio C_l*"),
    "cd_star": ("node", 0.01, None, "drag coefficient at the maximum lift-to-drag ratio C_d*"),
    "alpha_star": ("node", 0.1, "rad", "angle of attack of maximum lift-to-drag ratio alpha*"),
    "phi_ref": ("node", 0.1, "rad", "inflow angle at the reference station"),
    "speed_of_sound": ("node", 340.294, "m/s", "speed of sound a (ISA sea level by default)"),
    "collective_pitch": ("node", 0.0, "rad", "collective pitch, added to the twist at every station"),
    "radii": ("dist", 1.0, "m", "radius of each station"),
    "dr": ("dist", 0.1, "m", "radial width of each station"),
    "chord": ("dist", 0.1, "m", "blade chord"),
    "twist": ("dist", 0.3, "rad", "blade twist (pitch) angle"),
    "phi": ("dist", 0.1, "rad", "inflow angle"),
    "v_theta": ("dist", 50.0, "m/s", "rotational blade speed Omega*r at the stations"),
    "eta2": ("dist", 0.95, None, "annular efficiency for tangential induced losses, Eq. (23)"),
    "u_axial": ("dist", 5.0, "m/s", "axial velocity at the rotor disk u_axial (free stream plus induction)"),
    "u_theta": ("dist", 1.0, "m/s", "tangential induced velocity u_theta"),
    "inflow_speed": ("dist", 50.0, "m/s", "inflow speed W = sqrt(u_axial^2 + (V_theta - u_theta/2)^2), Eq. (7)"),
    "dthrust_dr": ("dist", 1.0, "N/m", "sectional thrust per unit span dT/dr (all blades)"),
    "dtorque_dr": ("dist", 1.0, "N*m/m", "sectional torque per unit span dQ/dr (all blades)"),
    "loss_factor": ("dist", 1.0, None, "Prandtl tip/hub loss factor F"),
    "lift_coefficient": ("dist", 1.0, None, "section lift coefficient C_l"),
    "drag_coefficient": ("dist", 0.01, None, "section drag coefficient C_d"),
    "chord_raw": ("dist", 0.1, "m", "back-computed chord before the root-chord correction, Eq. (31)"),
    "u_axial_ref": ("node", 10.0, "m/s", "axial velocity at the rotor disk at the reference station"),
    "u_theta_ref": ("node", 1.0, "m/s", "tangential induced velocity at the reference station"),
    "ideal_loading_constant": ("node", 10.0, "m/s",
                               "ideal-loading constant lambda: marginal energy loss per marginal thrust, Eq. (22)"),
}


def _declare(component, method, names, values):
    nn = component.options["num_nodes"]
    for name in names:
        axes, default, units, desc = VARIABLES[name]
        shape = (nn,) if axes == "node" else (nn, component.options["num_radial"])
        val = np.broadcast_to(values.get(name, default), shape).copy()
        method(name, val=val, units=units, desc=desc)


def add_inputs(component, names, **values):
    """Declare the inputs ``names`` of :data:`VARIABLES` on ``component`` with their shape, units and description.

    Parameters
    ----------
    component : openmdao.api.Component
        Called in its ``setup``; its ``num_nodes`` (and, for distributions,
        ``num_radial``) options give the shapes.
    names : iterable of str
        Keys of :data:`VARIABLES`.
    **values
        Default values that differ from the catalogue's (broadcast to the shape).
    """
    _declare(component, component.add_input, names, values)


def add_outputs(component, names, **values):
    """Declare the outputs ``names`` of :data:`VARIABLES` on ``component``, as :func:`add_inputs` does inputs."""
    _declare(component, component.add_output, names, values)
