"""Derive the BILD quartic for eta2 (Eq. (27)) with sympy and write ``bild_mdo/bild/variants/paper/quartic.py``.

Run from the repository root::

    python -m tools.derive_quartic           # (re)writes bild_mdo/bild/variants/paper/quartic.py
    python -m tools.derive_quartic --check   # exit status 1 if the committed file is stale

The output is a pure function of this script and the sympy version, so running
the script regenerates the committed module byte for byte.  The test suite
checks the committed module against a fresh symbolic derivation (it compares
expressions, not text, so it does not depend on how sympy prints).  Requires
sympy (the ``test`` extra); the package itself never imports this module.

Derivation (``s = C_d/C_l``, the inverse maximum lift-to-drag ratio)
---------------------------------------------------------------------
Eq. (24) gives ``u_theta = 2 V_theta (1 - eta)``.  Eq. (25) with Eq. (24) is
the quadratic ``u_axial**2 - 2 b u_axial - c = 0`` with::

    b = (V_x - V_theta s) / 2,   c = eta V_theta**2 (1 - eta) + eta V_theta V_x s,

and Eq. (26) is its ``+`` branch ``u+ = b + sqrt(b**2 + c)``.  Multiplying
Eq. (22) by ``2 (2 u_axial - V_x) (V_theta - u_theta)`` and eliminating ``u_axial**2``
with the quadratic leaves an equation that is linear in ``u_axial``:
``2 V_theta (M u_axial - N) = 0`` with::

    M = 2 (lam + V_x)(2 eta - 1) - V_x + 2 V_theta s
    N = (lam + V_x)(2 eta - 1) V_x + V_theta**2 (1 - eta)(2 eta - 1)
        + 2 eta (1 - eta) V_theta**2 + 2 eta V_theta V_x s.

Substituting ``u_axial = N/M`` into the quadratic gives the quartic::

    P(eta) = N**2 - 2 b N M - c M**2 = (N - u+ M)(N - u- M) = h(eta) k(eta).

``h = N - u+ M`` is the physical factor: inside ``0.5 < eta < 1`` (where the
denominators of Eq. (22) are non-zero) ``h = 0`` is equivalent to Eq. (22)
with ``u_axial`` from Eq. (26).  ``k = N - u- M`` belongs to the other branch of
the quadratic.  :func:`derive` asserts each of these identities.

Two facts the solver relies on are checked numerically by the tests (not
proved here): ``k > 0`` on [0.5, 1] (so ``P`` and ``h`` share sign and roots
there), and ``h`` has exactly one root in (0.5, 1).  ``h`` is not free of
spurious roots: in hover ``h(1) = 0`` (``u_axial = u_theta = 0``, where Eq. (22)
is 0/0; this is the factor ``1 - eta`` of Eq. (35)), and for small ``V_x > 0``
the root just above 1 that approaches the physical one near the tip is a root
of ``h``, not of ``k``.  Both lie outside the open bracket (0.5, 1).

The paper's Appendix Eq. (34)
-----------------------------
:func:`paper_eq34_coefficients` transcribes the printed Eq. (34) (in terms of
``J = pi V_x / V_theta`` and ``L/D``).  :func:`derive` proves, and records in
the generated docstring, that:

* as printed (with the ``lambda`` of Eq. (22)) it is *not* proportional to the
  quartic of Eqs. (22), (24), (26);
* its ``lambda`` is twice the ``lambda`` of Eq. (22) (Eqs. (29) and (35) say the
  same), and the term ``-12 lambda pi**6 / ((L/D) V_theta)`` of ``a_1`` has the
  wrong sign (the line break in the printed ``a_1`` reads ``... + \\ - 12 ...``);
* with both corrections, Eq. (34) equals ``-4 pi**6 / V_theta**4`` times the
  quartic derived here, coefficient by coefficient.
"""
import argparse
import pathlib
import sys

import sympy as sp

INPUT_NAMES = ("v_axial", "v_theta", "lam", "drag_to_lift")
TARGET = pathlib.Path(__file__).resolve().parents[1] / "bild_mdo" / "bild" / "variants" / "paper" / "quartic.py"


def symbols():
    """Return the sympy symbols ``(eta, v_axial, v_theta, lam, drag_to_lift)`` (all positive)."""
    return sp.symbols("eta v_axial v_theta lam drag_to_lift", positive=True)


