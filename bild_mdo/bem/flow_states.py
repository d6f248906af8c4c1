"""Flow states of a BEM station: integer codes, the classification and the invalid-station report.

Every station of the BEM analysis carries one of these codes (output ``flow_state[nn, nr]`` of
:class:`~bild_mdo.bem.bem_group.BEMAnalysisGroup`, field ``flow_state`` of
:class:`~bild_mdo.bem.analyze.BEMResult`).  They follow the quadrant logic of CCBlade.jl
(``byuflowlab/CCBlade.jl``, ``solve``) and AeroDyn's ``momentumRegion`` test
(``OpenFAST``, ``BEMTUncoupled.f90``), read from the signs of the loads and of the inflow at the
solved inflow angle (propeller convention: ``V_x >= 0`` from ahead, ``Omega > 0``;
``dT/dr = q C_x``, ``dQ/dr = q C_theta r`` with ``q > 0``; ``a = 1 - u_axial / V_x`` is the
wind-turbine axial induction, ``W > 0`` the inflow speed).

==  ====================  =====================================================================
 0  NO_SOLUTION           No admissible root of the momentum residual (none with ``W > 0``:
                          every sign change is a 180-deg mirror image ``phi +- pi`` of a real
                          flow, or there is no sign change at all).  CCBlade's documented fallback
                          "zero loading assumed" is returned: ``dT/dr = dQ/dr = 0``,
                          ``u_axial = V_x``, ``u_theta = 0``, ``phi = atan2(V_x, Omega r)``.
 1  PROPELLER             ``dT > 0`` and ``dQ > 0``: the normal working state.
 2  PROPELLER_BRAKE       ``V_x > 0``, ``dT <= 0``, ``dQ > 0`` (power absorbed, thrust reversed)
                          with ``a <= 0.4`` (``a <= 0.95`` with Buhl's correction): valid.
 3  WINDMILL              ``V_x > 0``, ``dT <= 0``, ``dQ <= 0``, ``a <= 0.4`` (``a <= 0.95`` with
                          Buhl's correction): power extracted.
 4  TURBULENT_WAKE        ``V_x > 0``, ``dT < 0`` and ``a > 0.4`` (``a > 0.95`` with Buhl's correction,
                          :data:`BUHL_MAX_INDUCTION`): the turbulent-wake state
                          (``0.4 < a < 1``) and, for ``a >= 1`` (flow reversed through the disk
                          against the freestream), the vortex-ring / windmill-brake state; and in
                          hover (``V_x = 0``) an annulus with ``dT < 0`` (see below).
                          Momentum theory does not hold there (Glauert; Buhl 2005,
                          NREL/TP-500-36834, Fig. 2); the values returned are those of the
                          momentum root and are not reliable.
 5  MIRROR_ROOT           Only with ``solve_range='full'``: a root with ``W < 0`` kept as found
                          (the pre-classification behaviour), loads as computed there.
==  ====================  =====================================================================

Hover with reversed thrust.  In hover (``V_x = 0``) a negative-pitch annulus pushes air
upward while the rest of the rotor drives its wake downward: the annulus recirculates in the
vortex-ring state, where the streamtube of momentum theory does not exist (Glauert; Leishman,
*Principles of Helicopter Aerodynamics*, 2nd ed., Sec. 2.14).  The value returned there is the
momentum root with the mass flux ``rho |u_axial|``, the exact mirror image of a normal hovering
annulus (``phi -> -phi``, ``u_axial -> -u_axial``, ``dT -> -dT``) and the root CCBlade.jl returns
in hover, which is the ``V_x -> 0`` limit of the reversed-flow branch; the station is flagged
``TURBULENT_WAKE`` (invalid), as is the same annulus for ``V_x > 0`` (``a > 1``).

What is returned where momentum theory fails.  Code 0 (no admissible root) gets CCBlade.jl's
documented fallback, zero loading: it is exact, smooth in the inputs (its partials are those of
``atan2(V_x, Omega r)`` and of the unloaded speeds), and with the search order of
:func:`~bild_mdo.bem.root_finding.solve_physical` it is rare (no station of 20,000 random rotors
in ``benchmarks/bem_robustness.py``).  Code 4 keeps the momentum root and is flagged.  Buhl's
turbulent-wake correction (NREL/TP-500-36834, used by AeroDyn and CCBlade) is applied with the
option ``high_induction='buhl'`` (:mod:`bild_mdo.bem.inflow_residual`): then a station with
``0.4 < a <= 0.95`` has Buhl's thrust and is a valid windmill or propeller brake (code 2 or 3), and
only a larger ``a``, the degenerate end of his relation (:data:`BUHL_MAX_INDUCTION`), stays code 4.  By
default (``'none'``) it is not applied: it is a fit to wind-turbine
data for ``0.4 < a < 1``, its extension to ``a > 1`` (reversed through-flow, the case of a
propeller annulus with negative pitch) is unvalidated, and without it such stations are flagged.

Invalid stations are those with code 0, 4 or 5 (:data:`INVALID_STATES`): with
``on_invalid='raise'`` the analysis raises :class:`openmdao.api.AnalysisError`, with ``'warn'``
it issues one :class:`BEMStateWarning` per analysis naming them, with ``'ignore'`` nothing.
"""
from __future__ import annotations

