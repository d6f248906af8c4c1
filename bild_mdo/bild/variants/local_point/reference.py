"""LocalReferenceComp: the reference station of the local-section-point variants, on the polar's load-path table."""
import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.load_path_table import load_path_table
from bild_mdo.bem.prandtl import loss_inputs
from bild_mdo.bild.annulus_stationarity import IDEAL_LOADINGS
from bild_mdo.bild.variants.exact.exact_ideal_loading import check_reference_annulus
from bild_mdo.bild.feasibility import report_infeasible
from bild_mdo.bild.variants.local_point.gap import (force_factors, gap_jets, reference_reynolds, reynolds_partials,
                                                   take_reference, terms)
from bild_mdo.bild.variants.local_point.options import declare_local_options
from bild_mdo.bild.variants.local_point.partials_kernel import DIRECTIONS, state_totals
from bild_mdo.bild.variants.local_point.reference_solve import ReferenceFlow, solve_reference, station_flow, table_jets
from bild_mdo.utils.jet import Jet, eliminate, jacobian, variable
from bild_mdo.utils.options import VARIABLES, add_inputs, add_outputs
from bild_mdo.utils.sparsity import node_wrt_node

#: Component input -> name of its partial in the jets.
_INPUT_KEYS = {"v_axial": "v_axial", "v_theta_ref": "v_theta", "ref_radius": "r", "ref_chord": "chord",
               "radius": "radius", "hub_radius": "hub_radius", "rho": "rho", "mu": "mu"}
_POINT = ("alpha_star_ref", "cl_star_ref", "cd_star_ref")
_REYNOLDS_INPUTS = ("v_axial", "v_theta_ref", "ref_chord", "rho", "mu")
_RE_ONLY = ("alpha_star_ref", "cl_star_ref", "cd_star_ref", "reynolds_ref")
#: Outputs of a table state -> their quantity in the compiled model (partials_kernel.QUANTITIES).
_TABLE_QUANTITIES = {"phi_ref": "phi", "alpha_star_ref": "alpha_star", "cl_star_ref": "cl_star",
                     "cd_star_ref": "cd_star", "load_reynolds_ref": "load_reynolds",
                     "ideal_loading_constant": "lambda_ratio"}
#: The most sheets whose exclusion a 64-bit mask records (a table with more keeps the first reference state).
_MAX_SHEETS = 63
#: Why a reference chord below the lightest ideal load of its station is infeasible (exact loading).
LIGHTEST_LOAD = ("Reynolds-aware exact ideal loading: ref_chord is below the lightest ideal load of the reference "
                 "station (there its marginal energy loss per thrust, lambda, falls as the chord grows, or loading "
                 "the annulus saves less than leaving it unloaded, so no station at r_ref takes that chord); raise "
                 "ref_chord")


