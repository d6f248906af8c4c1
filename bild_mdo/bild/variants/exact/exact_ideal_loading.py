"""Ideal-loading constant lambda of the exact ideal loading, at the reference station's BEM inflow angle."""
import numpy as np
import openmdao.api as om

from bild_mdo.bem.blade_element import declare_section_options
from bild_mdo.bem.prandtl import loss_inputs
from bild_mdo.bild.annulus_stationarity import residual_partials, stationarity, unloaded_angle
from bild_mdo.bild.feasibility import declare_feasibility_option, report_infeasible
from bild_mdo.utils.options import add_inputs, add_outputs
from bild_mdo.utils.sparsity import node_wrt_node

_INPUTS = ("phi_ref", "v_axial", "v_theta_ref", "ref_radius", "radius", "hub_radius", "cl_star", "cd_star")


class ExactIdealLoadingComp(om.ExplicitComponent):
    """lambda = (F e)'/(F t)' at the reference station (:mod:`~bild_mdo.bild.annulus_stationarity`).

    The marginal energy loss per marginal thrust of the reference annulus,
    with the Prandtl loss factor ``F`` differentiated too (the paper's Eq. (22)
    leaves it out).  ``phi_ref`` is the reference station's BEM inflow angle
    with ``c_ref`` (:class:`~bild_mdo.bild.variants.reference_point.reference_station.ReferenceStationComp`),
    so the station of the exact ideal loading at ``r_ref`` has the chord ``c_ref``.

    The reference annulus must carry thrust (``phi_ref > atan(V_x/V_theta_ref)``)
    and lie below its maximum annulus thrust (``(F t)' > 0``); nodes that fail
    raise :class:`openmdao.api.AnalysisError` (inside a BILDGroup: recorded in
    its feasibility ledger; placeholder ``lambda = V_theta_ref``, zero partials).

    Options: ``num_nodes``, ``num_blades``, ``loss_model`` and ``feasibility``.

    Inputs
    ------
    phi_ref[nn] (rad), v_axial[nn] (m/s), v_theta_ref[nn] (m/s)
        Reference inflow angle, axial velocity and blade speed ``Omega r_ref``.
    ref_radius[nn] (m), radius[nn] (m), hub_radius[nn] (m)
        Reference, tip and hub radii (for ``F``).
    cl_star[nn] (-), cd_star[nn] (-)
        Airfoil point of the reference station.

    Outputs
    -------
    ideal_loading_constant[nn] (m/s)
        lambda of the exact ideal loading.
    """

    def initialize(self):
        declare_section_options(self.options, radial=False, polar=False)
        declare_feasibility_option(self.options)

    def setup(self):
        add_inputs(self, _INPUTS)
        add_outputs(self, ("ideal_loading_constant",))

    def _wrt(self):
        return [name for name in _INPUTS if name not in ("radius", "hub_radius")] + list(
            loss_inputs(self.options["loss_model"]))

    def setup_partials(self):
        rows, cols = node_wrt_node(self.options["num_nodes"])
        self.declare_partials("ideal_loading_constant", self._wrt(), rows=rows, cols=cols)

    def _arguments(self, inputs):
        return (inputs["phi_ref"], inputs["v_axial"], inputs["v_theta_ref"], inputs["cd_star"] / inputs["cl_star"],
                inputs["ref_radius"], inputs["radius"], inputs["hub_radius"], self.options["num_blades"],
                self.options["loss_model"])

    def _validate(self, inputs, terms):
        return check_reference_annulus(self, inputs, terms.N, terms.D, "exact ideal loading", "(F t)' = 0")

    def compute(self, inputs, outputs):
        terms = stationarity(*self._arguments(inputs))
        failed = self._validate(inputs, terms)
        safe = np.where(failed, 1.0, terms.D)
        outputs["ideal_loading_constant"] = np.where(failed, inputs["v_theta_ref"], terms.N / safe)

    def compute_partials(self, inputs, partials):
        args = self._arguments(inputs)
        terms = stationarity(*args)
        failed = self._validate(inputs, terms)
        d = np.where(failed, 1.0, terms.D)
        lam = terms.N / d
        _, d_res, _ = residual_partials(args[0], lam, *args[1:])
        # lambda = N/D: d lambda = (dN - lambda dD)/D = dR/D at fixed lambda.
        cl, ratio = inputs["cl_star"], args[3]
        chain = {"phi_ref": d_res["phi"], "v_axial": d_res["v_axial"], "v_theta_ref": d_res["v_theta"],
                 "ref_radius": d_res["r"], "radius": d_res["radius"], "hub_radius": d_res["hub_radius"],
                 "cl_star": d_res["drag_to_lift"] * (-ratio / cl), "cd_star": d_res["drag_to_lift"] / cl}
        for name in self._wrt():
            value = np.where(failed, 0.0, chain[name] / d)
            if name == "v_theta_ref":
                value = np.where(failed, 1.0, value)
            partials["ideal_loading_constant", name] = value


def check_reference_annulus(component, inputs, numerator, denominator, method, maximum):
    """Record the nodes whose reference annulus cannot define lambda = N / D; return them (bool ``[nn]``).

    The annulus must be finite, carry thrust (``phi_ref > atan(V_x/V_theta_ref)``) and lie below its
    maximum thrust (``D > 0``; ``maximum`` names that condition in the message); ``method`` names the
    loading in the message.  Used by the exact and the Reynolds-aware exact loadings.
    """
    phi, v_x, v_t = (np.real(inputs[name]) for name in ("phi_ref", "v_axial", "v_theta_ref"))
    d, n = np.real(denominator), np.real(numerator)
    details = {"phi_ref [deg]": np.degrees(phi), "v_axial [m/s]": v_x, "v_theta_ref [m/s]": v_t}
    checks = (
        (np.isfinite(d) & np.isfinite(n) & (v_x >= 0.0) & (v_t > 0.0), "finite",
         "the reference annulus is not finite (V_x >= 0 and V_theta_ref > 0 are needed)", False),
        (phi > unloaded_angle(v_x, v_t), "thrust",
         "the reference station must produce thrust (phi_ref > atan(V_x/V_theta_ref)); raise ref_chord or rpm", True),
        (d > 0.0, "below_maximum_thrust",
         f"the reference station is loaded past its maximum annulus thrust {maximum}, where the {method} "
         "does not exist; reduce ref_chord or the advance ratio", False),
    )
    failed = np.zeros(phi.shape, dtype=bool)
    for ok, key, reason, light in checks:
        bad = ~ok & ~failed
        report_infeasible(component, key, bad, f"{method}: {reason}", details, light=light)
        failed |= bad
    return failed
