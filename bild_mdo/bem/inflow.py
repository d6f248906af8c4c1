"""InflowComp: the inflow angle phi as the implicit state of the BEM residual (paper Eq. 9)."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.bem.attached_branch import (attached_branch, high_induction_candidates, least_induced_root,
                                          stalled_candidates)
from bild_mdo.bem.blade_element import (NODE_INPUTS, add_station_section_inputs, declare_section_options,
                                        denominator_function, evaluate_section, inflow_angle_guess,
                                        residual_function, section_arguments, section_input_names)
from bild_mdo.bem.flow_states import (MIRROR_ROOT, NO_SOLUTION, PROPELLER, classify, declare_flow_state_options,
                                      declare_high_induction_option, report_invalid)
from bild_mdo.bem.inflow_residual import force_coefficients
from bild_mdo.bem.root_finding import MAX_ITER, RESIDUAL_TOL, solve_bracketed, solve_physical
from bild_mdo.bem.station_velocities import declare_station_velocity_option, kernel_key, station_mode
from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.utils.newton import complex_step_update
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node


def _every_root(phi, idx):
    """``solve_range='full'`` keeps roots with ``W < 0`` too (flagged as mirror roots): all are admissible."""
    return np.ones(np.shape(phi), dtype=bool)


class InflowComp(om.ImplicitComponent):
    """Inflow angle from the BEM residual with Prandtl loss (paper Eq. 9 generalised by F), and the flow state.

    ``R(phi) = (V_x/V_theta)(sigma C_theta + 4 F |sin| cos) + sigma C_x - 4 F sin |sin| = 0``
    at every station (:mod:`bild_mdo.bem.inflow_residual`).  ``solve_nonlinear`` is a vectorised
    guaranteed-bracket solve (Ning 2014): with ``solve_range='physical'`` (default)
    :func:`~bild_mdo.bem.root_finding.solve_physical`, CCBlade.jl's region order accepting only
    roots with ``W > 0``; with ``'full'`` :func:`~bild_mdo.bem.root_finding.solve_bracketed`,
    the first sign change anywhere in ``[-pi/2, pi)`` (a root with ``W < 0`` is kept and flagged
    :data:`~bild_mdo.bem.flow_states.MIRROR_ROOT`).  Where region 1 holds several roots (stall
    hysteresis, or Buhl's correction past ``a = 0.4``), the attached-flow, least induced root, at the
    largest ``phi``, is taken (:mod:`~bild_mdo.bem.attached_branch`).  Each station is then classified
    (:func:`~bild_mdo.bem.flow_states.classify`).  Where it has no momentum solution
    (:data:`~bild_mdo.bem.flow_states.NO_SOLUTION`) the state equation becomes
    ``phi = atan2(V_x, Omega r)`` (CCBlade's zero-loading fallback; the loads component then
    returns zero loads), so the outputs and their derivatives stay defined.  Invalid stations
    (:data:`~bild_mdo.bem.flow_states.INVALID_STATES`) are reported as ``on_invalid`` says.

    Under complex step the solve adds one complex Newton update
    (:func:`~bild_mdo.utils.newton.complex_step_update`) so the imaginary part carries the exact
    derivative.  The state Jacobian is diagonal: ``solve_linear`` divides.  Inputs outside the
    model's domain (``v_axial < 0``, non-positive rpm, chord, radii, rho or mu) raise ``om.AnalysisError``.

    Warm start (option ``warm_start=True``, for a driver that re-evaluates nearby inputs): each
    solve starts from the previous solve's phi per station
    (:func:`~bild_mdo.bem.root_finding.warm_region_one`).  In one residual pass it checks that the
    cold solve would search region 1 (sign change between its end points) and brackets the root
    between the previous phi and an end point; the Newton solve from there needs 2-3 passes
    instead of 5-8.  Every converged warm root in region 1 is kept (``warm_any_root=True``): the
    attached-branch rule that follows, as after the cold solve, makes it the root at the largest
    ``phi`` (below ``alpha*`` no root lies above it; above, the rule scans), which is the cold
    solve's root after the same rule, so the root, the flow state and the fallback agree with
    the cold solve's (to solver tolerance, ``|R| <= 1e-13``, wherever the rule's scan resolves
    the roots); stations where the cold solve would not search region 1 get the full cold search.
    The first solve is cold; ``warm_start=False`` (default) is the cold solve at every call.

    Options: ``num_nodes``, ``num_radial``, ``num_blades``, ``polar`` and ``loss_model``, declared by
    :func:`~bild_mdo.bem.blade_element.declare_section_options`; ``solve_range`` ('physical' or
    'full'), ``on_invalid`` ('warn', 'raise' or 'ignore'), ``high_induction`` ('none' or 'buhl': Buhl's
    correction above ``a = 0.4``, :mod:`bild_mdo.bem.inflow_residual`), ``warm_start`` (bool, default False) and
    ``station_velocities`` (bool, default False: inputs ``v_axial_local[nn, nr]`` and
    ``v_theta_local[nn, nr]`` (m/s) instead of ``v_axial`` and ``rpm``, for inclined flow,
    :mod:`bild_mdo.bem.station_velocities`; then ``V_x >= 0`` and ``V_theta > 0`` per station).

    Inputs
    ------
    v_axial[nn] (m/s), rpm[nn] (rpm), radius[nn] (m), hub_radius[nn] (m), rho[nn] (kg/m**3), mu[nn] (Pa*s),
    speed_of_sound[nn] (m/s), collective_pitch[nn] (rad), radii[nn, nr] (m), chord[nn, nr] (m), twist[nn, nr] (rad)
        The blade-element inputs (:data:`~bild_mdo.bem.blade_element.SECTION_INPUTS`); the polar sees
        ``alpha = twist + collective_pitch - phi``, the Mach number ``W0 / a`` where it varies with
        Mach number and ``r/R`` where it varies along the span.

    Outputs
    -------
    phi[nn, nr] (rad)
        Inflow angle (implicit state).
    flow_state[nn, nr]
        Flow-state code of :mod:`bild_mdo.bem.flow_states` (integer values; no derivatives).
    """

    def initialize(self):
        declare_section_options(self.options)
        declare_flow_state_options(self.options)
        declare_high_induction_option(self.options)
        self.options.declare("warm_start", types=bool, default=False,
                             desc="start each inflow solve from the previous solve's phi (same roots as cold)")
        declare_station_velocity_option(self.options)

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        add_station_section_inputs(self)
        self.add_output("phi", val=np.full((nn, nr), 0.2), units="rad", desc="inflow angle")
        self.add_output("flow_state", val=np.full((nn, nr), float(PROPELLER)),
                        desc="flow-state code (bild_mdo.bem.flow_states)")
        self._dR_dphi = np.ones((nn, nr))
        self._state = np.full((nn, nr), PROPELLER)
        self._unloaded = np.zeros((nn, nr), dtype=bool)
        self._previous_phi = None

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows_s, cols_s = dist_wrt_dist(nn, nr)
        rows_n, cols_n = dist_wrt_node(nn, nr)
        self.declare_partials("phi", "phi", rows=rows_s, cols=cols_s)
        # The flow state is a label fixed by the solve: its residual is flow_state - label.
        self.declare_partials("flow_state", "flow_state", rows=rows_s, cols=cols_s, val=1.0)
        for name in self._input_names():
            if name in NODE_INPUTS:
                self.declare_partials("phi", name, rows=rows_n, cols=cols_n)
            else:
                self.declare_partials("phi", name, rows=rows_s, cols=cols_s)

    def _input_names(self):
        return section_input_names(self.options["loss_model"], self.options["polar"], station_mode(self.options))

    def _velocities(self, inputs):
        """``V_x`` and ``V_theta`` of every station, shape (nn, nr) or (nn, 1) (m/s)."""
        if station_mode(self.options):
            return inputs["v_axial_local"], inputs["v_theta_local"]
        return inputs["v_axial"][:, None], inputs["rpm"][:, None] * RPM_TO_RAD_PER_S * inputs["radii"]

    def _describe(self, inputs):
        nr = self.options["num_radial"]
        v_x, v_theta = self._velocities(inputs)
        v_x, v_theta = (np.broadcast_to(np.real(v), (self.options["num_nodes"], nr)) for v in (v_x, v_theta))

        def describe(flat_index):
            node, station = divmod(int(flat_index), nr)
            return (f"design/node {node}, station {station} (r = {np.real(inputs['radii'][node, station]):.6g} m, "
                    f"V_x = {v_x[node, station]:.6g} m/s, V_theta = {v_theta[node, station]:.6g} m/s, "
                    f"twist = {np.degrees(np.real(inputs['twist'][node, station])):.6g} deg, "
                    f"chord = {np.real(inputs['chord'][node, station]):.6g} m) of {self.pathname}")
        return describe

    def _fallback_angle(self, inputs):
        """``atan2(V_x, V_theta)`` (complex-safe: ``V_theta > 0``) and its partials by input name, shape (nn, nr)."""
        v_x, v_theta = self._velocities(inputs)
        angle = np.arctan(v_x / v_theta)
        v_x, v_theta = np.real(v_x), np.real(v_theta)
        w2 = v_x**2 + v_theta**2
        d_vtheta = -v_x / w2
        if station_mode(self.options):
            return angle, {"v_axial_local": v_theta / w2, "v_theta_local": d_vtheta}
        omega = np.real(inputs["rpm"][:, None]) * RPM_TO_RAD_PER_S
        return angle, {"v_axial": v_theta / w2, "rpm": d_vtheta * RPM_TO_RAD_PER_S * np.real(inputs["radii"]),
                       "radii": d_vtheta * omega}

    def apply_nonlinear(self, inputs, outputs, residuals):
        values, _ = evaluate_section(outputs["phi"], loads=False, partials=False,
                                     **section_arguments(inputs, self.options))
        residual = values["residual"]
        if np.any(self._unloaded):
            residual = np.where(self._unloaded, outputs["phi"] - self._fallback_angle(inputs)[0], residual)
        residuals["phi"] = residual
        residuals["flow_state"] = outputs["flow_state"] - self._state

    def _check_domain(self, inputs):
        """The momentum model needs V_x >= 0, rpm > 0 and positive geometry (else AnalysisError)."""
        speeds = (("v_axial_local", True), ("v_theta_local", False)) if station_mode(self.options) else (
            ("v_axial", True), ("rpm", False))
        for name, allow_zero in (*speeds, ("chord", False), ("radii", False),
                                 ("rho", False), ("mu", False), ("speed_of_sound", False)):
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

        stations = station_mode(self.options)
        node_names = tuple(n for n in NODE_INPUTS if not (stations and n in ("v_axial", "rpm")))
        kernels = {name: flat(name) for name in node_names + ("radii", "chord", "twist")}
        kernels.update(num_blades=self.options["num_blades"], polar=self.options["polar"],
                       loss_model=self.options["loss_model"])
        v_theta = None
        if stations:
            kernels["v_axial"], v_theta = flat("v_axial_local"), flat("v_theta_local")
            # The stall-branch test (attached_branch) reads an rpm: the one of this tangential speed.
            kernels["rpm"] = v_theta / (RPM_TO_RAD_PER_S * kernels["radii"])
        residual = residual_function(**kernels, v_theta=v_theta, high_induction=self.options["high_induction"])
        guess = inflow_angle_guess(kernels["v_axial"], kernels["rpm"], kernels["radii"], kernels["chord"],
                                   kernels["twist"] + kernels["collective_pitch"], self.options["num_blades"],
                                   v_theta=v_theta)
        previous = self._previous_phi if self.options["warm_start"] else None
        describe = self._describe(inputs)
        if self.options["solve_range"] == "physical":
            admissible = denominator_function(**kernels, v_theta=v_theta)
            phi, found = solve_physical(residual, admissible, kernels["v_axial"] > 0.0, describe=describe,
                                        initial_guess=guess, previous=previous, warm_any_root=True)
        else:
            admissible = _every_root
            phi = solve_bracketed(residual, nn * nr, describe=describe, initial_guess=guess, previous=previous,
                                  warm_any_root=True)
            found = np.ones(nn * nr, dtype=bool)
        candidates, upper = stalled_candidates(phi, found, kernels)
        if candidates.size:
            attached_branch(residual, admissible, phi, candidates, upper, describe, RESIDUAL_TOL, MAX_ITER)
        candidates = high_induction_candidates(phi, found, kernels, self.options["high_induction"])
        if candidates.size:  # the least induced of the roots Buhl's correction allows (attached_branch)
            least_induced_root(residual, admissible, phi, candidates, describe, RESIDUAL_TOL, MAX_ITER)
        phi, found = phi.reshape(shape), found.reshape(shape)
        real_inputs = {name: np.real(inputs[name]) for name in inputs}
        fallback = np.real(self._fallback_angle(real_inputs)[0])
        phi = np.where(found, phi, fallback)
        self._state, self._unloaded = self._classify(phi, found, real_inputs)
        phi = np.where(self._unloaded, fallback, phi)
        report_invalid(self._state, self.options["on_invalid"],
                       r_over_r=real_inputs["radii"] / real_inputs["radius"][:, None],
                       suggest_buhl=self.options["high_induction"] == "none")
        self._previous_phi = phi.ravel().copy()
        if np.iscomplexobj(outputs["phi"]):
            kw = section_arguments(inputs, self.options)
            values, partials = evaluate_section(phi, loads=False, **kw)
            dR_dphi = np.broadcast_to(partials["residual"]["phi"], shape)
            phi = np.where(self._unloaded, self._fallback_angle(inputs)[0],
                           complex_step_update(phi, values["residual"], dR_dphi))
        outputs["phi"] = phi
        outputs["flow_state"] = self._state

    def _classify(self, phi, found, inputs):
        """Flow-state codes and the stations that get the zero-loading fallback."""
        values, _ = evaluate_section(phi, partials=False, **section_arguments(inputs, self.options))
        c_x, c_theta = force_coefficients(phi, values["lift_coefficient"], values["drag_coefficient"])
        admissible = found & (values["denominator"] > 0.0)
        v_axial = self._velocities(inputs)[0]
        corrected = self.options["high_induction"] == "buhl"
        if self.options["solve_range"] == "physical":
            state = classify(c_x, c_theta, v_axial, values["u_axial"], admissible, corrected)
        else:
            state = classify(c_x, c_theta, v_axial, values["u_axial"], found, corrected)
            state = np.where(found & ~admissible, MIRROR_ROOT, state)
        return state, state == NO_SOLUTION

    def linearize(self, inputs, outputs, jacobian):
        _, d = evaluate_section(outputs["phi"], loads=False, **section_arguments(inputs, self.options))
        shape = outputs["phi"].shape
        d_res = d["residual"]
        unloaded = self._unloaded
        d_fallback = self._fallback_angle(inputs)[1] if np.any(unloaded) else {}
        for name in ["phi"] + self._input_names():
            value = np.broadcast_to(d_res.get(kernel_key(name), 0.0), shape)
            if np.any(unloaded):
                value = np.where(unloaded, 1.0 if name == "phi" else -d_fallback.get(name, 0.0), value)
            jacobian["phi", name] = value.ravel()
        self._dR_dphi = np.where(unloaded, 1.0, np.broadcast_to(d_res["phi"], shape))

    def solve_linear(self, d_outputs, d_residuals, mode):
        if mode == "fwd":
            d_outputs["phi"] = d_residuals["phi"] / self._dR_dphi
            d_outputs["flow_state"] = d_residuals["flow_state"]
        else:
            d_residuals["phi"] = d_outputs["phi"] / self._dR_dphi
            d_residuals["flow_state"] = d_outputs["flow_state"]