def paper_eq34_coefficients(v_axial, v_theta, lam_paper, lift_to_drag, fix_a1_sign=False, pi=sp.pi):
    """Coefficients ``(a0, ..., a4)`` of the paper's printed Appendix Eq. (34).

    Pure arithmetic, so it accepts sympy expressions or numpy arrays (pass
    ``pi=numpy.pi`` for the latter).

    Parameters
    ----------
    v_axial, v_theta : array_like or sympy expression
        Axial and rotational velocities (m/s); ``J = pi v_axial / v_theta``.
    lam_paper : array_like or sympy expression
        The ``lambda`` of Eq. (34): twice the ``lambda`` of Eq. (22) (m/s).
    lift_to_drag : array_like or sympy expression
        Maximum lift-to-drag ratio ``L/D``.
    fix_a1_sign : bool
        Flip the sign of the ``lambda pi**6 / ((L/D) V_theta)`` term of ``a1``
        (the misprint documented in the module docstring).
    pi : number
        The value of pi to use.

    Returns
    -------
    tuple
        ``(a0, a1, a2, a3, a4)`` as printed (dimensionless).
    """
    j, ld, lam, vt = pi * v_axial / v_theta, lift_to_drag, lam_paper, v_theta
    a1_sign = 1 if fix_a1_sign else -1
    a0 = (-4 * pi**6 + 8 * pi**6 / ld**2 + 4 * j**2 * pi**4 + 8 * j**4 * pi**2 + lam**2 * j**2 * pi**4 / vt**2
          + 6 * lam * j**3 * pi**3 / vt - 4 * lam * pi**6 / (ld * vt) - 20 * j * pi**5 / ld
          - 20 * j**3 * pi**3 / ld + 8 * j**2 * pi**4 / ld**2 - 14 * lam * j**2 * pi**4 / (ld * vt)
          - 2 * lam**2 * j * pi**5 / (ld * vt**2) + 4 * lam * j * pi**5 / (ld**2 * vt))
    a1 = (40 * pi**6 - 24 * pi**6 / ld**2 + 4 * lam**2 * pi**6 / vt**2 + 16 * j**2 * pi**4 - 24 * j**4 * pi**2
          - 4 * lam**2 * j**2 * pi**4 / vt**2 + 24 * lam * j * pi**5 / vt - 20 * lam * j**3 * pi**3 / vt
          + a1_sign * 12 * lam * pi**6 / (ld * vt) + 84 * j * pi**5 / ld + 84 * j**3 * pi**3 / ld
          - 24 * j**2 * pi**4 / ld**2 + 68 * lam * j**2 * pi**4 / (ld * vt) + 12 * lam**2 * j * pi**5 / (ld * vt**2)
          - 16 * lam * j * pi**5 / (ld**2 * vt))
    a2 = (-132 * pi**6 + 16 * pi**6 / ld**2 - 20 * lam**2 * pi**6 / vt**2 - 116 * j**2 * pi**4 + 16 * j**4 * pi**2
          + 4 * lam**2 * j**2 * pi**4 / vt**2 - 104 * lam * j * pi**5 / vt + 16 * lam * j**3 * pi**3 / vt
          - 8 * lam * pi**6 / (ld * vt) - 128 * j * pi**5 / ld - 128 * j**3 * pi**3 / ld
          + 16 * j**2 * pi**4 / ld**2 - 112 * lam * j**2 * pi**4 / (ld * vt) - 24 * lam**2 * j * pi**5 / (ld * vt**2)
          + 16 * lam * j * pi**5 / (ld**2 * vt))
    a3 = (160 * pi**6 + 32 * lam**2 * pi**6 / vt**2 + 160 * j**2 * pi**4 + 144 * lam * j * pi**5 / vt
          + 64 * j * pi**5 / ld + 64 * j**3 * pi**3 / ld + 64 * lam * j**2 * pi**4 / (ld * vt)
          + 16 * lam**2 * j * pi**5 / (ld * vt**2))
    a4 = -64 * pi**6 - 64 * j**2 * pi**4 - 16 * lam**2 * pi**6 / vt**2 - 64 * lam * j * pi**5 / vt
    return a0, a1, a2, a3, a4


