"""The full-BEM rotor optimisation BILD is verified against (paper Sec. 5.1).

:func:`build_optimization_problem` returns a set-up ``om.Problem`` around
:class:`~bild_mdo.optimization.bem_optimization_group.BEMOptimizationGroup`
with the design variables, objective, thrust constraint and driver;
:func:`set_optimization_case` loads one case (operating point, thrust target,
initial design) into such a problem, so that a problem set up once can
optimise many cases; :func:`run_optimization` runs it and
:func:`optimize_rotor` does all of it.

Problem (paper Problem 1, Eq. 10, as solved numerically in Sec. 5.1)::

    minimise    E / E_ref                     (E = Omega Q - V_x T, Eq. 12)
    w.r.t.      c/R and twist at every station (or B-spline control points)
    subject to  T / T* - 1 = 0
                c/R in CHORD_RATIO_BOUNDS, twist in twist_bounds(...)

Bounds.  They keep the optimiser's trial points where blade elements make
sense; BILD's designs of the whole Sec. 5.1 sweep lie well inside them.

* ``c/R`` in [1e-4, 1]: the paper notes that without a lower bound the root
  chord of forward-flight designs goes to zero (Sec. 5.2.1, Fig. 11).  The
  lower bound only excludes zero and negative chords, where the solidity and
  the Reynolds number vanish; it is 40 times below BILD's smallest chord
  (4e-3 R, root, J = 3).  It is active at the optimum only at the first one
  or two stations of forward-flight rotors with small c_ref, where the
  optimal chord tends to zero and the station carries almost no load.  The
  upper bound is 1.6 times BILD's largest chord (0.63 R, hover root,
  R = 0.5 m, c_ref = 0.22 m).
* twist within [phi_0 - 15 deg, phi_0 + 60 deg] and [0, 90] deg, with
  ``phi_0 = atan(V_x / (Omega r))`` the inflow angle without induction:
  BILD's twist exceeds ``phi_0`` by 6 to 40 deg over the sweep.  Fixed
  bounds [0, 90] deg let SLSQP try a hovering root section at 90 deg, where
  the BEM residual has no root.

Scaling.  The objective is divided by ``E_ref``, the ideal induced loss of an
actuator disk producing ``T*``, and the constraint is relative, so both are
of order one for every case.  The design variables are scaled by the
curvature of the Lagrangian at the initial design (:func:`hessian_scaling`),
which cuts SLSQP's iterations five- to tenfold against fixed references.
"""
from __future__ import annotations

import contextlib
import dataclasses
import time

import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.builtin import get_polar
from bild_mdo.airfoil.polar import Polar
from bild_mdo.atmosphere import isa
from bild_mdo.bem.performance import PERFORMANCE_OUTPUTS
from bild_mdo.optimization.bem_optimization_group import BEMOptimizationGroup
from bild_mdo.optimization.parameterization import (PARAMETERIZATIONS, design_value_fractions, fit_design_values,
                                                    parameterization_matrix, station_fractions)

OPTIMIZERS = ("slsqp", "ipopt", "snopt")
INITIAL_DESIGNS = ("bild", "linear")
SCALINGS = ("hessian", "fixed")

#: Bounds on the chord design values, c/R (see the module docstring).
CHORD_RATIO_BOUNDS = (1.0e-4, 1.0)
#: Twist bounds relative to the inflow angle without induction (rad), and absolute (rad).
TWIST_MARGINS = (np.radians(-15.0), np.radians(60.0))
TWIST_LIMITS = (0.0, 0.5 * np.pi)

#: Fixed design-variable references of ``scaling='fixed'`` (c/R, rad).
CHORD_RATIO_REF = 0.1
TWIST_REF = 1.0

#: Default convergence tolerances (see :func:`build_optimization_problem`).
DEFAULT_TOL = {"slsqp": 1.0e-8, "ipopt": 1.0e-8, "snopt": 1.0e-8}
DEFAULT_MAXITER = {"slsqp": 300, "ipopt": 1000, "snopt": 1000}

