"""Sectional thrust, torque and energy loss of the ideally loaded rotor (Eqs. (1), (2), (12))."""
import numpy as np
import openmdao.api as om

from bild_mdo.bem.blade_element import declare_section_options
from bild_mdo.bem.prandtl import (EXPONENT_MAX, EXPONENT_MIN, SIN_PHI_FLOOR, loss_inputs, loss_partials,
                                  prandtl_loss)
from bild_mdo.bild.feasibility import declare_feasibility_option, report_infeasible
from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.utils.options import add_inputs, add_outputs
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node


def _loss_factor(phi, r, radius, hub_radius, num_blades, loss_model, out):
    """Prandtl's ``F`` alone, real, written into ``out``: :func:`~bild_mdo.bem.prandtl.prandtl_loss`'s value.

    The same floor of ``|sin phi|`` and clip of the exponents, without the partials (``compute`` needs
    none), the sign of each exponent folded into its clip.
    """
    if loss_model == "none":
        out[...] = 1.0
        return out
    if loss_model == "tip_hub" and np.any(hub_radius <= 0.0):
        prandtl_loss(phi, r, radius, hub_radius, num_blades, loss_model)  # raises its ValueError
    abs_sin = np.maximum(np.abs(np.sin(phi)), SIN_PHI_FLOOR)
    half_b = 0.5 * num_blades
    clip = (-EXPONENT_MAX, -EXPONENT_MIN)
    with np.errstate(over="ignore", divide="ignore"):
        tip = np.exp(np.clip((-half_b) * (radius - r) / (r * abs_sin), *clip))
        np.arccos(tip, out=out)
        if loss_model == "tip_hub":
            hub = np.exp(np.clip((-half_b) * (r - hub_radius) / (hub_radius * abs_sin), *clip))
            out *= np.arccos(hub, out=hub)
            out *= (2.0 / np.pi) ** 2
        else:
            out *= 2.0 / np.pi
    return out


