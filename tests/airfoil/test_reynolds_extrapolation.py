"""The tabulated polar past its Reynolds-number range: the C^1 continuation of TabulatedPolar.

Hand derivation (TabulatedPolar docstring), with ``L = log10 Re``, an edge ``L_e``
of the table, ``d = L - L_e`` and the edge's value ``f(alpha)`` and slope ``s = df/dL``, ``m = s / f``.
Above the table:

    cl = f + d s,    cd = f exp(d m) = f (Re / Re_e)^(m / ln 10).

Below it, the same saturating (``C, K`` = LOW_REYNOLDS_BOUNDS):

    cl = f + C tanh(d s / C),    cd = f exp(K tanh(d m / K)).

All match the edge's value and slope, and ``cd`` is positive wherever ``f`` is.  Their second
derivatives in ``L`` are ``0`` (lift) and ``cd m**2`` (drag) above, and with ``x = d s / C``, ``y = d m / K``
below: ``-2 s**2 / C tanh x sech**2 x`` (lift) and ``cd (G_LL + G_L**2)``, ``G_L = m sech**2 y``,
``G_LL = -2 m**2 / K tanh y sech**2 y`` (drag); in ``Re`` (``dL/dRe = 1 / (Re ln 10)``)::

    c_Re = c_L / (Re ln 10),   c_ReRe = (c_LL / ln 10 - c_L) / (Re**2 ln 10).
"""
import warnings

import numpy as np
import pytest

from bild_mdo.airfoil import AnalyticPolar, TabulatedPolar, naca4412
from bild_mdo.airfoil.sources import PolarData
from bild_mdo.airfoil.surrogate import LOW_REYNOLDS_BOUNDS
from bild_mdo.airfoil.surrogate_terms import extrapolate_log_reynolds
from bild_mdo.bild.variants.reference_point.reference_airfoil import ReferenceAirfoilComp
from bild_mdo.utils.testing import check_component_partials
from tests.bild.conftest import NN, state

H = 1e-30
LN10 = np.log(10.0)
# Attached flow, the stall blends and deep stall.
ALPHA = np.radians(np.array([-12.0, -4.1, 0.3, 3.7, 6.2, 9.9, 13.3, 17.8, 40.0, 120.0]))
TABLE_RE = (5e4, 1e5, 3e5, 1e6, 2e6)

pytestmark = pytest.mark.filterwarnings("ignore:.*Reynolds numbers outside the tabulated range:UserWarning")


def _analytic_tables():
    # Drag of the source polar scales with Re^-0.2 (turbulent skin friction).
    source = AnalyticPolar(reynolds_exponent=0.2, cl0=0.35)
    alpha = np.arange(-10.0, 20.01, 0.5)
    return [PolarData(re, 0.0, alpha, *source.evaluate(np.radians(alpha), re)[:2], f"analytic {re:g}")
            for re in TABLE_RE]


@pytest.fixture(scope="module", params=["naca4412", "synthetic"])
def polar(request):
    if request.param == "naca4412":
        return naca4412()
    return TabulatedPolar(_analytic_tables(), name="synthetic")


def _edges(polar):
    return (polar.reynolds[0], polar.reynolds[-1])


def _edge_slopes(polar, re_edge):
    """Edge value, slope d/dlog10(Re) and its alpha derivative, from the public first and second derivatives."""
    v = polar.evaluate(ALPHA, re_edge)
    s = polar.second_derivatives(ALPHA, re_edge)
    scale = re_edge * LN10
    return v, s, scale


@pytest.mark.parametrize("side", [0, 1])
def test_value_and_slopes_continuous_at_both_edges(polar, side):
    re_edge = _edges(polar)[side]
    outward = 1.0 + (1e-9 if side else -1e-9)
    v_in, s_in, _ = _edge_slopes(polar, re_edge)
    v_out = polar.evaluate(ALPHA, re_edge * outward)
    s_out = polar.second_derivatives(ALPHA, re_edge * outward)
    # Values, alpha slopes, Re slopes per unit log Re (Re d/dRe), alpha curvature and the cross terms.
    np.testing.assert_allclose(v_out.cl, v_in.cl, atol=1e-8)
    np.testing.assert_allclose(v_out.cd, v_in.cd, rtol=1e-8)
    for field in ("dcl_dalpha", "dcd_dalpha"):
        np.testing.assert_allclose(getattr(v_out, field), getattr(v_in, field), atol=1e-6)
    for field in ("dcl_dre", "dcd_dre"):
        np.testing.assert_allclose(getattr(v_out, field) * re_edge, getattr(v_in, field) * re_edge, atol=1e-7)
    for field in ("d2cl_dalpha2", "d2cd_dalpha2"):
        np.testing.assert_allclose(getattr(s_out, field), getattr(s_in, field), rtol=1e-6, atol=1e-5)
    for field in ("d2cl_dalpha_dre", "d2cd_dalpha_dre"):
        np.testing.assert_allclose(getattr(s_out, field) * re_edge, getattr(s_in, field) * re_edge, atol=1e-6)
    # Not a clamp: the Re slope is really there on both sides.
    assert np.max(np.abs(v_out.dcd_dre * re_edge)) > 1e-4