#: Relative thrust-constraint violation above which a run counts as not converged.
THRUST_TOLERANCE = 1.0e-6

#: Performance quantities reported by :func:`run_optimization`.
RESULT_QUANTITIES = tuple(PERFORMANCE_OUTPUTS)

_RPM_TO_RAD_S = np.pi / 30.0
_BLAS_THREADS = []


def _single_threaded_blas():
    """Context limiting BLAS to one thread, when threadpoolctl is installed.

    SciPy's SLSQP calls BLAS on small dense matrices; OpenBLAS's extra threads
    then busy-wait and double the CPU time of every optimisation, which slows
    a sweep that already runs one process per core.
    """
    if not _BLAS_THREADS:
        try:
            from threadpoolctl import ThreadpoolController
        except ImportError:
            _BLAS_THREADS.append(None)
        else:
            _BLAS_THREADS.append(ThreadpoolController())
    controller = _BLAS_THREADS[0]
    if controller is None:
        return contextlib.nullcontext()
    return controller.limit(limits=1, user_api="blas")


def _resolve_polar(polar):
    if isinstance(polar, Polar):
        return polar
    if isinstance(polar, str):
        return get_polar(polar)
    raise TypeError(f"polar must be a Polar or the name of a built-in airfoil, got {type(polar).__name__}")


def _make_driver(optimizer, tol, maxiter, print_level):
    if optimizer == "slsqp":
        return om.ScipyOptimizeDriver(optimizer="SLSQP", tol=tol, maxiter=maxiter, disp=print_level > 0)
    if optimizer == "ipopt":
        from bild_mdo.drivers.ipopt_driver import IpoptDriver

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
                               print_level=0, energy_loss_ref=None):
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
        :class:`~bild_mdo.drivers.IpoptDriver` (needs cyipopt), or SNOPT
        through ``om.pyOptSparseDriver`` (needs pyOptSparse with SNOPT).
    initial : {'bild', 'linear'}
        Warm start from the BILD geometry (``bild_chord``, ``bild_twist``) or
        cold start from a linear root-to-tip guess (:func:`linear_initial_design`).
    bild_chord, bild_twist : array_like, shape (num_radial,), optional
        BILD geometry at the stations (m, rad); required for ``initial='bild'``.
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
        Airfoil polar or the name of a built-in one (``'naca4412'``).
    loss_model : {'tip_hub', 'tip', 'none'}
        Prandtl loss model of the BEM analysis.
    scaling : {'hessian', 'fixed'}
        Design-variable scaling from the curvature of the Lagrangian at the
        initial design, recomputed every run (:func:`hessian_scaling`), or the
        fixed references :data:`CHORD_RATIO_REF` and :data:`TWIST_REF`.
    tol : float, optional
        Optimiser tolerance (default :data:`DEFAULT_TOL`): for SLSQP the
        change of ``E/E_ref`` over the last step and the constraint violation;
        for Ipopt and SNOPT the scaled optimality and feasibility errors.
    maxiter : int, optional
        Iteration limit (default :data:`DEFAULT_MAXITER`).
    print_level : int
        0 is silent; larger values let the optimiser print.
    energy_loss_ref : float, optional
        Objective reference (W); default :func:`ideal_energy_loss`.

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
    tol = DEFAULT_TOL[optimizer] if tol is None else float(tol)
    maxiter = DEFAULT_MAXITER[optimizer] if maxiter is None else int(maxiter)
    driver = _make_driver(optimizer, tol, maxiter, print_level)

    prob = om.Problem(reports=False)
    group = BEMOptimizationGroup(num_nodes=1, num_radial=num_radial, num_blades=num_blades,
                                 polar=_resolve_polar(polar), loss_model=loss_model,
                                 parameterization=parameterization, num_cp=num_cp, order=order)
    prob.model.add_subsystem("rotor", group, promotes=["*"])
    prob.model.add_design_var("chord_ratio_cp", lower=CHORD_RATIO_BOUNDS[0], upper=CHORD_RATIO_BOUNDS[1],
                              ref=CHORD_RATIO_REF)
    prob.model.add_design_var("twist_cp", lower=TWIST_LIMITS[0], upper=TWIST_LIMITS[1], ref=TWIST_REF)
    prob.model.add_objective("energy_loss_ratio")
    prob.model.add_constraint("thrust_residual", equals=0.0)
    prob.driver = driver
    # Two responses and 20-60 design variables: reverse mode needs two linear solves per gradient.
    prob.setup(mode="rev")
    prob.final_setup()
    prob._bild_optimization = {
        "optimizer": optimizer, "parameterization": parameterization, "scaling": scaling,
        "num_radial": num_radial, "num_blades": num_blades, "order": order,
        "matrix": parameterization_matrix(parameterization, num_radial, num_cp, order),
        "fractions": design_value_fractions(parameterization, num_radial, num_cp, order),
        "twist_bounds": TWIST_LIMITS,
    }
    if v_axial is not None:
        set_optimization_case(prob, v_axial, rpm, radius, hub_radius, thrust_target, altitude, initial=initial,
                              bild_chord=bild_chord, bild_twist=bild_twist, reference_chord=reference_chord,
                              energy_loss_ref=energy_loss_ref)
    return prob


