"""Annular efficiency eta2 of the ideally loaded rotor: the root of the BILD quartic (Eq. (27))."""
import numpy as np
import openmdao.api as om

from bild_mdo.bild.airfoil_point import (
    add_airfoil_point_inputs,
    airfoil_point_pattern,
    declare_spanwise_option,
    per_station,
)
from bild_mdo.bild.quartic import quartic, quartic_partials
from bild_mdo.bild.feasibility import declare_feasibility_option, report_infeasible, station_details
from bild_mdo.utils.newton import bracketed_newton, complex_step_update, false_position
from bild_mdo.utils.options import add_inputs, add_outputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node

_MAX_ITERATIONS = 200
#: Largest number of stations whose bracket is narrowed by a grid scan first (:func:`_scan_bracket`).
_SCAN_MAX = 2048
_SCAN_STEP = 0.01
_SCAN_GRID = 0.5 + _SCAN_STEP * np.arange(1, round(0.5 / _SCAN_STEP))


def _bracket_function(eta, v_axial, v_theta, lam, drag_to_lift, hover):
    """The function bracketed on [0.5, 1], its eta derivative and its rounding scale.

    Away from hover it is the quartic ``P = N**2 - 2 b N M - c M**2`` itself.
    ``P = h k`` where ``h`` is the physical factor and ``k = N - u- M > 0`` on
    [0.5, 1], so ``P`` and ``h`` have the same sign there and the same roots,
    but ``P`` is a polynomial while ``h`` contains ``sqrt(b**2 + c)``, which
    has a boundary layer of width ~``s**2`` at ``eta = 1`` near hover that
    slows Newton down.  ``P(0.5) > 0`` and ``P(1) = -lam V_x (...) < 0``.

    In hover ``P`` has the exact factor ``1 - eta`` (Eq. (35)): with
    ``N = V_theta**2 (1 - eta)(4 eta - 1)``, ``c = eta (1 - eta) V_theta**2``
    and ``b = -s V_theta / 2``, the bracketed function is the cubic::

        C = P / (1 - eta) = V_theta**2 [V_theta**2 (1 - eta)(4 eta - 1)**2
                                        + s V_theta (4 eta - 1) M - eta M**2],

        C(1) = 2 V_theta**2 (lam + s V_theta)(s V_theta - 2 lam).

    Returns ``(f, df/deta, scale)``; ``eps * scale`` bounds the rounding error
    of ``f``.
    """
    # N, M, b, c of tools/derive_quartic.py (bild_mdo.bild.quartic.physical_factor_terms) and their eta
    # derivatives, written out: this runs once per Newton pass.
    v2 = v_theta * v_theta
    one_minus = 1.0 - eta
    two_eta = 2.0 * eta - 1.0
    sum_axial = lam + v_axial
    sv_x = drag_to_lift * v_axial
    n_term = 2.0 * sv_x * eta * v_theta + v_axial * two_eta * sum_axial + v2 * one_minus * (4.0 * eta - 1.0)
    dn = 2.0 * sv_x * v_theta + 2.0 * v_axial * sum_axial + v2 * (5.0 - 8.0 * eta)
    m_term = 2.0 * drag_to_lift * v_theta - v_axial + two_eta * 2.0 * sum_axial
    dm = 4.0 * sum_axial
    b = 0.5 * (v_axial - drag_to_lift * v_theta)
    inner = v_theta * (sv_x + v_theta * one_minus)
    c = eta * inner
    dc = inner - eta * v2
    f = n_term * (n_term - 2.0 * b * m_term) - c * m_term * m_term
    df = 2.0 * (n_term - b * m_term) * dn - 2.0 * (b * n_term + c * m_term) * dm - m_term * m_term * dc
    scale = n_term * n_term + np.abs(2.0 * b * n_term * m_term) + np.abs(c) * m_term * m_term
    at = np.flatnonzero(hover)
    if at.size:
        # Only the hover stations (a large batch holds few of them).
        v2, one_minus, eta, m_term, dm = v2[at], one_minus[at], eta[at], m_term[at], dm[at]
        sv = drag_to_lift[at] * v_theta[at]
        q = 4.0 * eta - 1.0
        terms = (v2 * one_minus * q * q, sv * q * m_term, eta * m_term * m_term)
        f[at] = v2 * (terms[0] + terms[1] - terms[2])
        df[at] = v2 * (v2 * q * (8.0 * one_minus - q) + sv * (4.0 * m_term + q * dm)
                       - m_term * (m_term + 2.0 * eta * dm))
        scale[at] = v2 * (np.abs(terms[0]) + np.abs(terms[1]) + np.abs(terms[2]))
    return f, df, scale


