"""The full-BEM rotor optimisation BILD is verified against (paper Sec. 5.1): problem set-up.

:func:`build_optimization_problem` returns a set-up ``om.Problem`` around
:class:`~bild_mdo.optimization.bem_optimization_group.BEMOptimizationGroup`
with the design variables, objective, thrust constraint and driver;
:func:`set_optimization_case` loads one case (operating point, thrust target,
initial design) into such a problem, so that a problem set up once can
optimise many cases.  :func:`~bild_mdo.optimization.run.run_optimization`
runs it and :func:`~bild_mdo.optimization.run.optimize_rotor` does all of it.

Problem (paper Problem 1, Eq. 10, as solved numerically in Sec. 5.1)::

    minimise    E / E_ref                     (E = Omega Q - V_x T, Eq. 12)
    w.r.t.      c/R and twist at every station (or B-spline control points)
    subject to  T / T* - 1 = 0
                c/R in CHORD_RATIO_BOUNDS, twist in twist_bounds(...)

The bounds and the initial designs are explained in
:mod:`bild_mdo.optimization.initial_design`, the scaling in
:mod:`bild_mdo.optimization.scaling`.
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.text import polar_from
from bild_mdo.atmosphere import isa
from bild_mdo.bem.turbine_polar import TurbinePolar
from bild_mdo.optimization.bem_optimization_group import BEMOptimizationGroup
from bild_mdo.optimization.initial_design import (CHORD_RATIO_BOUNDS, INITIAL_DESIGNS, TWIST_LIMITS,
                                                  bild_initial_design, ideal_energy_loss, linear_initial_design,
                                                  twist_bounds)
from bild_mdo.optimization.ipopt_driver import IpoptDriver
from bild_mdo.optimization.parameterization import (PARAMETERIZATIONS, design_value_fractions, fit_design_values,
                                                    parameterization_matrix)
from bild_mdo.optimization.scaling import CHORD_RATIO_REF, SCALINGS, TWIST_REF
from bild_mdo.optimization.turbine import (ROTOR_TYPES, THRUST_SIGN, TURBINE_TWIST_LIMITS, ideal_turbine_energy_loss,
                                           turbine_bild_initial_design, turbine_linear_initial_design,
                                           turbine_twist_bounds)

#: The NLP optimisers of the BEM optimisation (and of ``bild-mdo verify --optimizer``).
OPTIMIZERS = ("slsqp", "ipopt", "snopt")

#: Default convergence tolerances (see :func:`build_optimization_problem`).
DEFAULT_TOL = {"slsqp": 1.0e-8, "ipopt": 1.0e-8, "snopt": 1.0e-8}
DEFAULT_MAXITER = {"slsqp": 300, "ipopt": 1000, "snopt": 1000}


def make_driver(optimizer, tol, maxiter, print_level=0):
    """The OpenMDAO driver of one optimiser, set up for the rotor problem.

    Parameters
    ----------
    optimizer : {'slsqp', 'ipopt', 'snopt'}
        See :func:`build_optimization_problem`.
    tol : float
        Convergence tolerance.
    maxiter : int
        Iteration limit.
    print_level : int
        0 is silent; larger values let the optimiser print.

    Returns
    -------
    openmdao.core.driver.Driver

    Raises
    ------
    ValueError
        For an unknown optimiser.
    ImportError
        If the optimiser's package is not installed.
    """
    if optimizer == "slsqp":
        return om.ScipyOptimizeDriver(optimizer="SLSQP", tol=tol, maxiter=maxiter, disp=print_level > 0)
    if optimizer == "ipopt":
        driver = IpoptDriver(tol=tol, maxiter=maxiter, print_level=min(int(print_level), 12), disp=print_level > 0)
        driver.opt_settings.update({
            # The start is a good design: a small barrier parameter and no push away from the bounds
            # keep Ipopt near it instead of re-centring in the box.
            "mu_strategy": "monotone",
            "mu_init": 1.0e-6,
            "bound_push": 1.0e-10,
            "bound_frac": 1.0e-10,
            "constr_viol_tol": min(float(tol), 1.0e-8),
            # The problem is scaled already (hessian_scaling, normalised responses).
            "nlp_scaling_method": "none",
        })
        return driver
    if optimizer == "snopt":
        try:
            import pyoptsparse  # noqa: F401
        except ImportError:
            raise ImportError("optimizer='snopt' needs pyOptSparse built with SNOPT (a commercial licence), which "
                              "is not importable here; use optimizer='slsqp' or 'ipopt'.") from None
        driver = om.pyOptSparseDriver(optimizer="SNOPT", print_results=print_level > 0)
        driver.opt_settings.update({"Major optimality tolerance": float(tol),
                                    "Major feasibility tolerance": float(tol),
                                    "Major iterations limit": int(maxiter)})
        if print_level == 0:
            driver.opt_settings.update({"Print file": "", "Summary file": ""})
        return driver
    raise ValueError(f"optimizer must be one of {OPTIMIZERS}, got {optimizer!r}")


def build_optimization_problem(v_axial=None, rpm=None, radius=None, hub_radius=None, thrust_target=None,
                               altitude=0.0, *, optimizer="slsqp", initial="bild", bild_chord=None,
                               bild_twist=None, reference_chord=None, parameterization="stations",
                               num_cp=10, order=4, num_radial=30, num_blades=3, polar="naca4412",
                               loss_model="tip_hub", scaling="hessian", tol=None, maxiter=None,
                               print_level=0, energy_loss_ref=None, approx_totals=None, rotor_type="propeller"):
    """Set up the BEM energy-loss minimisation of one rotor (paper Sec. 5.1) as an ``om.Problem``.

    Parameters
    ----------
    v_axial, rpm, radius, hub_radius, thrust_target, altitude : float, optional
        The case: axial speed (m/s, >= 0), rotational speed (rpm), tip and hub
        radius (m), required thrust T* (N) and altitude (m, ISA).  When
        ``v_axial`` is None the problem is only set up; load a case with
        :func:`set_optimization_case`.
    optimizer : {'slsqp', 'ipopt', 'snopt'}
        SciPy's SLSQP (always available), Ipopt through
        :class:`~bild_mdo.optimization.ipopt_driver.IpoptDriver` (needs cyipopt), or SNOPT
        through ``om.pyOptSparseDriver`` (needs pyOptSparse with SNOPT).
    initial : {'bild', 'linear'}
        Warm start from the BILD geometry (``bild_chord``, ``bild_twist``) or
        cold start from a linear root-to-tip guess
        (:func:`~bild_mdo.optimization.initial_design.linear_initial_design`).
    bild_chord, bild_twist : array_like, shape (num_radial,), optional
        BILD geometry at the stations (m, rad) for ``initial='bild'``; without them the
        paper's BILD designs the case's blade for ``thrust_target``
        (:func:`~bild_mdo.optimization.initial_design.bild_initial_design`).
    reference_chord : float, optional
        Chord scale of the linear guess (m); default 0.1 R.
    parameterization : {'stations', 'bspline'}
        One design value per station (the paper's 30 + 30) or ``num_cp``
        B-spline control points of order ``order`` per distribution (the
        authors' scripts: 10 + 10, order 4).
    num_cp, order : int
        B-spline control points and order.
    num_radial, num_blades : int
        Stations and blades.
    polar : Polar or str
        Airfoil polar, or airfoil text as :func:`~bild_mdo.airfoil.text.sweep_polar` reads it (a built-in
        name such as ``'naca4412'``, a NACA designation, polar files, ``'naca4412@re=2e6'``, a spanwise set).
    loss_model : {'tip_hub', 'tip', 'none'}
        Prandtl loss model of the BEM analysis.
    scaling : {'hessian', 'fixed'}
        Design-variable scaling from the curvature of the Lagrangian at the
        initial design, recomputed every run
        (:func:`~bild_mdo.optimization.scaling.hessian_scaling`), or the fixed
        references :data:`~bild_mdo.optimization.scaling.CHORD_RATIO_REF` and
        :data:`~bild_mdo.optimization.scaling.TWIST_REF`.
    tol : float, optional
        Optimiser tolerance (default :data:`DEFAULT_TOL`): for SLSQP the
        change of ``E/E_ref`` over the last step and the constraint violation;
        for Ipopt and SNOPT the scaled optimality and feasibility errors.
    maxiter : int, optional
        Iteration limit (default :data:`DEFAULT_MAXITER`).
    print_level : int
        0 is silent; larger values let the optimiser print.
    energy_loss_ref : float, optional
        Objective reference (W); default
        :func:`~bild_mdo.optimization.initial_design.ideal_energy_loss`.
    approx_totals : {None, 'fd'}
        None (default): exact totals from the analytic partials.  ``'fd'``:
        forward finite differences of the whole model
        (``model.approx_totals(method='fd')``), what a user without analytic
        partials would run; for speed comparisons (``benchmarks/optimization_speed.py``).
    rotor_type : {'propeller', 'turbine'}
        'turbine': a wind turbine, the most power for the thrust ``thrust_target`` (downwind, > 0) in the wind
        ``v_axial``, with ``polar`` the airfoil's own polar (:mod:`bild_mdo.optimization.turbine`).

    Returns
    -------
    om.Problem
        Set up with ``reports=False``; the group is ``prob.model.rotor`` and
        its variables are promoted to the model.

    Raises
    ------
    ValueError
        On unknown option values or inconsistent case inputs.
    ImportError
        If the chosen optimiser's package is not installed.
    """
    if optimizer not in OPTIMIZERS:
        raise ValueError(f"optimizer must be one of {OPTIMIZERS}, got {optimizer!r}")
    if parameterization not in PARAMETERIZATIONS:
        raise ValueError(f"parameterization must be one of {PARAMETERIZATIONS}, got {parameterization!r}")
    if scaling not in SCALINGS:
        raise ValueError(f"scaling must be one of {SCALINGS}, got {scaling!r}")
    if approx_totals not in (None, "fd"):
        raise ValueError(f"approx_totals must be None (analytic) or 'fd', got {approx_totals!r}")
    if rotor_type not in ROTOR_TYPES:
        raise ValueError(f"rotor_type must be one of {ROTOR_TYPES}, got {rotor_type!r}")
    tol = DEFAULT_TOL[optimizer] if tol is None else float(tol)
    maxiter = DEFAULT_MAXITER[optimizer] if maxiter is None else int(maxiter)
    driver = make_driver(optimizer, tol, maxiter, print_level)

    prob = om.Problem(reports=False)
    polar = polar_from(polar)
    polar = TurbinePolar(polar) if rotor_type == "turbine" else polar
    group = BEMOptimizationGroup(num_nodes=1, num_radial=num_radial, num_blades=num_blades,
                                 polar=polar, loss_model=loss_model,
                                 parameterization=parameterization, num_cp=num_cp, order=order)
    prob.model.add_subsystem("rotor", group, promotes=["*"])
    prob.model.add_design_var("chord_ratio_cp", lower=CHORD_RATIO_BOUNDS[0], upper=CHORD_RATIO_BOUNDS[1],
                              ref=CHORD_RATIO_REF)
    limits = TURBINE_TWIST_LIMITS if rotor_type == "turbine" else TWIST_LIMITS
    prob.model.add_design_var("twist_cp", lower=limits[0], upper=limits[1], ref=TWIST_REF)
    prob.model.add_objective("energy_loss_ratio")
    prob.model.add_constraint("thrust_residual", equals=0.0)
    prob.driver = driver
    if approx_totals is not None:
        prob.model.approx_totals(method=approx_totals)
    # Two responses and 20-60 design variables: reverse mode needs two linear solves per gradient.
    prob.setup(mode="rev")
    prob.final_setup()
    prob._bild_optimization = {
        "optimizer": optimizer, "parameterization": parameterization, "scaling": scaling,
        "num_radial": num_radial, "num_blades": num_blades, "order": order,
        "matrix": parameterization_matrix(parameterization, num_radial, num_cp, order),
        "fractions": design_value_fractions(parameterization, num_radial, num_cp, order),
        "twist_bounds": limits,
        # What a batched twin of this problem needs (bild_mdo.optimization.lockstep) and the SLSQP engine reads.
        "num_cp": num_cp, "polar": polar, "loss_model": loss_model, "tol": tol, "maxiter": maxiter,
        "approx_totals": approx_totals, "rotor_type": rotor_type,
    }
    if v_axial is not None:
        set_optimization_case(prob, v_axial, rpm, radius, hub_radius, thrust_target, altitude, initial=initial,
                              bild_chord=bild_chord, bild_twist=bild_twist, reference_chord=reference_chord,
                              energy_loss_ref=energy_loss_ref)
    return prob


def check_case(v_axial, rpm, radius, hub_radius, thrust_target, altitude):
    values = dict(v_axial=v_axial, rpm=rpm, radius=radius, hub_radius=hub_radius, thrust_target=thrust_target,
                  altitude=altitude)
    for name, value in values.items():
        if value is None or not np.isfinite(value):
            raise ValueError(f"{name} must be a finite number, got {value!r}")
    if v_axial < 0.0:
        raise ValueError(f"v_axial must be >= 0 (axial inflow; 0 is hover), got {v_axial}")
    if rpm <= 0.0 or thrust_target <= 0.0:
        raise ValueError(f"rpm and thrust_target must be positive, got {rpm} and {thrust_target}")
    if not 0.0 <= hub_radius < radius:
        raise ValueError(f"need 0 <= hub_radius < radius, got {hub_radius} and {radius}")


def set_optimization_case(prob, v_axial, rpm, radius, hub_radius, thrust_target, altitude=0.0, *,
                          initial="bild", bild_chord=None, bild_twist=None, reference_chord=None,
                          energy_loss_ref=None):
    """Load one case and its initial design into a problem from :func:`build_optimization_problem`.

    Parameters
    ----------
    prob : om.Problem
        From :func:`build_optimization_problem`.
    v_axial, rpm, radius, hub_radius, thrust_target, altitude, initial, bild_chord, bild_twist,
    reference_chord, energy_loss_ref
        See :func:`build_optimization_problem`.

    Raises
    ------
    ValueError
        On inconsistent inputs or a missing BILD geometry for ``initial='bild'``.
    """
    meta = getattr(prob, "_bild_optimization", None)
    if meta is None:
        raise ValueError("prob was not made by build_optimization_problem")
    try:
        v_axial, rpm, radius, hub_radius, thrust_target, altitude = (
            float(v) for v in (v_axial, rpm, radius, hub_radius, thrust_target, altitude))
    except TypeError:
        raise ValueError("v_axial, rpm, radius, hub_radius, thrust_target and altitude must be numbers") from None
    check_case(v_axial, rpm, radius, hub_radius, thrust_target, altitude)
    values = case_design_values(meta, v_axial, rpm, radius, hub_radius, thrust_target, altitude, initial=initial,
                                bild_chord=bild_chord, bild_twist=bild_twist, reference_chord=reference_chord,
                                energy_loss_ref=energy_loss_ref)
    meta["twist_bounds"] = values["twist_bounds"]
    chord_cp, twist_cp, energy_loss_ref = values["chord_ratio_cp"], values["twist_cp"], values["energy_loss_ref"]
    prob.set_val("v_axial", v_axial, units="m/s")
    prob.set_val("rpm", rpm, units="rpm")
    prob.set_val("radius", radius, units="m")
    prob.set_val("hub_radius", hub_radius, units="m")
    prob.set_val("altitude", altitude, units="m")
    prob.set_val("thrust_target", THRUST_SIGN[meta.get("rotor_type", "propeller")] * thrust_target, units="N")
    prob.set_val("energy_loss_ref", energy_loss_ref, units="W")
    prob.set_val("chord_ratio_cp", chord_cp[None, :])
    prob.set_val("twist_cp", twist_cp[None, :], units="rad")


def case_design_values(meta, v_axial, rpm, radius, hub_radius, thrust_target, altitude, *, initial="bild",
                       bild_chord=None, bild_twist=None, reference_chord=None, energy_loss_ref=None):
    """Initial design values, twist bounds and objective reference of one (checked) case.

    Parameters
    ----------
    meta : dict
        ``prob._bild_optimization`` of a problem from :func:`build_optimization_problem`.
    v_axial, rpm, radius, hub_radius, thrust_target, altitude : float
        The case, already checked.
    initial, bild_chord, bild_twist, reference_chord, energy_loss_ref
        See :func:`build_optimization_problem`.

    Returns
    -------
    dict
        ``chord_ratio_cp``, ``twist_cp`` (ndarray, shape (ncp,); within the
        bounds), ``twist_bounds`` (lower, upper arrays, rad) and
        ``energy_loss_ref`` (W).
    """
    nr = meta["num_radial"]
    rho = float(isa(altitude).rho)
    turbine = meta.get("rotor_type") == "turbine"
    if initial == "bild":
        if (bild_chord is None) != (bild_twist is None):
            raise ValueError("initial='bild' takes bild_chord and bild_twist together (the BILD geometry at the "
                             "stations), or neither (then the paper's BILD designs the case's blade)")
        if bild_chord is None and turbine:
            bild_chord, bild_twist = turbine_bild_initial_design(
                v_axial, rpm, radius, hub_radius, thrust_target, altitude, nr, meta["num_blades"], meta["polar"].base,
                meta["loss_model"])
        elif bild_chord is None:
            bild_chord, bild_twist = bild_initial_design(v_axial, rpm, radius, hub_radius, thrust_target, altitude,
                                                         nr, meta["num_blades"], meta["polar"], meta["loss_model"])
        chord0 = np.asarray(bild_chord, dtype=float).ravel()
        twist0 = np.asarray(bild_twist, dtype=float).ravel()
    elif initial == "linear" and turbine:
        chord0, twist0 = turbine_linear_initial_design(v_axial, rpm, radius, hub_radius, thrust_target, rho, nr,
                                                       meta["num_blades"], reference_chord=reference_chord)
    elif initial == "linear":
        chord0, twist0 = linear_initial_design(v_axial, rpm, radius, hub_radius, thrust_target, rho, nr,
                                               reference_chord=reference_chord)
    else:
        raise ValueError(f"initial must be one of {INITIAL_DESIGNS}, got {initial!r}")
    if chord0.shape != (nr,) or twist0.shape != (nr,):
        raise ValueError(f"initial chord and twist must have {nr} stations, got {chord0.shape} and {twist0.shape}")
    if not (np.all(np.isfinite(chord0)) and np.all(np.isfinite(twist0))):
        raise ValueError("initial chord and twist must be finite")
    lower, upper = (turbine_twist_bounds if turbine else twist_bounds)(v_axial, rpm, radius, hub_radius,
                                                                       meta["fractions"])
    matrix = meta["matrix"]
    if energy_loss_ref is None:
        energy_loss_ref = (ideal_turbine_energy_loss if turbine else ideal_energy_loss)(
            thrust_target, v_axial, radius, hub_radius, rho)
    return {"chord_ratio_cp": np.clip(fit_design_values(matrix, chord0 / radius), *CHORD_RATIO_BOUNDS),
            "twist_cp": np.clip(fit_design_values(matrix, twist0), lower, upper),
            "twist_bounds": (lower, upper), "energy_loss_ref": float(energy_loss_ref)}
