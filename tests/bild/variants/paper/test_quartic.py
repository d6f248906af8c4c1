"""The BILD quartic for eta2 (Eq. (27)): derivation, closed forms, and the misprinted Appendix Eq. (34)."""
import numpy as np
import pytest
import sympy as sp

from bild_mdo.bild.variants.paper import quartic as qc
from tools.derive_quartic import derive, paper_eq34_coefficients


def eq22_lambda(eta, v_x, v_t, s):
    """Eq. (22) with u_theta from Eq. (24) and u_axial from Eq. (26), evaluated in extended precision.

    Eq. (26) is used in its rationalised form ``u_axial = c / (sqrt(b**2 + c) - b)`` when ``b < 0`` (the same
    number; it avoids cancellation near eta = 1) so the check is limited by eta's rounding only.
    """
    eta, v_x, v_t, s = (np.asarray(a, dtype=np.longdouble) for a in (eta, v_x, v_t, s))
    u_t = 2 * v_t * (1 - eta)  # Eq. (24)
    b = (v_x - v_t * s) / 2
    c = eta * v_t**2 * (1 - eta + v_x / v_t * s)
    r = np.sqrt(b * b + c)
    u_axial = np.where(b >= 0, b + r, c / np.where(b >= 0, 1, r - b))  # Eq. (26)
    return v_t * u_t / (2 * (2 * u_axial - v_x)) + v_t * u_axial / (v_t - u_t) - v_x


def random_domain(n, seed):
    """V_x in [0, 150] (a fifth exactly 0), V_theta in [1, 300], L/D in [5, 200], lambda log-uniform in [0.5, 100];
    in hover lambda is redrawn above the existence threshold V_theta/(2 L/D)."""
    rng = np.random.default_rng(seed)
    v_x = rng.uniform(0.0, 150.0, n)
    v_x[rng.random(n) < 0.2] = 0.0
    v_t = rng.uniform(1.0, 300.0, n)
    s = 1.0 / rng.uniform(5.0, 200.0, n)
    lam = np.exp(rng.uniform(np.log(0.5), np.log(100.0), n))
    redraw = (v_x == 0.0) & (2.0 * lam <= s * v_t)
    lam[redraw] = 0.5 * s[redraw] * v_t[redraw] * np.exp(rng.uniform(1e-6, np.log(50.0), redraw.sum()))
    return v_x, v_t, lam, s


def horner(coefficients, eta):
    a0, a1, a2, a3, a4 = coefficients
    return (((a4 * eta + a3) * eta + a2) * eta + a1) * eta + a0


def test_generated_module_matches_fresh_derivation():
    # The committed quartic_coefficients.py is the output of derive_quartic.py: evaluating its (pure-arithmetic)
    # functions on sympy symbols must give exactly the freshly derived expressions.
    d = derive()
    eta, v_x, v_t, lam, s = d["symbols"]

    def same(generated, derived):
        return sp.expand(sp.nsimplify(generated) - derived) == 0

    assert all(map(same, qc.quartic_coefficients(v_x, v_t, lam, s), d["coefficients"]))
    partials = qc.quartic_coefficient_partials(v_x, v_t, lam, s)
    for name in qc.INPUT_NAMES:
        assert all(map(same, partials[name], d["coefficient_partials"][name]))
    assert all(map(same, qc.physical_factor_terms(eta, v_x, v_t, lam, s), d["terms"]))
    term_partials = qc.physical_factor_term_partials(eta, v_x, v_t, lam, s)
    for name in ("eta",) + qc.INPUT_NAMES:
        assert all(map(same, term_partials[name], d["term_partials"][name]))
    # The product form used by the solver is the same polynomial as sum(a_k eta**k).
    assert same(qc.quartic(eta, v_x, v_t, lam, s), horner(d["coefficients"], eta))


def test_quartic_root_satisfies_eq22():
    # Eq. (27) must be Eq. (22) rewritten: its real roots in (0.5, 1), polished by Newton on P, satisfy Eq. (22)
    # (with Eqs. (24), (26)); exactly one root lies there (V_x > 0; in hover eta = 1 is the extra root, Eq. (35)).
    v_x, v_t, lam, s = random_domain(400, seed=3)
    for i in range(v_x.size):
        args = (v_x[i], v_t[i], lam[i], s[i])
        roots = np.roots(np.array(qc.quartic_coefficients(*args))[::-1])
        real = np.real(roots[(np.abs(np.imag(roots)) < 1e-7) & (np.real(roots) > 0.5) & (np.real(roots) < 1 - 1e-7)])
        assert real.size == 1, (args, roots)
        eta = real[0]
        for _ in range(3):
            eta -= qc.quartic(eta, *args) / qc.quartic_partials(eta, *args, wrt=("eta",))["eta"]
        assert 0.5 < eta < 1.0
        assert abs(eq22_lambda(eta, v_x[i], v_t[i], s[i]) - lam[i]) <= 1e-9 * lam[i]


