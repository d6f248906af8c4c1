"""Back-computed chord of the ideal blade (Eq. (31), or its torque counterpart from Eq. (6))."""
import numpy as np
import openmdao.api as om

from bild_mdo.bild.airfoil_point import (
    add_airfoil_point_inputs,
    airfoil_point_pattern,
    declare_spanwise_option,
    per_station,
)
from bild_mdo.bild.feasibility import declare_feasibility_option, report_infeasible, station_details
from bild_mdo.utils.options import add_inputs, add_outputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node

CHORD_FORMS = ("thrust", "torque")


class ChordComp(om.ExplicitComponent):
    """Chord that makes the blade element carry the ideal sectional load.

    Thrust form (default, Eq. (31))::

        c = 2 dT/dr / (C_x rho W**2 B),           C_x = C_l* cos(phi) - C_d* sin(phi)

    Torque form (Eq. (6) solved for c)::

        c = 2 dQ/dr / (C_theta rho W**2 B r),     C_theta = C_l* sin(phi) + C_d* cos(phi)

    Both forms give the same chord when the induced velocities satisfy
    Eq. (25), which Eq. (26) guarantees; the option exists to check that and
    to choose the better-conditioned one.  An unloaded station (zero load)
    gets zero chord: ``C_x`` and ``C_theta`` stay positive for
    ``0 <= phi < atan(C_l/C_d)``, so no division by zero occurs.  Where the
    coefficient is not positive the compute raises
    :class:`openmdao.api.AnalysisError` naming every failing node (inside a
    :class:`~bild_mdo.bild.bild_group.BILDGroup` the nodes are recorded in the
    group's feasibility ledger and their chord is a placeholder computed with
    the coefficient set to 1, partials consistent with it).

    The section's lift and drag coefficients (the constant ``C_l*``, ``C_d*``
    of Assumption 2) are also given as distributions for plotting.

    Options
    -------
    num_nodes, num_radial, num_blades : int
        Sizes (:func:`~bild_mdo.utils.options.declare_size_options`) and the number of blades B.
    chord_form : str
        ``'thrust'`` (Eq. (31), default) or ``'torque'``.
    feasibility : FeasibilityLedger or None
        See :func:`~bild_mdo.bild.feasibility.declare_feasibility_option`.
    varies_along_span : bool
        ``cl_star``, ``cd_star`` per station (:mod:`~bild_mdo.bild.airfoil_point`).

    Inputs
    ------
    dthrust_dr[nn, nr] (N/m)
        dT/dr (thrust form only).
    dtorque_dr[nn, nr] (N*m/m)
        dQ/dr (torque form only).
    radii[nn, nr] (m)
        Station radii (torque form only).
    phi[nn, nr] (rad)
        Inflow angle.
    inflow_speed[nn, nr] (m/s)
        Resultant inflow speed W.
    rho[nn] (kg/m**3)
        Air density.
    cl_star[nn] (-), cd_star[nn] (-)
        Lift and drag coefficients at the maximum lift-to-drag ratio
        (``[nn, nr]`` with ``varies_along_span=True``).

    Outputs
    -------
    chord_raw[nn, nr] (m)
        Back-computed chord, before any root-chord correction.
    lift_coefficient[nn, nr] (-), drag_coefficient[nn, nr] (-)
        Section coefficients (``C_l*``, ``C_d*`` at every station).
    """

    def initialize(self):
        declare_size_options(self.options)
        declare_feasibility_option(self.options)
        declare_spanwise_option(self.options)
        self.options.declare("num_blades", types=int, default=3, desc="number of blades B")
        self.options.declare("chord_form", default="thrust", values=CHORD_FORMS,
                             desc="'thrust': Eq. (31) from dT/dr; 'torque': Eq. (6) from dQ/dr")

    def setup(self):
        if self.options["chord_form"] == "thrust":
            add_inputs(self, ("dthrust_dr",))
        else:
            add_inputs(self, ("dtorque_dr", "radii"))
        add_inputs(self, ("phi", "inflow_speed", "rho"))
        add_airfoil_point_inputs(self, ("cl_star", "cd_star"))
        add_outputs(self, ("chord_raw", "lift_coefficient", "drag_coefficient"))

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = dist_wrt_dist(nn, nr)
        load = "dthrust_dr" if self.options["chord_form"] == "thrust" else "dtorque_dr"
        wrt = [load, "phi", "inflow_speed"]
        if self.options["chord_form"] == "torque":
            wrt.append("radii")
        self.declare_partials("chord_raw", wrt, rows=rows, cols=cols)
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials("chord_raw", ["rho"], rows=rows, cols=cols)
        rows, cols = airfoil_point_pattern(self)
        self.declare_partials("chord_raw", ["cl_star", "cd_star"], rows=rows, cols=cols)
        self.declare_partials("lift_coefficient", "cl_star", rows=rows, cols=cols, val=1.0)
        self.declare_partials("drag_coefficient", "cd_star", rows=rows, cols=cols, val=1.0)

    def _parts(self, inputs, derivatives=True):
        """Return load, force coefficient, its phi, cl, cd derivatives (None without ``derivatives``), denominator.

        The denominator is ``rho W**2 B / 2`` (times ``r`` in the torque form): ``chord = load / (coef denominator)``.
        """
        thrust_form = self.options["chord_form"] == "thrust"
        phi = inputs["phi"]
        cl = per_station(inputs["cl_star"])
        cd = per_station(inputs["cd_star"])
        sin, cos = np.sin(phi), np.cos(phi)
        w = inputs["inflow_speed"]
        scale = (0.5 * self.options["num_blades"] * inputs["rho"])[:, None] * (w * w)
        if thrust_form:
            load = inputs["dthrust_dr"]
            coef = cl * cos - cd * sin
        else:
            load = inputs["dtorque_dr"]
            coef = cl * sin + cd * cos
            scale = scale * inputs["radii"]
        positive = np.real(coef) > 0.0
        bad = None if positive.all() else ~positive
        if thrust_form:
            kind, rule = "C_x = C_l cos(phi) - C_d sin(phi)", "phi < atan(C_l/C_d)"
        else:
            kind, rule = "C_theta = C_l sin(phi) + C_d cos(phi)", "phi > -atan(C_d/C_l)"
        report_infeasible(
            self, "force_coefficient", np.zeros(load.shape[0], dtype=bool) if bad is None else np.any(bad, axis=1),
            f"the blade-element force coefficient {kind} is not positive; the chord needs {rule} to be "
            "back-computed. In the BILD chain the station cannot carry the ideal load (Assumption 3): increase "
            "hub_radius_ratio, lower the advance ratio / V_x, or use an airfoil with a higher maximum L/D",
            {} if bad is None else station_details(bad, {"phi [rad]": phi, "C_l/C_d": cl / cd}))
        if bad is not None:  # placeholder values of infeasible nodes inside a BILDGroup
            coef = np.where(bad, 1.0, coef)
        if not derivatives:
            return load, coef, None, None, None, scale
        if thrust_form:
            dcoef_dphi, dcoef_dcl, dcoef_dcd = -cl * sin - cd * cos, cos, -sin
        else:
            dcoef_dphi, dcoef_dcl, dcoef_dcd = cl * cos - cd * sin, sin, cos
        if bad is not None:
            dcoef_dphi, dcoef_dcl, dcoef_dcd = (np.where(bad, 0.0, d) for d in (dcoef_dphi, dcoef_dcl, dcoef_dcd))
        return load, coef, dcoef_dphi, dcoef_dcl, dcoef_dcd, scale

    def compute(self, inputs, outputs):
        load, coef, _, _, _, scale = self._parts(inputs, derivatives=False)
        np.divide(load, coef * scale, out=outputs["chord_raw"])
        outputs["lift_coefficient"] = per_station(inputs["cl_star"])
        outputs["drag_coefficient"] = per_station(inputs["cd_star"])

    def compute_partials(self, inputs, partials):
        load, coef, dcoef_dphi, dcoef_dcl, dcoef_dcd, scale = self._parts(inputs)
        chord = load / (coef * scale)
        name = "dthrust_dr" if self.options["chord_form"] == "thrust" else "dtorque_dr"
        partials["chord_raw", name] = (1.0 / (coef * scale)).ravel()
        partials["chord_raw", "phi"] = (-chord * dcoef_dphi / coef).ravel()
        partials["chord_raw", "inflow_speed"] = (-2.0 * chord / inputs["inflow_speed"]).ravel()
        partials["chord_raw", "rho"] = (-chord / inputs["rho"][:, None]).ravel()
        partials["chord_raw", "cl_star"] = (-chord * dcoef_dcl / coef).ravel()
        partials["chord_raw", "cd_star"] = (-chord * dcoef_dcd / coef).ravel()
        if self.options["chord_form"] == "torque":
            partials["chord_raw", "radii"] = (-chord / inputs["radii"]).ravel()