def derive():
    """Derive the quartic and its physical factor symbolically, asserting every step.

    Returns
    -------
    dict
        ``symbols``: ``(eta, v_axial, v_theta, lam, drag_to_lift)``;
        ``coefficients``: ``[a0, ..., a4]`` of ``P`` (Eq. (27));
        ``coefficient_partials``: ``{name: [da0, ..., da4]}`` for every input;
        ``terms``: ``[N, M, b, c]``; ``term_partials``: ``{name: [dN, dM, db, dc]}``
        for ``eta`` and every input.
    """
    eta, vx, vt, lam, s = symbols()
    u = sp.Symbol("u_axial")
    u_theta = 2 * vt * (1 - eta)  # Eq. (24)
    b = (vx - vt * s) / 2
    c = eta * vt**2 * (1 - eta) + eta * vt * vx * s
    quadratic = u**2 - 2 * b * u - c

    # Eq. (25) with C_d/C_l = s and V_theta - u_theta/2 = eta V_theta, cleared of its denominators.
    eq25 = 2 * (u - vx) * (u + s * eta * vt) - u_theta * (eta * vt - s * u)
    assert sp.expand(eq25 - 2 * quadratic) == 0

    # Eq. (22) times 2 (2 u_axial - V_x)(V_theta - u_theta), then u_axial**2 eliminated with the quadratic.
    lhs = lam * 2 * (2 * u - vx) * (vt - u_theta)
    rhs = vt * u_theta * (vt - u_theta) + 2 * vt * u * (2 * u - vx) - 2 * vx * (2 * u - vx) * (vt - u_theta)
    linear = sp.expand(sp.expand(lhs - rhs).subs(u**2, 2 * b * u + c))
    assert sp.degree(linear, u) == 1
    m_term = 2 * (lam + vx) * (2 * eta - 1) - vx + 2 * vt * s
    n_term = ((lam + vx) * (2 * eta - 1) * vx + vt**2 * (1 - eta) * (2 * eta - 1)
              + 2 * eta * (1 - eta) * vt**2 + 2 * eta * vt * vx * s)
    assert sp.expand(linear - 2 * vt * (m_term * u - n_term)) == 0

    quartic = sp.expand(n_term**2 - 2 * b * n_term * m_term - c * m_term**2)
    root = sp.sqrt(b**2 + c)
    assert sp.expand(quartic - sp.expand((n_term - (b + root) * m_term) * (n_term - (b - root) * m_term))) == 0
    coefficients = sp.Poly(quartic, eta).all_coeffs()[::-1]
    assert len(coefficients) == 5

    # Bracket ends (Theorem 1), derived by hand and re-checked here.
    assert sp.expand(quartic.subs(eta, 1) + lam * vx * (vx + 2 * s * vt) * (lam + vx + s * vt)) == 0
    assert sp.expand(quartic.subs(eta, sp.Rational(1, 2)) - vt * (vt**2 + vx**2) * (vt + 2 * s * vx) / 4) == 0
    # Hover: P = (1 - eta) C with the cubic C bracketed by the eta2 solver, and C(1).
    m_hover = m_term.subs(vx, 0)
    cubic = vt**2 * (vt**2 * (1 - eta) * (4 * eta - 1)**2 + s * vt * (4 * eta - 1) * m_hover - eta * m_hover**2)
    assert sp.expand(quartic.subs(vx, 0) - (1 - eta) * cubic) == 0
    assert sp.expand(cubic.subs(eta, 1) - 2 * vt**2 * (lam + s * vt) * (s * vt - 2 * lam)) == 0

    # The printed Eq. (34): wrong as printed; right with lambda_paper = 2 lambda and the a1 sign fixed.
    scale = -4 * sp.pi**6 / vt**4
    printed = paper_eq34_coefficients(vx, vt, lam, 1 / s)
    assert any(sp.simplify(p - scale * q) != 0 for p, q in zip(printed, coefficients))
    doubled = paper_eq34_coefficients(vx, vt, 2 * lam, 1 / s)
    mismatch = [k for k in range(5) if sp.simplify(doubled[k] - scale * coefficients[k]) != 0]
    assert mismatch == [1]
    assert sp.simplify(doubled[1] - scale * coefficients[1] + 48 * sp.pi**6 * lam * s / vt) == 0
    fixed = paper_eq34_coefficients(vx, vt, 2 * lam, 1 / s, fix_a1_sign=True)
    assert all(sp.simplify(p - scale * q) == 0 for p, q in zip(fixed, coefficients))

    # The terms as the generated module evaluates them: with explicit (1 - eta) factors, because 1 - eta is
    # exact in floating point for 0.5 <= eta <= 1 while expanded forms cancel catastrophically near eta = 1.
    terms = [
        (lam + vx) * (2 * eta - 1) * vx + vt**2 * (1 - eta) * (4 * eta - 1) + 2 * eta * vt * vx * s,
        2 * (lam + vx) * (2 * eta - 1) - vx + 2 * vt * s,
        (vx - vt * s) / 2,
        eta * vt * (vt * (1 - eta) + vx * s),
    ]
    for term, reference in zip(terms, (n_term, m_term, b, c)):
        assert sp.expand(term - reference) == 0

    inputs = dict(zip(INPUT_NAMES, (vx, vt, lam, s)))
    coefficient_partials = {name: [sp.diff(a, sym) for a in coefficients] for name, sym in inputs.items()}
    term_partials = {name: [sp.diff(t, sym) for t in terms]
                     for name, sym in dict(eta=eta, **inputs).items()}
    return dict(symbols=(eta, vx, vt, lam, s), coefficients=coefficients,
                coefficient_partials=coefficient_partials, terms=terms, term_partials=term_partials)