def test_bracket_end_closed_forms():
    # Hand derivation: at eta = 1/2, u_theta = V_theta, M = 2 V_theta s - V_x, N = V_theta (V_theta/2 + V_x s);
    # at eta = 1, u+ = V_x and u- = -s V_theta.  Paper Eqs. (28), (29) are -4 V_theta**2 times these with the
    # paper's lambda = 2 lambda (the appendix convention, see test_printed_eq34_...).
    v_x, v_t, lam, s = random_domain(1000, seed=4)
    p_half = v_t * (v_t**2 + v_x**2) * (v_t + 2 * s * v_x) / 4
    p_one = -lam * v_x * (v_x + 2 * s * v_t) * (lam + v_x + s * v_t)
    coefficients = qc.quartic_coefficients(v_x, v_t, lam, s)
    scale = (v_t**2 + v_x**2 + lam**2) ** 2
    for value, eta in ((p_half, 0.5), (p_one, 1.0)):
        np.testing.assert_allclose(horner(coefficients, eta) / scale, value / scale, rtol=0, atol=1e-13)
        np.testing.assert_allclose(qc.quartic(eta, v_x, v_t, lam, s) / scale, value / scale, rtol=0, atol=1e-13)
    eq28 = -v_t**3 * (2 * v_x * s + v_t) * (v_t**2 + v_x**2)
    eq29 = v_x * v_t**2 * (2 * lam) * (2 * v_t * s + v_x) * (2 * lam + 2 * v_t * s + 2 * v_x)
    np.testing.assert_allclose(eq28, -4 * v_t**2 * p_half, rtol=1e-13)
    np.testing.assert_allclose(eq29, -4 * v_t**2 * p_one, rtol=1e-13)
    assert np.all(p_half > 0) and np.all(p_one[v_x > 0] < 0)
    # The physical factor at the bracket ends: h(1) = -lam V_x (u+(1) = V_x), h(0.5) > 0.
    h_one, u_one = qc.physical_factor(1.0, v_x, v_t, lam, s)
    np.testing.assert_allclose(u_one, v_x, rtol=1e-13, atol=1e-12)
    np.testing.assert_allclose(h_one, -lam * v_x, rtol=1e-9, atol=1e-9)
    assert np.all(qc.physical_factor(0.5, v_x, v_t, lam, s)[0] > 0)


def test_hover_factorisation_matches_eq35():
    # Paper Eq. (35): at V_x = 0, P = const * (eta - 1) * [cubic].  Our P equals V_theta**2 (eta - 1) times the
    # printed cubic with the appendix's lambda = 2 lambda; with lambda as in Eq. (22) it does not factor so.
    eta, v_x, v_t, lam, s = sp.symbols("eta v_axial v_theta lam s", positive=True)
    p_hover = horner(qc.quartic_coefficients(0, v_t, lam, s), eta)
    ld = 1 / s

    def eq35_cubic(lp):
        return ((4 * lp**2 + 16 * v_t**2) * eta**3 - (4 * lp**2 + 24 * v_t**2) * eta**2
                + (lp**2 + 9 * v_t**2 - 4 * v_t**2 / ld**2 + 2 * v_t * lp / ld) * eta
                - v_t**2 + 2 * v_t**2 / ld**2 - v_t * lp / ld)

    assert sp.expand(p_hover - v_t**2 * (eta - 1) * eq35_cubic(2 * lam)) == 0
    assert sp.cancel(p_hover / ((eta - 1) * eq35_cubic(lam))).has(eta)