import warnings

import numpy as np
import openmdao.api as om

from bild_mdo.bem.inflow_residual import HIGH_INDUCTION

NO_SOLUTION = 0
PROPELLER = 1
PROPELLER_BRAKE = 2
WINDMILL = 3
TURBULENT_WAKE = 4
MIRROR_ROOT = 5

#: Code -> name.
FLOW_STATE_NAMES = {NO_SOLUTION: "no momentum solution", PROPELLER: "propeller",
                    PROPELLER_BRAKE: "propeller brake", WINDMILL: "windmill",
                    TURBULENT_WAKE: "turbulent wake / vortex ring", MIRROR_ROOT: "mirror root (W < 0)"}
#: Codes the analysis flags (``on_invalid``).
INVALID_STATES = (NO_SOLUTION, TURBULENT_WAKE, MIRROR_ROOT)
#: Values of the ``on_invalid`` option.
ON_INVALID = ("warn", "raise", "ignore")
#: Values of the ``solve_range`` option.
SOLVE_RANGES = ("physical", "full")
#: Axial induction above which momentum theory fails for V_x > 0 (Glauert; Buhl 2005: a_c = 0.4).
CRITICAL_INDUCTION = 0.4
#: Axial induction above which a root with Buhl's correction is flagged: his thrust reaches C_T = 2 at a = 1,
#: where the speed through the disk and the inflow speed W vanish; a root past a = 0.95 (the disk speed below 5 %
#: of the freestream) lies at that degenerate end (in forward flow it appears where the induction grows without
#: another root, e.g. a propeller near hover or a turbine far beyond its design tip-speed ratio).
BUHL_MAX_INDUCTION = 0.95
#: Stations named in a warning or error message (the count says how many in all).
MAX_LISTED = 5


def declare_flow_state_options(options):
    """Declare ``solve_range`` and ``on_invalid`` (the BEM inflow component and group)."""
    options.declare("solve_range", default="physical", values=SOLVE_RANGES,
                    desc="'physical': CCBlade.jl's region order, roots with W > 0 only; "
                         "'full': first sign change in [-pi/2, pi), mirror roots kept and flagged")
    options.declare("on_invalid", default="warn", values=ON_INVALID,
                    desc="stations in an invalid flow state: one BEMStateWarning, om.AnalysisError, or nothing")


def declare_high_induction_option(options, by_rotor_type=False):
    """Declare ``high_induction`` (the BEM inflow and loads components and the BEM groups).

    With ``by_rotor_type`` None is allowed and the default: the rotor type's
    (:func:`~bild_mdo.bem.inflow_residual.resolve_high_induction`)."""
    options.declare("high_induction", default=None if by_rotor_type else "none",
                    values=((None,) if by_rotor_type else ()) + HIGH_INDUCTION, allow_none=by_rotor_type,
                    desc="momentum thrust above a = 0.4: 'none' (momentum theory, the station flagged) or "
                         "'buhl' (Buhl's 2005 correction, as CCBlade and AeroDyn)"
                         + ("; None: 'buhl' for a turbine, 'none' for a propeller" if by_rotor_type else ""))


class BEMStateWarning(UserWarning):
    """Stations of a BEM analysis in a flow state the momentum model does not represent."""


