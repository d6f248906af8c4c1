"""Ideal-loading constant lambda from the reference-station induced velocities (Eq. (22))."""
import numpy as np
import openmdao.api as om

from bild_mdo.utils.sparsity import node_wrt_node


class IdealLoadingComp(om.ExplicitComponent):
    """Ideal-loading constant lambda of the optimal rotor, evaluated at the reference station.

    ::

        lambda = V_theta u_theta / (2 (2 u_x - V_x)) + V_theta u_x / (V_theta - u_theta) - V_x     Eq. (22)

    with the reference station's induced velocities (Alg. 1, step 3).  Eq. (22)
    requires Assumption 3, ``0 <= V_x < u_x`` and ``0 < u_theta < V_theta``,
    under which ``lambda > u_x - V_x > 0`` (Appendix 7.1); inputs that violate
    it raise :class:`openmdao.api.AnalysisError`.  (Eq. (22) is the negative of
    Eq. (14) as printed; the paper, and this library, use Eq. (22).)

    Options
    -------
    num_nodes : int
        Number of designs / operating points.
    num_radial : int
        Number of radial stations (unused; declared for a uniform interface).

    Inputs
    ------
    u_x_ref[nn] (m/s)
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
        self.options.declare("num_nodes", types=int, default=1, desc="number of designs / operating points")
        self.options.declare("num_radial", types=int, default=10,
                             desc="number of radial stations (unused; uniform interface)")

    def setup(self):
        nn = self.options["num_nodes"]
        self.add_input("u_x_ref", val=np.full(nn, 10.0), units="m/s",
                       desc="axial velocity at the rotor disk at the reference station")
        self.add_input("u_theta_ref", val=np.ones(nn), units="m/s",
                       desc="tangential induced velocity at the reference station")
        self.add_input("v_axial", val=np.zeros(nn), units="m/s", desc="axial free-stream velocity")
        self.add_input("v_theta_ref", val=np.full(nn, 50.0), units="m/s",
                       desc="rotational blade speed Omega*r at the reference station")
        self.add_output("ideal_loading_constant", val=np.full(nn, 10.0), units="m/s",
                        desc="ideal-loading constant lambda, Eq. (22)")

    def setup_partials(self):
        rows, cols = node_wrt_node(self.options["num_nodes"])
        self.declare_partials("ideal_loading_constant", ["u_x_ref", "u_theta_ref", "v_axial", "v_theta_ref"],
                              rows=rows, cols=cols)

    def _validate(self, u_x, u_t, v_x, v_t):
        u_x, u_t, v_x, v_t = (np.real(a) for a in (u_x, u_t, v_x, v_t))
        checks = (
            (v_x >= 0.0, "V_x >= 0", "the axial free-stream velocity must not be negative"),
            (u_x > v_x, "u_x_ref > V_x", "the reference station must produce thrust (check the reference chord, "
                                         "rpm and airfoil point)"),
            (u_t > 0.0, "u_theta_ref > 0", "the reference station must absorb torque"),
            (u_t < v_t, "u_theta_ref < V_theta_ref", "the reference station is overloaded (the tangential "
                                                      "induction reaches the blade speed): reduce ref_chord "
                                                      "(reference solidity) or the advance ratio"),
        )
        for ok, rule, hint in checks:
            bad = ~(ok & np.isfinite(u_x) & np.isfinite(u_t) & np.isfinite(v_x) & np.isfinite(v_t))
            if np.any(bad):
                i = int(np.flatnonzero(bad)[0])
                at = ", ".join(f"{label}={float(a[i])!r}" for label, a in
                               (("u_x_ref", u_x), ("u_theta_ref", u_t), ("v_axial", v_x), ("v_theta_ref", v_t)))
                raise om.AnalysisError(f"{self.msginfo}: Assumption 3 violated at node {i} ({rule} fails: {at} m/s); "
                                       f"{hint}.")

    def compute(self, inputs, outputs):
        u_x, u_t = inputs["u_x_ref"], inputs["u_theta_ref"]
        v_x, v_t = inputs["v_axial"], inputs["v_theta_ref"]
        self._validate(u_x, u_t, v_x, v_t)
        outputs["ideal_loading_constant"] = v_t * u_t / (2.0 * (2.0 * u_x - v_x)) + v_t * u_x / (v_t - u_t) - v_x

    def compute_partials(self, inputs, partials):
        u_x, u_t = inputs["u_x_ref"], inputs["u_theta_ref"]
        v_x, v_t = inputs["v_axial"], inputs["v_theta_ref"]
        thrust_slope = 2.0 * u_x - v_x  # proportional to dT_r/du_x, Eq. (21)
        gap = v_t - u_t
        name = "ideal_loading_constant"
        partials[name, "u_x_ref"] = -v_t * u_t / thrust_slope**2 + v_t / gap
        partials[name, "u_theta_ref"] = v_t / (2.0 * thrust_slope) + v_t * u_x / gap**2
        partials[name, "v_axial"] = v_t * u_t / (2.0 * thrust_slope**2) - 1.0
        partials[name, "v_theta_ref"] = u_t / (2.0 * thrust_slope) - u_x * u_t / gap**2
