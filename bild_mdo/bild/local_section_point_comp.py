"""Components of the Reynolds-aware BILD (``BILDGroup(section_point='local')``).

:class:`LoadReynoldsComp` turns each station's ideal load into its load
Reynolds number ``Q = Re C`` (the constant of the path of fixed load) and
:class:`LocalSectionPointComp` chooses the angle of attack that minimises
``cd/cl`` along that path (:mod:`bild_mdo.bild.local_section_point`).  At the
reference station the chord is given: :class:`ReferenceReynoldsComp` gives its
Reynolds number and :class:`ReferenceSectionPointComp` its point
(:mod:`bild_mdo.bild.local_section_point_reference`).
"""
import numpy as np
import openmdao.api as om

from bild_mdo.bild.local_section_point import point_derivatives, solve_local_point
from bild_mdo.bild.local_section_point_reference import solve_reference_point
from bild_mdo.bild.chord import CHORD_FORMS
from bild_mdo.utils.options import VARIABLES, add_inputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node, node_wrt_node

#: Load Reynolds numbers below this (unloaded hover stations, placeholders of infeasible nodes) are
#: evaluated at it: such a station carries (next to) no load, so its chord is (next to) zero whatever
#: its section point.
LOAD_REYNOLDS_FLOOR = 1.0e3
#: Scale of the Reynolds-number outputs: their residuals inside the Newton loops are then O(1), so the
#: loops' absolute tolerance means the same for them as for the loads and angles.
_REYNOLDS_SCALE = 1.0e5


_REFERENCE_FLOW = ("v_axial", "v_theta_ref", "ref_chord", "rho", "mu")
_OUT = {"alpha": "alpha_star", "cl": "cl_star", "cd": "cd_star"}
_LOCAL_DESC = {"alpha_star": "angle of attack of minimum cd/cl at fixed load",
               "cl_star": "lift coefficient of minimum cd/cl at fixed load",
               "cd_star": "drag coefficient of minimum cd/cl at fixed load"}


def _declare_common(options):
    declare_size_options(options)
    options.declare("num_blades", types=int, default=3, desc="number of blades B")
    options.declare("chord_form", default="thrust", values=CHORD_FORMS,
                    desc="force coefficient of the chord formula: 'thrust' (C_x) or 'torque' (C_theta)")