def ideal_energy_loss(thrust, v_axial, radius, hub_radius, rho):
    """Ideal induced energy loss of an actuator disk (momentum theory): the objective reference.

    ``T = 2 rho A (V_x + w) w`` on the annulus ``A = pi (R^2 - r_hub^2)``
    gives the induced velocity ``w``; the loss is ``E = T w``.

    Parameters
    ----------
    thrust, v_axial, radius, hub_radius, rho : float
        N, m/s, m, m, kg/m^3.

    Returns
    -------
    float
        Rate of energy loss (W).
    """
    area = np.pi * (radius**2 - hub_radius**2)
    w = -0.5 * v_axial + np.sqrt(0.25 * v_axial**2 + thrust / (2.0 * rho * area))
    return float(thrust * w)


def twist_bounds(v_axial, rpm, radius, hub_radius, fractions):
    """Per-design-value twist bounds around the inflow angle without induction.

    Parameters
    ----------
    v_axial, rpm, radius, hub_radius : float
        m/s, rpm, m, m.
    fractions : array_like
        Normalised span positions of the design values
        (:func:`~bild_mdo.optimization.parameterization.design_value_fractions`).

    Returns
    -------
    lower, upper : ndarray
        Bounds (rad): ``phi_0 + TWIST_MARGINS`` clipped to ``TWIST_LIMITS``.
    """
    radii = hub_radius + np.asarray(fractions) * (radius - hub_radius)
    phi0 = np.arctan2(v_axial, rpm * _RPM_TO_RAD_S * radii)
    lower = np.clip(phi0 + TWIST_MARGINS[0], *TWIST_LIMITS)
    upper = np.clip(phi0 + TWIST_MARGINS[1], *TWIST_LIMITS)
    return lower, upper


def linear_initial_design(v_axial, rpm, radius, hub_radius, thrust_target, rho, num_radial,
                          reference_chord=None, alpha_design=np.radians(5.0)):
    """Cold-start geometry: chord and twist linear from root to tip.

    As in the authors' optimisation scripts, the initial chord and twist are
    straight lines from root to tip.  Their end values come from the case:
    the chord falls from ``1.5 c_ref`` at the root to ``0.5 c_ref`` at the
    tip, and the twist is ``alpha_design`` plus the inflow angle
    ``atan((V_x + w) / (Omega r))`` of an actuator disk producing ``T*``
    (momentum theory) at the first and the last station.

    Parameters
    ----------
    v_axial, rpm, radius, hub_radius, thrust_target, rho : float
        Case inputs (m/s, rpm, m, m, N, kg/m^3).
    num_radial : int
        Number of stations.
    reference_chord : float, optional
        Chord scale c_ref (m); default 0.1 R.
    alpha_design : float
        Angle of attack added to the inflow angle (rad).

    Returns
    -------
    chord, twist : ndarray, shape (num_radial,)
        m and rad.
    """
    c_ref = 0.1 * radius if reference_chord is None else float(reference_chord)
    x = station_fractions(num_radial)
    radii = hub_radius + x * (radius - hub_radius)
    area = np.pi * (radius**2 - hub_radius**2)
    w = -0.5 * v_axial + np.sqrt(0.25 * v_axial**2 + thrust_target / (2.0 * rho * area))
    ends = np.arctan((v_axial + w) / (rpm * _RPM_TO_RAD_S * radii[[0, -1]])) + alpha_design
    chord = c_ref * (1.5 - x)
    twist = ends[0] + (ends[1] - ends[0]) * (radii - radii[0]) / (radii[-1] - radii[0])
    return chord, twist


