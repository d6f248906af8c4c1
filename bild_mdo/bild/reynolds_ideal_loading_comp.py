"""Components of the Reynolds-aware exact ideal loading (``section_point='local'``, ``ideal_loading='exact'``).

:class:`ReynoldsIdealLoadingComp` gives lambda at the reference station and
:class:`ReynoldsStationComp` solves every station's ``(phi, alpha, Re)``
(:mod:`bild_mdo.bild.reynolds_ideal_loading`).  The station component replaces
the eta2 solve and the station's section point of the other BILD chains: its
outputs feed the same induced-velocity, inflow-angle, loads and chord
components, so the design's chord at each station follows from its ``Re``.
"""
import numpy as np
import openmdao.api as om

from bild_mdo.bem.prandtl import LOSS_MODELS, loss_inputs
from bild_mdo.bild.chord import CHORD_FORMS
from bild_mdo.bild.exact_ideal_loading import check_reference_annulus
from bild_mdo.bild.feasibility import declare_feasibility_option, report_station_status
from bild_mdo.bild.reynolds_ideal_loading import (
    STATES,
    Flow,
    jacobian,
    reference_constant,
    state_sensitivities,
    take,
    terms,
)
from bild_mdo.bild.reynolds_ideal_loading_solve import StationSolution, solve_stations
from bild_mdo.utils.options import VARIABLES, add_inputs, add_outputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node, node_wrt_node

#: Relative change of every input below which a design's stations keep their states (ReynoldsStationComp).
_SAME_INPUTS = 1.0e-12
#: Scale of the Reynolds-number outputs (as in local_section_point_comp).
_REYNOLDS_SCALE = 1.0e5
_FAILURES = {
    3: ("overloaded", "lambda lies beyond the station's maximum annulus thrust before eta2 = 1/2; reduce ref_chord"),
    4: ("solve", "Reynolds-aware exact ideal loading: an input is outside its domain or the solve did not converge"),
}
_POINT_DESC = {"alpha_star": "angle of attack of the station (Reynolds-aware exact ideal loading)",
               "cl_star": "lift coefficient of the station (Reynolds-aware exact ideal loading)",
               "cd_star": "drag coefficient of the station (Reynolds-aware exact ideal loading)"}


def _declare(options, radial=True):
    declare_size_options(options, radial=radial)
    options.declare("num_blades", types=int, default=3, desc="number of blades B")
    options.declare("loss_model", default="tip_hub", values=LOSS_MODELS, desc="Prandtl losses")
    options.declare("chord_form", default="thrust", values=CHORD_FORMS,
                    desc="force coefficient of the chord formula: 'thrust' (C_x) or 'torque' (C_theta)")
    options.declare("polar", recordable=False, desc="airfoil Polar (Reynolds-dependent only)")
    declare_feasibility_option(options)


def _flow(options, **arrays):
    return Flow(**arrays, num_blades=options["num_blades"], loss_model=options["loss_model"],
                chord_form=options["chord_form"])