class LoadReynoldsComp(om.ExplicitComponent):
    """Load Reynolds number ``Q = Re C`` of every station, the constant of its path of fixed load.

    With the chord of :class:`~bild_mdo.bild.chord.ChordComp` and
    ``Re = rho W0 c / mu`` (``W0 = sqrt(V_x**2 + V_theta**2)``, the convention of
    the BEM analysis)::

        Q = 2 (dT/dr) W0 / (mu W**2 B)          (thrust form)
        Q = 2 (dQ/dr) W0 / (mu W**2 B r)        (torque form)

    Options: ``num_nodes``, ``num_radial``, ``num_blades``, ``chord_form``.

    Inputs
    ------
    dthrust_dr[nn, nr] (N/m) or dtorque_dr[nn, nr] (N*m/m) and radii[nn, nr] (m)
        Ideal load per unit span.
    inflow_speed[nn, nr] (m/s), v_theta[nn, nr] (m/s)
        ``W`` (with induction) and ``Omega r``.
    v_axial[nn] (m/s), mu[nn] (Pa*s)
        Axial speed and viscosity.

    Outputs
    -------
    load_reynolds[nn, nr] (-)
        ``Q = Re C``.
    """

    def initialize(self):
        _declare_common(self.options)

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        torque = self.options["chord_form"] == "torque"
        add_inputs(self, ("dtorque_dr", "radii") if torque else ("dthrust_dr",))
        add_inputs(self, ("inflow_speed", "v_theta", "v_axial", "mu"))
        self.add_output("load_reynolds", val=np.full((nn, nr), 1e5), units=None, ref=_REYNOLDS_SCALE,
                        desc="load Reynolds number Re*C of the path of fixed load per unit span")
        rows, cols = dist_wrt_dist(nn, nr)
        dist = ["inflow_speed", "v_theta"] + (["dtorque_dr", "radii"] if torque else ["dthrust_dr"])
        self.declare_partials("load_reynolds", dist, rows=rows, cols=cols)
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials("load_reynolds", ["v_axial", "mu"], rows=rows, cols=cols)

    def _parts(self, inputs):
        torque = self.options["chord_form"] == "torque"
        load = inputs["dtorque_dr"] / inputs["radii"] if torque else inputs["dthrust_dr"]
        v_x = inputs["v_axial"][:, None]
        w0_sq = v_x ** 2 + inputs["v_theta"] ** 2
        factor = 2.0 * np.sqrt(w0_sq) / (inputs["mu"][:, None] * inputs["inflow_speed"] ** 2
                                         * self.options["num_blades"])
        return load, factor, w0_sq, v_x

    def compute(self, inputs, outputs):
        load, factor, _, _ = self._parts(inputs)
        outputs["load_reynolds"] = load * factor

    def compute_partials(self, inputs, partials):
        load, factor, w0_sq, v_x = self._parts(inputs)
        q = load * factor
        if self.options["chord_form"] == "torque":
            partials["load_reynolds", "dtorque_dr"] = (factor / inputs["radii"]).ravel()
            partials["load_reynolds", "radii"] = (-q / inputs["radii"]).ravel()
        else:
            partials["load_reynolds", "dthrust_dr"] = factor.ravel()
        partials["load_reynolds", "inflow_speed"] = (-2.0 * q / inputs["inflow_speed"]).ravel()
        partials["load_reynolds", "v_theta"] = (q * inputs["v_theta"] / w0_sq).ravel()
        partials["load_reynolds", "v_axial"] = (q * v_x / w0_sq).ravel()
        partials["load_reynolds", "mu"] = (-q / inputs["mu"][:, None]).ravel()


class ReferenceReynoldsComp(om.ExplicitComponent):
    """Reynolds number of the reference station, whose chord is ``c_ref``.

    ::

        Re_ref = rho W0 c_ref / mu,   W0 = sqrt(V_x**2 + (Omega r_ref)**2)   (the BEM convention)

    Options: ``num_nodes``.

    Inputs
    ------
    v_axial[nn] (m/s), v_theta_ref[nn] (m/s), ref_chord[nn] (m), rho[nn] (kg/m**3), mu[nn] (Pa*s)
        Flow and chord of the reference station.

    Outputs
    -------
    reynolds_ref[nn] (-)
    """

    def initialize(self):
        declare_size_options(self.options, radial=False)

    def setup(self):
        nn = self.options["num_nodes"]
        add_inputs(self, _REFERENCE_FLOW)
        self.add_output("reynolds_ref", val=np.full(nn, 3e5), units=None, ref=_REYNOLDS_SCALE,
                        desc="chord Reynolds number at the reference station (speed without induction)")
        rows, cols = node_wrt_node(nn)
        self.declare_partials("reynolds_ref", _REFERENCE_FLOW, rows=rows, cols=cols)

    def _parts(self, inputs):
        w0 = np.sqrt(inputs["v_axial"] ** 2 + inputs["v_theta_ref"] ** 2)
        return w0, inputs["rho"] * w0 * inputs["ref_chord"] / inputs["mu"]

    def compute(self, inputs, outputs):
        outputs["reynolds_ref"] = self._parts(inputs)[1]

    def compute_partials(self, inputs, partials):
        w0, re = self._parts(inputs)
        partials["reynolds_ref", "v_axial"] = re * inputs["v_axial"] / w0 ** 2
        partials["reynolds_ref", "v_theta_ref"] = re * inputs["v_theta_ref"] / w0 ** 2
        partials["reynolds_ref", "ref_chord"] = re / inputs["ref_chord"]
        partials["reynolds_ref", "rho"] = re / inputs["rho"]
        partials["reynolds_ref", "mu"] = -re / inputs["mu"]


