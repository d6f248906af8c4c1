"""Ideal induced velocities u_axial, u_theta from the annular efficiency eta2 (Eqs. (24), (26))."""
import numpy as np
import openmdao.api as om

from bild_mdo.bild.airfoil_point import (
    add_airfoil_point_inputs,
    airfoil_point_pattern,
    declare_spanwise_option,
    per_station,
)
from bild_mdo.bild.feasibility import declare_feasibility_option, report_infeasible, station_details
from bild_mdo.bild.variants.paper.quartic import axial_velocity_root
from bild_mdo.utils.options import add_inputs, add_outputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node


class InducedVelocityComp(om.ExplicitComponent):
    """Axial and tangential induced velocities of the ideally loaded rotor.

    With ``s = C_d*/C_l*`` (inverse maximum lift-to-drag ratio)::

        u_theta = 2 V_theta (1 - eta2)                                  Eq. (24)
        b       = (V_x - V_theta s) / 2
        c       = eta2 V_theta (V_theta (1 - eta2) + V_x s)
        u_axial     = b + sqrt(b**2 + c)                                    Eq. (26)

    ``c >= 0`` for ``0.5 <= eta2 <= 1``, so the root is real.  For ``b < 0``
    (always in hover) ``b + sqrt(b**2 + c)`` cancels when ``c`` is small
    (``eta2`` near 1); the root is then evaluated as ``c / (sqrt(b**2 + c) - b)``
    (:func:`~bild_mdo.bild.variants.paper.quartic.axial_velocity_root`).  An
    unloaded station in hover (``eta2 = 1``, ``V_x = 0``) gives ``u_axial = 0``
    and ``u_theta = 0`` with finite derivatives (``sqrt(b**2 + c) = |b| > 0``).

    Assumption 3 (positive local thrust, ``u_axial > V_x``) is checked here:
    ``u_axial - V_x`` has the sign of ``(1 - eta2)(eta2 V_theta - s V_x)``
    (hand derivation from Eq. (25)), so a loaded station needs
    ``V_x < eta2 V_theta C_l*/C_d*``.  It fails at inboard stations (small
    ``V_theta``) at a high advance ratio with a low-L/D airfoil; such a
    station would windmill, and the compute raises
    :class:`openmdao.api.AnalysisError` naming every failing node (inside a
    :class:`~bild_mdo.bild.bild_group.BILDGroup` the nodes are recorded in
    the group's feasibility ledger instead; their values, still finite, are
    placeholders).  The unloaded hover
    station (``eta2 = 1``, ``V_x = 0``, so ``u_axial = V_x = 0``) satisfies the
    rule and is legitimate.

    Options: the sizes ``num_nodes`` and ``num_radial``
    (:func:`~bild_mdo.utils.options.declare_size_options`) and ``feasibility``
    (:func:`~bild_mdo.bild.feasibility.declare_feasibility_option`).

    Inputs
    ------
    eta2[nn, nr] (-)
        Annular efficiency for tangential induced losses, Eq. (23).
    v_axial[nn] (m/s)
        Axial free-stream velocity.
    v_theta[nn, nr] (m/s)
        Rotational blade speed ``Omega r``.
    cl_star[nn] (-), cd_star[nn] (-)
        Lift and drag coefficients at the maximum lift-to-drag ratio
        (``[nn, nr]`` with ``varies_along_span=True``, :mod:`~bild_mdo.bild.airfoil_point`).

    Outputs
    -------
    u_axial[nn, nr] (m/s)
        Axial velocity at the rotor disk (free stream plus induction), Eq. (26).
    u_theta[nn, nr] (m/s)
        Tangential induced velocity in the far wake, Eq. (24).
    """

    def initialize(self):
        declare_size_options(self.options)
        declare_feasibility_option(self.options)
        declare_spanwise_option(self.options)

    def setup(self):
        add_inputs(self, ("eta2", "v_axial", "v_theta"))
        add_airfoil_point_inputs(self, ("cl_star", "cd_star"))
        add_outputs(self, ("u_axial", "u_theta"))

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = dist_wrt_dist(nn, nr)
        self.declare_partials("u_axial", ["eta2", "v_theta"], rows=rows, cols=cols)
        self.declare_partials("u_theta", ["eta2", "v_theta"], rows=rows, cols=cols)
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials("u_axial", ["v_axial"], rows=rows, cols=cols)
        rows, cols = airfoil_point_pattern(self)
        self.declare_partials("u_axial", ["cl_star", "cd_star"], rows=rows, cols=cols)

    def _terms(self, inputs):
        eta2 = inputs["eta2"]
        v_t = inputs["v_theta"]
        v_x = inputs["v_axial"][:, None]
        s = per_station(inputs["cd_star"] / inputs["cl_star"])
        b = 0.5 * (v_x - v_t * s)
        c = eta2 * v_t * (v_t * (1.0 - eta2) + v_x * s)
        return eta2, v_t, v_x, s, b, c

    def _check_positive_thrust(self, eta2, v_t, v_x, s, eta2_v_t=None):
        """Report the nodes where ``V_x < eta2 V_theta / s`` (Assumption 3, ``u_axial > V_x``) fails somewhere."""
        eta2, v_t, v_x, s = (np.real(a) for a in (eta2, v_t, v_x, s))
        limit = (eta2 * v_t if eta2_v_t is None else np.real(eta2_v_t)) / s
        holds = v_x < limit
        bad = None if holds.all() else ~holds
        details = {} if bad is None else station_details(
            bad, {"V_theta [m/s]": v_t, "eta2": eta2, "V_x [m/s]": v_x, "C_l*/C_d*": 1.0 / s,
                  "limit eta2 V_theta C_l*/C_d* [m/s]": limit})
        report_infeasible(
            self, "positive_thrust", np.zeros(holds.shape[0], dtype=bool) if bad is None else np.any(bad, axis=1),
            "Assumption 3 (u_axial > V_x, positive local thrust) fails: a station needs "
            "V_x < eta2 V_theta C_l*/C_d*, else the blade element windmills. Increase hub_radius_ratio "
            "(inboard stations have the lowest V_theta), lower the advance ratio / V_x, or use an airfoil "
            "with a higher maximum L/D", details)

    def compute(self, inputs, outputs):
        eta2, v_t = inputs["eta2"], inputs["v_theta"]
        v_x = inputs["v_axial"][:, None]
        s = per_station(inputs["cd_star"] / inputs["cl_star"])
        swirl = v_t * (1.0 - eta2)  # u_theta/2, Eq. (24)
        eta2_v_t = eta2 * v_t
        self._check_positive_thrust(eta2, v_t, v_x, s, eta2_v_t)
        b = 0.5 * v_x - (0.5 * s) * v_t  # = (V_x - V_theta s)/2 exactly
        c = eta2_v_t * (swirl + v_x * s)
        # Eq. (26) without cancellation (as axial_velocity_root): u+ = c/(r - b) for b < 0, b + r for b >= 0.
        r = np.sqrt(b * b + c)
        u_axial = outputs["u_axial"]
        with np.errstate(divide="ignore", invalid="ignore"):
            np.divide(c, r - b, out=u_axial)
        np.add(b, r, out=u_axial, where=np.real(b) >= 0.0)
        np.multiply(swirl, 2.0, out=outputs["u_theta"])

    def compute_partials(self, inputs, partials):
        eta2, v_t, v_x, s, b, c = self._terms(inputs)
        u_axial, root = axial_velocity_root(b, c)
        cl = per_station(inputs["cl_star"])
        cd = per_station(inputs["cd_star"])

        # Differentiating u**2 - 2 b u - c = 0 (Eq. (25)): du = (2 u db + dc) / (2 sqrt(b**2 + c)).
        inv_two_root = 0.5 / root
        dc_deta2 = v_t * (v_t * (1.0 - 2.0 * eta2) + v_x * s)
        dc_dvx = eta2 * v_t * s
        dc_dvt = eta2 * (2.0 * v_t * (1.0 - eta2) + v_x * s)
        dc_ds = eta2 * v_t * v_x
        dux_ds = (-u_axial * v_t + dc_ds) * inv_two_root

        partials["u_axial", "eta2"] = (dc_deta2 * inv_two_root).ravel()
        partials["u_axial", "v_axial"] = ((u_axial + dc_dvx) * inv_two_root).ravel()
        partials["u_axial", "v_theta"] = ((-u_axial * s + dc_dvt) * inv_two_root).ravel()
        partials["u_axial", "cl_star"] = (dux_ds * (-cd / cl ** 2)).ravel()
        partials["u_axial", "cd_star"] = (dux_ds / cl).ravel()
        partials["u_theta", "eta2"] = (-2.0 * v_t).ravel()
        partials["u_theta", "v_theta"] = (2.0 * (1.0 - eta2)).ravel()