def _check_case(v_axial, rpm, radius, hub_radius, thrust_target, altitude):
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
    _check_case(v_axial, rpm, radius, hub_radius, thrust_target, altitude)
    nr = meta["num_radial"]
    rho = float(isa(altitude).rho)
    if initial == "bild":
        if bild_chord is None or bild_twist is None:
            raise ValueError("initial='bild' needs bild_chord and bild_twist (the BILD geometry at the stations)")
        chord0 = np.asarray(bild_chord, dtype=float).ravel()
        twist0 = np.asarray(bild_twist, dtype=float).ravel()
    elif initial == "linear":
        chord0, twist0 = linear_initial_design(v_axial, rpm, radius, hub_radius, thrust_target, rho, nr,
                                               reference_chord=reference_chord)
    else:
        raise ValueError(f"initial must be one of {INITIAL_DESIGNS}, got {initial!r}")
    if chord0.shape != (nr,) or twist0.shape != (nr,):
        raise ValueError(f"initial chord and twist must have {nr} stations, got {chord0.shape} and {twist0.shape}")
    if not (np.all(np.isfinite(chord0)) and np.all(np.isfinite(twist0))):
        raise ValueError("initial chord and twist must be finite")

    lower, upper = twist_bounds(v_axial, rpm, radius, hub_radius, meta["fractions"])
    meta["twist_bounds"] = (lower, upper)
    matrix = meta["matrix"]
    chord_cp = np.clip(fit_design_values(matrix, chord0 / radius), *CHORD_RATIO_BOUNDS)
    twist_cp = np.clip(fit_design_values(matrix, twist0), lower, upper)
    if energy_loss_ref is None:
        energy_loss_ref = ideal_energy_loss(thrust_target, v_axial, radius, hub_radius, rho)

    prob.set_val("v_axial", v_axial, units="m/s")
    prob.set_val("rpm", rpm, units="rpm")
    prob.set_val("radius", radius, units="m")
    prob.set_val("hub_radius", hub_radius, units="m")
    prob.set_val("altitude", altitude, units="m")
    prob.set_val("thrust_target", thrust_target, units="N")
    prob.set_val("energy_loss_ref", energy_loss_ref, units="W")
    prob.set_val("chord_ratio_cp", chord_cp[None, :])
    prob.set_val("twist_cp", twist_cp[None, :], units="rad")


def _totals(prob, x_chord, x_twist):
    """Objective and constraint gradients (model units) at the given design values."""
    prob.set_val("chord_ratio_cp", x_chord[None, :])
    prob.set_val("twist_cp", x_twist[None, :], units="rad")
    prob.run_model()
    jac = prob.compute_totals(of=["energy_loss_ratio", "thrust_residual"], wrt=["chord_ratio_cp", "twist_cp"],
                              return_format="array", driver_scaling=False)
    return jac[0], jac[1]


