"""BEMOptimizationGroup: the full-BEM rotor energy-loss minimisation BILD is verified against (Sec. 5.1)."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.polar import Polar
from bild_mdo.bem.bem_group import BEMAnalysisGroup
from bild_mdo.bem.flow_states import ON_INVALID
from bild_mdo.bem.metrics import PERFORMANCE_OUTPUTS
from bild_mdo.bem.prandtl import LOSS_MODELS
from bild_mdo.optimization.parameterization import PARAMETERIZATIONS, ParameterizationComp
from bild_mdo.optimization.responses import NormalizedResponsesComp
from bild_mdo.utils.options import declare_size_options, sizes


class BEMOptimizationGroup(om.Group):
    """Blade parameterisation, BEM analysis and the normalised objective and thrust constraint.

    The numerical counterpart of paper Problem 1 (Eq. 10), as solved in
    Sec. 5.1: minimise the rate of energy loss ``E = Omega Q - V_x T``
    (Eq. 12 integrated) over the chord and twist distributions subject to
    ``T = T*``.  Feed-forward on RunOnce:
    ``parameterization -> bem (BEMAnalysisGroup) -> responses``.

    Design variables are ``chord_ratio_cp`` (c/R) and ``twist_cp``; the
    objective is ``energy_loss_ratio`` and the equality constraint
    ``thrust_residual = 0`` (see :func:`bild_mdo.optimization.problem.build_optimization_problem`).

    Options
    -------
    num_nodes : int
        Number of designs / operating points (axis 0); 1 for one optimisation.
    num_radial : int
        Number of radial stations (axis 1).
    num_blades : int
        Number of blades B.
    polar : Polar
        Airfoil polar (not recorded).
    loss_model : {'tip_hub', 'tip', 'none'}
        Prandtl loss factor model of the BEM analysis.
    parameterization : {'stations', 'bspline'}
        Per-station design values or B-spline control points.
    num_cp : int
        Number of B-spline control points (``'bspline'`` only).
    order : int
        B-spline order (``'bspline'`` only).
    on_invalid : {'ignore', 'warn', 'raise'}
        What the BEM analysis does about stations in an invalid flow state
        (:mod:`bild_mdo.bem.flow_states`).  Default ``'ignore'``: an optimiser's
        trial points may pass through such states (a line search that
        overshoots, a scaling probe); a warning per model evaluation would
        flood the output and an error would end a run that recovers on its
        own.  The state at the optimum is checked instead
        (:attr:`~bild_mdo.optimization.run.OptimizationResult.invalid_stations`).
    warm_start : bool
        Start the inflow solve of each evaluation from the previous one's
        phi where its bracket still holds (``BEMAnalysisGroup``'s option;
        the same root to solver tolerance).  Default True: an optimiser
        evaluates nearby designs one after the other.

    Inputs
    ------
    chord_ratio_cp[nn, ncp] (-), twist_cp[nn, ncp] (rad)
        Design variables: chord / R and twist (per station or control points).
    v_axial[nn] (m/s), rpm[nn] (rpm), radius[nn] (m), hub_radius[nn] (m), altitude[nn] (m)
        Operating point, rotor size and altitude (ISA).
    thrust_target[nn] (N)
        Required thrust T*.
    energy_loss_ref[nn] (W)
        Reference energy loss that scales the objective.

    Outputs
    -------
    energy_loss_ratio[nn] (-), thrust_residual[nn] (-)
        Objective ``E / E_ref`` and constraint ``T / T* - 1``.
    chord[nn, nr] (m), twist[nn, nr] (rad)
        Blade geometry at the stations.
    bem.flow_state[nn, nr]
        Flow-state code of every station (:mod:`bild_mdo.bem.flow_states`).
    thrust, torque, power, ... [nn]
        Rotor performance, one output per entry of :data:`bild_mdo.bem.metrics.METRICS`
        (:class:`~bild_mdo.bem.performance.RotorPerformanceComp`); station
        quantities stay under ``bem.*``.
    """

    def initialize(self):
        declare_size_options(self.options)
        self.options.declare("num_blades", types=int, default=3, desc="number of blades B")
        self.options.declare("polar", types=Polar, recordable=False, desc="airfoil polar cl, cd (alpha, Re)")
        self.options.declare("loss_model", default="tip_hub", values=LOSS_MODELS,
                             desc="Prandtl loss factor of the BEM analysis")
        self.options.declare("parameterization", default="stations", values=PARAMETERIZATIONS,
                             desc="'stations': one design value per station; 'bspline': B-spline control points")
        self.options.declare("num_cp", types=int, default=10, desc="number of B-spline control points")
        self.options.declare("order", types=int, default=4, desc="B-spline order (degree + 1)")
        self.options.declare("on_invalid", default="ignore", values=ON_INVALID,
                             desc="invalid BEM flow states at a trial point: nothing (default), a warning or an error")
        self.options.declare("warm_start", types=bool, default=True,
                             desc="start each inflow solve from the previous evaluation's phi where its bracket holds")

    def setup(self):
        opts = self.options
        nn, nr = opts["num_nodes"], opts["num_radial"]
        parameterization = ParameterizationComp(**sizes(opts), parameterization=opts["parameterization"],
                                                num_cp=opts["num_cp"], order=opts["order"])
        self.add_subsystem("parameterization", parameterization,
                           promotes_inputs=["chord_ratio_cp", "twist_cp", "radius"],
                           promotes_outputs=["chord", "twist"])
        self.add_subsystem("bem",
                           BEMAnalysisGroup(**sizes(opts), num_blades=opts["num_blades"],
                                            polar=opts["polar"], loss_model=opts["loss_model"],
                                            on_invalid=opts["on_invalid"], warm_start=opts["warm_start"]),
                           promotes_inputs=["v_axial", "rpm", "radius", "hub_radius", "altitude", "chord", "twist"],
                           promotes_outputs=list(PERFORMANCE_OUTPUTS))
        self.add_subsystem("responses", NormalizedResponsesComp(num_nodes=nn),
                           promotes_inputs=["thrust", "energy_loss", "thrust_target", "energy_loss_ref"],
                           promotes_outputs=["energy_loss_ratio", "thrust_residual"])

        ncp = nr if opts["parameterization"] == "stations" else opts["num_cp"]
        self.set_input_defaults("chord_ratio_cp", val=np.full((nn, ncp), 0.1), units=None)
        self.set_input_defaults("twist_cp", val=np.full((nn, ncp), 0.3), units="rad")
        self.set_input_defaults("radius", val=np.ones(nn), units="m")
        self.set_input_defaults("thrust_target", val=np.ones(nn), units="N")
        self.set_input_defaults("energy_loss_ref", val=np.ones(nn), units="W")