def _describe(index, names=None):
    if names is None:
        return f"index {tuple(int(i) for i in index)}"
    return ", ".join(f"{name} {int(i)}" for name, i in zip(names, index))


def _domain_checks(v_axial, v_theta, lam, cl, cd):
    """``(ok_mask, name, values, rule)`` of each input's domain check, elementwise."""
    rules = (
        (v_axial, lambda x: x >= 0.0, "v_axial", "must be >= 0 (axial inflow; BILD assumes 0 <= V_x, Assumption 3)"),
        (v_theta, lambda x: x > 0.0, "v_theta", "must be > 0 (blade speed Omega*r at a station off the axis)"),
        (lam, lambda x: x > 0.0, "ideal-loading constant lambda",
         "must be > 0 (Appendix 7.1; check the reference-station induced velocities)"),
        (cl, lambda x: x > 0.0, "cl_star", "must be > 0 (lift coefficient at maximum L/D)"),
        (cd, lambda x: x > 0.0, "cd_star", "must be > 0 (drag coefficient at maximum L/D)"),
    )
    with np.errstate(invalid="ignore"):
        return [(np.isfinite(values) & ok(values), name, values, rule) for values, ok, name, rule in rules]


def _validate(v_axial, v_theta, lam, cl, cd, index_names):
    for ok, name, values, rule in _domain_checks(v_axial, v_theta, lam, cl, cd):
        if not np.all(ok):
            index = np.argwhere(~ok)[0]
            value = float(values[tuple(index)])
            raise ValueError(f"eta2 solve: {name} = {value!r} at {_describe(index, index_names)}: {rule}.")


def solve_eta2_flagged(v_axial, v_theta, lam, cl, cd):
    """:func:`solve_eta2` that flags instead of raising: ``(eta2, failed)``, both of the broadcast shape.

    ``failed`` marks elements outside the domain or not converged; their
    eta2 is a placeholder in [0.5, 1] (the root for a benign hover station).
    """
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (v_axial, v_theta, lam, cl, cd)))
    invalid = np.zeros(arrays[0].shape, dtype=bool)
    for ok, _, _, _ in _domain_checks(*arrays):
        invalid |= ~ok
    benign = (0.0, 1.0, 1.0, 1.0, 0.01)  # hover, loaded: lam > V_theta C_d/(2 C_l)
    if invalid.any():
        flat = [np.where(invalid, value, a).ravel() for value, a in zip(benign, arrays)]
    else:
        flat = [a.ravel() for a in arrays]
    eta, converged = _solve_flat(flat[0], flat[1], flat[2], flat[4] / flat[3])
    return eta.reshape(invalid.shape), invalid | ~converged.reshape(invalid.shape)