def classify(c_x, c_theta, v_axial, u_axial, admissible, corrected=False):
    """Flow-state code per station from the signs of the loads and of the inflow.

    Parameters
    ----------
    c_x, c_theta : ndarray
        Axial and tangential force coefficients (signs of ``dT/dr`` and ``dQ/dr``).
    v_axial : ndarray
        Freestream axial velocity V_x >= 0 (m/s), broadcast to the station shape.
    u_axial : ndarray
        Axial velocity at the disk (m/s).
    admissible : ndarray of bool
        Whether the root is kinematically consistent (``W > 0``).
    corrected : bool
        Whether the thrust above ``a = 0.4`` is Buhl's (``high_induction='buhl'``): then a station
        with ``0.4 < a <=`` :data:`BUHL_MAX_INDUCTION` is a windmill or propeller brake, valid, and
        only a larger ``a`` is flagged.

    Returns
    -------
    ndarray of int
        Codes of this module (never :data:`MIRROR_ROOT`; the solve assigns that one).
    """
    c_x, c_theta, v_axial, u_axial = np.broadcast_arrays(*(np.real(x) for x in (c_x, c_theta, v_axial, u_axial)))
    forward = v_axial > 0.0
    # a = 1 - u_axial / V_x > a_c  <=>  u_axial < (1 - a_c) V_x at V_x > 0: no division, so a tiny V_x
    # cannot overflow.
    past_critical = u_axial < (1.0 - (BUHL_MAX_INDUCTION if corrected else CRITICAL_INDUCTION)) * v_axial
    thrust, torque = c_x > 0.0, c_theta > 0.0
    # Forward flight past a = 0.4, or a hover annulus pushing air upward (vortex ring).
    wake = (forward & ~thrust & past_critical) | (~forward & (c_x < 0.0) & (u_axial < 0.0))
    state = np.full(c_x.shape, NO_SOLUTION, dtype=int)
    state[thrust & torque] = PROPELLER
    state[~thrust & torque & ~wake] = PROPELLER_BRAKE
    state[forward & ~thrust & ~torque & ~wake] = WINDMILL
    state[wake] = TURBULENT_WAKE
    # Hover with dT < 0 needs the flow reversed through the annulus (the mirror solution, flagged above);
    # dT > 0 with dQ <= 0 breaks the energy balance Omega dQ >= V_x dT + (kinetic energy) at a consistent root.
    state[~forward & ~thrust & (u_axial > 0.0)] = NO_SOLUTION
    state[~np.asarray(admissible)] = NO_SOLUTION
    return state


def describe_invalid(state, r_over_r=None, suggest_buhl=True):
    """One line naming the invalid stations (node, station, r/R, state): the first few and the count.

    Parameters
    ----------
    state : ndarray
        Codes, shape ``(nn, nr)``.
    r_over_r : ndarray, optional
        Station radii as fractions of the tip radius, shape ``(nn, nr)``.
    suggest_buhl : bool
        Whether the line suggests ``high_induction='buhl'`` for turbulent-wake stations (False where it is on).

    Returns
    -------
    str or None
        None if no station is invalid.
    """
    state = np.asarray(np.real(state)).astype(int)
    bad = np.isin(state, INVALID_STATES)
    count = int(np.count_nonzero(bad))
    if count == 0:
        return None
    nodes, stations = np.nonzero(bad)
    items = []
    for node, station in zip(nodes[:MAX_LISTED], stations[:MAX_LISTED]):
        where = f"node {node}, station {station}"
        if r_over_r is not None:
            where += f" (r/R = {np.real(r_over_r[node, station]):.3f})"
        items.append(f"{where}: {FLOW_STATE_NAMES[state[node, station]]}")
    more = f"; and {count - MAX_LISTED} more" if count > MAX_LISTED else ""
    hint = (" or, past a = 0.4 in forward flow, high_induction='buhl' (Buhl's correction, as CCBlade)"
            if suggest_buhl and np.any(state == TURBULENT_WAKE) else "")
    return (f"BEM analysis: {count} station(s) outside the momentum model's valid flow states "
            f"({'; '.join(items)}{more}); their loads are not reliable (see bild_mdo.bem.flow_states{hint})")


def report_invalid(state, on_invalid, r_over_r=None, prefix="", suggest_buhl=True):
    """Raise, warn once or do nothing about the invalid stations, as ``on_invalid`` says.

    Raises
    ------
    openmdao.api.AnalysisError
        With ``on_invalid='raise'`` and at least one invalid station.
    """
    if on_invalid == "ignore":
        return
    message = describe_invalid(state, r_over_r, suggest_buhl)
    if message is None:
        return
    if on_invalid == "raise":
        raise om.AnalysisError(prefix + message)
    warnings.warn(prefix + message, BEMStateWarning, stacklevel=2)
