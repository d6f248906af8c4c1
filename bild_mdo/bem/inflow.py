"""InflowComp: the inflow angle phi as the implicit state of the BEM residual (paper Eq. 9)."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.bem.blade_element import (NODE_INPUTS, add_section_inputs, declare_section_options,
                                        evaluate_section, inflow_angle_guess, residual_function,
                                        section_arguments, section_input_names)
from bild_mdo.bem.root_finding import solve_bracketed
from bild_mdo.utils.newton import complex_step_update
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node


class InflowComp(om.ImplicitComponent):
    """Inflow angle from the BEM residual with Prandtl loss (paper Eq. 9 generalised by F).

    ``R(phi) = (V_x/V_theta)(sigma C_theta + 4 F sin cos) + sigma C_x - 4 F sin^2 = 0``
    at every station.  ``solve_nonlinear`` is the vectorised guaranteed-bracket
    solve of :mod:`bild_mdo.bem.root_finding` (Ning 2014); under complex step it
    adds one complex Newton update (:func:`~bild_mdo.utils.newton.complex_step_update`)
    so the imaginary part carries the exact derivative.  The state Jacobian is diagonal: ``solve_linear`` divides.
    Inputs outside the model's domain (``v_axial < 0``, non-positive rpm, chord,
    radii, rho or mu) and stations without a bracket raise ``om.AnalysisError``.

    Options: ``num_nodes``, ``num_radial``, ``num_blades``, ``polar`` and ``loss_model``, declared by
    :func:`~bild_mdo.bem.blade_element.declare_section_options`.

    Inputs
    ------
    v_axial[nn] (m/s), rpm[nn] (rpm), radius[nn] (m), hub_radius[nn] (m), rho[nn] (kg/m**3), mu[nn] (Pa*s),
    radii[nn, nr] (m), chord[nn, nr] (m), twist[nn, nr] (rad)
        The blade-element inputs (:data:`~bild_mdo.bem.blade_element.SECTION_INPUTS`).

    Outputs
    -------
    phi[nn, nr] (rad)
        Inflow angle (implicit state).
    """

    def initialize(self):
        declare_section_options(self.options)

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        add_section_inputs(self)
        self.add_output("phi", val=np.full((nn, nr), 0.2), units="rad", desc="inflow angle")
        self._dR_dphi = np.ones((nn, nr))

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows_s, cols_s = dist_wrt_dist(nn, nr)
        rows_n, cols_n = dist_wrt_node(nn, nr)
        self.declare_partials("phi", "phi", rows=rows_s, cols=cols_s)
        for name in section_input_names(self.options["loss_model"]):
            if name in NODE_INPUTS:
                self.declare_partials("phi", name, rows=rows_n, cols=cols_n)
            else:
                self.declare_partials("phi", name, rows=rows_s, cols=cols_s)

    def _describe(self, inputs):
        nr = self.options["num_radial"]

        def describe(flat_index):
            node, station = divmod(int(flat_index), nr)
            return (f"design/node {node}, station {station} (r = {np.real(inputs['radii'][node, station]):.6g} m, "
                    f"v_axial = {np.real(inputs['v_axial'][node]):.6g} m/s, rpm = {np.real(inputs['rpm'][node]):.6g}, "
                    f"twist = {np.degrees(np.real(inputs['twist'][node, station])):.6g} deg, "
                    f"chord = {np.real(inputs['chord'][node, station]):.6g} m) of {self.pathname}")
        return describe

    def apply_nonlinear(self, inputs, outputs, residuals):
        values, _ = evaluate_section(outputs["phi"], loads=False, partials=False,
                                     **section_arguments(inputs, self.options))
        residuals["phi"] = values["residual"]

    def _check_domain(self, inputs):
        """The momentum model needs V_x >= 0, rpm > 0 and positive geometry (else AnalysisError)."""
        for name, allow_zero in (("v_axial", True), ("rpm", False), ("chord", False), ("radii", False),
                                 ("rho", False), ("mu", False)):
            value = np.real(inputs[name])
            bad = (value < 0.0) if allow_zero else (value <= 0.0)
            if np.any(bad | ~np.isfinite(value)):
                flat = int(np.argmax((bad | ~np.isfinite(value)).ravel()))
                limit = "non-negative" if allow_zero else "positive"
                raise om.AnalysisError(
                    f"{self.pathname}: {name} must be finite and {limit}; got {value.ravel()[flat]!r} "
                    f"at flat index {flat}")

    def solve_nonlinear(self, inputs, outputs):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        shape = (nn, nr)
        self._check_domain(inputs)

        def flat(name):
            return np.broadcast_to(np.real(inputs[name]).reshape(nn, -1), shape).ravel()

        residual = residual_function(
            **{name: flat(name) for name in NODE_INPUTS + ("radii", "chord", "twist")},
            num_blades=self.options["num_blades"], polar=self.options["polar"],
            loss_model=self.options["loss_model"])
        guess = inflow_angle_guess(flat("v_axial"), flat("rpm"), flat("radii"), flat("chord"), flat("twist"),
                                   self.options["num_blades"])
        phi = solve_bracketed(residual, nn * nr, describe=self._describe(inputs),
                              initial_guess=guess).reshape(shape)
        if np.iscomplexobj(outputs["phi"]):
            kw = section_arguments(inputs, self.options)
            values, partials = evaluate_section(phi, loads=False, **kw)
            dR_dphi = np.broadcast_to(partials["residual"]["phi"], shape)
            phi = complex_step_update(phi, values["residual"], dR_dphi)
        outputs["phi"] = phi

    def linearize(self, inputs, outputs, jacobian):
        _, d = evaluate_section(outputs["phi"], loads=False, **section_arguments(inputs, self.options))
        shape = outputs["phi"].shape
        d_res = d["residual"]
        for name in ["phi"] + section_input_names(self.options["loss_model"]):
            jacobian["phi", name] = np.broadcast_to(d_res[name], shape).ravel()
        self._dR_dphi = np.broadcast_to(d_res["phi"], shape).copy()

    def solve_linear(self, d_outputs, d_residuals, mode):
        if mode == "fwd":
            d_outputs["phi"] = d_residuals["phi"] / self._dR_dphi
        else:
            d_residuals["phi"] = d_outputs["phi"] / self._dR_dphi

