"""Annular efficiency eta2 of the ideally loaded rotor: the root of the BILD quartic (Eq. (27))."""
import numpy as np
import openmdao.api as om

from bild_mdo.bild.airfoil_point import (
    add_airfoil_point_inputs,
    airfoil_point_pattern,
    declare_spanwise_option,
    per_station,
)
from bild_mdo.bild.variants.paper.quartic import quartic, quartic_and_partials, quartic_partials
from bild_mdo.bild.feasibility import declare_feasibility_option, report_infeasible, station_details
from bild_mdo.utils.newton import bracketed_newton, complex_step_update, false_position
from bild_mdo.utils.options import add_inputs, add_outputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_dist, dist_wrt_node

_MAX_ITERATIONS = 200
#: Moebius parameter ``a`` of the starting model (:func:`_start`): ``y -> infinity`` is ``t = 3/4``, the double root
#: of the V_theta**4 part ``t**2 (3 - 4 t)**2 + 2 s**2 t (1 - 2 t)`` of P at s -> 0.  Paper sweep (Sec. 5.1, 300,000
#: stations): two Newton passes leave 0.3 % to the safeguarded solve; stations off by > 1e-9: 19 % with a = 1.
_START_SHIFT = 4.0 / 3.0
_EPS = np.finfo(float).eps


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
    # N, M, b, c of tools/derive_quartic.py (bild_mdo.bild.variants.paper.quartic.physical_factor_terms) and their eta
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
    """``(ok_mask, name, values, rule)`` of each input's domain check, each in its input's own shape."""
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


def _arrays(*values):
    """The inputs as float arrays, not broadcast (a per-design value stays small), and their broadcast shape."""
    arrays = [np.asarray(a, dtype=float) for a in values]
    return arrays, np.broadcast_shapes(*(a.shape for a in arrays))


def _validate(arrays, shape, index_names):
    for ok, name, values, rule in _domain_checks(*arrays):
        if not np.all(ok):
            index = np.argwhere(~np.broadcast_to(ok, shape))[0]
            value = float(np.broadcast_to(values, shape)[tuple(index)])
            raise ValueError(f"eta2 solve: {name} = {value!r} at {_describe(index, index_names)}: {rule}.")


def solve_eta2_flagged(v_axial, v_theta, lam, cl, cd):
    """:func:`solve_eta2` that flags instead of raising: ``(eta2, failed)``, both of the broadcast shape.

    ``failed`` marks elements outside the domain or not converged; their
    eta2 is a placeholder in [0.5, 1] (the root for a benign hover station).
    """
    arrays, shape = _arrays(v_axial, v_theta, lam, cl, cd)
    invalid = np.zeros(shape, dtype=bool)
    for ok, _, _, _ in _domain_checks(*arrays):
        if not np.all(ok):
            invalid |= ~ok
    if invalid.any():
        benign = (0.0, 1.0, 1.0, 1.0, 0.01)  # hover, loaded: lam > V_theta C_d/(2 C_l)
        arrays = [np.where(invalid, value, a) for value, a in zip(benign, arrays)]
    eta, converged = _solve(arrays[0], arrays[1], arrays[2], arrays[4] / arrays[3], shape)
    return eta, (invalid | ~converged) if invalid.any() else ~converged