def test_printed_eq34_violates_eq22_and_corrected_eq34_matches():
    # Documents the pitfall: the printed Appendix Eq. (34) does not reproduce Eq. (22), neither with its lambda
    # read as Eq. (22)'s nor doubled; doubled and with the sign of a1's 12 lambda pi^6/((L/D) V_theta) term flipped,
    # it is -4 pi^6/V_theta^4 times our quartic (both facts proved symbolically in derive_quartic.derive()).
    v_x, v_t, lam, s = np.array([20.0, 60.0]), np.array([80.0, 150.0]), np.array([15.0, 5.0]), np.array([0.02, 0.05])
    eta_ours = []
    for i in range(2):
        args = (v_x[i], v_t[i], lam[i], s[i])
        roots = np.roots(np.array(qc.quartic_coefficients(*args))[::-1])
        eta_ours.append(float(np.real(roots[(np.abs(roots.imag) < 1e-9) & (roots.real > 0.5) & (roots.real < 1)])[0]))
        for lam_paper, fixed in ((lam[i], False), (2 * lam[i], False)):
            printed = paper_eq34_coefficients(v_x[i], v_t[i], lam_paper, 1 / s[i], fix_a1_sign=fixed, pi=np.pi)
            roots = np.roots(np.array(printed)[::-1])
            candidates = np.real(roots[(np.abs(roots.imag) < 1e-9) & (roots.real > 0.5) & (roots.real < 1)])
            errors = [abs(eq22_lambda(e, v_x[i], v_t[i], s[i]) - lam[i]) / lam[i] for e in candidates]
            assert all(err > 1e-2 for err in errors), (lam_paper, candidates, errors)
        corrected = paper_eq34_coefficients(v_x[i], v_t[i], 2 * lam[i], 1 / s[i], fix_a1_sign=True, pi=np.pi)
        ours = qc.quartic_coefficients(*args)
        np.testing.assert_allclose(np.array(corrected), -4 * np.pi**6 / v_t[i] ** 4 * np.array(ours), rtol=1e-10)
    np.testing.assert_allclose(eq22_lambda(np.array(eta_ours), v_x, v_t, s), lam, rtol=1e-10)


def test_quartic_is_physical_factor_times_positive_cofactor():
    # P = h k with k = N - u- M (Eq. (26)'s other branch); k > 0 on [0.5, 1] (here: >= 1/3 of its own terms),
    # so P and h share their sign and roots there.
    v_x, v_t, lam, s = random_domain(20000, seed=5)
    worst = np.inf
    for eta in np.linspace(0.5, 1.0, 101):
        n_term, m_term, b, c = qc.physical_factor_terms(eta, v_x, v_t, lam, s)
        h, _ = qc.physical_factor(eta, v_x, v_t, lam, s)
        r = np.sqrt(b * b + c)
        u_minus = np.where(b <= 0, b - r, -c / np.where(b <= 0, 1.0, b + r))  # Eq. (26), other sign
        k = n_term - u_minus * m_term
        p = qc.quartic(eta, v_x, v_t, lam, s)
        terms = n_term**2 + np.abs(2 * b * n_term * m_term) + np.abs(c) * m_term**2 + np.finfo(float).tiny
        np.testing.assert_allclose(p / terms, h * k / terms, rtol=0, atol=1e-12)
        worst = min(worst, np.min(k / (np.abs(n_term) + np.abs(u_minus * m_term))))
    assert worst > 0.3


@pytest.mark.parametrize("function", ["coefficients", "quartic", "physical_factor"])
def test_partials_against_complex_step(function):
    v_x, v_t, lam, s = random_domain(200, seed=6)
    eta = np.random.default_rng(7).uniform(0.5, 1.0, v_x.size)
    values = dict(eta=eta, v_axial=v_x, v_theta=v_t, lam=lam, drag_to_lift=s)
    if function == "coefficients":
        def f(**kw):
            return np.array(qc.quartic_coefficients(*(kw[n] for n in qc.INPUT_NAMES)))
        analytic = {k: np.array(v) for k, v in qc.quartic_coefficient_partials(v_x, v_t, lam, s).items()}
    elif function == "quartic":
        def f(**kw):
            return qc.quartic(**kw)
        analytic = qc.quartic_partials(**values)
    else:
        def f(**kw):
            return qc.physical_factor(**kw)[0]
        analytic = qc.physical_factor_partials(**values)
    step = 1e-30
    for name, derivative in analytic.items():
        perturbed = dict(values)
        perturbed[name] = values[name] + 1j * step
        expected = np.imag(f(**perturbed)) / step
        scale = np.max(np.abs(expected)) + 1e-300
        np.testing.assert_allclose(derivative / scale, expected / scale, rtol=0, atol=1e-12, err_msg=name)