class LocalReferenceComp(om.ExplicitComponent):
    """Inflow angle and section point of the reference station with the chord ``c_ref`` (local section point).

    The reference station's BEM state with ``c_ref`` at the minimum of ``cd/cl``
    along its own path of fixed load whose chord Reynolds number is ``Re_ref =
    rho W0 c_ref / mu`` (:mod:`~bild_mdo.bild.variants.local_point.reference_solve`,
    in the model of the polar's load-path table, so that a station of the same
    model placed at ``r_ref`` has the chord ``c_ref``; in the Reynolds gap, the
    exact rule described there).  With ``ideal_loading='exact'`` it also gives
    lambda of the Reynolds-aware exact loading, ``N_tot / D_tot`` of the
    reference annulus (its marginal energy loss per marginal thrust with the
    section point following the load), so the station at ``r_ref`` solves its
    residuals at the reference state.  Partials by the implicit-function
    theorem on the two residuals of the state, all analytic.

    A node whose reference state cannot be solved, or whose reference annulus
    is past its maximum thrust (exact loading), is infeasible (placeholders,
    zero partials); with the exact loading so is a reference chord below the
    lightest ideal load of its station (:data:`LIGHTEST_LOAD`: a station at
    ``r_ref`` would not take the state, so the design is not that chord's),
    a light infeasibility (:attr:`~bild_mdo.bild.feasibility.FeasibilityLedger.light`).

    Options: ``num_nodes``, ``num_blades``, ``loss_model``, ``chord_form``, ``polar``, ``feasibility``,
    ``ideal_loading`` (``'paper'``: no lambda output; ``'exact'``).

    Inputs
    ------
    v_axial[nn] (m/s), v_theta_ref[nn] (m/s), ref_radius[nn] (m), ref_chord[nn] (m), radius[nn] (m),
    hub_radius[nn] (m), rho[nn] (kg/m**3), mu[nn] (Pa*s)

    Outputs
    -------
    phi_ref[nn] (rad), alpha_star_ref[nn] (rad), cl_star_ref[nn], cd_star_ref[nn], reynolds_ref[nn],
    load_reynolds_ref[nn], section_branch_ref[nn] (-1 in the Reynolds gap), ideal_loading_constant[nn] (m/s),
    station_branch_ref[nn] (exact loading: the sheet a station at ``r_ref`` takes at that lambda, -1 unloaded, -2
    not checked)
    """

    def initialize(self):
        declare_local_options(self.options, radial=False)
        self.options.declare("ideal_loading", default="paper", values=IDEAL_LOADINGS,
                             desc="'exact': also lambda of the Reynolds-aware exact loading")
        self._cache = None
        self._table = None

    def setup(self):
        nn = self.options["num_nodes"]
        add_inputs(self, ("v_axial", "v_theta_ref", "ref_radius", "ref_chord", "radius", "hub_radius", "rho", "mu"))
        add_outputs(self, ("phi_ref",))
        for name in ("alpha_star", "cl_star", "cd_star"):
            _, default, units, desc = VARIABLES[name]
            self.add_output(f"{name}_ref", val=np.full(nn, default), units=units,
                            desc=f"{desc} of the reference station's own path of fixed load")
        self.add_output("reynolds_ref", val=np.full(nn, 3e5), units=None,
                        desc="chord Reynolds number at the reference station (speed without induction)")
        self.add_output("load_reynolds_ref", val=np.full(nn, 3e5), units=None,
                        desc="load Reynolds number Re*C of the reference station")
        self.add_output("section_branch_ref", val=np.zeros(nn), units=None,
                        desc="sheet of the load-path table of the reference point (-1: the Reynolds gap)")
        self._output_names = ["phi_ref", *_POINT, "reynolds_ref", "load_reynolds_ref"]
        if self.options["ideal_loading"] == "exact":
            add_outputs(self, ("ideal_loading_constant",))
            self.add_output("station_branch_ref", val=np.zeros(nn), units=None,
                            desc="sheet a station at r_ref takes at the reference lambda (-1 unloaded, -2 not "
                                 "checked); another than section_branch_ref: the blade has not ref_chord there")
            self._output_names.append("ideal_loading_constant")
        self._wrt = [name for name in _INPUT_KEYS if name not in ("radius", "hub_radius")
                     or name in loss_inputs(self.options["loss_model"])]
        rows, cols = node_wrt_node(nn)
        # The section point lies on a curve of the polar that depends on Re alone (load_path), so it and Re_ref
        # depend on the inputs of Re_ref only.
        self._out_wrt = {out: [name for name in self._wrt if out not in _RE_ONLY or name in _REYNOLDS_INPUTS]
                         for out in self._output_names}
        for out, wrt in self._out_wrt.items():
            self.declare_partials(out, wrt, rows=rows, cols=cols)

    @property
    def table(self):
        if self._table is None:
            self._table = load_path_table(self.options["polar"])
        return self._table

    def _flow(self, inputs, real=True):
        get = (lambda name: np.real(inputs[name])) if real else (lambda name: inputs[name])
        opts = self.options
        return ReferenceFlow(*(get(name) for name in _INPUT_KEYS), num_blades=opts["num_blades"],
                             loss_model=opts["loss_model"], chord_form=opts["chord_form"])

    def _solve(self, inputs):
        key = np.concatenate([np.real(inputs[name]) for name in _INPUT_KEYS])
        if self._cache is not None and np.array_equal(self._cache["key"], key):
            return self._cache
        ref = self._flow(inputs)
        solution = solve_reference(self.table, self.options["polar"], ref)
        re_ref = reference_reynolds(ref)
        report_infeasible(self, "reference_point", ~solution.ok,
                          "local section point: the reference station's BEM state at its own section point did not "
                          "converge (check ref_chord and the operating point)",
                          {"ref_chord [m]": ref.chord, "Re_ref": re_ref})
        values = self._values(ref, solution)
        exact = self.options["ideal_loading"] == "exact"
        if exact:
            solution, values, branch = self._consistent_sheet(ref, solution, values)
        self._cache = {"key": key, "solution": solution, "values": values, "linear": None}
        if exact:
            states = {"phi_ref": solution.phi, "v_axial": ref.v_axial, "v_theta_ref": ref.v_theta}
            failed = check_reference_annulus(self, states, values["lambda_n"], values["lambda_d"],
                                             "Reynolds-aware exact ideal loading", "D_tot = 0")
            light = ~failed & self._below_lightest_load(ref, re_ref, solution, values)
            report_infeasible(self, "lightest_load", light, LIGHTEST_LOAD,
                              {"ref_chord [m]": ref.chord, "Re_ref": re_ref,
                               "lambda [m/s]": values["ideal_loading_constant"]}, light=True)
            self._cache["lam_failed"] = failed | light | ~solution.ok
            self._cache["station_branch"] = np.where(self._cache["lam_failed"], -2.0, branch)
        return self._cache

    def _consistent_sheet(self, ref, solution, values):
        """The reference state whose lambda makes it the ideal load of a station at ``r_ref`` (exact loading):
        ``(solution, values, station_branch)``.

        ``station_branch`` is the sheet such a station takes at the state's lambda (the stations' own solve, -1
        unloaded; -2 where the state is not on the table).  Where that is not the state's sheet, or the state is
        no ideal load there (``slope <= 0`` or ``Phi >= 0``), the station's state has another chord, so the blade
        would not have ``ref_chord`` at ``r_ref``: the next table minimum with ``c_ref`` at ``Re_ref`` (the
        lowest ``cd/cl`` first) is tried, and the first one a station at its own lambda takes, on its sheet,
        replaces it.  Where none does, ``c_ref`` lies in a jump of the blade's chord at ``r_ref`` along the
        designs of growing lambda (the first state is kept; the design result says so).  On the levels-10 sweep
        of the paper that corrects 48 of 1,268 such designs.
        """
        from bild_mdo.bild.variants.reynolds_exact.solve import solve_stations

        branch = np.full(ref.r.size, -2.0)
        lam = values["ideal_loading_constant"]
        at = np.flatnonzero(solution.ok & solution.on_table & np.isfinite(lam) & (values["lambda_d"] > 0.0))
        if not at.size:
            return solution, values, branch
        branch[at] = solve_stations(self.table, station_flow(take_reference(ref, at))._replace(lam=lam[at])).label
        with np.errstate(invalid="ignore"):
            wrong = (branch[at] != solution.label[at]) | ~((solution.slope[at] > 0.0) & (solution.objective[at] < 0.0))
        todo = at[wrong]
        if not todo.size or self.table.num_sheets > _MAX_SHEETS:
            return solution, values, branch
        fields = {name: np.array(value, copy=True) for name, value in solution._asdict().items()}
        values = {name: value.copy() for name, value in values.items()}
        exclude = np.left_shift(np.int64(1), solution.label[todo].astype(np.int64))
        while todo.size:  # one pass per sheet tried: at most the table's number of sheets
            sub = take_reference(ref, todo)
            other = solve_reference(self.table, self.options["polar"], sub, exclude, gap=False)
            other_values = self._values(sub, other)
            lam = other_values["ideal_loading_constant"]
            with np.errstate(invalid="ignore"):
                ideal = np.flatnonzero(other.ok & np.isfinite(lam) & (other_values["lambda_d"] > 0.0)
                                       & (other.slope > 0.0) & (other.objective < 0.0))
            taken = np.zeros(todo.size, dtype=bool)
            if ideal.size:
                labels = solve_stations(self.table, station_flow(take_reference(sub, ideal))._replace(
                    lam=lam[ideal])).label
                taken[ideal] = labels == other.label[ideal]
            for name, value in fields.items():
                value[todo[taken]] = getattr(other, name)[taken]
            for name, value in values.items():
                value[todo[taken]] = other_values[name][taken]
            branch[todo[taken]] = other.label[taken]
            more = other.ok & ~taken
            exclude = exclude[more] | np.left_shift(np.int64(1), other.label[more].astype(np.int64))
            todo = todo[more]
        return type(solution)(**fields), values, branch

    def _below_lightest_load(self, ref, re_ref, solution, values):
        """Nodes whose reference state is no ideal load of a station at ``r_ref`` at its own lambda (exact
        loading).  On the table: the residual ``N_tot/D_tot - lambda`` does not rise through the state (lambda
        falls as ``c_ref`` grows) or its ``Phi = F (e - lambda t)`` is not below the unloaded 0.  In the Reynolds
        gap (where the state is a maximum along its path, and lambda may fall with ``c_ref``): ``Phi`` not below
        0, or a load coordinate ``ln(Re cl)`` below the table's lightest (which stations leave unloaded)."""
        ok = solution.ok & np.isfinite(values["ideal_loading_constant"])
        with np.errstate(invalid="ignore"):
            light = ok & solution.on_table & ~((solution.slope > 0.0) & (solution.objective < 0.0))
        gap = np.flatnonzero(ok & ~solution.on_table)
        if gap.size:
            sub = take_reference(ref, gap)
            reynolds = re_ref[gap]
            item = terms(self.options["polar"], solution.phi[gap], solution.alpha[gap], reynolds,
                         station_flow(sub)._replace(lam=values["ideal_loading_constant"][gap]))
            with np.errstate(all="ignore"):
                below = np.log(reynolds * values["cl_star_ref"][gap]) < self.table.x_first
                light[gap] = below | ~(np.real(item.objective.v) < 0.0)
        return light

    def _values(self, ref, solution):
        """The outputs at the solved states (values only; the Reynolds gap through its jets)."""
        n = ref.r.size
        values = {name: np.zeros(n) for name in self._output_names}
        values["phi_ref"] = solution.phi.copy()
        values["lambda_n"], values["lambda_d"] = np.ones(n), np.ones(n)
        at = np.flatnonzero(solution.on_table & solution.ok)
        if at.size:
            point = self.table.curve(solution.x0[at], solution.label[at])
            s, ell = point["s"].f, point["ell"].f
            cl = np.exp(solution.x0[at] - ell)
            p, q = force_factors(solution.phi[at], ref.chord_form)
            values["alpha_star_ref"][at], values["cl_star_ref"][at], values["cd_star_ref"][at] = (
                point["alpha"].f, cl, s * cl)
            values["load_reynolds_ref"][at] = p * np.exp(solution.x0[at]) * (1.0 + (q / p) * s)
            if self.options["ideal_loading"] == "exact":
                values["lambda_n"][at], values["lambda_d"][at] = solution.n_tot[at], solution.d_tot[at]
                with np.errstate(all="ignore"):
                    values["ideal_loading_constant"][at] = solution.n_tot[at] / solution.d_tot[at]
        gap = np.flatnonzero(~solution.on_table & solution.ok)
        if gap.size:
            _, _, outputs, lam = self._gap_jets(take_reference(ref, gap), solution, gap)
            for name, jet in outputs.items():
                values[name][gap] = np.real(jet.v)
            if lam is not None:
                values["lambda_n"][gap], values["lambda_d"][gap] = np.real(lam[0]), np.real(lam[1])
        return values

    def _linear(self, ref, solution, lam_failed=None):
        """Partials of the outputs with respect to the inputs (the states eliminated by the implicit-function
        theorem); ``lam_failed``: the nodes whose lambda's partials :meth:`compute_partials` replaces."""
        n = ref.r.size
        keys = list(_INPUT_KEYS.values())
        partials = {(out, wrt): np.zeros(n) for out in self._output_names for wrt in keys}
        at = np.flatnonzero(solution.on_table & solution.ok)
        if at.size:  # on the table: the compiled model (partials_kernel), the same as _table_jets
            outputs = [name for name in self._output_names if name in _TABLE_QUANTITIES]
            points = np.column_stack([solution.phi[at], solution.x0[at], np.zeros(at.size)]
                                     + [getattr(ref, name)[at] for name in DIRECTIONS[3:]])
            totals = state_totals(self.table, points, solution.label[at], ref.num_blades, ref.chord_form == "torque",
                                  ref.loss_model, ("r2", "r_ell"), keys,
                                  [_TABLE_QUANTITIES[name] for name in outputs],
                                  required=None if lam_failed is None else ~lam_failed[at])
            for i, out in enumerate(outputs):
                for j, k in enumerate(keys):
                    partials[out, k][at] = totals[:, i, j]
        at = np.flatnonzero(~solution.on_table & solution.ok)
        if at.size:  # in the Reynolds gap: its jets
            residuals, states, outputs, _ = self._gap_jets(take_reference(ref, at), solution, at)
            jac = jacobian(residuals, states, at.size)
            rhs = jacobian(residuals, keys, at.size)
            with np.errstate(all="ignore"):
                sens = -np.linalg.solve(jac, rhs)
            totals = eliminate(outputs.values(), states, keys, sens, at.size)
            for i, out in enumerate(outputs):
                for j, k in enumerate(keys):
                    partials[out, k][at] = totals[:, i, j]
        return partials

    def _table_jets(self, ref, solution, at):
        residuals, (n_tot, d_tot), alpha, cl, cd, load = table_jets(self.table, ref, solution.phi[at],
                                                                     solution.x0[at], solution.label[at])
        outputs = {"phi_ref": variable(solution.phi[at], "phi"), "alpha_star_ref": alpha, "cl_star_ref": cl,
                   "cd_star_ref": cd, "load_reynolds_ref": load}
        lam = None
        if self.options["ideal_loading"] == "exact":
            outputs["ideal_loading_constant"] = n_tot / d_tot
            lam = (n_tot.v, d_tot.v)
        return residuals, ("phi", "x0"), outputs, lam

    def _gap_jets(self, ref, solution, at):
        jets = gap_jets(self.options["polar"], ref, solution.phi[at], solution.alpha[at])
        outputs = {"phi_ref": variable(solution.phi[at], "phi"), "alpha_star_ref": variable(solution.alpha[at], "alpha"),
                   "cl_star_ref": jets.cl, "cd_star_ref": jets.cd, "load_reynolds_ref": jets.load_reynolds}
        lam = None
        if self.options["ideal_loading"] == "exact":
            flow = station_flow(ref)._replace(lam=np.ones(at.size))
            re_real = np.real(jets.reynolds.v)
            item = terms(self.options["polar"], solution.phi[at], solution.alpha[at], re_real, flow)
            ratio = item.n_tot / item.d_tot
            # Re is a function of the inputs here: its partial chained, its complex part carried to first order.
            d = {k: v for k, v in ratio.d.items() if k != "re"}
            for k, x in jets.reynolds.d.items():
                d[k] = d.get(k, 0.0) + ratio.partial("re") * x
            outputs["ideal_loading_constant"] = Jet(ratio.v + ratio.partial("re") * (jets.reynolds.v - re_real), d)
            lam = (item.n_tot.v, item.d_tot.v)
        return (jets.bem, jets.g), ("phi", "alpha"), outputs, lam

    def compute(self, inputs, outputs):
        cache = self._solve(inputs)
        solution = cache["solution"]
        result = {name: cache["values"][name].copy() for name in self._output_names}
        if self.under_complex_step:
            # The states are real; one Newton update in complex arithmetic carries their derivatives, and the
            # outputs are evaluated with the complex inputs (jets of the model, not of its partials).
            ref = self._flow(inputs, real=False)
            for name in result:
                result[name] = result[name].astype(complex)
            for at, jets_of in ((np.flatnonzero(solution.on_table & solution.ok), self._table_jets),
                                (np.flatnonzero(~solution.on_table & solution.ok), self._gap_jets)):
                if at.size == 0:
                    continue
                residuals, states, outs, _ = jets_of(take_reference(ref, at), solution, at)
                jac = jacobian(residuals, states, at.size)
                imag = np.stack([np.imag(r.v) for r in residuals], axis=-1)
                with np.errstate(all="ignore"):
                    d_state = -np.linalg.solve(jac, imag[..., None])[..., 0]
                state_partials = jacobian(outs.values(), states, at.size)
                for i, (name, jet) in enumerate(outs.items()):
                    if name == "phi_ref":
                        result[name][at] = solution.phi[at] + 1j * d_state[:, 0]
                        continue
                    carried = np.imag(jet.v) + np.einsum("ns,ns->n", state_partials[:, i], d_state)
                    result[name][at] = np.real(result[name][at]) + 1j * carried
        if "ideal_loading_constant" in result:
            result["ideal_loading_constant"] = np.where(cache["lam_failed"], inputs["v_theta_ref"],
                                                        result["ideal_loading_constant"])
        result["reynolds_ref"] = reference_reynolds(self._flow(inputs, real=False))
        for name, value in result.items():
            outputs[name] = value
        outputs["section_branch_ref"] = np.where(solution.on_table, solution.label, -1).astype(float)
        if "station_branch" in cache:
            outputs["station_branch_ref"] = cache["station_branch"]

    def compute_partials(self, inputs, partials):
        cache = self._solve(inputs)
        if cache["linear"] is None:
            cache["linear"] = self._linear(self._flow(inputs), cache["solution"], cache.get("lam_failed"))
        linear = cache["linear"]
        ok = cache["solution"].ok
        _, d_re = reynolds_partials(*(np.real(inputs[name]) for name in _REYNOLDS_INPUTS))
        for out in self._output_names:
            for wrt in self._out_wrt[out]:
                if out == "reynolds_ref":
                    partials[out, wrt] = d_re[_INPUT_KEYS[wrt]]
                    continue
                value = np.where(ok, linear[out, _INPUT_KEYS[wrt]], 0.0)
                if out == "ideal_loading_constant":
                    failed = cache["lam_failed"]
                    value = np.where(failed, 1.0 if wrt == "v_theta_ref" else 0.0, value)
                partials[out, wrt] = value
