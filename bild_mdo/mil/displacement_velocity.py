"""DisplacementVelocityComp: the displacement velocity ratio zeta of a minimum-induced-loss design (implicit)."""
import numpy as np
import openmdao.api as om

from bild_mdo.mil.kernel import add_mil_inputs, declare_design_options, nondimensional_load, station_state
from bild_mdo.utils.newton import bracketed_newton, complex_step_update
from bild_mdo.utils.options import add_inputs, declare_size_options
from bild_mdo.utils.sparsity import node_wrt_dist, node_wrt_node

#: What the design is specified by: A&L give a thrust-specified and a power-specified form.
DESIGN_FOR = ("thrust", "power")
# Growth of the upper end of the bracket per step, from twice the Rankine-Froude (no loss) estimate, and the
# number of steps (1.25**40 ~ 7500): small steps so that a target just below the largest reachable T_c is found.
_GROWTH, _MAX_STEPS = 1.25, 40


class DisplacementVelocityComp(om.ImplicitComponent):
    """Displacement velocity ratio ``zeta = v'/V`` for a thrust (or power) target.

    Adkins & Liebeck (1994) iterate on ``zeta``: the flow angles, Prandtl's
    ``F`` and the design integrals ``I1, I2`` (``J1, J2``) depend on it, and
    the thrust-specified design takes the smaller root of
    ``T_c = I1 zeta - I2 zeta^2`` (power-specified: ``P_c = J1 zeta + J2 zeta^2``).
    Their fixed point is the root of the residual::

        R(zeta) = I1(zeta) zeta - I2(zeta) zeta^2 - T_c,    T_c = 2 T / (rho V^2 pi R^2)
        R(zeta) = J1(zeta) zeta + J2(zeta) zeta^2 - P_c,    P_c = 2 P / (rho V^3 pi R^2)

    with the integrals as midpoint sums over the stations (``sum(I1' dxi)``).
    ``R(0) = -T_c < 0``; the bracket's upper end starts at twice the
    Rankine-Froude value ``sqrt(1 + T_c) - 1`` and grows by 25 % steps until
    ``R > 0``, so the smallest root (A&L's branch) is found by
    :func:`~bild_mdo.utils.newton.bracketed_newton`.

    ``T_c(zeta)`` has a maximum: A&L's closed form
    ``zeta = I1/(2 I2) (1 - sqrt(1 - 4 I2 T_c / I1^2))`` has no real root
    beyond ``T_c = I1^2/(4 I2)``.  It falls with the speed ratio (about 2.5
    at ``lambda = 0.3``, 0.65 at 0.57, 0.23 at 0.95 for three blades), so
    heavily loaded designs at high advance ratios have no MIL solution; such a
    target raises :class:`openmdao.api.AnalysisError` naming ``T_c``.  ``linearize`` stores ``dR/dzeta``
    and ``solve_linear`` divides by it (one scalar per design), so totals are
    exact under RunOnce.

    Options
    -------
    num_nodes, num_radial, num_blades : int
        Sizes and the number of blades B.
    design_for : {'thrust', 'power'}
        Target quantity.
    loss_form : {'adkins_liebeck', 'local', 'qmil'}
        Prandtl exponent (see :mod:`bild_mdo.mil.kernel`).

    Inputs
    ------
    speed_ratio[nn] (-), radius_fraction[nn, nr] (-), width_fraction[nn, nr] (-)
        ``lambda``, ``xi`` and ``dxi`` (:class:`~bild_mdo.mil.speed_ratio.SpeedRatioComp`).
    cl_star[nn] (-), cd_star[nn] (-)
        Design airfoil point (``eps = C_d/C_l``).
    design_thrust[nn] (N) or design_power[nn] (W)
        Target (> 0).
    rho[nn] (kg/m**3), v_axial[nn] (m/s), radius[nn] (m)
        For ``T_c`` (``P_c``).

    Outputs
    -------
    zeta[nn] (-)
        Displacement velocity ratio ``v'/V``.
    """

    def initialize(self):
        declare_size_options(self.options)
        declare_design_options(self.options)
        self.options.declare("design_for", default="thrust", values=DESIGN_FOR, desc="target: thrust or power")

    def setup(self):
        nn = self.options["num_nodes"]
        add_mil_inputs(self, ("speed_ratio", "radius_fraction", "width_fraction"))
        add_inputs(self, ("cl_star", "cd_star", "rho", "v_axial", "radius"), cl_star=0.7, v_axial=50.0)
        if self.options["design_for"] == "thrust":
            self._target, units, desc = "design_thrust", "N", "thrust the design is specified for (> 0)"
        else:
            self._target, units, desc = "design_power", "W", "shaft power the design is specified for (> 0)"
        self.add_input(self._target, val=np.full(nn, 1000.0), units=units, desc=desc)
        self.add_output("zeta", val=np.full(nn, 0.1), units=None, desc="displacement velocity ratio v'/V")

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = node_wrt_node(nn)
        self.declare_partials("zeta", ["zeta", "speed_ratio", "cl_star", "cd_star", self._target, "rho",
                                       "v_axial", "radius"], rows=rows, cols=cols)
        rows, cols = node_wrt_dist(nn, nr)
        self.declare_partials("zeta", ["radius_fraction", "width_fraction"], rows=rows, cols=cols)

    def _target_coefficient(self, inputs):
        """``T_c`` or ``P_c`` of the target and the exponent of ``V`` in its denominator."""
        exponent = 2.0 if self.options["design_for"] == "thrust" else 3.0
        target = inputs[self._target]
        bad = ~(np.real(target) > 0.0)
        if np.any(bad):
            node = int(np.flatnonzero(bad)[0])
            raise om.AnalysisError(f"{self.msginfo}: {self._target} must be positive, got "
                                   f"{np.real(target)[node]!r} at node {node}")
        scale = inputs["rho"] * inputs["v_axial"] ** exponent * np.pi * inputs["radius"] ** 2
        return 2.0 * target / scale, exponent

    def _load(self, inputs, zeta, idx=slice(None)):
        eps = inputs["cd_star"][idx] / inputs["cl_star"][idx]
        state = station_state(inputs["speed_ratio"][idx, None], inputs["radius_fraction"][idx], zeta[:, None],
                              eps[:, None], self.options["num_blades"], self.options["loss_form"])
        return nondimensional_load(state, zeta, inputs["width_fraction"][idx], self.options["design_for"])

    def apply_nonlinear(self, inputs, outputs, residuals):
        target, _ = self._target_coefficient(inputs)
        residuals["zeta"] = self._load(inputs, outputs["zeta"])[0] - target

    def solve_nonlinear(self, inputs, outputs):
        target = np.real(self._target_coefficient(inputs)[0])
        real = {name: np.real(inputs[name]) for name in ("speed_ratio", "radius_fraction", "width_fraction",
                                                         "cl_star", "cd_star")}

        def residual(zeta, idx):
            value, grad, _ = self._load(real, zeta, idx)
            return value - target[idx], np.sum(grad[2], axis=1)

        hi = np.maximum(2.0 * (np.sqrt(1.0 + target) - 1.0), 1e-3)
        pending = np.arange(target.size)
        for _ in range(_MAX_STEPS):
            pending = pending[residual(hi[pending], pending)[0] <= 0.0]
            if pending.size == 0:
                break
            hi[pending] *= _GROWTH
        if pending.size:
            node = int(pending[0])
            symbol = "T_c" if self.options["design_for"] == "thrust" else "P_c"
            raise om.AnalysisError(
                f"{self.msginfo}: node {node}: the {self.options['design_for']} target "
                f"({self._target} = {np.real(inputs[self._target])[node]:.6g}, {symbol} = {target[node]:.4g}) is "
                "beyond the largest a minimum-induced-loss design (Adkins & Liebeck) reaches at this speed ratio: "
                "lower the target, or raise the rpm or the radius")
        result = bracketed_newton(residual, np.zeros_like(hi), hi, -target, x0=0.5 * hi, atol=1e-13)
        if result.first_failure() is not None:
            node = result.first_failure()
            raise om.AnalysisError(f"{self.msginfo}: node {node}: the displacement velocity ratio did not converge "
                                   f"(residual {result.residual[node]:.3g})")
        zeta = result.x
        if self.under_complex_step:
            # One Newton update in complex arithmetic carries the exact implicit derivative in the imaginary part.
            value = self._load(inputs, zeta.astype(complex))[0] - self._target_coefficient(inputs)[0]
            zeta = complex_step_update(zeta, value, result.slope)
        outputs["zeta"] = zeta

    def linearize(self, inputs, outputs, partials):
        target, exponent = self._target_coefficient(inputs)
        nn = self.options["num_nodes"]
        _, grad, local = self._load(inputs, outputs["zeta"], np.arange(nn))
        self._slope = np.sum(grad[2], axis=1)
        partials["zeta", "zeta"] = self._slope
        partials["zeta", "speed_ratio"] = np.sum(grad[0], axis=1)
        partials["zeta", "radius_fraction"] = grad[1].ravel()
        partials["zeta", "width_fraction"] = local.ravel()
        cl, cd = np.real(inputs["cl_star"]), np.real(inputs["cd_star"])
        deps = np.sum(grad[3], axis=1)
        partials["zeta", "cl_star"] = -deps * cd / cl ** 2
        partials["zeta", "cd_star"] = deps / cl
        target = np.real(target)
        partials["zeta", self._target] = -target / np.real(inputs[self._target])
        partials["zeta", "rho"] = target / np.real(inputs["rho"])
        partials["zeta", "v_axial"] = exponent * target / np.real(inputs["v_axial"])
        partials["zeta", "radius"] = 2.0 * target / np.real(inputs["radius"])

    def solve_linear(self, d_outputs, d_residuals, mode):
        if mode == "fwd":
            d_outputs["zeta"] = d_residuals["zeta"] / self._slope
        else:
            d_residuals["zeta"] = d_outputs["zeta"] / self._slope