def _code(expr, factor=True):
    """Python source for a polynomial expression (the symbol names are the argument names)."""
    if factor:
        expr = sp.factor(expr)
    text = sp.pycode(expr, fully_qualified_modules=False)
    assert "math" not in text and "sqrt" not in text
    return text


_HEADER = '''"""Coefficients of the BILD quartic P(eta2) (Eq. (27)) and of its physical factor, with first partials.

GENERATED by ``python -m tools.derive_quartic`` -- do not edit by hand;
edit the generator and rerun it.  The derivation and the identities it asserts
are in that script's docstring.

With ``s = drag_to_lift = C_d/C_l`` and ``lam`` the ideal-loading constant of
Eq. (22)::

    P(eta) = a4 eta**4 + a3 eta**3 + a2 eta**2 + a1 eta + a0        Eq. (27)
           = N**2 - 2 b N M - c M**2 = h(eta) k(eta),
    h = N - u+ M   (physical factor),   u+ = b + sqrt(b**2 + c)     Eq. (26)

where ``u_axial = N/M`` is Eq. (22) made linear in ``u_axial`` and ``u_axial**2 - 2 b u_axial
- c = 0`` is Eq. (25).  Inside ``0.5 < eta < 1`` the roots of ``h`` are
exactly the solutions of Eq. (22) with Eqs. (24) and (26).  Closed forms at
the bracket ends (hand derivation, asserted by the generator)::

    P(1/2) = V_theta (V_theta**2 + V_x**2)(V_theta + 2 s V_x) / 4 > 0
    P(1)   = -lam V_x (V_x + 2 s V_theta)(lam + V_x + s V_theta)      (<= 0)
    h(1)   = -lam V_x

``P`` is in (m/s)**4.  With the paper's ``lambda = 2 lam`` (below), its
Eqs. (28) and (29) are ``-4 V_theta**2 P(1/2)`` and ``-4 V_theta**2 P(1)``
(the overall sign is arbitrary), and in hover ``P = V_theta**2 (eta - 1)``
times the cubic in brackets of Eq. (35).

:func:`quartic` and :func:`quartic_partials` evaluate ``P`` in the product
form ``N**2 - 2 b N M - c M**2`` with explicit ``1 - eta`` factors (exact in
floating point for 0.5 <= eta <= 1); summing the expanded coefficients
cancels catastrophically near ``eta = 1`` (``dP/deta`` at roots of the test
domain was off by up to 1.5e-7 relative).  The coefficient functions are kept
for reference and for the comparison with the paper.

Pitfall: the paper's Appendix Eq. (34) is misprinted
-----------------------------------------------------
Proved symbolically by the generator:

* As printed, with the ``lambda`` of Eq. (22), Eq. (34) is not proportional to
  this quartic, so its roots do not satisfy Eq. (22).
* Its ``lambda`` is twice the ``lambda`` of Eq. (22) (so are those of
  Eqs. (29) and (35); Eq. (28) does not contain ``lambda``).
* Even with ``lambda -> 2 lambda`` one coefficient is wrong: the term
  ``-12 lambda pi**6 / ((L/D) V_theta)`` of ``a1`` must be ``+12 ...``; the
  printed difference is ``-48 pi**6 lambda s / V_theta`` (in this module's
  ``lam``).
* With both corrections, Eq. (34) is ``-4 pi**6 / V_theta**4`` times ``P``.

Every function is pure arithmetic on broadcastable arrays (complex-step safe);
``physical_factor`` and ``physical_factor_partials`` choose the cancellation-free
form of ``u+`` on the real part of ``b``.
"""
import numpy as np

INPUT_NAMES = ("v_axial", "v_theta", "lam", "drag_to_lift")
'''