def _taylor_coefficients(v_axial, v_theta, lam, drag_to_lift):
    """``(q0, ..., q4)`` with ``P(1 - t) = lam**4 sum_k q_k t**k``: the quartic (Eq. (27)) about ``eta = 1``.

    Expanded with sympy from the ``N``, ``M``, ``b``, ``c`` of tools/derive_quartic.py (tests/bild/test_eta2.py
    asserts the identity against :func:`~bild_mdo.bild.variants.paper.quartic.quartic`), with ``rho = V_x/lam`` per design and
    ``z = V_theta/lam`` per station, each coefficient a polynomial in ``z``; ``q0 = P(1)/lam**4``.
    """
    rho, s = v_axial / lam, drag_to_lift
    z = v_theta * (1.0 / lam)
    r1 = rho + 1.0
    s2, rs = s * s, rho * s
    q0 = z * (z * (-2.0 * rho * s2) - rs * (3.0 * rho + 2.0)) - rho * rho * r1
    q1 = z * (z * (z * (2.0 * s2 * z + s * (5.0 * rho - 2.0))
                   + 2.0 * (rho * (rho * (s2 + 1.0) + 4.0 * s2 - 2.0) - 2.0))
              + rs * (rho * (5.0 * rho + 18.0) + 12.0)) + 2.0 * rho * rho * r1 * (rho + 2.0)
    q2 = z * (z * (z * ((9.0 - 4.0 * s2) * z + 4.0 * s * (1.0 - 4.0 * rho))
                   + rho * (rho * (5.0 - 4.0 * s2) + 28.0 - 8.0 * s2) + 20.0)
              - 8.0 * rs * r1 * (2.0 * rho + 3.0)) - 4.0 * (rho * r1) ** 2
    q3 = z * (z * (z * (16.0 * rs - 24.0 * z) - 8.0 * r1 * (3.0 * rho + 4.0)) + 16.0 * rs * r1 * r1)
    z2 = z * z
    q4 = (16.0 * z2) * (z2 + r1 * r1)
    return q0, q1, q2, q3, q4


def _product_form(t, v_axial, v_theta, lam, drag_to_lift):
    """``P(1 - t)`` as ``N (N - 2 b M) - c M**2`` (the form of :func:`_bracket_function`, written in ``t``)."""
    eta, t_v_theta, s_v_theta = 1.0 - t, t * v_theta, drag_to_lift * v_theta
    two_eta = eta - t
    n_term = (v_theta * ((2.0 * drag_to_lift * v_axial) * eta + t_v_theta * (3.0 - 4.0 * t))
              + (v_axial * (lam + v_axial)) * two_eta)
    m_term = 2.0 * (s_v_theta + (lam + v_axial) * two_eta) - v_axial
    c = eta * v_theta * (drag_to_lift * v_axial + t_v_theta)
    return n_term * (n_term - (v_axial - s_v_theta) * m_term) - c * m_term * m_term