def _solve_flat(v_axial, v_theta, lam, drag_to_lift):
    """Bracket [0.5, 1] per element and solve with :func:`~bild_mdo.utils.newton.bracketed_newton`.

    Returns ``(eta2, converged)`` on 1-D arrays.
    """
    n = v_axial.size
    hover = v_axial * lam == 0.0
    lo = np.full(n, 0.5)
    hi = np.ones(n)
    # Exact values at the bracket ends (hand derivations, asserted in tools/derive_quartic.py:derive):
    # P(1/2) > 0 (C(1/2) = 2 P(1/2) in hover), P(1) away from hover, C(1) in it.
    sv = drag_to_lift * v_theta
    f_lo = 0.25 * v_theta * (v_theta**2 + v_axial**2) * (v_theta + 2.0 * drag_to_lift * v_axial)
    f_lo = np.where(hover, 2.0 * f_lo, f_lo)
    f_hi = np.where(hover, 2.0 * v_theta**2 * (lam + sv) * (sv - 2.0 * lam),
                    -lam * v_axial * (v_axial + 2.0 * sv) * (lam + v_axial + sv))
    unloaded = hover & ~(f_hi < 0.0)
    # P(0.5) > 0 analytically; a station without a bracket is reported, never guessed.
    active = np.flatnonzero(~unloaded & (f_lo > 0.0))
    eta = np.ones(n)
    converged = unloaded.copy()
    if active.size == 0:
        return eta, converged
    lo, hi, f_lo, f_hi = lo[active], hi[active], f_lo[active], f_hi[active]
    slopes = None
    if active.size <= _SCAN_MAX:
        lo, hi, f_lo, f_hi, slopes = _scan_bracket(active, lo, hi, f_lo, f_hi, v_axial, v_theta, lam, drag_to_lift,
                                                   hover)
    x0 = np.clip(false_position(lo, hi, f_lo, f_hi), lo + 2e-3 * (hi - lo), hi - 1e-12)
    if slopes is not None:
        x0 = _hermite_root(lo, hi, f_lo, f_hi, *slopes, x0)
    if active.size > _SCAN_MAX:
        # The Newton point from eta = 1 (lightly loaded stations have their root close to 1) where it
        # lies in the bracket: a pass less on average than the false-position point.
        at = active
        f_1, df_1, _ = _bracket_function(hi, v_axial[at], v_theta[at], lam[at], drag_to_lift[at], hover[at])
        with np.errstate(divide="ignore", invalid="ignore"):
            newton = 1.0 - f_1 / df_1
        x0 = np.where((newton > 0.5) & (newton < 1.0), newton, x0)

    def function(x, idx):
        at = active[idx]
        return _bracket_function(x, v_axial[at], v_theta[at], lam[at], drag_to_lift[at], hover[at])

    result = bracketed_newton(function, lo, hi, f_lo, x0, max_iter=_MAX_ITERATIONS, quadratic_stop=True)
    eta[active] = result.x
    converged[active] = result.converged
    return eta, converged


def _scan_bracket(active, lo, hi, f_lo, f_hi, v_axial, v_theta, lam, drag_to_lift, hover):
    """Narrow each bracket [0.5, 1] to the grid interval of width :data:`_SCAN_STEP` with the sign change.

    One vectorised evaluation on the grid replaces the first Newton passes: worth it for a few
    designs (the passes cost Python overhead, not arithmetic), not for large batches.  The
    bracketed function has exactly one root in (0.5, 1), so its first sign change is the root.
    """
    grid = _SCAN_GRID
    at = np.repeat(active, grid.size)
    values, derivatives, _ = _bracket_function(np.tile(grid, active.size), v_axial[at], v_theta[at], lam[at],
                                               drag_to_lift[at], hover[at])
    values = values.reshape(active.size, grid.size)
    values = np.concatenate([f_lo[:, None], values, f_hi[:, None]], axis=1)
    points = np.concatenate([[0.5], grid, [1.0]])
    # First grid point where the function is no longer positive (f(1) <= 0 for every active station).
    first = np.argmax(values <= 0.0, axis=1)
    first = np.maximum(first, 1)
    rows = np.arange(active.size)
    # The slopes at the grid points (unknown at the bracket ends 0.5 and 1: NaN).
    slopes = np.full((active.size, grid.size + 2), np.nan)
    slopes[:, 1:-1] = derivatives.reshape(active.size, grid.size)
    return (points[first - 1], points[first], values[rows, first - 1], values[rows, first],
            (slopes[rows, first - 1], slopes[rows, first]))