def lagrangian_hessian_diagonal(prob, step=1.0e-6):
    """Diagonal of the Hessian of the Lagrangian at the current design, by forward differences.

    The Lagrangian is ``E/E_ref + lambda (T/T* - 1)`` with ``lambda`` the
    least-squares multiplier ``-(g_E . g_T) / (g_T . g_T)`` of the exact
    gradients at the current design.

    Blade elements interact only through the thrust constraint (every annulus
    is an independent BEM solve), so ``E`` and ``T`` are sums of per-station
    terms and their Hessians in the station values are block diagonal: one
    perturbation of all chords and one of all twists give every diagonal
    entry.  B-spline control points couple ``order`` neighbours, so they are
    perturbed in ``order`` interleaved groups per distribution.  That costs
    3 gradients for ``'stations'`` and ``2 order + 1`` for ``'bspline'``.

    Parameters
    ----------
    prob : om.Problem
        From :func:`build_optimization_problem`, with a case loaded; its
        design values are left unchanged.
    step : float
        Forward-difference step of the design values (model units).

    Returns
    -------
    diagonal : ndarray, shape (2 ncp,)
        Chord entries (per (c/R)^2), then twist entries (per rad^2).
    multiplier : float
        ``lambda``.
    """
    meta = prob._bild_optimization
    x_c = prob.get_val("chord_ratio_cp")[0].copy()
    x_t = prob.get_val("twist_cp", units="rad")[0].copy()
    n = x_c.size
    g_e, g_t = _totals(prob, x_c, x_t)
    lam = -float(g_e @ g_t) / float(g_t @ g_t)
    g0 = g_e + lam * g_t
    stride = 1 if meta["parameterization"] == "stations" else meta["order"]
    diag = np.zeros(2 * n)
    for which in range(2):
        for color in range(stride):
            dx = np.zeros(n)
            dx[color::stride] = step
            if which == 0:
                g_e1, g_t1 = _totals(prob, x_c + dx, x_t)
            else:
                g_e1, g_t1 = _totals(prob, x_c, x_t + dx)
            idx = which * n + np.arange(color, n, stride)
            diag[idx] = ((g_e1 + lam * g_t1) - g0)[idx] / step
    prob.set_val("chord_ratio_cp", x_c[None, :])
    prob.set_val("twist_cp", x_t[None, :], units="rad")
    return diag, lam


def hessian_scaling(prob, step=1.0e-6, floor=1.0e-2):
    """Design-variable references from the curvature of the Lagrangian at the current design.

    Each design value ``x_i`` gets the reference ``1 / sqrt(|H_ii|)``
    (:func:`lagrangian_hessian_diagonal`), so that the quasi-Newton Hessian of
    SLSQP or Ipopt, which starts as the identity in scaled variables, starts
    close to the true one.  The curvatures of chord and twist from root to
    tip differ by orders of magnitude; with fixed references SLSQP needs
    several hundred iterations, with these about thirty from a BILD start.

    Parameters
    ----------
    prob : om.Problem
        From :func:`build_optimization_problem`, with a case loaded.
    step : float
        Forward-difference step of the design values (model units).
    floor : float
        Curvatures below ``floor`` times the median of their distribution are
        raised to it (flat or concave directions, e.g. near the tip).

    Returns
    -------
    ref_chord, ref_twist : ndarray
        The references (model units).
    """
    diag, _ = lagrangian_hessian_diagonal(prob, step)
    n = diag.size // 2
    refs = []
    for part in (np.abs(diag[:n]), np.abs(diag[n:])):
        refs.append(1.0 / np.sqrt(np.maximum(part, floor * np.median(part))))
    return refs[0], refs[1]


def trim_to_thrust(prob, tol=1.0e-12, max_iter=20):
    """Shift the loaded design's twist uniformly until the BEM thrust equals the target (collective pitch).

    Makes a design feasible without the optimiser, e.g. to evaluate the BILD
    geometry in the BEM model at exactly ``T*``: the energy loss of that
    design is an upper bound that the optimum must not exceed.  Newton's
    method on the pitch offset with the exact ``dT/dtwist``.

    Parameters
    ----------
    prob : om.Problem
        From :func:`build_optimization_problem`, with a case loaded; its twist
        design values are updated in place and the model is left run.
    tol : float
        Tolerance on ``|T/T* - 1|``.
    max_iter : int
        Newton iterations.

    Returns
    -------
    float
        The pitch offset (rad).

    Raises
    ------
    om.AnalysisError
        If the thrust target cannot be met within ``max_iter`` iterations.
    """
    x_c = prob.get_val("chord_ratio_cp")[0].copy()
    x_t = prob.get_val("twist_cp", units="rad")[0].copy()
    offset = 0.0
    for _ in range(max_iter):
        _, g_t = _totals(prob, x_c, x_t + offset)
        residual = float(prob.get_val("thrust_residual")[0])
        if abs(residual) <= tol:
            return offset
        # A uniform offset moves every twist design value, stations or B-spline control points alike.
        offset -= residual / float(np.sum(g_t[x_c.size:]))
    raise om.AnalysisError(f"trim_to_thrust: |T/T* - 1| = {abs(residual):.3e} after {max_iter} Newton steps")