def _solve(v_axial, v_theta, lam, drag_to_lift, shape):
    """eta2 of every element: ``(eta2, converged)`` of the broadcast ``shape``.

    The bracketed function (:func:`_bracket_function`) in ``t = 1 - eta`` is the polynomial ``Q`` of
    :func:`_taylor_coefficients` (``P``, or ``C = P/t`` in hover, a cubic).  Every element starts from the root of
    a quadratic model (:func:`_start`), takes two Newton steps on ``Q`` (a few flops each), then one on ``P`` in
    its product form, the function :func:`_bracket_function` brackets.  An element is done where that last step
    is inside the bracket and its predicted error ``|step|**2 |Q''/(2 Q')|`` is below an eighth of an ulp of
    ``eta``; the others (0.3 % on the paper's sweep, more in heavy loading ``lam >> V_theta``) are solved by
    :func:`~bild_mdo.utils.newton.bracketed_newton` on [0.5, 1] from that estimate (:func:`_solve_tail`), which
    guarantees convergence with ``P(1/2) > 0 > P(1)``.
    """
    work = shape if shape else (1,)  # 0-d inputs are solved as one element
    hover = v_axial * lam == 0.0
    q = list(_taylor_coefficients(v_axial, v_theta, lam, drag_to_lift))
    at = None
    if np.any(hover):
        # In hover P(1) = 0: the bracketed function is the cubic C = P/t (Eq. (35)), whose coefficients are P's
        # shifted by one.  A station with C(t = 0) >= 0 (lam <= V_theta s/2) is unloaded: eta2 = 1.
        at = np.nonzero(np.broadcast_to(hover, work))
        q = [a if a.shape == work else np.array(np.broadcast_to(a, work)) for a in q]
        for k in range(4):
            q[k][at] = q[k + 1][at]
        q[4][at] = 0.0
        pick = [np.broadcast_to(a, work)[at] for a in (drag_to_lift, v_theta, lam)]
        unloaded = at, ~(pick[0] * pick[1] < 2.0 * pick[2])
    q0, q1, q2, q3, q4 = q
    with np.errstate(all="ignore"):
        t = _start(q0, q1, q2)
        if t.shape != work:
            t = np.array(np.broadcast_to(t, work))
        d1, d2, d3 = 2.0 * q2, 3.0 * q3, 4.0 * q4
        for _ in range(2):
            t -= ((((q4 * t + q3) * t + q2) * t + q1) * t + q0) / (((d3 * t + d2) * t + d1) * t + q1)
        top = d3 * t
        slope = ((top + d2) * t + d1) * t + q1
        curvature = (1.5 * top + d2) * t + q2  # Q''/2
        f = _product_form(t, v_axial, v_theta, lam, drag_to_lift)
        if at is not None:
            f[at] /= t[at]
        step = f / (slope * (lam * lam) ** 2)  # P = lam**4 Q
        t -= step
        done = (np.abs(step * step * curvature) <= (0.125 * _EPS) * slope) & (np.abs(t - 0.25) < 0.25)
    eta = 1.0 - t
    if at is not None:
        eta[at] = np.where(unloaded[1], 1.0, eta[at])
        done[at] |= unloaded[1]
    if not done.all():
        eta, done = _solve_tail(eta, done, v_axial, v_theta, lam, drag_to_lift, work)
    return eta.reshape(shape), done.reshape(shape)


def _start(q0, q1, q2):
    """Root in ``t`` of the quadratic Taylor model at ``y = 0`` of ``(1 + a y)**4 Q(t)``, ``t = y/(1 + a y)``.

    ``a`` is :data:`_START_SHIFT`; with ``a = 0`` this is the quadratic model of ``Q`` at ``eta = 1``,
    whose root is poor for heavily loaded stations.  Its discriminant reduces to
    ``q1**2 - 4 q0 (q2 + a (q1 + 2 a q0))``.
    """
    a = _START_SHIFT
    w = q1 + (2.0 * a) * q0
    root = np.sqrt(np.maximum(q1 * q1 - (4.0 * q0) * (q2 + a * w), 0.0))
    return (-2.0 * q0) / (w + root)


def _solve_tail(eta, done, v_axial, v_theta, lam, drag_to_lift, shape):
    """Bracketed Newton (:func:`_bracket_function` on [0.5, 1]) for the elements not ``done``, from ``eta``."""
    at = np.flatnonzero(~done)
    v_x, v_t, lam, s = (np.broadcast_to(a, shape).ravel()[at] for a in (v_axial, v_theta, lam, drag_to_lift))
    hover = v_x * lam == 0.0
    # Bracket-end values (hand derivations, asserted in tools/derive_quartic.py:derive): P(1/2) > 0
    # (C(1/2) = 2 P(1/2) in hover), P(1) away from hover, C(1) in it.
    sv = s * v_t
    f_lo = np.where(hover, 0.5, 0.25) * v_t * (v_t**2 + v_x**2) * (v_t + 2.0 * s * v_x)
    f_hi = np.where(hover, 2.0 * v_t**2 * (lam + sv) * (sv - 2.0 * lam),
                    -lam * v_x * (v_x + 2.0 * sv) * (lam + v_x + sv))
    x0 = eta.ravel()[at]
    x0 = np.where((x0 > 0.5) & (x0 < 1.0), x0, np.clip(false_position(0.5, 1.0, f_lo, f_hi), 0.501, 1.0 - 1e-12))

    def function(x, idx):
        return _bracket_function(x, v_x[idx], v_t[idx], lam[idx], s[idx], hover[idx])

    result = bracketed_newton(function, np.full(at.size, 0.5), np.ones(at.size), f_lo, x0, max_iter=_MAX_ITERATIONS,
                              quadratic_stop=True)
    eta, done = eta.ravel(), done.ravel()
    eta[at] = result.x
    done[at] = result.converged & (f_lo > 0.0)  # P(0.5) > 0 analytically: without a bracket, reported
    return eta.reshape(shape), done.reshape(shape)