class MomentumLoadsComp(om.ExplicitComponent):
    """Momentum-theory loads of the ideal induced velocities, with Prandtl's loss factor.

    ::

        F     = F_tip(phi, r) F_hub(phi, r)                 Prandtl (paper Sec. 3)
        dT/dr = 4 pi rho u_axial (u_axial - V_x) r F                 Eq. (1)
        dQ/dr = 2 pi rho u_axial u_theta r**2 F                  Eq. (2)
        dE/dr = Omega dQ/dr - V_x dT/dr                      Eq. (12)

    The paper leaves ``F`` out of the presentation but uses it in every
    result; multiplying both momentum loads by the same ``F`` keeps Eq. (25)
    (the ratio of thrust to torque) unchanged, so a BEM analysis with the same
    loss model reproduces these loads on the back-computed blade.

    Inside a :class:`~bild_mdo.bild.bild_group.BILDGroup` (option
    ``feasibility`` set) a node with no torque at any station (a hover rotor
    whose ideal loading leaves every station unloaded, ``lambda <= V_theta
    C_d*/(2 C_l*)`` everywhere) is recorded as infeasible and gets the
    placeholder loads ``dT/dr = dQ/dr = 1`` with zero partials, so that the
    performance of the batch stays finite; used alone the component
    computes the (zero) loads.

    Options
    -------
    num_nodes, num_radial, num_blades : int
        Sizes (:func:`~bild_mdo.utils.options.declare_size_options`) and the number of blades B.
    loss_model : str
        ``'tip_hub'`` (default), ``'tip'`` or ``'none'``.
    feasibility : FeasibilityLedger or None
        See :func:`~bild_mdo.bild.feasibility.declare_feasibility_option`.

    Inputs
    ------
    u_axial[nn, nr] (m/s), u_theta[nn, nr] (m/s)
        Ideal axial velocity at the disk and tangential induced velocity.
    phi[nn, nr] (rad)
        Inflow angle (for the loss factor).
    radii[nn, nr] (m)
        Station radii.
    v_axial[nn] (m/s), rho[nn] (kg/m**3), rpm[nn] (rpm)
        Free stream velocity, density, rotor speed.
    radius[nn] (m), hub_radius[nn] (m)
        Tip and hub radii (for the loss factor).

    Outputs
    -------
    loss_factor[nn, nr] (-)
        Prandtl tip/hub loss factor F.
    dthrust_dr[nn, nr] (N/m)
        dT/dr.
    dtorque_dr[nn, nr] (N*m/m)
        dQ/dr.
    denergy_loss_dr[nn, nr] (W/m)
        dE/dr, the rate of energy loss per unit span.
    """

    def initialize(self):
        declare_section_options(self.options, polar=False)
        declare_feasibility_option(self.options)

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        add_inputs(self, ("u_axial", "u_theta", "phi", "radii", "v_axial", "rho", "rpm", "radius", "hub_radius"))
        add_outputs(self, ("loss_factor", "dthrust_dr", "dtorque_dr"))
        self.add_output("denergy_loss_dr", val=np.ones((nn, nr)), units="W/m",
                        desc="sectional rate of energy loss dE/dr, Eq. (12)")

    def _loss_inputs(self):
        """Inputs that the loss factor depends on (exact sparsity per loss model)."""
        model = self.options["loss_model"]
        return [] if model == "none" else ["phi", *loss_inputs(model)]

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        loss_inputs = self._loss_inputs()
        dist = [name for name in ("phi",) if name in loss_inputs]
        node = [name for name in ("radius", "hub_radius") if name in loss_inputs]
        rows, cols = dist_wrt_dist(nn, nr)
        if loss_inputs:
            self.declare_partials("loss_factor", ["radii"] + dist, rows=rows, cols=cols)
        self.declare_partials(["dthrust_dr", "denergy_loss_dr"], ["u_axial", "radii"] + dist,
                              rows=rows, cols=cols)
        self.declare_partials(["dtorque_dr", "denergy_loss_dr"],
                              ["u_axial", "u_theta", "radii"] + dist, rows=rows, cols=cols)
        rows, cols = dist_wrt_node(nn, nr)
        if node:
            self.declare_partials("loss_factor", node, rows=rows, cols=cols)
        self.declare_partials(["dthrust_dr", "denergy_loss_dr"], ["v_axial", "rho"] + node,
                              rows=rows, cols=cols)
        self.declare_partials(["dtorque_dr", "denergy_loss_dr"], ["rho"] + node,
                              rows=rows, cols=cols)
        self.declare_partials("denergy_loss_dr", "rpm", rows=rows, cols=cols)

    def _loss(self, inputs):
        nr = self.options["num_radial"]
        return prandtl_loss(inputs["phi"], inputs["radii"],
                            np.repeat(inputs["radius"][:, None], nr, axis=1),
                            np.repeat(inputs["hub_radius"][:, None], nr, axis=1),
                            self.options["num_blades"], self.options["loss_model"])

    def _terms(self, inputs):
        """Loss factor, the inputs broadcast to (nn, nr), and the loads of Eqs. (1), (2) without ``F``."""
        u_axial, u_t, r = inputs["u_axial"], inputs["u_theta"], inputs["radii"]
        v_x = inputs["v_axial"][:, None]
        rho = inputs["rho"][:, None]
        omega = RPM_TO_RAD_PER_S * inputs["rpm"][:, None]
        t_no_f = 4.0 * np.pi * rho * u_axial * (u_axial - v_x) * r
        q_no_f = 2.0 * np.pi * rho * u_axial * u_t * r ** 2
        return self._loss(inputs), u_axial, u_t, r, v_x, rho, omega, t_no_f, q_no_f

    def _unloaded(self, torque):
        """Nodes with no torque at any station, reported to the group's ledger (none for the component alone)."""
        if self.options["feasibility"] is None:
            return np.zeros(torque.shape[0], dtype=bool)
        loaded = np.real(torque) > 0.0
        unloaded = ~np.any(loaded, axis=1)
        details = {"loaded stations": np.sum(loaded, axis=1)} if unloaded.any() else {}
        report_infeasible(self, "unloaded", unloaded,
                          "no station can be loaded (hover: lambda <= V_theta C_d*/(2 C_l*) at every station), "
                          "so the rotor has zero torque: increase ref_chord or rpm, or use an airfoil with a "
                          "higher maximum L/D", details, light=True)
        return unloaded

    def compute(self, inputs, outputs):
        v_x = inputs["v_axial"][:, None]
        omega = RPM_TO_RAD_PER_S * inputs["rpm"][:, None]
        thrust, torque = outputs["dthrust_dr"], outputs["dtorque_dr"]
        if np.iscomplexobj(inputs["phi"]):
            loss, _, _, _, _, _, _, t_no_f, q_no_f = self._terms(inputs)
            outputs["loss_factor"] = loss.F
            thrust[...], torque[...] = t_no_f * loss.F, q_no_f * loss.F
        else:
            # Real: F alone (its partials are needed in compute_partials only); w = 2 pi rho u_axial r F.
            u_axial, r = inputs["u_axial"], inputs["radii"]
            loss = _loss_factor(inputs["phi"], r, inputs["radius"][:, None], inputs["hub_radius"][:, None],
                                self.options["num_blades"], self.options["loss_model"], outputs["loss_factor"])
            w = (2.0 * np.pi * inputs["rho"][:, None]) * u_axial * r * loss
            np.multiply(u_axial - v_x, 2.0 * w, out=thrust)  # Eq. (1)
            np.multiply(w * inputs["u_theta"], r, out=torque)  # Eq. (2)
        unloaded = self._unloaded(torque)
        if unloaded.any():
            thrust[unloaded], torque[unloaded] = 1.0, 1.0
        np.subtract(omega * torque, v_x * thrust, out=outputs["denergy_loss_dr"])

    def compute_partials(self, inputs, partials):
        loss, u_axial, u_t, r, v_x, rho, omega, t_no_f, q_no_f = self._terms(inputs)
        f = loss.F
        thrust, torque = t_no_f * f, q_no_f * f
        # Placeholder loads of unloaded nodes (inside a BILDGroup) are constants: their partials are zero.
        unloaded = self._unloaded(torque)
        keep = ~unloaded[:, None] if unloaded.any() else None
        w_t = (4.0 * np.pi) * rho * r * f  # dT/dr = w_t u_axial (u_axial - V_x)
        w_q = (2.0 * np.pi) * rho * r * r * f  # dQ/dr = w_q u_axial u_theta
        d_thrust = {
            "u_axial": w_t * (2.0 * u_axial - v_x),
            "radii": (t_no_f / r) * f + t_no_f * loss.dF_dr,
            "v_axial": -w_t * u_axial,
            "rho": thrust / rho,
        }
        d_torque = {
            "u_axial": w_q * u_t,
            "u_theta": w_q * u_axial,
            "radii": (2.0 * q_no_f / r) * f + q_no_f * loss.dF_dr,
            "rho": torque / rho,
        }
        d_loss = loss_partials(loss, self.options["loss_model"])
        for name in self._loss_inputs():
            d_thrust[name] = t_no_f * d_loss[name]
            d_torque[name] = q_no_f * d_loss[name]
        if self.options["loss_model"] != "none":
            partials["loss_factor", "radii"] = loss.dF_dr.ravel()
            for name in self._loss_inputs():
                partials["loss_factor", name] = d_loss[name].ravel()

        if keep is not None:
            d_thrust = {name: keep * value for name, value in d_thrust.items()}
            d_torque = {name: keep * value for name, value in d_torque.items()}
        for name, value in d_thrust.items():
            partials["dthrust_dr", name] = value.ravel()
        for name, value in d_torque.items():
            partials["dtorque_dr", name] = value.ravel()
        # dE/dr = Omega dQ/dr - V_x dT/dr.
        for name in set(d_thrust) | set(d_torque):
            if name in d_thrust and name in d_torque:
                value = omega * d_torque[name] - v_x * d_thrust[name]
            elif name in d_torque:
                value = omega * d_torque[name]
            else:
                value = -v_x * d_thrust[name]
            if name == "v_axial":
                value = value - (thrust if keep is None else np.where(keep, thrust, 1.0))  # dE/dV_x -= dT/dr
            partials["denergy_loss_dr", name] = value.ravel()
        partials["denergy_loss_dr", "rpm"] = (RPM_TO_RAD_PER_S * (torque if keep is None
                                                                  else np.where(keep, torque, 1.0))).ravel()
