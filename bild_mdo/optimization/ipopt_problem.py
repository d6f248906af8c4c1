"""How :class:`~bild_mdo.optimization.ipopt_driver.IpoptDriver` lays out its problem for Ipopt.

Ipopt (Waechter & Biegler, Math. Program. 106(1), 2006) solves

    min f(x)  s.t.  g_L <= g(x) <= g_U,  x_L <= x <= x_U.

This module builds the bounds ``x_L, x_U, g_L, g_U`` in OpenMDAO's driver
scaling, the coordinate (COO) sparsity of the constraint Jacobian, and the
callback object cyipopt calls.  It needs no cyipopt: only
:func:`import_cyipopt` imports it, when a driver is made.
"""
import numpy as np

_INSTALL_RECIPE = (
    "IpoptDriver needs cyipopt, which compiles against the Ipopt C++ library. Install it with\n"
    "    sudo apt-get install coinor-libipopt-dev liblapack-dev libblas-dev pkg-config\n"
    "    pip install 'bild-mdo[ipopt]'\n"
    "(on conda: conda install -c conda-forge cyipopt)."
)

# Ipopt's ApplicationReturnStatus codes (IpReturnCodes_inc.h).
IPOPT_STATUS_NAMES = {
    0: "Solve_Succeeded",
    1: "Solved_To_Acceptable_Level",
    2: "Infeasible_Problem_Detected",
    3: "Search_Direction_Becomes_Too_Small",
    4: "Diverging_Iterates",
    5: "User_Requested_Stop",
    6: "Feasible_Point_Found",
    -1: "Maximum_Iterations_Exceeded",
    -2: "Restoration_Failed",
    -3: "Error_In_Step_Computation",
    -4: "Maximum_CpuTime_Exceeded",
    -5: "Maximum_WallTime_Exceeded",
    -10: "Not_Enough_Degrees_Of_Freedom",
    -11: "Invalid_Problem_Definition",
    -12: "Invalid_Option",
    -13: "Invalid_Number_Detected",
    -100: "Unrecoverable_Exception",
    -101: "NonIpopt_Exception_Thrown",
    -102: "Insufficient_Memory",
    -199: "Internal_Error",
}

# Same convention as pyOptSparse's IPOPT wrapper: an acceptable-level stop is a converged point.
SUCCESS_STATUSES = (0, 1)


def import_cyipopt():
    """Import cyipopt or raise ImportError with the install recipe.

    Returns
    -------
    module
    """
    try:
        import cyipopt
    except ImportError as exc:
        raise ImportError(_INSTALL_RECIPE) from exc
    return cyipopt


def voi_size(meta):
    """Global size of a design variable or response from its metadata."""
    return meta["global_size"] if meta["distributed"] else meta["size"]


def design_var_bounds(driver):
    """Ipopt's x_L, x_U in driver scaling (infinite where a design variable has no bound)."""
    bounds = driver._autoscaler.get_bounds_scaling("design_var")
    lower, upper = [], []
    for name, meta in driver._designvars.items():
        size = voi_size(meta)
        lo, up = bounds[name].lower, bounds[name].upper
        lower.append(np.full(size, -np.inf) if lo is None else np.asarray(lo, dtype=float))
        upper.append(np.full(size, np.inf) if up is None else np.asarray(up, dtype=float))
    return np.concatenate(lower), np.concatenate(upper)


def constraint_bounds(driver, names):
    """Ipopt's g_L, g_U in driver scaling for the constraints ``names``, in that order."""
    bounds = driver._autoscaler.get_bounds_scaling("constraint")
    lower, upper = [np.zeros(0)], [np.zeros(0)]
    for name in names:
        size = voi_size(driver._cons[name])
        b = bounds[name]
        if b.equals is not None:
            eq = np.broadcast_to(np.asarray(b.equals, dtype=float), (size,))
            lower.append(eq)
            upper.append(eq)
        else:
            lower.append(np.full(size, -np.inf) if b.lower is None
                         else np.broadcast_to(np.asarray(b.lower, dtype=float), (size,)))
            upper.append(np.full(size, np.inf) if b.upper is None
                         else np.broadcast_to(np.asarray(b.upper, dtype=float), (size,)))
    return np.concatenate(lower), np.concatenate(upper)


def nonlinear_jacobian_pattern(driver, nl_names, coloring):
    """COO pattern (rows, cols) of d(nonlinear constraints)/dx.

    The pattern comes from the total coloring when there is one.  Otherwise
    every (constraint, design variable) block that the relevance graph
    connects is taken as dense.
    """
    col_offsets = {}
    offset = 0
    for name, meta in driver._designvars.items():
        col_offsets[name] = offset
        offset += voi_size(meta)

    subjac_sparsity = coloring.get_subjac_sparsity() if coloring is not None else None
    relevance = driver._problem().model._relevance
    dv_sources = tuple(meta["source"] for meta in driver._designvars.values())

    rows, cols = [np.zeros(0, dtype=int)], [np.zeros(0, dtype=int)]
    row_offset = 0
    for con in nl_names:
        cmeta = driver._cons[con]
        con_size = voi_size(cmeta)
        with relevance.seeds_active(fwd_seeds=dv_sources, rev_seeds=(cmeta["source"],)):
            linked = {dv: relevance.is_relevant(dmeta["source"]) for dv, dmeta in driver._designvars.items()}
        for dv, dmeta in driver._designvars.items():
            dv_size = voi_size(dmeta)
            block = None
            if subjac_sparsity is not None:
                block = subjac_sparsity.get(con, {}).get(dv)
                if block is None:
                    block = subjac_sparsity.get(cmeta["source"], {}).get(dmeta["source"])
            if block is not None:
                r, c = np.asarray(block[0], dtype=int), np.asarray(block[1], dtype=int)
            elif linked[dv]:
                r, c = np.divmod(np.arange(con_size * dv_size), dv_size)
            else:
                continue
            rows.append(r + row_offset)
            cols.append(c + col_offsets[dv])
        row_offset += con_size
    return np.concatenate(rows), np.concatenate(cols)


class IpoptCallbacks:
    """The problem object cyipopt calls; forwards to the driver's evaluation methods.

    Parameters
    ----------
    driver : IpoptDriver
        The driver whose model is evaluated.
    """

    def __init__(self, driver):
        self._driver = driver

    def objective(self, x):
        """Objective f(x) (driver scaling)."""
        return self._driver._objective(x)

    def gradient(self, x):
        """Gradient of f at x."""
        return self._driver._gradient(x)

    def constraints(self, x):
        """Constraints g(x): nonlinear ones, then linear ones."""
        return self._driver._constraints(x)

    def jacobian(self, x):
        """Non-zero values of dg/dx in the order of :meth:`jacobianstructure`."""
        return self._driver._jacobian(x)

    def jacobianstructure(self):
        """COO rows and columns of dg/dx."""
        return self._driver._jacobian_structure()

    def intermediate(self, alg_mod, iter_count, obj_value, inf_pr, inf_du, mu, d_norm,
                     regularization_size, alpha_du, alpha_pr, ls_trials):
        """Ipopt's per-iteration report: records the iteration count."""
        self._driver._intermediate(iter_count)