class ReferenceSectionPointComp(om.ExplicitComponent):
    """The reference station's local section point at its given Reynolds number.

    Solved as in :mod:`bild_mdo.bild.local_section_point_reference`: the point
    ``(alpha, Re_ref)`` that is a minimum of ``cd/cl`` along its own path of
    fixed load (the lowest ``cd/cl`` of those), with implicit-function
    derivatives; complex inputs are carried with them.

    Options: ``num_nodes``, ``polar``, ``chord_form``.

    Inputs
    ------
    phi_ref[nn] (rad), reynolds_ref[nn] (-)

    Outputs
    -------
    alpha_star_ref[nn] (rad), cl_star_ref[nn] (-), cd_star_ref[nn] (-)
    """

    def initialize(self):
        declare_size_options(self.options, radial=False)
        self.options.declare("polar", recordable=False, desc="airfoil Polar (Reynolds-dependent only)")
        self.options.declare("chord_form", default="thrust", values=CHORD_FORMS,
                             desc="force coefficient of the chord formula: 'thrust' (C_x) or 'torque' (C_theta)")

    def setup(self):
        nn = self.options["num_nodes"]
        add_inputs(self, ("phi_ref",))
        self.add_input("reynolds_ref", val=np.full(nn, 3e5), units=None,
                       desc="chord Reynolds number at the reference station")
        for name in ("alpha_star", "cl_star", "cd_star"):
            _, default, units, desc = VARIABLES[name]
            self.add_output(f"{name}_ref", val=np.full(nn, default), units=units,
                            desc=f"{_LOCAL_DESC[name]}, of the reference station")
        rows, cols = node_wrt_node(nn)
        self.declare_partials(["alpha_star_ref", "cl_star_ref", "cd_star_ref"], ["phi_ref", "reynolds_ref"],
                              rows=rows, cols=cols)
        self._cache = None

    def _solve(self, inputs):
        phi, re = np.real(inputs["phi_ref"]), np.real(inputs["reynolds_ref"])
        key = (phi.tobytes(), re.tobytes())
        if self._cache is None or self._cache[0] != key:
            try:
                point = solve_reference_point(self.options["polar"], phi, re, self.options["chord_form"])
            except ValueError as err:
                raise om.AnalysisError(f"{self.msginfo}: {err}") from err
            self._cache = (key, point)
        return self._cache[1]

    def compute(self, inputs, outputs):
        point = self._solve(inputs)
        d_phi, d_re = np.imag(inputs["phi_ref"]), np.imag(inputs["reynolds_ref"])
        for field in ("alpha", "cl", "cd"):
            value = getattr(point, field)
            if np.iscomplexobj(inputs["phi_ref"]):
                value = value + 1j * (getattr(point, f"d{field}_dphi") * d_phi + getattr(point, f"d{field}_dre") * d_re)
            outputs[f"{_OUT[field]}_ref"] = value

    def compute_partials(self, inputs, partials):
        point = self._solve(inputs)
        for field in ("alpha", "cl", "cd"):
            partials[f"{_OUT[field]}_ref", "phi_ref"] = getattr(point, f"d{field}_dphi")
            partials[f"{_OUT[field]}_ref", "reynolds_ref"] = getattr(point, f"d{field}_dre")