def _hermite_root(lo, hi, f_lo, f_hi, d_lo, d_hi, x0):
    """Root of the cubic Hermite interpolant of ``f`` on each narrowed bracket, by two Newton steps from ``x0``.

    On a bracket of width 0.01 it is within ~1e-9 of the root, so the Newton solve needs one pass
    less than from the false-position point; where it is not a finite point inside the bracket (or a
    slope is unknown), ``x0`` is kept.
    """
    width = hi - lo
    m_lo, m_hi = d_lo * width, d_hi * width
    t = (x0 - lo) / width
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for _ in range(2):
            u = 1.0 - t
            value = ((1.0 + 2.0 * t) * u * u * f_lo + t * u * u * m_lo + t * t * (3.0 - 2.0 * t) * f_hi
                     - t * t * u * m_hi)
            slope = 6.0 * t * u * (f_hi - f_lo) + u * (1.0 - 3.0 * t) * m_lo + t * (3.0 * t - 2.0) * m_hi
            t = t - value / slope
        x = lo + t * width
    return np.where(np.isfinite(x) & (x > lo) & (x < hi), x, x0)


def solve_eta2(v_axial, v_theta, lam, cl, cd, index_names=None):
    """Solve the BILD quartic (Eq. (27)) for the physical annular efficiency eta2.

    Each element is the unique root in (0.5, 1) of the quartic ``P`` (and of
    its physical factor ``h``: ``P = h k`` with ``k > 0`` on [0.5, 1]), so it
    satisfies Eq. (22) with ``u_axial`` from Eq. (26) and ``u_theta`` from
    Eq. (24).  The solve is the package's vectorised safeguarded Newton
    iteration (:func:`bild_mdo.utils.newton.bracketed_newton`) on the bracket
    [0.5, 1], converged to round-off of the bracketed function's terms; see
    :func:`_bracket_function` for the function it brackets.  The root is unique and the other real root of ``h`` near
    hover lies above 1, so it is never returned, however close it is.

    Hover (``V_x == 0``): the station carries load only if
    ``lam > V_theta C_d / (2 C_l)``; otherwise there is no root in (0.5, 1)
    and the station is unloaded: eta2 = 1 (``u_axial = u_theta = 0``), the limit
    of the root as ``V_x -> 0+``.

    Parameters
    ----------
    v_axial : array_like
        Axial free-stream velocity V_x (m/s), >= 0.
    v_theta : array_like
        Blade speed ``Omega r`` (m/s), > 0.
    lam : array_like
        Ideal-loading constant of Eq. (22) (m/s), > 0.
    cl, cd : array_like
        Lift and drag coefficients at the maximum lift-to-drag ratio, > 0.
    index_names : sequence of str, optional
        Names of the broadcast axes, used in error messages (e.g.
        ``("node", "station")``).

    Returns
    -------
    numpy.ndarray
        eta2 with the broadcast shape of the inputs, in (0.5, 1].

    Raises
    ------
    ValueError
        If an input is outside the valid domain or (not expected in the
        valid domain) the solve fails; the message names the element.
    """
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (v_axial, v_theta, lam, cl, cd)))
    _validate(*arrays, index_names)
    flat = [a.ravel() for a in arrays]
    eta, converged = _solve_flat(flat[0], flat[1], flat[2], flat[4] / flat[3])
    if not np.all(converged):
        index = np.unravel_index(np.flatnonzero(~converged)[0], arrays[0].shape)
        at = ", ".join(f"{label}={float(a[index])!r}" for label, a in zip(("V_x", "V_theta", "lambda", "C_l", "C_d"),
                                                                           arrays))
        raise ValueError(f"eta2 solve did not converge at {_describe(index, index_names)} ({at}); "
                         "please report this case.")
    return eta.reshape(arrays[0].shape)


