"""Ideal-loading constant lambda from the reference-station induced velocities (Eq. (22))."""
import numpy as np
import openmdao.api as om

from bild_mdo.bild.feasibility import declare_feasibility_option, report_infeasible
from bild_mdo.utils.options import add_inputs, add_outputs, declare_size_options
from bild_mdo.utils.sparsity import node_wrt_node


class IdealLoadingComp(om.ExplicitComponent):
    """Ideal-loading constant lambda of the optimal rotor, evaluated at the reference station.

    ::

        lambda = V_theta u_theta / (2 (2 u_axial - V_x)) + V_theta u_axial / (V_theta - u_theta) - V_x     Eq. (22)

    with the reference station's induced velocities (Alg. 1, step 3).  Eq. (22)
    requires Assumption 3, ``0 <= V_x < u_axial`` and ``0 < u_theta < V_theta``,
    under which ``lambda > u_axial - V_x > 0`` (Appendix 7.1); inputs that violate
    it raise :class:`openmdao.api.AnalysisError` naming every failing node
    (inside a :class:`~bild_mdo.bild.bild_group.BILDGroup` they are recorded
    in the group's feasibility ledger instead and get the placeholder
    ``lambda = V_theta_ref``, zero partials).  (Eq. (22) is the negative of
    Eq. (14) as printed; the paper, and this library, use Eq. (22).)

    Options: the size ``num_nodes`` (:func:`~bild_mdo.utils.options.declare_size_options`) and
    ``feasibility`` (:func:`~bild_mdo.bild.feasibility.declare_feasibility_option`).

    Inputs
    ------
    u_axial_ref[nn] (m/s)
        Axial velocity at the rotor disk at the reference station.
    u_theta_ref[nn] (m/s)
        Tangential induced velocity at the reference station.
    v_axial[nn] (m/s)
        Axial free-stream velocity.
    v_theta_ref[nn] (m/s)
        Rotational blade speed ``Omega r_ref`` at the reference station.

    Outputs
    -------
    ideal_loading_constant[nn] (m/s)
        Ideal-loading constant lambda, Eq. (22).
    """

    def initialize(self):
        declare_size_options(self.options, radial=False)
        declare_feasibility_option(self.options)

    def setup(self):
        add_inputs(self, ("u_axial_ref", "u_theta_ref", "v_axial", "v_theta_ref"))
        add_outputs(self, ("ideal_loading_constant",))

    def setup_partials(self):
        rows, cols = node_wrt_node(self.options["num_nodes"])
        self.declare_partials("ideal_loading_constant", ["u_axial_ref", "u_theta_ref", "v_axial", "v_theta_ref"],
                              rows=rows, cols=cols)

    def _validate(self, u_axial, u_t, v_x, v_t):
        """Check Assumption 3 at the reference station; return the mask of the failing nodes."""
        u_axial, u_t, v_x, v_t = (np.real(a) for a in (u_axial, u_t, v_x, v_t))
        finite = np.isfinite(u_axial) & np.isfinite(u_t) & np.isfinite(v_x) & np.isfinite(v_t)
        details = {"u_axial_ref [m/s]": u_axial, "u_theta_ref [m/s]": u_t, "v_axial [m/s]": v_x,
                   "v_theta_ref [m/s]": v_t}
        checks = (
            (v_x >= 0.0, "V_x >= 0", "the axial free-stream velocity must not be negative"),
            (u_axial > v_x, "u_axial_ref > V_x",
             "the reference station must produce thrust (check the reference chord, rpm and airfoil point)"),
            (u_t > 0.0, "u_theta_ref > 0", "the reference station must absorb torque"),
            (u_t < v_t, "u_theta_ref < V_theta_ref", "the reference station is overloaded (the tangential "
                                                      "induction reaches the blade speed); reduce ref_chord "
                                                      "(reference solidity) or the advance ratio"),
        )
        failed = np.zeros(v_x.shape, dtype=bool)
        for ok, rule, hint in checks:
            bad = ~(ok & finite) & ~failed
            report_infeasible(self, rule, bad, f"Assumption 3 violated at the reference station: {rule} fails; "
                                               f"{hint}", details)
            failed |= bad
        return failed

    def compute(self, inputs, outputs):
        u_axial, u_t = inputs["u_axial_ref"], inputs["u_theta_ref"]
        v_x, v_t = inputs["v_axial"], inputs["v_theta_ref"]
        failed = self._validate(u_axial, u_t, v_x, v_t)
        with np.errstate(divide="ignore", invalid="ignore"):
            lam = v_t * u_t / (2.0 * (2.0 * u_axial - v_x)) + v_t * u_axial / (v_t - u_t) - v_x
        outputs["ideal_loading_constant"] = np.where(failed, v_t, lam)

    def compute_partials(self, inputs, partials):
        u_axial, u_t = inputs["u_axial_ref"], inputs["u_theta_ref"]
        v_x, v_t = inputs["v_axial"], inputs["v_theta_ref"]
        thrust_slope = 2.0 * u_axial - v_x  # proportional to dT_r/du_axial, Eq. (21)
        gap = v_t - u_t
        name = "ideal_loading_constant"
        # Placeholder nodes (infeasible, inside a BILDGroup) hold lambda = V_theta_ref.
        failed = self._validate(u_axial, u_t, v_x, v_t)
        with np.errstate(divide="ignore", invalid="ignore"):
            partials[name, "u_axial_ref"] = np.where(failed, 0.0, -v_t * u_t / thrust_slope**2 + v_t / gap)
            partials[name, "u_theta_ref"] = np.where(failed, 0.0, v_t / (2.0 * thrust_slope) + v_t * u_axial / gap**2)
            partials[name, "v_axial"] = np.where(failed, 0.0, v_t * u_t / (2.0 * thrust_slope**2) - 1.0)
            partials[name, "v_theta_ref"] = np.where(failed, 1.0, u_t / (2.0 * thrust_slope) - u_axial * u_t / gap**2)