def _apply_design_var_options(prob, ref_chord, ref_twist):
    lower, upper = prob._bild_optimization["twist_bounds"]
    prob.model.set_design_var_options("chord_ratio_cp", ref=ref_chord, lower=CHORD_RATIO_BOUNDS[0],
                                      upper=CHORD_RATIO_BOUNDS[1])
    prob.model.set_design_var_options("twist_cp", ref=ref_twist, lower=lower, upper=upper)
    # The driver copies design-variable metadata in final_setup.
    prob.final_setup()


@dataclasses.dataclass
class OptimizationResult:
    """Outcome of :func:`run_optimization` and :func:`optimize_rotor`.

    Attributes
    ----------
    converged : bool
        The optimiser reports success and ``|T/T* - 1| <= THRUST_TOLERANCE``.
    status : str
        The optimiser's exit message.
    iterations : int
        Major iterations of the optimiser.
    model_evaluations : int
        Model evaluations by the driver (OpenMDAO ``iter_count``).
    wall_time : float
        Time of the scaling step and the driver run (s), without set-up.
    setup_time : float
        Time to build and set up the problem (s); 0 when a problem was reused.
    chord, twist : ndarray, shape (nr,)
        Optimal geometry at the stations (m, rad).
    performance : dict
        Per-design BEM outputs at the optimum (float): ``thrust`` (N),
        ``torque`` (N m), ``power`` (W), ``efficiency``, ``figure_of_merit``,
        ``thrust_coefficient``, ``torque_coefficient``, ``power_coefficient``,
        ``energy_loss`` (W), ``solidity``, ``blade_loading``.
    thrust_error : float
        ``T/T* - 1`` at the optimum.
    optimizer : str
        Optimiser name.
    """

    converged: bool
    status: str
    iterations: int
    model_evaluations: int
    wall_time: float
    setup_time: float
    chord: np.ndarray
    twist: np.ndarray
    performance: dict
    thrust_error: float
    optimizer: str


def _driver_outcome(prob, optimizer):
    driver = prob.driver
    if optimizer == "slsqp":
        res = getattr(driver, "_scipy_optimize_result", None)
        if res is None:
            return False, "SLSQP returned no result", 0
        return bool(res.success), str(res.message), int(getattr(res, "nit", 0))
    if optimizer == "ipopt":
        return (not driver.fail, f"{driver.ipopt_status_name}: {driver.ipopt_message}",
                int(driver.ipopt_iterations))
    inform = getattr(getattr(driver, "pyopt_solution", None), "optInform", None) or {}
    return not driver.fail, str(inform.get("text", "SNOPT finished")), int(driver.iter_count)