class Eta2Comp(om.ImplicitComponent):
    """Annular efficiency eta2 at every station: the physical root of the quartic of Eq. (27).

    Residual (dimensionless)::

        R = P(eta2; V_x, V_theta, lam, s) / (V_theta**2 + V_x**2 + lam**2)**2,   s = C_d*/C_l*,

    where ``P`` (in (m/s)**4) is the quartic derived in
    :mod:`tools.derive_quartic` from Eqs. (22), (24), (26) (the
    paper's printed Eq. (34) is misprinted; see
    :mod:`bild_mdo.bild.quartic`).  The positive per-point scale
    has the units of ``P`` and makes ``R`` O(1) at hub and tip alike; it is
    included in the partials.

    ``solve_nonlinear`` finds the unique root in (0.5, 1) by a vectorised,
    bracketed, safeguarded Newton solve (:func:`solve_eta2`).  In hover
    (``V_x == 0``) a station is loaded only if ``lam > V_theta C_d/(2 C_l)``;
    otherwise it is unloaded and ``eta2 = 1`` (``u_axial = u_theta = 0``), the
    limit of the root as ``V_x -> 0+``, which is still a simple root of ``P``,
    so the linearization stays finite and consistent there.  Under complex
    step one Newton update in complex arithmetic on ``P`` carries the exact
    derivative in the imaginary part.

    Inputs outside the domain or a solve that does not converge raise
    :class:`openmdao.api.AnalysisError`; inside a BILDGroup the nodes are
    recorded in the group's feasibility ledger instead
    (:func:`solve_eta2_flagged`).

    Options: the sizes ``num_nodes`` and ``num_radial``
    (:func:`~bild_mdo.utils.options.declare_size_options`) and ``feasibility``
    (:func:`~bild_mdo.bild.feasibility.declare_feasibility_option`).

    Inputs
    ------
    v_axial[nn] (m/s)
        Axial free-stream velocity, >= 0.
    v_theta[nn, nr] (m/s)
        Rotational blade speed ``Omega r`` at the stations, > 0.
    ideal_loading_constant[nn] (m/s)
        Ideal-loading constant lambda of Eq. (22), > 0.
    cl_star[nn] (-), cd_star[nn] (-)
        Lift and drag coefficients at the maximum lift-to-drag ratio, > 0;
        ``[nn, nr]`` with ``varies_along_span=True``
        (:mod:`~bild_mdo.bild.airfoil_point`).

    Outputs
    -------
    eta2[nn, nr] (-)
        Annular efficiency for tangential induced losses, Eq. (23), in (0.5, 1].
    """

    def initialize(self):
        declare_size_options(self.options)
        declare_feasibility_option(self.options)
        declare_spanwise_option(self.options)

    def setup(self):
        add_inputs(self, ("v_axial", "v_theta", "ideal_loading_constant"))
        add_airfoil_point_inputs(self, ("cl_star", "cd_star"))
        add_outputs(self, ("eta2",))

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = dist_wrt_dist(nn, nr)
        self.declare_partials("eta2", ["eta2", "v_theta"], rows=rows, cols=cols)
        rows, cols = dist_wrt_node(nn, nr)
        self.declare_partials("eta2", ["v_axial", "ideal_loading_constant"], rows=rows, cols=cols)
        rows, cols = airfoil_point_pattern(self)
        self.declare_partials("eta2", ["cl_star", "cd_star"], rows=rows, cols=cols)

    @staticmethod
    def _arguments(inputs):
        """``(V_x, V_theta, lam, s)`` broadcast to ``(nn, nr)``-compatible shapes."""
        v_x = inputs["v_axial"][:, None]
        lam = inputs["ideal_loading_constant"][:, None]
        s = per_station(inputs["cd_star"] / inputs["cl_star"])
        return v_x, inputs["v_theta"], lam, s

    @staticmethod
    def _scale(v_x, v_t, lam):
        return (v_t * v_t + v_x * v_x + lam * lam) ** 2

    def apply_nonlinear(self, inputs, outputs, residuals):
        v_x, v_t, lam, s = self._arguments(inputs)
        residuals["eta2"] = quartic(outputs["eta2"], v_x, v_t, lam, s) / self._scale(v_x, v_t, lam)

    def solve_nonlinear(self, inputs, outputs):
        real = {name: np.real(inputs[name]) for name in
                ("v_axial", "v_theta", "ideal_loading_constant", "cl_star", "cd_star")}
        args = (real["v_axial"][:, None], real["v_theta"], real["ideal_loading_constant"][:, None],
                per_station(real["cl_star"]), per_station(real["cd_star"]))
        if self.options["feasibility"] is None:
            try:
                eta = solve_eta2(*args, index_names=("node", "station"))
            except ValueError as err:
                raise om.AnalysisError(f"{self.msginfo}: {err}") from err
        else:
            eta, failed = solve_eta2_flagged(*args)
            details = station_details(failed, {"V_x [m/s]": args[0], "V_theta [m/s]": args[1],
                                                     "lambda [m/s]": args[2]})
            report_infeasible(self, "solve", np.any(failed, axis=1),
                              "eta2 solve: an input is outside its domain or the solve did not converge",
                              details)
        if self.under_complex_step:
            residual = quartic(eta, *self._arguments(inputs))
            slope = quartic_partials(eta, *self._arguments(real), wrt=("eta",))["eta"]
            eta = complex_step_update(eta, residual, slope)
        outputs["eta2"] = eta

    def linearize(self, inputs, outputs, partials):
        v_x, v_t, lam, s = self._arguments(inputs)
        eta = outputs["eta2"]
        scale = self._scale(v_x, v_t, lam)
        residual = quartic(eta, v_x, v_t, lam, s) / scale
        dp = quartic_partials(eta, v_x, v_t, lam, s)
        # d(P/S) = (dP - R dS)/S with dS = 4 sqrt(S) x dx for x in (V_x, V_theta, lam).
        root_scale = np.sqrt(scale)
        d_vx = (dp["v_axial"] - residual * 4.0 * root_scale * v_x) / scale
        d_vt = (dp["v_theta"] - residual * 4.0 * root_scale * v_t) / scale
        d_lam = (dp["lam"] - residual * 4.0 * root_scale * lam) / scale
        d_s = dp["drag_to_lift"] / scale
        cl = per_station(inputs["cl_star"])
        d_eta = dp["eta"] / scale
        if not np.all(np.isfinite(d_eta) & (d_eta != 0.0)):
            index = np.argwhere(~(np.isfinite(d_eta) & (d_eta != 0.0)))[0]
            raise om.AnalysisError(
                f"{self.msginfo}: dP/deta2 is singular at node {index[0]}, station {index[1]} (a hover station "
                f"exactly at the loading threshold lambda = V_theta C_d/(2 C_l), where eta2 is not differentiable).")
        self._d_eta = d_eta
        partials["eta2", "eta2"] = d_eta.ravel()
        partials["eta2", "v_theta"] = d_vt.ravel()
        partials["eta2", "v_axial"] = d_vx.ravel()
        partials["eta2", "ideal_loading_constant"] = d_lam.ravel()
        partials["eta2", "cl_star"] = (d_s * (-s / cl)).ravel()
        partials["eta2", "cd_star"] = (d_s / cl).ravel()

    def solve_linear(self, d_outputs, d_residuals, mode):
        if mode == "fwd":
            d_outputs["eta2"] = d_residuals["eta2"] / self._d_eta
        else:
            d_residuals["eta2"] = d_outputs["eta2"] / self._d_eta