class ReynoldsIdealLoadingComp(om.ExplicitComponent):
    """lambda = N_tot / D_tot at the reference station (:mod:`~bild_mdo.bild.reynolds_ideal_loading`).

    The marginal energy loss per marginal thrust of the reference annulus, with
    its section's ``cd/cl`` following its load (the Reynolds feedback
    ``kappa``) and the Prandtl factor differentiated.  ``phi_ref`` is the
    reference station's BEM inflow angle with ``c_ref`` and ``(alpha_star_ref,
    reynolds_ref)`` its local section point, so the station at ``r_ref`` of the
    Reynolds-aware exact loading has the chord ``c_ref``.  The reference annulus
    must carry thrust and lie below its maximum thrust (``D_tot > 0``); nodes
    that fail are infeasible (placeholder ``lambda = V_theta_ref``, zero partials).

    Options: ``num_nodes``, ``num_blades``, ``loss_model``, ``chord_form``, ``polar``, ``feasibility``.

    Inputs
    ------
    phi_ref[nn] (rad), alpha_star_ref[nn] (rad), reynolds_ref[nn] (-)
        Reference state.
    v_axial[nn] (m/s), v_theta_ref[nn] (m/s), ref_radius[nn] (m), radius[nn] (m), hub_radius[nn] (m),
    rho[nn] (kg/m**3), mu[nn] (Pa*s)

    Outputs
    -------
    ideal_loading_constant[nn] (m/s)
    """

    def initialize(self):
        _declare(self.options, radial=False)

    def setup(self):
        nn = self.options["num_nodes"]
        add_inputs(self, ("phi_ref", "v_axial", "v_theta_ref", "ref_radius", "radius", "hub_radius", "rho", "mu"))
        self.add_input("alpha_star_ref", val=np.full(nn, 0.1), units="rad",
                       desc="angle of attack of the reference station's section point")
        self.add_input("reynolds_ref", val=np.full(nn, 3e5), units=None,
                       desc="chord Reynolds number at the reference station")
        add_outputs(self, ("ideal_loading_constant",))
        self._wrt = {"phi_ref": "phi", "alpha_star_ref": "alpha", "reynolds_ref": "re", "v_axial": "v_axial",
                     "v_theta_ref": "v_theta", "ref_radius": "r", "rho": "rho", "mu": "mu"}
        self._wrt.update({name: name for name in loss_inputs(self.options["loss_model"])})
        rows, cols = node_wrt_node(nn)
        self.declare_partials("ideal_loading_constant", list(self._wrt), rows=rows, cols=cols)

    def _evaluate(self, inputs, real=True):
        get = (lambda name: np.real(inputs[name])) if real else (lambda name: inputs[name])
        flow = _flow(self.options, lam=None, v_axial=get("v_axial"), v_theta=get("v_theta_ref"),
                     r=get("ref_radius"), radius=get("radius"), hub_radius=get("hub_radius"), rho=get("rho"),
                     mu=get("mu"))
        return reference_constant(self.options["polar"], np.real(inputs["phi_ref"]),
                                  np.real(inputs["alpha_star_ref"]), np.real(inputs["reynolds_ref"]), flow)

    def _validate(self, inputs, item):
        return check_reference_annulus(self, inputs, item.n_tot.v, item.d_tot.v,
                                       "Reynolds-aware exact ideal loading", "D_tot = 0")

    def compute(self, inputs, outputs):
        lam, item = self._evaluate(inputs, real=not self.under_complex_step)
        failed = self._validate(inputs, item)
        value = lam.v
        if self.under_complex_step:
            # The polar is evaluated at the real state; its imaginary parts enter through the exact partials.
            value = value + 1j * sum(np.real(lam.partial(key)) * np.imag(inputs[name])
                                     for name, key in (("alpha_star_ref", "alpha"), ("reynolds_ref", "re"),
                                                       ("phi_ref", "phi")))
        outputs["ideal_loading_constant"] = np.where(failed, inputs["v_theta_ref"], value)

    def compute_partials(self, inputs, partials):
        lam, item = self._evaluate(inputs)
        failed = self._validate(inputs, item)
        for name, key in self._wrt.items():
            value = np.broadcast_to(lam.partial(key), failed.shape)
            if name == "v_theta_ref":
                value = np.where(failed, 1.0, value)
            partials["ideal_loading_constant", name] = np.where(failed, 0.0, value)


