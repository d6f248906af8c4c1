"""LocalStationComp: what the station components of the two local-section-point variants share.

Both solve every station on its own given lambda, on a sheet of the polar's
load-path table (:mod:`bild_mdo.airfoil.load_path_table`), and pass on the
same outputs: ``eta2`` (from which
:class:`~bild_mdo.bild.induced_velocity.InducedVelocityComp` recovers the
induced velocities), the section point ``alpha_star, cl_star, cd_star`` (``ln
cl = x0 - ln Re``, so the back-computed chord runs at exactly ``reynolds``),
the chord Reynolds number ``reynolds``, the load Reynolds number
``load_reynolds = Re C`` and ``section_branch``, the table's sheet of the
station's section point (sheets are numbered by angle of attack; adjacent
stations on different sheets are a jump of the design).  Partials by the
implicit-function theorem on the variant's residuals in its states, all
analytic, from the compiled model of
:mod:`~bild_mdo.bild.variants.local_point.partials_kernel`; under complex step
the jets (:class:`~bild_mdo.utils.jet.Jet`) of the same model: one Newton
update in complex arithmetic carries the derivative of the states and the
outputs are evaluated with the complex inputs.  A subclass gives the solve
(:meth:`LocalStationComp.solve`) and the jets (:meth:`LocalStationComp.jets`).
"""
import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.load_path_table import load_path_table
from bild_mdo.bem.prandtl import loss_inputs
from bild_mdo.bild.feasibility import report_station_status
from bild_mdo.bild.variants.local_point.load_path_model import FLOW_ARRAYS, INPUTS, StationFlow, take
from bild_mdo.bild.variants.local_point.options import UNLOADED_OUTPUTS, declare_local_options
from bild_mdo.bild.variants.local_point.partials_kernel import state_totals
from bild_mdo.utils.jet import jacobian
from bild_mdo.utils.options import VARIABLES, add_inputs, add_outputs
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node

OUTPUTS = ("eta2", "alpha_star", "cl_star", "cd_star", "reynolds", "load_reynolds")
#: Largest relative change of lambda under which a station starts from its last solution (:attr:`warm_start`).
WARM_RANGE = 1e-2
_NODE = {"ideal_loading_constant": "lam", "v_axial": "v_axial", "rho": "rho", "mu": "mu", "radius": "radius",
         "hub_radius": "hub_radius"}
_DIST = {"v_theta": "v_theta", "radii": "r"}
_UNLOADED_ROW = np.array([UNLOADED_OUTPUTS[name] for name in OUTPUTS])


