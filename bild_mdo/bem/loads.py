"""BladeElementLoadsComp: section aerodynamics and blade-element loads at the solved inflow angle."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.bem.blade_element import (NODE_INPUTS, add_station_section_inputs, declare_section_options,
                                        evaluate_section, section_arguments, section_input_names)
from bild_mdo.bem.flow_states import NO_SOLUTION, PROPELLER, declare_high_induction_option
from bild_mdo.bem.station_velocities import declare_station_velocity_option, kernel_key, station_mode
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node

#: Station outputs: name -> (units, description).
SECTION_OUTPUTS = {
    "alpha": ("rad", "angle of attack alpha = twist - phi"),
    "reynolds": (None, "chord Reynolds number rho W0 c / mu, W0 = sqrt(V_x^2 + V_theta^2)"),
    "mach": (None, "local Mach number W / a (inflow speed with induction; the polar sees W0 / a)"),
    "lift_coefficient": (None, "section lift coefficient C_l"),
    "drag_coefficient": (None, "section drag coefficient C_d"),
    "u_axial": ("m/s", "axial velocity at the disk u_axial (Eq. 8)"),
    "u_theta": ("m/s", "tangential induced velocity u_theta (Eq. 8)"),
    "loss_factor": (None, "Prandtl loss factor F"),
    "inflow_speed": ("m/s", "inflow speed W = sqrt(u_axial^2 + (V_theta - u_theta/2)^2) (Eq. 7)"),
    "dthrust_dr": ("N/m", "sectional thrust per unit span, all blades (Eq. 5)"),
    "dtorque_dr": ("N*m/m", "sectional torque per unit span, all blades (Eq. 6 with the arm r)"),
}


class BladeElementLoadsComp(om.ExplicitComponent):
    """Angle of attack, polar, induced velocities and blade-element loads (Eqs. 5-8).

    ``dT/dr = 1/2 rho W^2 B c C_x`` and ``dQ/dr = 1/2 rho W^2 B c C_theta r`` with
    ``W^2 = u_axial^2 + (V_theta - u_theta/2)^2`` and ``u_axial, u_theta`` from
    Eq. (8) with the Prandtl factor.  At stations without a momentum solution (input
    ``flow_state`` equal to :data:`~bild_mdo.bem.flow_states.NO_SOLUTION`) the loads are CCBlade's
    "zero loading" fallback: ``u_axial = V_x``, ``u_theta = 0``, ``W = sqrt(V_x^2 + V_theta^2)``,
    ``dT/dr = dQ/dr = 0``.  At the converged ``phi`` these equal the
    momentum loads ``4 pi rho u_axial (u_axial - V_x) r F`` and
    ``2 pi rho u_axial u_theta r^2 F`` (:class:`~bild_mdo.bild.momentum_loads.MomentumLoadsComp`).

    Options: ``num_nodes``, ``num_radial``, ``num_blades``, ``polar`` and ``loss_model``, declared by
    :func:`~bild_mdo.bem.blade_element.declare_section_options`; ``station_velocities`` (default
    False; True: inputs ``v_axial_local[nn, nr]``, ``v_theta_local[nn, nr]`` (m/s) instead of
    ``v_axial`` and ``rpm``, see :mod:`bild_mdo.bem.station_velocities`).

    Inputs
    ------
    phi[nn, nr] (rad), flow_state[nn, nr]
        Inflow angle and flow-state code, and the blade-element inputs
        (:data:`~bild_mdo.bem.blade_element.SECTION_INPUTS`).

    Outputs
    -------
    alpha[nn, nr] (rad), reynolds[nn, nr], mach[nn, nr], lift_coefficient[nn, nr], drag_coefficient[nn, nr],
    u_axial[nn, nr] (m/s),
    u_theta[nn, nr] (m/s), loss_factor[nn, nr], inflow_speed[nn, nr] (m/s),
    dthrust_dr[nn, nr] (N/m), dtorque_dr[nn, nr] (N*m/m)
    """

    def initialize(self):
        declare_section_options(self.options)
        declare_high_induction_option(self.options)
        declare_station_velocity_option(self.options)

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        self.add_input("phi", val=np.full((nn, nr), 0.2), units="rad", desc="inflow angle")
        self.add_input("flow_state", val=np.full((nn, nr), float(PROPELLER)),
                       desc="flow-state code (bild_mdo.bem.flow_states); no derivatives")
        add_station_section_inputs(self)
        for name, (units, desc) in SECTION_OUTPUTS.items():
            self.add_output(name, val=np.ones((nn, nr)), units=units, desc=desc)

    def _dependencies(self, output):
        loss_model, polar = self.options["loss_model"], self.options["polar"]
        stations = station_mode(self.options)
        names = ["phi"] + section_input_names(loss_model, polar, stations)
        if output == "alpha":
            return ["phi", "twist", "collective_pitch"]
        if output == "reynolds":
            speeds = ["v_axial_local", "v_theta_local"] if stations else ["v_axial", "rpm", "radii"]
            return speeds + ["chord", "rho", "mu"]
        if output == "mach":
            # W / a: everything the inflow speed depends on, and the speed of sound.
            return names + ([] if "speed_of_sound" in names else ["speed_of_sound"])
        if output in ("lift_coefficient", "drag_coefficient"):
            return [n for n in names if n not in ("hub_radius",) and (n != "radius" or polar.varies_along_span)]
        if output == "loss_factor":
            if loss_model == "none":
                return []
            return [n for n in names if n in ("phi", "radii", "radius", "hub_radius")]
        return names

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows_s, cols_s = dist_wrt_dist(nn, nr)
        rows_n, cols_n = dist_wrt_node(nn, nr)
        for out in SECTION_OUTPUTS:
            for name in self._dependencies(out):
                if name in NODE_INPUTS:
                    self.declare_partials(out, name, rows=rows_n, cols=cols_n)
                else:
                    self.declare_partials(out, name, rows=rows_s, cols=cols_s)

    @staticmethod
    def _unloaded(inputs):
        return np.real(inputs["flow_state"]) == NO_SOLUTION

    def compute(self, inputs, outputs):
        values, _ = evaluate_section(inputs["phi"], partials=False, unloaded=self._unloaded(inputs),
                                     **section_arguments(inputs, self.options))
        for name in SECTION_OUTPUTS:
            outputs[name] = values[name]

    def compute_partials(self, inputs, partials):
        _, d = evaluate_section(inputs["phi"], unloaded=self._unloaded(inputs),
                                **section_arguments(inputs, self.options))
        shape = inputs["phi"].shape
        for out in SECTION_OUTPUTS:
            for name in self._dependencies(out):
                val = d[out].get(kernel_key(name))
                partials[out, name] = 0.0 if val is None else np.broadcast_to(val, shape).ravel()