class ReynoldsStationComp(om.ExplicitComponent):
    """Every station's ``(phi, alpha, Re)`` of the Reynolds-aware exact ideal loading, as eta2 and a section point.

    Solved by :func:`~bild_mdo.bild.reynolds_ideal_loading.solve_stations`;
    partials by the implicit-function theorem on the three residuals
    (``d states/dx = -J^-1 R_x``), all analytic; under complex step one Newton
    update in complex arithmetic carries the derivative.  Outputs: ``eta2 = A
    cos(phi)/V_theta`` (from which
    :class:`~bild_mdo.bild.induced_velocity.InducedVelocityComp` recovers the
    same induced velocities), the section point ``alpha_star, cl_star,
    cd_star``, its chord Reynolds number ``reynolds`` and the load Reynolds
    number ``load_reynolds = Re C``.  An unloaded station (no minimum of ``F (e
    - lambda t)`` below its unloaded value 0) gets ``eta2 = 1``, zero chord
    (``reynolds = load_reynolds = 0``), a placeholder section point from the
    bracketing grid and zero partials; an overloaded station or a failed solve
    is infeasible.

    Options: ``num_nodes``, ``num_radial``, ``num_blades``, ``loss_model``, ``chord_form``, ``polar``,
    ``feasibility``.

    Inputs
    ------
    ideal_loading_constant[nn] (m/s), v_axial[nn] (m/s), radius[nn] (m), hub_radius[nn] (m),
    rho[nn] (kg/m**3), mu[nn] (Pa*s), v_theta[nn, nr] (m/s), radii[nn, nr] (m)

    Outputs
    -------
    eta2, alpha_star (rad), cl_star, cd_star, reynolds, load_reynolds : [nn, nr]
    """

    def initialize(self):
        _declare(self.options)
        self._cache = None

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        shape = (nn, nr)
        add_inputs(self, ("ideal_loading_constant", "v_axial", "v_theta", "radii", "radius", "hub_radius", "rho",
                          "mu"))
        add_outputs(self, ("eta2",))
        for name in ("alpha_star", "cl_star", "cd_star"):
            _, default, units, _ = VARIABLES[name]
            self.add_output(name, val=np.full(shape, default), units=units, desc=_POINT_DESC[name])
        self.add_output("reynolds", val=np.full(shape, 3e5), units=None, ref=_REYNOLDS_SCALE,
                        desc="chord Reynolds number rho W0 c / mu of the station")
        self.add_output("load_reynolds", val=np.full(shape, 1e5), units=None, ref=_REYNOLDS_SCALE,
                        desc="load Reynolds number Re*C of the station")
        self._outputs = ("eta2", "alpha_star", "cl_star", "cd_star", "reynolds", "load_reynolds")
        self._dist = {"v_theta": "v_theta", "radii": "r"}
        self._node = {"ideal_loading_constant": "lam", "v_axial": "v_axial", "rho": "rho", "mu": "mu"}
        self._node.update({name: name for name in loss_inputs(self.options["loss_model"])})
        rows, cols = dist_wrt_dist(nn, nr)
        self.declare_partials(list(self._outputs), list(self._dist), rows=rows, cols=cols)
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials(list(self._outputs), list(self._node), rows=rows, cols=cols)

    def _flow(self, inputs, real=True):
        get = (lambda name: np.real(inputs[name])) if real else (lambda name: inputs[name])
        shape = inputs["v_theta"].shape
        node = {field: np.broadcast_to(get(name)[:, None], shape).ravel() for field, name in
                (("lam", "ideal_loading_constant"), ("v_axial", "v_axial"), ("radius", "radius"),
                 ("hub_radius", "hub_radius"), ("rho", "rho"), ("mu", "mu"))}
        return _flow(self.options, v_theta=get("v_theta").ravel(), r=get("radii").ravel(), **node)

    def _solve(self, inputs):
        """The stations' solution, sensitivities and Jacobian; only designs whose inputs changed are re-solved.

        Every station is solved on its own given lambda, so a design (node) whose inputs equal those of the
        last call to ``_SAME_INPUTS`` (relative) keeps its stations' states, corrected by one Newton step
        (:meth:`_correct`) where they moved: a thrust-target solve re-runs the chain for every design on each
        pass, while most designs have converged (and their lambda, from the reference station's solve, moves
        by round-off only).
        """
        names = ("ideal_loading_constant", "v_axial", "v_theta", "radii", "radius", "hub_radius", "rho", "mu")
        shape = inputs["v_theta"].shape
        key = np.concatenate([np.real(inputs[name]).reshape(shape[0], -1) for name in names], axis=1)
        kept = np.zeros(shape[0], dtype=bool)
        if self._cache is not None:
            kept = np.all(np.abs(key - self._cache[0]) <= _SAME_INPUTS * np.abs(key), axis=1)
            if kept.all() and np.array_equal(key, self._cache[0]):
                return self._cache[1:]
        flow = self._flow(inputs)
        stations = np.flatnonzero(np.repeat(~kept, shape[1]))
        try:
            part = solve_stations(self.options["polar"], take(flow, stations)) if stations.size else None
        except ValueError as err:
            raise om.AnalysisError(f"{self.msginfo}: {err}") from err
        if kept.any():
            solution = StationSolution(*(np.array(field) for field in self._cache[1]))
            for field, value in zip(solution, part or ()):
                field[stations] = value
            moved = kept & ~np.all(key == self._cache[0], axis=1)
            self._correct(solution, flow, np.flatnonzero(np.repeat(moved, shape[1]) & (solution.status == 0)))
        else:
            solution = part
        report_station_status(self, solution.status.reshape(shape), _FAILURES, np.real(inputs["v_axial"])[:, None],
                              np.real(inputs["v_theta"]), np.real(inputs["ideal_loading_constant"])[:, None])
        item = terms(self.options["polar"], solution.phi, solution.alpha, solution.reynolds, flow)
        loaded = solution.status == 0
        wrt = list(self._dist.values()) + list(self._node.values())
        sens, jac = state_sensitivities(item, wrt, loaded) if np.any(loaded) else ({}, None)
        self._cache = (key, solution, item, sens, jac)
        return solution, item, sens, jac

    def _correct(self, solution, flow, at):
        """One Newton step on the three residuals at the stations ``at``, whose inputs moved by round-off.

        Their states solved the residuals at inputs within ``_SAME_INPUTS`` (relative) of these, so the step
        leaves them off by O(``_SAME_INPUTS``**2): as converged as a fresh solve.
        """
        if at.size == 0:
            return
        near = terms(self.options["polar"], solution.phi[at], solution.alpha[at], solution.reynolds[at], take(flow, at))
        residual = np.stack([near.r1.v, near.r2.v, near.r3.v], axis=-1)[..., None]
        step = np.linalg.solve(jacobian((near.r1, near.r2, near.r3), STATES), residual)[..., 0]
        for k, field in enumerate((solution.phi, solution.alpha, solution.reynolds)):
            field[at] -= step[:, k]

    def _values(self, solution, item):
        loaded = solution.status == 0
        return {"eta2": np.where(loaded, item.eta2.v, 1.0), "alpha_star": solution.alpha,
                "cl_star": item.cl.v, "cd_star": item.cd.v,
                "reynolds": np.where(loaded, solution.reynolds, 0.0),
                "load_reynolds": np.where(loaded, item.load_reynolds.v, 0.0)}

    def _state_partials(self, item):
        """``d output / d (phi, alpha, Re)`` at fixed inputs, per output."""
        zero = np.zeros(np.shape(item.eta2.v))
        jets = {"eta2": item.eta2, "cl_star": item.cl, "cd_star": item.cd, "load_reynolds": item.load_reynolds}
        out = {name: [np.broadcast_to(jet.partial(s), zero.shape) for s in ("phi", "alpha", "re")]
               for name, jet in jets.items()}
        out["alpha_star"] = [zero, zero + 1.0, zero]
        out["reynolds"] = [zero, zero, zero + 1.0]
        return out

    def compute(self, inputs, outputs):
        solution, item, sens, jac = self._solve(inputs)
        shape = inputs["v_theta"].shape
        values = self._values(solution, item)
        if self.under_complex_step and jac is not None:
            flow = self._flow(inputs, real=False)
            complex_item = terms(self.options["polar"], solution.phi, solution.alpha, solution.reynolds, flow)
            residual = np.stack([complex_item.r1.v, complex_item.r2.v, complex_item.r3.v], axis=-1)
            loaded = solution.status == 0
            safe = np.where(loaded[:, None, None], jac, np.eye(3))
            d_state = -np.linalg.solve(safe, np.imag(residual)[..., None])[..., 0]
            d_state[~loaded] = 0.0
            state_partials = self._state_partials(item)
            direct = {"eta2": complex_item.eta2.v, "cl_star": item.cl.v, "cd_star": item.cd.v,
                      "load_reynolds": complex_item.load_reynolds.v}
            for name in self._outputs:
                base = direct.get(name, values[name])
                imag = np.imag(base) + sum(state_partials[name][j] * d_state[:, j] for j in range(3))
                values[name] = np.real(values[name]) + 1j * np.where(loaded, imag, 0.0)
        for name in self._outputs:
            outputs[name] = values[name].reshape(shape)

    def compute_partials(self, inputs, partials):
        solution, item, sens, jac = self._solve(inputs)
        loaded = solution.status == 0
        state_partials = self._state_partials(item)
        direct = {"eta2": item.eta2, "load_reynolds": item.load_reynolds}
        for wrt, key in list(self._dist.items()) + list(self._node.items()):
            for name in self._outputs:
                value = np.broadcast_to(direct[name].partial(key), loaded.shape) if name in direct else 0.0
                if sens:
                    value = value + sum(state_partials[name][j] * sens[key][:, j] for j in range(3))
                partials[name, wrt] = np.where(loaded, value, 0.0)