@pytest.mark.parametrize("side, factor", [(0, 1 / 3), (0, 1e-3), (1, 4.0), (1, 1e3)])
def test_matches_the_extrapolation_formula(polar, side, factor):
    # Above: cl = f + d s, cd = f (Re/Re_e)^(m / ln 10); below: cl = f + C tanh(d s / C),
    # cd = f exp(K tanh(d m / K)); s the edge's d/dlog10(Re), m = s / f (module docstring).
    re_edge = _edges(polar)[side]
    v_edge, _, scale = _edge_slopes(polar, re_edge)
    v = polar.evaluate(ALPHA, re_edge * factor)
    d = np.log10(factor)
    s_cl, s_cd = v_edge.dcl_dre * scale, v_edge.dcd_dre * scale
    m = s_cd / v_edge.cd
    if side == 1:
        np.testing.assert_allclose(v.cl, v_edge.cl + d * s_cl, rtol=1e-12, atol=1e-13)
        np.testing.assert_allclose(v.cd, v_edge.cd * factor ** (m / LN10), rtol=1e-12)
        # d/dRe = d/dL / (Re ln 10): cl's slope per unit log Re stays the edge's; cd's is cd s / f.
        np.testing.assert_allclose(v.dcl_dre * re_edge * factor * LN10, s_cl, rtol=1e-12, atol=1e-14)
        np.testing.assert_allclose(v.dcd_dre * re_edge * factor * LN10, v.cd * m, rtol=1e-12)
        return
    c, k = LOW_REYNOLDS_BOUNDS
    x, y = d * s_cl / c, d * m / k
    np.testing.assert_allclose(v.cl, v_edge.cl + c * np.tanh(x), rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(v.cd, v_edge.cd * np.exp(k * np.tanh(y)), rtol=1e-12)
    np.testing.assert_allclose(v.dcl_dre * re_edge * factor * LN10, s_cl / np.cosh(x) ** 2, rtol=1e-11, atol=1e-14)
    np.testing.assert_allclose(v.dcd_dre * re_edge * factor * LN10, v.cd * m / np.cosh(y) ** 2, rtol=1e-11,
                               atol=1e-15)
    # Bounded: the lift moves less than C and the drag less than a factor e^K = 3 from the edge's.
    assert np.all(np.abs(v.cl - v_edge.cl) < c) and np.all(np.abs(np.log(v.cd / v_edge.cd)) < k)


@pytest.mark.parametrize("side, factor", [(0, 0.3), (0, 0.01), (1, 1.5), (1, 50.0)])
def test_reynolds_derivatives_beyond_the_edges_by_complex_step(polar, side, factor):
    # The formula evaluated at a complex Re from the edge's public values: its complex step
    # is the Re derivative of the polar beyond the edge, and of its alpha slope the cross term.
    re_edge = _edges(polar)[side]
    v_edge, s_edge, scale = _edge_slopes(polar, re_edge)
    edge = np.stack([np.stack([v_edge.cl, v_edge.dcl_dalpha, s_edge.d2cl_dalpha2, v_edge.dcl_dre * scale,
                               s_edge.d2cl_dalpha_dre * scale, np.zeros_like(ALPHA)]),
                     np.stack([v_edge.cd, v_edge.dcd_dalpha, s_edge.d2cd_dalpha2, v_edge.dcd_dre * scale,
                               s_edge.d2cd_dalpha_dre * scale, np.zeros_like(ALPHA)])], axis=1)
    re = re_edge * factor
    c, c_a = extrapolate_log_reynolds(edge, np.log10((re + 1j * H) / re_edge),
                                      LOW_REYNOLDS_BOUNDS if side == 0 else None)[:2]
    v = polar.evaluate(ALPHA, re)
    s = polar.second_derivatives(ALPHA, re)
    np.testing.assert_allclose(c.real, [v.cl, v.cd], rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(c_a.real, [v.dcl_dalpha, v.dcd_dalpha], rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(c.imag / H * re, [v.dcl_dre * re, v.dcd_dre * re], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(c_a.imag / H * re, [s.d2cl_dalpha_dre * re, s.d2cd_dalpha_dre * re],
                               rtol=1e-10, atol=1e-12)


def test_formula_derivatives_by_complex_step():
    # Edge curves with known derivatives (smooth functions of alpha, drag positive), pushed
    # through the formula at complex alpha or complex d: every derivative it returns is the
    # complex step of the value (or of the alpha slope) it returns.
    alpha = np.radians(np.linspace(-20.0, 30.0, 11))
    delta = np.array([-2.0, -0.7, -0.1, 0.05, 0.3, 1.1, 2.5, 4.0, -3.0, 0.9, 1.7])

    def edge_terms(a):
        sin, cos = np.sin(a), np.cos(a)
        lift = [0.3 + sin, cos, -sin, 0.05 * cos, -0.05 * sin, -0.05 * cos, ]
        drag = [0.01 + 0.2 * sin**2, 0.4 * sin * cos, 0.4 * (cos**2 - sin**2),
                -0.002 + 0.01 * sin, 0.01 * cos, -0.01 * sin]
        return np.stack([np.stack(lift), np.stack(drag)], axis=1)

    for bounds in (None, LOW_REYNOLDS_BOUNDS, (0.05, 0.1)):
        c, c_a, c_aa, c_l, c_al, c_ll = extrapolate_log_reynolds(edge_terms(alpha), delta, bounds)
        by_alpha = extrapolate_log_reynolds(edge_terms(alpha + 1j * H), delta, bounds)
        np.testing.assert_allclose(by_alpha[0].imag / H, c_a, rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(by_alpha[1].imag / H, c_aa, rtol=1e-12, atol=1e-15)
        by_delta = extrapolate_log_reynolds(edge_terms(alpha), delta + 1j * H, bounds)
        np.testing.assert_allclose(by_delta[0].imag / H, c_l, rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(by_delta[1].imag / H, c_al, rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(by_delta[3].imag / H, c_ll, rtol=1e-12, atol=1e-15)
        # At the edge (d = 0) value, slopes and the zero curvature in L of lift and log cd are the lines'.
        at_edge = extrapolate_log_reynolds(edge_terms(alpha), np.zeros_like(alpha), bounds)
        line = extrapolate_log_reynolds(edge_terms(alpha), np.zeros_like(alpha))
        for got, want in zip(at_edge, line):
            np.testing.assert_allclose(got, want, rtol=1e-14, atol=1e-16)
    c, c_a, c_aa, c_l, c_al, c_ll = extrapolate_log_reynolds(edge_terms(alpha), delta)
    # Lift linear in L; drag f exp(d m): its curvature is cd m**2 (module docstring).
    np.testing.assert_array_equal(c_ll[0], 0.0)
    m = edge_terms(alpha)[3, 1] / edge_terms(alpha)[0, 1]
    np.testing.assert_allclose(c_ll[1], c[1] * m * m, rtol=1e-14)
    # At the edge (d = 0) every returned quantity is the edge's.
    at_edge = extrapolate_log_reynolds(edge_terms(alpha), np.zeros_like(alpha))
    for k, row in enumerate((0, 1, 2, 3, 4)):
        np.testing.assert_allclose(at_edge[k], edge_terms(alpha)[row], rtol=1e-14, atol=1e-16)


def _reynolds_positions(polar):
    """Reynolds numbers inside the table (cell middles), at every tabulated one (both edges included), just
    past the edges and far past them on both sides."""
    table = polar.reynolds
    edges = (table[0], table[-1])
    return np.concatenate([np.sqrt(table[:-1] * table[1:]), table, [edges[0] * (1 - 1e-9), edges[1] * (1 + 1e-9)],
                           edges[0] * np.array([0.5, 1e-2, 1e-4]), edges[1] * np.array([2.0, 1e2, 1e4])])


def test_second_reynolds_derivatives_by_complex_step(polar):
    # TabulatedPolar._compute is complex-step safe in Re (spline in log10 Re within the table, the
    # continuation past it), so the complex step of its first derivatives dc/dRe and dc/dalpha is the exact
    # Re derivative of the implemented formulas: it must equal d2c/dRe2 and d2c/(dalpha dRe).  At a
    # tabulated Reynolds number the real part picks the cell above it (the table's top edge: the cell below),
    # the same one-sided cell as the real evaluation.
    alpha = ALPHA + np.radians(0.06)
    for re in _reynolds_positions(polar):
        reynolds = np.full(alpha.shape, re)
        (_, cl_a, cl_re), (_, cd_a, cd_re) = polar._compute(alpha, reynolds + 1j * H * re, second=False)
        s = polar.second_derivatives(alpha, reynolds)
        scale = re * re  # per unit (ln Re)**2
        np.testing.assert_allclose(cl_re.imag / H * re, s.d2cl_dre2 * scale, rtol=1e-10, atol=1e-11)
        np.testing.assert_allclose(cd_re.imag / H * re, s.d2cd_dre2 * scale, rtol=1e-10, atol=1e-12)
        np.testing.assert_allclose(cl_a.imag / H, s.d2cl_dalpha_dre * re, rtol=1e-10, atol=1e-11)
        np.testing.assert_allclose(cd_a.imag / H, s.d2cd_dalpha_dre * re, rtol=1e-10, atol=1e-12)
        # The real parts are the public first derivatives (to the round-off of complex arithmetic).
        v = polar.evaluate(alpha, reynolds)
        np.testing.assert_allclose(cl_re.real, v.dcl_dre, rtol=1e-12, atol=1e-20)
        np.testing.assert_allclose(cd_a.real, v.dcd_dalpha, rtol=1e-12, atol=1e-14)
    # The curvature is really there, inside the table and past it, so the check can fail (the synthetic
    # polar's lift does not depend on Re: its source, AnalyticPolar, has Re in its drag only).
    for re in (np.sqrt(polar.reynolds[0] * polar.reynolds[1]), polar.reynolds[-1] * 100.0):
        s = polar.second_derivatives(alpha, np.full(alpha.shape, re))
        assert np.max(np.abs(s.d2cd_dre2)) * re**2 > 1e-4
        if polar.name != "synthetic":
            assert np.max(np.abs(s.d2cl_dre2)) * re**2 > 1e-3


@pytest.mark.parametrize("side, factor", [(0, 0.3), (0, 1e-3), (1, 1.5), (1, 1e3)])
def test_second_reynolds_derivatives_past_the_edges_hand_formula(polar, side, factor):
    # Module docstring: past an edge c_LL = 0 (lift), cd (s_cd / f_cd)**2 (drag), with the edge's public values.
    re_edge = _edges(polar)[side]
    v_edge, _, scale = _edge_slopes(polar, re_edge)
    re = re_edge * factor
    v, s = polar.evaluate(ALPHA, re), polar.second_derivatives(ALPHA, re)
    s_cl, m = v_edge.dcl_dre * scale, v_edge.dcd_dre * scale / v_edge.cd
    if side == 1:
        lift_ll, drag_ll = 0.0, v.cd * m**2
    else:
        bound_cl, bound_cd = LOW_REYNOLDS_BOUNDS
        d = np.log10(factor)
        x, y = d * s_cl / bound_cl, d * m / bound_cd
        g_l = m / np.cosh(y) ** 2
        lift_ll = -2.0 * s_cl**2 / bound_cl * np.tanh(x) / np.cosh(x) ** 2
        drag_ll = v.cd * (-2.0 * m**2 / bound_cd * np.tanh(y) / np.cosh(y) ** 2 + g_l**2)
    for c, c_re, c_rere, c_ll in ((v.cl, v.dcl_dre, s.d2cl_dre2, lift_ll), (v.cd, v.dcd_dre, s.d2cd_dre2, drag_ll)):
        c_l = c_re * re * LN10
        np.testing.assert_allclose(c_rere * re * re, (c_ll / LN10 - c_l) / LN10, rtol=1e-10, atol=1e-14)


def test_second_derivatives_beyond_the_edges_match_central_differences(polar):
    # Alpha curvature beyond the table (it needs the edge's d3/(dalpha2 dlogRe)); angles off the grid knots.
    alpha = ALPHA + np.radians(0.06)
    h = 1e-6
    for re in (polar.reynolds[0] / 5.0, polar.reynolds[-1] * 7.0):
        s = polar.second_derivatives(alpha, re)
        up, down = polar.evaluate(alpha + h, re), polar.evaluate(alpha - h, re)
        np.testing.assert_allclose((up.dcl_dalpha - down.dcl_dalpha) / (2 * h), s.d2cl_dalpha2,
                                   rtol=1e-6, atol=1e-6)
        np.testing.assert_allclose((up.dcd_dalpha - down.dcd_dalpha) / (2 * h), s.d2cd_dalpha2,
                                   rtol=1e-6, atol=1e-7)


def test_drag_positive_far_beyond_the_table(polar):
    # Physical invariant: a drag coefficient is positive, at every angle, however far the
    # Reynolds number is from the data (here six decades below and four above).
    alpha, reynolds = np.meshgrid(np.linspace(-np.pi, np.pi, 721), np.geomspace(0.1, 1e10, 45))
    v = polar.evaluate(alpha, reynolds)
    assert np.all(v.cd > 0.0) and np.all(np.isfinite(v.cd)) and np.all(np.isfinite(v.cl))


def test_power_law_drag_is_extrapolated_as_a_power_law():
    # The synthetic data's minimum drag scales as Re^-0.2 (AnalyticPolar, reynolds_exponent=0.2);
    # a power law in Re is what the drag continuation is above the table, so there it follows the source
    # polar (to the not-a-knot spline's slope error at the edge), where a clamp is off by 5^0.2 - 1 = 38 %.
    # Below, the bounded power law: at 1e4, 0.7 decades below the table, K tanh(y / K) is within 1 % of y
    # (y = 0.32, K = ln 3).
    surrogate = TabulatedPolar(_analytic_tables(), name="power law")
    source = AnalyticPolar(reynolds_exponent=0.2, cl0=0.35)
    alpha = np.radians(np.linspace(-2.0, 6.0, 9))
    for re in (1e4, 1e7):
        np.testing.assert_allclose(surrogate.evaluate(alpha, re).cd, source.evaluate(alpha, re).cd, rtol=0.03)


@pytest.mark.parametrize("side", [0, 1])
def test_max_lift_to_drag_point_continuous_across_the_edges(polar, side):
    # BILD's operating point and its Re derivatives (implicit function theorem on the polar's
    # first and second derivatives) do not jump where the table ends.
    re_edge = _edges(polar)[side]
    inner = polar.max_lift_to_drag(np.array([re_edge]))
    outer = polar.max_lift_to_drag(np.array([re_edge * (1.0 + (1e-9 if side else -1e-9))]))
    for field in ("alpha", "cl", "cd"):
        np.testing.assert_allclose(getattr(outer, field), getattr(inner, field), rtol=1e-7)
    for field in ("dalpha_dre", "dcl_dre", "dcd_dre"):
        np.testing.assert_allclose(getattr(outer, field) * re_edge, getattr(inner, field) * re_edge,
                                   rtol=1e-5, atol=1e-9)
    assert abs(float(outer.dcl_dre[0])) > 0.0


def test_reference_airfoil_partials_beyond_the_table_by_complex_step():
    # The max-L/D component at reference Reynolds numbers above (about 3e6) and below (about 4e3)
    # the built-in NACA 4412 table (1e4..2e6), and one inside it.
    values = state("hover")
    values["ref_chord"] = np.array([0.75, 0.1, 0.0012])
    prob = check_component_partials(ReferenceAirfoilComp(num_nodes=NN), values)
    reynolds = prob.get_val("reynolds_ref")
    assert reynolds[0] > 2e6 and 5e4 < reynolds[1] < 2e6 and reynolds[2] < 1e4


def test_warns_once_that_it_extrapolates():
    polar = TabulatedPolar(_analytic_tables()[:3], name="fresh")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        polar.evaluate(0.05, 1e6)
        polar.evaluate(0.05, 1e3)
    messages = [str(w.message) for w in caught]
    assert len(messages) == 1
    assert "outside the tabulated range 5e+04..3e+05 are extrapolated" in messages[0]


def test_nonpositive_drag_at_the_edge_raises():
    # A polar whose drag is not positive at the table edge cannot be continued as a power law.
    good = TabulatedPolar(_analytic_tables()[:2], name="bad drag")
    state_arrays = good.state()
    coef = state_arrays["coef"].reshape(-1, 2, 4, 4).copy()
    coef[:, 1, 0, 0] = -0.01                     # drag's constant term in every cell
    state_arrays["coef"] = coef.reshape(-1, 32)
    bad = TabulatedPolar.from_state(state_arrays)
    with pytest.raises(ValueError, match="cd <= 0 at the table edge"):
        bad.evaluate(0.05, 1e6)