_QUARTIC_HELPERS = '''

def quartic(eta, v_axial, v_theta, lam, drag_to_lift):
    """The quartic ``P(eta)`` of Eq. (27), (m/s)**4, evaluated as ``N**2 - 2 b N M - c M**2``.

    This is the same polynomial as ``sum(a_k eta**k)``, but its rounding error
    scales with the terms that cancel at the root rather than with the (much
    larger) coefficients, which matters near ``eta = 1``.
    """
    n_term, m_term, b, c = physical_factor_terms(eta, v_axial, v_theta, lam, drag_to_lift)
    return n_term * (n_term - 2.0 * b * m_term) - c * m_term * m_term


def quartic_partials(eta, v_axial, v_theta, lam, drag_to_lift, wrt=("eta",) + INPUT_NAMES):
    """First partials of ``P(eta)`` (same form as :func:`quartic`): ``{name: dP/dname for name in wrt}``."""
    return quartic_and_partials(eta, v_axial, v_theta, lam, drag_to_lift, wrt)[1]


def quartic_and_partials(eta, v_axial, v_theta, lam, drag_to_lift, wrt=("eta",) + INPUT_NAMES):
    """:func:`quartic` and :func:`quartic_partials` from one evaluation of ``N, M, b, c``.

    ``dP = 2 (N - b M) dN - 2 (b N + c M) dM - 2 N M db - M**2 dc``; a term whose partial is the
    number 0 is left out (each array operation counts in component partials).
    """
    n_term, m_term, b, c = physical_factor_terms(eta, v_axial, v_theta, lam, drag_to_lift)
    factors = (2.0 * (n_term - b * m_term), -2.0 * (b * n_term + c * m_term), -2.0 * n_term * m_term,
               -m_term * m_term)
    partials = {name: sum(f * d for f, d in zip(factors, terms) if not (np.isscalar(d) and d == 0))
                for name, terms in physical_factor_term_partials(
                    eta, v_axial, v_theta, lam, drag_to_lift, wrt=wrt).items()}
    return n_term * (n_term - 2.0 * b * m_term) - c * m_term * m_term, partials
'''

_FACTOR_HELPERS = '''

def axial_velocity_root(b, c):
    """``(u+, r)`` with ``r = sqrt(b**2 + c)`` and ``u+ = b + r`` (Eq. (26)) without cancellation.

    For ``b < 0`` the product of the roots, ``u+ u- = -c``, gives
    ``u+ = c / (r - b)``, which keeps full relative accuracy when ``c`` is
    small (near ``eta = 1`` in hover).
    """
    r = np.sqrt(b * b + c)
    positive = np.real(b) >= 0.0
    u_plus = np.where(positive, b + r, c / np.where(positive, 1.0, r - b))
    return u_plus, r


def physical_factor(eta, v_axial, v_theta, lam, drag_to_lift):
    """The physical factor ``h = N - u+ M`` of ``P``, (m/s)**2, and ``u+`` (Eq. (26)), m/s."""
    n_term, m_term, b, c = physical_factor_terms(eta, v_axial, v_theta, lam, drag_to_lift)
    u_plus, _ = axial_velocity_root(b, c)
    return n_term - u_plus * m_term, u_plus


def physical_factor_partials(eta, v_axial, v_theta, lam, drag_to_lift, wrt=("eta",) + INPUT_NAMES):
    """First partials of ``h = N - u+ M``: ``{name: dh/dname for name in wrt}``.

    ``du+ = (2 u+ db + dc) / (2 r)`` follows from differentiating the quadratic
    ``u**2 - 2 b u - c = 0`` (Eq. (25)), with ``u+ - b = r > 0``.
    """
    n_term, m_term, b, c = physical_factor_terms(eta, v_axial, v_theta, lam, drag_to_lift)
    u_plus, r = axial_velocity_root(b, c)
    partials = {}
    for name, (dn, dm, db, dc) in physical_factor_term_partials(
            eta, v_axial, v_theta, lam, drag_to_lift, wrt=wrt).items():
        du = (2.0 * u_plus * db + dc) / (2.0 * r)
        partials[name] = dn - du * m_term - u_plus * dm
    return partials
'''