class LocalSectionPointComp(om.ExplicitComponent):
    """Angle of attack, lift and drag that minimise ``cd/cl`` along each station's path of fixed load.

    The stationarity condition, its solution and its implicit-function
    derivatives are those of :mod:`bild_mdo.bild.local_section_point`; complex
    inputs (complex step) are carried to first order with those derivatives.
    Where two minima are nearly equal the lower ``cd/cl`` is taken, so the point
    can jump as the inputs move (a kink in the design).  Load Reynolds numbers
    below :data:`LOAD_REYNOLDS_FLOOR` (unloaded stations) are evaluated at it.

    Options
    -------
    num_nodes, num_radial : int
        Sizes.
    polar : Polar
        A polar that varies with the Reynolds number only.
    chord_form : str
        ``'thrust'`` or ``'torque'`` (the force coefficient ``C``).

    Inputs
    ------
    phi[nn, nr] (rad), load_reynolds[nn, nr] (-)

    Outputs
    -------
    alpha_star[nn, nr] (rad), cl_star[nn, nr] (-), cd_star[nn, nr] (-), reynolds[nn, nr] (-)
        The section point and the chord Reynolds number ``rho W0 c / mu`` it runs at.
    """

    def initialize(self):
        _declare_common(self.options)
        self.options.declare("polar", recordable=False, desc="airfoil Polar (Reynolds-dependent only)")

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        shape = (nn, nr)
        self._names = {k: k for k in ("phi", "load_reynolds", "alpha_star", "cl_star", "cd_star", "reynolds")}
        self.add_input(self._names["phi"], val=np.full(shape, 0.1), units="rad", desc="inflow angle")
        self.add_input(self._names["load_reynolds"], val=np.full(shape, 1e5), units=None,
                       desc="load Reynolds number Re*C of the path of fixed load")
        outputs = ["alpha_star", "cl_star", "cd_star"]
        for name in outputs:
            _, default, units, desc = VARIABLES[name]
            self.add_output(name, val=np.full(shape, default), units=units, desc=f"{_LOCAL_DESC[name]}, per station")
        self.add_output("reynolds", val=np.full(shape, 3e5), units=None, ref=_REYNOLDS_SCALE,
                        desc="chord Reynolds number rho W0 c / mu of the station")
        outputs.append("reynolds")
        n = int(np.prod(shape))
        for name in outputs:
            self.declare_partials(self._names[name], [self._names["phi"], self._names["load_reynolds"]],
                                  rows=np.arange(n), cols=np.arange(n))
        self._cache = None

    def _solve(self, inputs):
        phi = np.real(inputs[self._names["phi"]]).ravel()
        load = np.real(inputs[self._names["load_reynolds"]]).ravel()
        key = (phi.tobytes(), load.tobytes())
        if self._cache is not None and self._cache[0] == key:
            return self._cache[1:]
        floored = ~(load > LOAD_REYNOLDS_FLOOR)
        phi_eff = np.where(np.isfinite(phi), phi, 0.0)
        load_eff = np.where(floored, LOAD_REYNOLDS_FLOOR, load)
        polar, form = self.options["polar"], self.options["chord_form"]
        try:
            point = solve_local_point(polar, phi_eff, load_eff, form)
        except ValueError as err:
            raise om.AnalysisError(f"{self.msginfo}: {err}") from err
        derivs = point_derivatives(polar, point, phi_eff, form)
        if np.any(floored):
            derivs = derivs._replace(**{f: np.where(floored, 0.0, getattr(derivs, f))
                                        for f in derivs._fields if f.endswith("_dq")})
        self._cache = (key, point, derivs)
        return point, derivs

    def compute(self, inputs, outputs):
        point, derivs = self._solve(inputs)
        shape = inputs[self._names["phi"]].shape
        d_phi = np.imag(inputs[self._names["phi"]]).ravel()
        d_q = np.imag(inputs[self._names["load_reynolds"]]).ravel()
        carry = np.iscomplexobj(inputs[self._names["phi"]]) and (np.any(d_phi) or np.any(d_q))
        fields = {"alpha_star": "alpha", "cl_star": "cl", "cd_star": "cd", "reynolds": "re"}
        for out, field in fields.items():
            if out not in self._names:
                continue
            value = getattr(point, "reynolds" if field == "re" else field)
            if carry:
                value = value + 1j * (getattr(derivs, f"d{field}_dphi") * d_phi + getattr(derivs, f"d{field}_dq") * d_q)
            outputs[self._names[out]] = value.reshape(shape)

    def compute_partials(self, inputs, partials):
        _, derivs = self._solve(inputs)
        phi, load = self._names["phi"], self._names["load_reynolds"]
        for out, field in (("alpha_star", "alpha"), ("cl_star", "cl"), ("cd_star", "cd"), ("reynolds", "re")):
            if out not in self._names:
                continue
            partials[self._names[out], phi] = getattr(derivs, f"d{field}_dphi")
            partials[self._names[out], load] = getattr(derivs, f"d{field}_dq")
