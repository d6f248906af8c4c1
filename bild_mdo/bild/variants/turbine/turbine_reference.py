"""The reference station of the turbine loading: the multiplier from the reference chord, or the chord from it."""
import numpy as np
import openmdao.api as om

from bild_mdo.bem.blade_element import declare_section_options
from bild_mdo.bem.prandtl import loss_inputs
from bild_mdo.bild.variants.turbine.kernel import (
    chord_jet, implicit_sensitivities, reference_chord, residual_jacobian, solve_reference_chord, station_angle,
    station_jets, turbine_terms)
from bild_mdo.bild.variants.turbine.turbine_inflow import add_multiplier
from bild_mdo.utils.jet import variable
from bild_mdo.utils.options import add_inputs, add_outputs
from bild_mdo.utils.sparsity import node_wrt_node

GIVEN = ("multiplier", "ref_chord")
_NODE = ("v_axial", "v_theta_ref", "ref_radius", "radius", "hub_radius", "cl_star", "cd_star")


class TurbineReferenceStationComp(om.ExplicitComponent):
    """The turbine ideal loading at the reference station ``r_ref``: the family's parameter both ways.

    The turbine family is parameterised by its multiplier ``mu`` (:mod:`.kernel`, Eq. (T3)); at the reference
    station the chord (T2) is a monotone function of the load on ``[phi_half, phi0]``, so ``mu`` and the
    reference chord ``c_ref`` name the same member:

    * ``given='multiplier'`` (the maximum-power member ``mu = 0``, or a thrust limit's ``mu``): ``phi_ref``
      solves (T3), ``ref_chord = c(phi_ref)`` (zero if the station is unloaded);
    * ``given='ref_chord'``: ``phi_ref`` solves ``c(phi) = c_ref`` (bracketed Newton from the unloaded
      ``c = 0``), ``mu = G(phi_ref) = (F p)'/(F t)'``.  A ``c_ref`` beyond the chord at ``a = 1/2`` or past the
      maximum of ``F t`` raises AnalysisError (reduce ref_chord).

    Options: ``num_nodes``, ``num_blades``, ``loss_model``, ``given``.

    Inputs
    ------
    v_axial[nn] (m/s), v_theta_ref[nn] (m/s), ref_radius[nn] (m), radius[nn] (m), hub_radius[nn] (m),
    cl_star[nn] (-), cd_star[nn] (-); power_thrust_multiplier[nn] (m/s) or ref_chord[nn] (m) (``given``)

    Outputs
    -------
    phi_ref[nn] (rad)
        Inflow angle of the reference station.
    ref_chord[nn] (m) or power_thrust_multiplier[nn] (m/s)
        The other parameter of the member.
    """

    def initialize(self):
        declare_section_options(self.options, radial=False, polar=False)
        self.options.declare("given", default="multiplier", values=GIVEN,
                             desc="'multiplier': mu in, ref_chord out; 'ref_chord': ref_chord in, mu out")

    def setup(self):
        nn = self.options["num_nodes"]
        add_inputs(self, _NODE)
        add_outputs(self, ("phi_ref",))
        if self.options["given"] == "multiplier":
            add_multiplier(self.add_input, nn)
            add_outputs(self, ("ref_chord",))
        else:
            add_inputs(self, ("ref_chord",))
            add_multiplier(self.add_output, nn)

    def _result_names(self):
        return ["phi_ref", "ref_chord" if self.options["given"] == "multiplier" else "power_thrust_multiplier"]

    def _wrt(self):
        given = "power_thrust_multiplier" if self.options["given"] == "multiplier" else "ref_chord"
        return ["v_axial", "v_theta_ref", "ref_radius", "cl_star", "cd_star", given] + list(
            loss_inputs(self.options["loss_model"]))

    def setup_partials(self):
        rows, cols = node_wrt_node(self.options["num_nodes"])
        self.declare_partials(self._result_names(), self._wrt(), rows=rows, cols=cols)

    def _args(self, inputs):
        return (inputs["v_axial"], inputs["v_theta_ref"], inputs["cd_star"] / inputs["cl_star"], inputs["ref_radius"],
                inputs["radius"], inputs["hub_radius"])

    def _chord(self, phi, args, cl):
        jets = station_jets(phi, *args, self.options["num_blades"], self.options["loss_model"])
        return chord_jet(jets, variable(args[3], "r"), self.options["num_blades"], cl)

    def _solve_chord(self, inputs):
        """Real ``phi_ref`` with ``c(phi_ref) = c_ref`` and the multiplier there."""
        args = [np.real(a) for a in self._args(inputs)]
        cl, c_ref = np.real(inputs["cl_star"]), np.real(inputs["ref_chord"])
        phi, mu, c_lo, status = solve_reference_chord(*args, cl, c_ref, self.options["num_blades"],
                                                      self.options["loss_model"])
        if np.any(status == 1):
            i = int(np.flatnonzero(status == 1)[0])
            raise om.AnalysisError(f"{self.msginfo}: ref_chord {c_ref[i]:.4g} m (node {i}) is not in (0, "
                                   f"{c_lo[i]:.4g}) m, the chord that loads the reference station to a = 1/2: "
                                   "reduce ref_chord (or raise the tip-speed ratio)")
        if np.any(status == 2):
            i = int(np.flatnonzero(status == 2)[0])
            raise om.AnalysisError(f"{self.msginfo}: ref_chord {c_ref[i]:.4g} m (node {i}) loads the reference "
                                   "station past its maximum thrust, where the turbine loading does not exist: "
                                   "reduce ref_chord")
        return phi, args, cl, mu

    def compute(self, inputs, outputs):
        opts = (self.options["num_blades"], self.options["loss_model"])
        args = self._args(inputs)
        given = "power_thrust_multiplier" if self.options["given"] == "multiplier" else "ref_chord"
        complex_step = any(np.iscomplexobj(a) for a in args + (inputs["cl_star"], inputs[given]))
        if self.options["given"] == "multiplier":
            phi, _ = station_angle(inputs["power_thrust_multiplier"], *args, *opts)
            outputs["phi_ref"] = phi
            outputs["ref_chord"] = (self._chord(phi, args, inputs["cl_star"]).v if complex_step else
                                    reference_chord(phi, *args, inputs["cl_star"], *opts))
            return
        phi, real_args, cl, mu = self._solve_chord(inputs)
        if complex_step:
            jet = self._chord(phi, real_args, cl)
            value = self._chord(phi, args, inputs["cl_star"]).v - inputs["ref_chord"]
            phi = phi - 1j * np.imag(value) / jet.partial("phi")
            terms = turbine_terms(phi, *args, *opts)
            mu = terms.power_slope / terms.thrust_slope
        outputs["phi_ref"] = phi
        outputs["power_thrust_multiplier"] = mu

    def compute_partials(self, inputs, partials):
        opts = (self.options["num_blades"], self.options["loss_model"])
        cl = np.real(inputs["cl_star"])
        if self.options["given"] == "multiplier":
            args = [np.real(a) for a in self._args(inputs)]
            mu = np.real(inputs["power_thrust_multiplier"])
            phi, status = station_angle(mu, *args, *opts)
            sens = implicit_sensitivities(phi, mu, status, *args, *opts)
            sens["power_thrust_multiplier"] = sens.pop("mu")
            chord = self._chord(phi, args, cl)
            total = {name: chord.partial(name) + chord.partial("phi") * sens[name] for name in sens}
            out = "ref_chord"
            d_cl_direct, sens_cl = -chord.v / cl, 0.0
        else:
            phi, args, _, _ = self._solve_chord(inputs)
            chord = self._chord(phi, args, cl)
            c_phi = chord.partial("phi")
            sens = {name: -chord.partial(name) / c_phi for name in ("v_axial", "v_theta", "drag_to_lift", "r",
                                                                    "radius", "hub_radius")}
            sens["ref_chord"] = 1.0 / c_phi
            sens_cl = chord.v / cl / c_phi
            terms = turbine_terms(phi, *args, *opts)
            mu = terms.power_slope / terms.thrust_slope
            d_res = residual_jacobian(phi, mu, *args, *opts)
            total = {name: (d_res.get(name, 0.0) + d_res["phi"] * sens[name]) / terms.thrust_slope for name in sens}
            out = "power_thrust_multiplier"
            d_cl_direct = d_res["phi"] * sens_cl / terms.thrust_slope
        names = {"v_axial": "v_axial", "v_theta_ref": "v_theta", "ref_radius": "r", "radius": "radius",
                 "hub_radius": "hub_radius"}
        for name, key in names.items():
            if name in self._wrt():
                partials["phi_ref", name] = sens[key]
                partials[out, name] = total[key]
        ratio = args[2]
        given = "power_thrust_multiplier" if self.options["given"] == "multiplier" else "ref_chord"
        partials["phi_ref", given] = sens[given]
        partials[out, given] = total[given]
        partials["phi_ref", "cd_star"] = sens["drag_to_lift"] / cl
        partials[out, "cd_star"] = total["drag_to_lift"] / cl
        partials[out, "cl_star"] = -total["drag_to_lift"] * ratio / cl + d_cl_direct
        cl_phi = -sens["drag_to_lift"] * ratio / cl
        partials["phi_ref", "cl_star"] = cl_phi + sens_cl