def run_optimization(prob):
    """Run the optimisation of the case loaded in ``prob`` and collect the result.

    Scales the design variables (``scaling='hessian'``), applies the case's
    bounds and runs the driver with single-threaded BLAS.  A BEM solve that
    fails at a trial point (``om.AnalysisError``, which SLSQP cannot back off
    from) ends the run as not converged; the error is in ``status``.

    Parameters
    ----------
    prob : om.Problem
        From :func:`build_optimization_problem`, with a case loaded.

    Returns
    -------
    OptimizationResult
        ``setup_time`` is 0.
    """
    meta = prob._bild_optimization
    optimizer = meta["optimizer"]
    start = time.perf_counter()
    try:
        with _single_threaded_blas():
            if meta["scaling"] == "hessian":
                refs = hessian_scaling(prob)
            else:
                refs = (CHORD_RATIO_REF, TWIST_REF)
            _apply_design_var_options(prob, *refs)
            prob.run_driver()
    except om.AnalysisError as exc:
        success, status, iterations = False, f"{_ANALYSIS_FAILED}: {exc}", 0
    else:
        success, status, iterations = _driver_outcome(prob, optimizer)
    wall_time = time.perf_counter() - start
    thrust_error = float(prob.get_val("thrust_residual")[0])
    performance = {name: float(prob.get_val(name)[0]) for name in RESULT_QUANTITIES}
    converged = bool(success and abs(thrust_error) <= THRUST_TOLERANCE
                     and all(np.isfinite(v) for v in performance.values()))
    return OptimizationResult(
        converged=converged, status=status, iterations=iterations,
        model_evaluations=int(prob.driver.iter_count), wall_time=wall_time, setup_time=0.0,
        chord=prob.get_val("chord", units="m")[0].copy(), twist=prob.get_val("twist", units="rad")[0].copy(),
        performance=performance, thrust_error=thrust_error, optimizer=optimizer)


_ANALYSIS_FAILED = "BEM analysis failed at a trial point"
_CASE_OPTIONS = ("initial", "bild_chord", "bild_twist", "reference_chord", "energy_loss_ref")


def optimize_rotor(v_axial, rpm, radius, hub_radius, thrust_target, altitude=0.0, *, problem=None, restarts=0,
                   **options):
    """Optimise one rotor for minimum energy loss at the required thrust (paper Sec. 5.1).

    Parameters
    ----------
    v_axial, rpm, radius, hub_radius, thrust_target, altitude : float
        The case (m/s, rpm, m, m, N, m).
    problem : om.Problem, optional
        A problem from :func:`build_optimization_problem` to reuse: its
        optimiser, parameterisation and sizes are kept and only the case
        options (``initial``, ``bild_chord``, ``bild_twist``,
        ``reference_chord``, ``energy_loss_ref``) are read from ``options``.
        Reusing skips the set-up (0.05-0.2 s, several seconds for the
        first problem of a process, which builds the polar).
    restarts : int
        How often to restart the optimiser from where it stopped when it
        reports failure (not after a failed BEM analysis): a restart
        recomputes the scaling and forgets the quasi-Newton Hessian, which
        clears stalls such as SLSQP's "Positive directional derivative for
        linesearch".  ``iterations``, ``model_evaluations`` and ``wall_time``
        add up over the attempts; ``status`` names the earlier failures.
    **options
        Keyword options of :func:`build_optimization_problem`.

    Returns
    -------
    OptimizationResult

    Examples
    --------
    >>> result = optimize_rotor(0.0, 800.0, 1.0, 0.2, 420.0, initial="linear")  # doctest: +SKIP
    >>> result.converged, result.performance["figure_of_merit"]  # doctest: +SKIP
    """
    start = time.perf_counter()
    if problem is None:
        prob = build_optimization_problem(v_axial, rpm, radius, hub_radius, thrust_target, altitude, **options)
        setup_time = time.perf_counter() - start
    else:
        unknown = set(options) - set(_CASE_OPTIONS)
        if unknown:
            raise ValueError(f"with problem=..., only the case options {_CASE_OPTIONS} can be given; "
                             f"got {sorted(unknown)}")
        set_optimization_case(problem, v_axial, rpm, radius, hub_radius, thrust_target, altitude, **options)
        prob, setup_time = problem, 0.0
    result = run_optimization(prob)
    failures = []
    for _ in range(int(restarts)):
        if result.converged or result.status.startswith(_ANALYSIS_FAILED):
            break
        failures.append(result.status)
        again = run_optimization(prob)
        again.iterations += result.iterations
        again.model_evaluations += result.model_evaluations
        again.wall_time += result.wall_time
        result = again
    if failures:
        result.status = f"{result.status} (after restarts from: {'; '.join(failures)})"
    result.setup_time = setup_time
    return result