class LocalStationComp(om.ExplicitComponent):
    """Base of the local-section-point station components (module docstring).

    Options: ``num_nodes``, ``num_radial``, ``num_blades``, ``loss_model``, ``chord_form``, ``polar``,
    ``feasibility``.

    Inputs
    ------
    ideal_loading_constant[nn] (m/s), v_axial[nn] (m/s), radius[nn] (m), hub_radius[nn] (m),
    rho[nn] (kg/m**3), mu[nn] (Pa*s), v_theta[nn, nr] (m/s), radii[nn, nr] (m)

    Outputs
    -------
    eta2, alpha_star (rad), cl_star, cd_star, reynolds, load_reynolds, section_branch : [nn, nr]
    """

    #: Name of the method in messages; the station status codes of its solve that are failures.
    METHOD = ""
    FAILURES = {}
    #: The loaded status code of the solve.
    LOADED = 0
    #: The residuals of the compiled partials (:data:`~bild_mdo.bild.variants.local_point.partials_kernel.QUANTITIES`):
    #: two in the states ``(phi, x0)``, or one in ``x0`` (the paper loading, whose ``phi`` follows from ``x0``).
    RESIDUALS = ()

    def initialize(self):
        declare_local_options(self.options)
        self._cache = None
        self._table = None
        self._rows = None
        #: Start a station from its last solution where it was loaded and lambda moved by at most
        #: :data:`WARM_RANGE` (the passes of a thrust-target solve after the first set it).
        self.warm_start = False

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        shape = (nn, nr)
        add_inputs(self, ("ideal_loading_constant", "v_axial", "v_theta", "radii", "radius", "hub_radius", "rho",
                          "mu"))
        add_outputs(self, ("eta2",))
        for name in ("alpha_star", "cl_star", "cd_star"):
            _, default, units, desc = VARIABLES[name]
            self.add_output(name, val=np.full(shape, default), units=units,
                            desc=f"{desc} of the station's own section point ({self.METHOD})")
        self.add_output("reynolds", val=np.full(shape, 3e5), units=None,
                        desc="chord Reynolds number rho W0 c / mu of the station")
        self.add_output("load_reynolds", val=np.full(shape, 1e5), units=None,
                        desc="load Reynolds number Re*C of the station")
        self.add_output("section_branch", val=np.zeros(shape), units=None,
                        desc="sheet of the polar's load-path table of the station's section point (-1 unloaded)")
        self._node = {"ideal_loading_constant": "lam", "v_axial": "v_axial", "rho": "rho", "mu": "mu"}
        self._node.update({name: name for name in loss_inputs(self.options["loss_model"])})
        rows, cols = dist_wrt_dist(nn, nr)
        self.declare_partials(list(OUTPUTS), list(_DIST), rows=rows, cols=cols)
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials(list(OUTPUTS), list(self._node), rows=rows, cols=cols)

    @property
    def table(self):
        """The polar's load-path table (built or read on first use)."""
        if self._table is None:
            self._table = load_path_table(self.options["polar"])
        return self._table

    # ------------------------------------------------------------ the variant's part
    def solve(self, flow, start):
        """``(states, label, status, values)`` of the stations of ``flow``: ``states`` a tuple of flat arrays (the
        first the inflow angle where the variant has it, for warm starts), ``values[n, 6]`` the :data:`OUTPUTS`
        of the loaded stations; ``start`` None, or the last solution's ``(states, label)`` to start from
        (:attr:`warm_start`)."""
        raise NotImplementedError

    def jets(self, flow, states, label):
        """``(residuals, state_names, outputs)``: jets of the residuals in the states and of :data:`OUTPUTS`."""
        raise NotImplementedError

    # ------------------------------------------------------------------ the component
    def _flow(self, inputs, real=True):
        get = (lambda name: np.real(inputs[name])) if real else (lambda name: inputs[name])
        shape = inputs["v_theta"].shape
        fields = {field: name for name, field in {**_NODE, **_DIST}.items()}
        # One [8, n] block whose rows are the flow's arrays: the rows the compiled solves read, without a copy
        # (flow_rows of reynolds_exact.solve).
        values = [get(fields[field]) for field in FLOW_ARRAYS]
        size, dtype = (len(values), shape[0] * shape[1]), np.result_type(*values)
        if dtype == float:
            # The real flow is read once per solve and not kept (take copies): one block reused from call to call.
            if self._rows is None or self._rows.shape != size:
                self._rows = np.empty(size)
            rows = self._rows
        else:
            rows = np.empty(size, dtype=dtype)
        for row, value in zip(rows, values):
            row.reshape(shape)[...] = value[:, None] if value.ndim == 1 else value
        opts = self.options
        return StationFlow(*rows, num_blades=opts["num_blades"], loss_model=opts["loss_model"],
                           chord_form=opts["chord_form"])

    def _solve(self, inputs):
        """Solution and outputs; designs whose inputs did not change keep their states."""
        names = ("ideal_loading_constant", "v_axial", "v_theta", "radii", "radius", "hub_radius", "rho", "mu")
        shape = inputs["v_theta"].shape
        key = np.concatenate([np.real(inputs[name]).reshape(shape[0], -1) for name in names], axis=1)
        previous = self._cache
        if previous is not None and np.array_equal(key, previous["key"]):
            return previous
        flow = self._flow(inputs)
        kept = np.zeros(shape[0], dtype=bool) if previous is None else np.all(key == previous["key"], axis=1)
        if not kept.any():
            # Every design changed (a new batch, a new point of a sweep): no copies of the last solution.
            warm = self.warm_start and previous is not None
            states, label, status, table = self.solve(flow, self._warm_start(inputs, previous, slice(None))
                                                      if warm else None)
        else:
            stations = np.flatnonzero(np.repeat(~kept, shape[1]))
            states = tuple(x.copy() for x in previous["states"])
            label, status = previous["label"].copy(), previous["status"].copy()
            table = previous["value_table"].copy()
            if stations.size:
                start = self._warm_start(inputs, previous, stations) if self.warm_start else None
                part_states, part_label, part_status, part_values = self.solve(take(flow, stations), start)
                for full, part_state in zip(states, part_states):
                    full[stations] = part_state
                label[stations], status[stations] = part_label, part_status
                table[stations] = part_values
        report_station_status(self, status.reshape(shape), self.FAILURES, np.real(inputs["v_axial"])[:, None],
                              np.real(inputs["v_theta"]), np.real(inputs["ideal_loading_constant"])[:, None])
        # The outputs of a station without a load (the solve leaves NaN there, or the values of a state past the
        # table's top) are UNLOADED_OUTPUTS; the columns of the table are the outputs.
        table[status != self.LOADED] = _UNLOADED_ROW
        values = {name: table[:, k] for k, name in enumerate(OUTPUTS)}
        self._cache = {"key": key, "states": states, "label": label, "status": status, "values": values,
                       "value_table": table, "linear": None, "lam": flow.lam.copy()}
        return self._cache

    def _warm_start(self, inputs, previous, stations):
        """The last solution's ``(states, label)`` at ``stations`` where they start a solve: only stations that
        were loaded, under a lambda within :data:`WARM_RANGE` of theirs (a larger step, the first passes of a
        thrust target, can cross to another branch, which a cold start sees afresh); NaN and -1 elsewhere."""
        shape = inputs["v_theta"].shape
        lam = np.repeat(np.real(inputs["ideal_loading_constant"]), shape[1])[stations]
        near = (previous["status"][stations] == self.LOADED) & (
            np.abs(lam / previous["lam"][stations] - 1.0) <= WARM_RANGE)
        return (tuple(np.where(near, x[stations], np.nan) for x in previous["states"]),
                np.where(near, previous["label"][stations], -1))

    def _linear(self, inputs, cache):
        """Jets at the loaded stations (real inputs) and the Jacobian of their residuals in their states (the
        complex-step path of :meth:`compute`)."""
        if cache["linear"] is None:
            at = np.flatnonzero(cache["status"] == self.LOADED)
            flow = take(self._flow(inputs), at)
            residuals, names, outputs = self.jets(flow, tuple(x[at] for x in cache["states"]), cache["label"][at])
            cache["linear"] = (at, names, outputs, jacobian(residuals, names, at.size))
        return cache["linear"]

    def compute(self, inputs, outputs):
        cache = self._solve(inputs)
        shape = inputs["v_theta"].shape
        values = dict(cache["values"])  # outputs[name] = ... copies them into the output vector
        if self.under_complex_step:
            at, names, real_outputs, jac = self._linear({k: np.real(v) for k, v in inputs.items()}, cache)
            if at.size:
                flow = take(self._flow(inputs, real=False), at)
                residuals, _, complex_outputs = self.jets(flow, tuple(x[at] for x in cache["states"]),
                                                          cache["label"][at])
                imag = np.stack([np.imag(r.v) for r in residuals], axis=-1)
                with np.errstate(all="ignore"):
                    d_state = -np.linalg.solve(jac, imag[..., None])[..., 0]
                state_partials = jacobian((real_outputs[name] for name in OUTPUTS), names, at.size)
                for i, name in enumerate(OUTPUTS):
                    carried = np.imag(complex_outputs[name].v) + np.einsum("ns,ns->n", state_partials[:, i], d_state)
                    values[name] = values[name].astype(complex)
                    values[name][at] = values[name][at] + 1j * carried
        for name in OUTPUTS:
            outputs[name] = values[name].reshape(shape)
        outputs["section_branch"] = cache["label"].reshape(shape).astype(float)

    def _totals(self, inputs, cache):
        """``(at, totals[at, OUTPUTS, INPUTS])``: the partials of the outputs at the loaded stations ``at``, the
        states eliminated, from the compiled model
        (:func:`~bild_mdo.bild.variants.local_point.partials_kernel.state_totals` with :attr:`RESIDUALS`; the
        paper loading's one state is ``x0``, its ``phi`` follows from it)."""
        if cache.get("totals") is None:
            at = np.flatnonzero(cache["status"] == self.LOADED)
            flow = take(self._flow(inputs), at)
            states = [x[at] for x in cache["states"]]
            phi = states[0] if len(states) == 2 else np.zeros(at.size)
            points = np.column_stack([phi, states[-1]] + [getattr(flow, name) for name in INPUTS]
                                     + [np.ones(at.size)])
            cache["totals"] = (at, state_totals(self.table, points, cache["label"][at], flow.num_blades,
                                                flow.chord_form == "torque", flow.loss_model, self.RESIDUALS,
                                                INPUTS, OUTPUTS, paper=len(self.RESIDUALS) == 1))
        return cache["totals"]

    def compute_partials(self, inputs, partials):
        cache = self._solve(inputs)
        n = cache["label"].size
        at, totals = self._totals(inputs, cache)
        if at.size != n:  # zero partials at the stations without a load
            full = np.zeros((n,) + totals.shape[1:])
            full[at] = totals
            totals = full
        for wrt, key in list(_DIST.items()) + list(self._node.items()):
            j = INPUTS.index(key)
            for i, name in enumerate(OUTPUTS):
                partials[name, wrt] = totals[:, i, j]