def render():
    """Return the text of ``bild_mdo/bild/variants/paper/quartic.py``."""
    d = derive()
    args = ", ".join(INPUT_NAMES)
    zero = "    zero = 0.0 * (v_axial + v_theta + lam + drag_to_lift)\n"
    lines = [_HEADER, "\n\n"]
    lines.append(f"def quartic_coefficients({args}):\n")
    lines.append('    """Coefficients ``(a0, ..., a4)`` of ``P(eta)`` (Eq. (27)), broadcast over the inputs."""\n')
    lines.append(zero)
    for k, a in enumerate(d["coefficients"]):
        lines.append(f"    a{k} = {_code(a)} + zero\n")
    lines.append("    return a0, a1, a2, a3, a4\n\n\n")

    lines.append(f"def quartic_coefficient_partials({args}):\n")
    lines.append('    """``{name: (da0/dname, ..., da4/dname) for name in INPUT_NAMES}``."""\n')
    lines.append(zero)
    lines.append("    return {\n")
    for name in INPUT_NAMES:
        body = ", ".join(f"{_code(e)} + zero" for e in d["coefficient_partials"][name])
        lines.append(f'        "{name}": ({body}),\n')
    lines.append("    }\n\n\n")

    lines.append(f"def physical_factor_terms(eta, {args}):\n")
    lines.append('    """``(N, M, b, c)``: ``u_axial = N/M`` (Eq. (22) made linear); ``u_axial`` solves '
                 '``u_axial**2 - 2 b u_axial - c = 0`` (Eq. (25))."""\n')
    lines.append("    zero = 0.0 * (eta + v_axial + v_theta + lam + drag_to_lift)\n")
    for label, t in zip(("n_term", "m_term", "b", "c"), d["terms"]):
        lines.append(f"    {label} = {_code(t, factor=False)} + zero\n")
    lines.append("    return n_term, m_term, b, c\n\n\n")

    lines.append(f'def physical_factor_term_partials(eta, {args}, wrt=("eta",) + INPUT_NAMES):\n')
    lines.append('    """``{name: (dN, dM, db, dc) for name in wrt}`` for ``name`` in ``("eta",) + INPUT_NAMES``.\n\n'
                 '    Not broadcast to a common shape (a constant partial is a number): they enter products\n'
                 '    with ``N, M, b, c``, which are (component partials pay for every array operation).\n'
                 '    """\n')
    lines.append("    partials = {}\n")
    for name in ("eta",) + INPUT_NAMES:
        body = ", ".join(f"{_code(e, factor=False)}" for e in d["term_partials"][name])
        lines.append(f'    if "{name}" in wrt:\n        partials["{name}"] = ({body})\n')
    lines.append("    return partials\n")
    lines.append(_QUARTIC_HELPERS)
    lines.append(_FACTOR_HELPERS)
    return "".join(lines)


def main(argv=None):
    """Write (or with ``--check``, verify) ``bild_mdo/bild/variants/paper/quartic.py``; return the exit status."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 if the committed file differs")
    args = parser.parse_args(argv)
    text = render()
    if args.check:
        current = TARGET.read_text() if TARGET.exists() else ""
        if current != text:
            print(f"{TARGET} is stale; run python -m tools.derive_quartic")
            return 1
        print(f"{TARGET} is up to date")
        return 0
    TARGET.write_text(text)
    print(f"wrote {TARGET}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
