"""Maximum-L/D operating point of the airfoil at the reference station's Reynolds number."""
import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.builtin import resolve_polar
from bild_mdo.utils.options import add_inputs, add_outputs, declare_size_options
from bild_mdo.utils.sparsity import node_wrt_node


def default_polar():
    """The built-in NACA 4412 polar, BILD's default airfoil (paper Sec. 5.2)."""
    return resolve_polar("naca4412")


class ReferenceAirfoilComp(om.ExplicitComponent):
    """Angle of attack, lift and drag coefficients of maximum lift-to-drag ratio.

    BILD operates every blade element at the airfoil's maximum ``C_l/C_d``
    (paper Assumption 2).  The point depends on the Reynolds number, which
    this component evaluates at the reference station with the *local speed
    without induction*::

        Re_ref = rho * W0 * c_ref / mu,   W0 = sqrt(V_x**2 + (Omega r_ref)**2).

    Why ``W0`` and not the inflow speed ``W`` with induction: ``W`` follows
    from the reference-station BEM solve, which itself needs ``C_l*, C_d*``;
    using ``W`` would close a loop and need a coupled solver around two
    components.  ``W0`` keeps the BILD chain feed-forward (RunOnce), uses the
    same convention as the BEM analysis of this package, and changes
    ``Re_ref`` by a few percent only, to which the max-L/D point of a smooth
    polar is weakly sensitive.

    Options
    -------
    num_nodes : int
        Number of designs / operating points.
    polar : Polar or None
        Airfoil polar (``bild_mdo.airfoil.polar.Polar``); ``None`` selects the
        built-in NACA 4412.

    Inputs
    ------
    v_axial[nn] (m/s)
        Axial free-stream velocity V_x.
    v_theta_ref[nn] (m/s)
        Rotational speed at the reference station, ``Omega r_ref``.
    ref_chord[nn] (m)
        Chord prescribed at the reference station.
    rho[nn] (kg/m**3)
        Air density.
    mu[nn] (Pa*s)
        Dynamic viscosity of air.

    Outputs
    -------
    reynolds_ref[nn] (-)
        Reynolds number of the reference station.
    alpha_star[nn] (rad)
        Angle of attack of maximum lift-to-drag ratio.
    cl_star[nn] (-)
        Lift coefficient at ``alpha_star``.
    cd_star[nn] (-)
        Drag coefficient at ``alpha_star``.
    """

    def initialize(self):
        declare_size_options(self.options, radial=False)
        self.options.declare("polar", default=None, allow_none=True, recordable=False,
                             desc="airfoil Polar object; None selects the built-in NACA 4412")

    def setup(self):
        nn = self.options["num_nodes"]
        polar = self.options["polar"]
        self._polar = default_polar() if polar is None else polar
        add_inputs(self, ("v_axial", "v_theta_ref", "ref_chord", "rho", "mu"))
        self.add_output("reynolds_ref", val=np.full(nn, 3e5), units=None,
                        desc="chord Reynolds number at the reference station (speed without induction)")
        add_outputs(self, ("alpha_star", "cl_star", "cd_star"))

    def setup_partials(self):
        rows, cols = node_wrt_node(self.options["num_nodes"])
        wrt = ["v_axial", "v_theta_ref", "ref_chord", "rho", "mu"]
        for name in ("reynolds_ref", "alpha_star", "cl_star", "cd_star"):
            self.declare_partials(name, wrt, rows=rows, cols=cols)

    def _reynolds(self, inputs):
        for name in ("v_axial", "v_theta_ref", "ref_chord", "rho", "mu"):
            value = np.real(inputs[name])
            bad = ~np.isfinite(value)
            if np.any(bad):
                node = int(np.flatnonzero(bad)[0])
                raise om.AnalysisError(f"{self.msginfo}: {name} must be finite for the reference Reynolds "
                                       f"number, got {float(value[node])!r} at node {node}")
        v_x = inputs["v_axial"]
        v_t = inputs["v_theta_ref"]
        speed = np.sqrt(v_x ** 2 + v_t ** 2)
        if np.any(~(np.real(speed) > 0.0)):
            raise om.AnalysisError(
                f"{self.msginfo}: the reference station has no inflow (v_axial = 0 and rpm = 0); "
                "give a positive rotor speed")
        for name in ("ref_chord", "rho", "mu"):
            if np.any(~(np.real(inputs[name]) > 0.0)):
                raise om.AnalysisError(f"{self.msginfo}: {name} must be positive, got {np.real(inputs[name])}")
        return speed, inputs["rho"] * speed * inputs["ref_chord"] / inputs["mu"]

    def _max_lift_to_drag(self, reynolds):
        try:
            return self._polar.max_lift_to_drag(reynolds)
        except ValueError as err:
            raise om.AnalysisError(f"{self.msginfo}: no maximum-L/D point at the reference "
                                   f"Reynolds number: {err}") from err

    def compute(self, inputs, outputs):
        _, reynolds = self._reynolds(inputs)
        point = self._max_lift_to_drag(reynolds)
        outputs["reynolds_ref"] = reynolds
        outputs["alpha_star"] = point.alpha
        outputs["cl_star"] = point.cl
        outputs["cd_star"] = point.cd

    def compute_partials(self, inputs, partials):
        speed, reynolds = self._reynolds(inputs)
        point = self._max_lift_to_drag(reynolds)
        dre = {
            "v_axial": reynolds * inputs["v_axial"] / speed ** 2,
            "v_theta_ref": reynolds * inputs["v_theta_ref"] / speed ** 2,
            "ref_chord": reynolds / inputs["ref_chord"],
            "rho": reynolds / inputs["rho"],
            "mu": -reynolds / inputs["mu"],
        }
        for name, d in dre.items():
            partials["reynolds_ref", name] = d
            partials["alpha_star", name] = point.dalpha_dre * d
            partials["cl_star", name] = point.dcl_dre * d
            partials["cd_star", name] = point.dcd_dre * d