def solve_eta2(v_axial, v_theta, lam, cl, cd, index_names=None):
    """Solve the BILD quartic (Eq. (27)) for the physical annular efficiency eta2.

    Each element is the unique root in (0.5, 1) of the quartic ``P`` (and of
    its physical factor ``h``: ``P = h k`` with ``k > 0`` on [0.5, 1]), so it
    satisfies Eq. (22) with ``u_axial`` from Eq. (26) and ``u_theta`` from
    Eq. (24).  Newton steps from a close explicit start, finished by the
    package's safeguarded Newton iteration on the bracket [0.5, 1] wherever
    they do not converge, give the root to round-off of the bracketed
    function (:func:`_solve`, :func:`_bracket_function`).  The root is unique and the other real root of ``h`` near
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
    arrays, shape = _arrays(v_axial, v_theta, lam, cl, cd)
    _validate(arrays, shape, index_names)
    eta, converged = _solve(arrays[0], arrays[1], arrays[2], arrays[4] / arrays[3], shape)
    if not np.all(converged):
        index = np.unravel_index(np.flatnonzero(~converged)[0], shape)
        at = ", ".join(f"{label}={float(np.broadcast_to(a, shape)[index])!r}"
                       for label, a in zip(("V_x", "V_theta", "lambda", "C_l", "C_d"), arrays))
        raise ValueError(f"eta2 solve did not converge at {_describe(index, index_names)} ({at}); "
                         "please report this case.")
    return eta


class Eta2Comp(om.ImplicitComponent):
    """Annular efficiency eta2 at every station: the physical root of the quartic of Eq. (27).

    Residual (dimensionless)::

        R = P(eta2; V_x, V_theta, lam, s) / (V_theta**2 + V_x**2 + lam**2)**2,   s = C_d*/C_l*,

    where ``P`` (in (m/s)**4) is the quartic derived in
    :mod:`tools.derive_quartic` from Eqs. (22), (24), (26) (the
    paper's printed Eq. (34) is misprinted; see
    :mod:`bild_mdo.bild.variants.paper.quartic`).  The positive per-point scale
    has the units of ``P`` and makes ``R`` O(1) at hub and tip alike; it is
    included in the partials.

    ``solve_nonlinear`` finds the unique root in (0.5, 1) (:func:`solve_eta2`:
    Newton steps from an explicit start, the bracketed solve as fallback).  In hover
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
            bad = failed.any()  # the details and the mask per node only where some station failed
            details = station_details(failed, {"V_x [m/s]": args[0], "V_theta [m/s]": args[1],
                                               "lambda [m/s]": args[2]}) if bad else {}
            report_infeasible(self, "solve", np.any(failed, axis=1) if bad else np.zeros(len(eta), dtype=bool),
                              "eta2 solve: an input is outside its domain or the solve did not converge", details)
        if self.under_complex_step:
            residual = quartic(eta, *self._arguments(inputs))
            slope = quartic_partials(eta, *self._arguments(real), wrt=("eta",))["eta"]
            eta = complex_step_update(eta, residual, slope)
        outputs["eta2"] = eta

    def linearize(self, inputs, outputs, partials):
        v_x, v_t, lam, s = self._arguments(inputs)
        eta = outputs["eta2"]
        scale = self._scale(v_x, v_t, lam)
        p, dp = quartic_and_partials(eta, v_x, v_t, lam, s)
        residual = p / scale
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
