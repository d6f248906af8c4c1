"""The built-in NACA 4412 at low Reynolds numbers (issue 24): XFOIL tables down to 1e4, a bounded continuation below.

Source of the data: the XFOIL 6.99 tables shipped in bild_mdo/airfoil/data (NACA 4412, Ncrit 9, Mach 0; the
command and settings are in its README.md).  The continuation below the data is the hand formula of the
TabulatedPolar docstring with ``low_end='physical'``: lift flat in Re, drag ``f exp(K tanh(d m / K))``.
"""
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bild_mdo.airfoil import TabulatedPolar, naca4412
from bild_mdo.airfoil import load_path_table as load_path_module
from bild_mdo.airfoil import surrogate
from bild_mdo.airfoil.builtin import NACA4412_PAPER_LOWEST_REYNOLDS
from bild_mdo.airfoil.load_path_table import data_reynolds_range
from bild_mdo.airfoil.sources.readers import load_builtin_polars
from bild_mdo.airfoil.surrogate import LOW_REYNOLDS_DRAG_FACTOR

pytestmark = pytest.mark.filterwarnings("ignore:.*Reynolds numbers outside the tabulated range:UserWarning")


@pytest.fixture(scope="module")
def paper_only():
    """The surrogate of the paper's ten tables alone (5e4..2e6): the built-in polar before issue 24."""
    tables = [p for p in load_builtin_polars("naca4412") if p.reynolds >= NACA4412_PAPER_LOWEST_REYNOLDS]
    return TabulatedPolar(tables, name="paper")


@pytest.mark.parametrize("reynolds", [1e4, 2e4, 3e4, 5e4])
def test_acceptance_low_reynolds_polar_is_physical(reynolds):
    # Issue 24's acceptance, on the XFOIL 6.99 tables (data/README.md): lift rising with alpha through
    # 0..8 deg, positive lift and a drag below 0.1 at 4 deg.
    polar = naca4412()
    alpha = np.radians(np.linspace(0.0, 8.0, 321))
    values = polar.evaluate(alpha, reynolds)
    assert np.all(np.diff(values.cl) > 0.0) and np.all(values.dcl_dalpha > 0.0)
    at4 = polar.evaluate(np.radians(4.0), reynolds)
    assert at4.cl > 0.0 and at4.cd < 0.1


@pytest.mark.parametrize("reynolds", [1e4, 1.5e4, 2e4, 2.5e4, 3e4, 4e4, 4.5e4])
def test_surrogate_follows_the_xfoil_tables(reynolds):
    # The surrogate at a tabulated Re against the XFOIL points it smooths (0..8 deg): within 0.03 in cl
    # (the smoothing spline removes XFOIL's point-to-point scatter, largest 0.023 at 8 deg at 4.5e4) and 5 % in cd.
    data = next(p for p in load_builtin_polars("naca4412") if p.reynolds == reynolds)
    keep = (data.alpha_deg >= 0.0) & (data.alpha_deg <= 8.0)
    values = naca4412().evaluate(np.radians(data.alpha_deg[keep]), reynolds)
    np.testing.assert_allclose(values.cl, data.cl[keep], atol=0.03)
    np.testing.assert_allclose(values.cd, data.cd[keep], rtol=0.05)


def test_the_old_extrapolation_was_unphysical(paper_only):
    # The numbers of issue 24: the paper's tables continued below 5e4 by the old lines (lift linear in
    # log Re, drag a power of Re, from the 5e4 edge's value and slope) give negative lift at 4 deg at 2e4 and
    # at 0 deg at 3e4, and a drag of 0.50 at 1e4.  The tables now give these Reynolds numbers (see above).
    def old(alpha, reynolds):
        edge = paper_only.evaluate(alpha, 5e4)
        d, scale = np.log10(reynolds / 5e4), 5e4 * np.log(10.0)
        return (edge.cl + d * edge.dcl_dre * scale,
                edge.cd * np.exp(d * edge.dcd_dre * scale / edge.cd))

    assert old(np.radians(4.0), 2e4)[0] == pytest.approx(-0.056, abs=0.001)
    assert old(0.0, 3e4)[0] == pytest.approx(-0.12, abs=0.005)
    assert old(np.radians(4.0), 1e4)[1] == pytest.approx(0.50, abs=0.005)


def test_above_5e4_the_paper_surrogate_bit_for_bit(paper_only):
    # split_reynolds=5e4: the low-Reynolds tables leave the paper's polar unchanged from 5e4 up, also
    # past its top (2e6), values and first and second derivatives.
    polar = naca4412()
    alpha, reynolds = np.meshgrid(np.radians(np.linspace(-180.0, 180.0, 721)), np.geomspace(5e4, 1e7, 61))
    for got, want in zip(polar.evaluate(alpha, reynolds), paper_only.evaluate(alpha, reynolds)):
        np.testing.assert_array_equal(got, want)
    for got, want in zip(polar.second_derivatives(alpha, reynolds), paper_only.second_derivatives(alpha, reynolds)):
        np.testing.assert_array_equal(got, want)


def test_c1_at_the_split(paper_only):
    # Below 5e4 the low-Reynolds spline takes the paper spline's slope at 5e4: value and Re slope match.
    polar = naca4412()
    alpha = np.radians(np.linspace(-20.0, 30.0, 51))
    below, at = polar.evaluate(alpha, 5e4 * (1 - 1e-9)), paper_only.evaluate(alpha, 5e4)
    np.testing.assert_allclose(below.cl, at.cl, atol=1e-8)
    np.testing.assert_allclose(below.cd, at.cd, rtol=1e-8)
    np.testing.assert_allclose(below.dcl_dre * 5e4, at.dcl_dre * 5e4, atol=1e-6)
    np.testing.assert_allclose(below.dcd_dre * 5e4, at.dcd_dre * 5e4, atol=1e-7)


def test_continuation_below_the_data_on_a_grid():
    # Below 1e4, down to Re = 1 and all round the circle: the lift stays the 1e4 lift, the drag grows as Re
    # drops (never falls, to round-off) and stays below three times the 1e4 drag (and 2.5); cd > 0.
    polar = naca4412()
    alpha = np.radians(np.linspace(-180.0, 180.0, 1441))
    reynolds = np.geomspace(1.0, 1e4, 81)
    values = polar.evaluate(alpha[:, None], reynolds[None, :])
    edge = polar.evaluate(alpha, 1e4)
    np.testing.assert_allclose(values.cl, np.broadcast_to(edge.cl[:, None], values.cl.shape), rtol=0, atol=1e-12)
    ratio = values.cd / edge.cd[:, None]
    assert np.all(ratio >= 1.0 - 1e-9) and np.all(ratio < LOW_REYNOLDS_DRAG_FACTOR)
    assert np.all(np.diff(values.cd, axis=1) <= 1e-14)
    assert np.max(np.abs(values.cl)) < 1.2 and np.max(values.cd) < 2.5
    # Attached flow (0..8 deg): the drag really rises as Re drops (with the two lowest tables' power law).
    attached = (alpha >= 0.0) & (alpha <= np.radians(8.0))
    assert np.all(np.diff(values.cd[attached], axis=1) < 0.0)


@settings(max_examples=60, deadline=None)
@given(alpha_deg=st.floats(-180.0, 180.0), low=st.floats(-2.0, 4.0), gap=st.floats(1e-3, 3.0))
def test_continuation_is_monotone_and_bounded(alpha_deg, low, gap):
    # Two Reynolds numbers 10**low < 10**(low + gap), the upper one at most 1e4: lift unchanged, drag not
    # rising with Re, both within their bounds of the 1e4 values.
    polar = naca4412()
    upper = min(low + gap, 4.0)
    alpha = np.radians(alpha_deg)
    lo, hi, edge = (polar.evaluate(alpha, 10.0 ** x) for x in (low, upper, 4.0))
    assert lo.cl == pytest.approx(hi.cl, abs=1e-12) == edge.cl
    assert lo.cd >= hi.cd * (1.0 - 1e-9) and edge.cd * (1 - 1e-9) <= hi.cd
    assert lo.cd < LOW_REYNOLDS_DRAG_FACTOR * edge.cd and lo.dcd_dre * 10.0 ** low <= 1e-12 and lo.cd > 0.0


def test_stations_are_flagged_against_the_new_data_range():
    # bild_mdo.results.design.station_reynolds flags stations outside data_reynolds_range(polar).
    assert data_reynolds_range(naca4412()) == (1e4, 2e6)


def test_changed_data_give_new_cache_keys(paper_only):
    # The polar cache is keyed by the data: the seventeen tables do not read the ten tables' surrogate,
    # and the surrogate's settings (the split, the low end) are part of the key too.
    tables = load_builtin_polars("naca4412")
    paper = [p for p in tables if p.reynolds >= 5e4]
    built_in = TabulatedPolar.cache_key(tables, split_reynolds=5e4, low_end="physical")
    assert len({TabulatedPolar.cache_key(paper), TabulatedPolar.cache_key(tables), built_in,
                TabulatedPolar.cache_key(tables, split_reynolds=5e4)}) == 4
    # The load-path table on disk is keyed by the surrogate's state, which holds the code version of the
    # evaluation (the continuation past the table is computed there, not stored).
    polar = naca4412()
    assert str(polar.state()["code_version"]) == surrogate.code_version()
    key = load_path_module._cache_key(polar)
    assert key != load_path_module._cache_key(paper_only)
    state = polar.state()
    state["code_version"] = np.array("another version")
    other = TabulatedPolar.from_state(state)
    other.state = lambda: state
    assert load_path_module._cache_key(other) != key


@pytest.mark.parametrize("kwargs, match", [
    ({"split_reynolds": 6e4}, "split_reynolds=60000 must be one of the tabulated"),
    ({"split_reynolds": 5e5}, "other than the first and the last"),
    ({"low_end": "clamped"}, "low_end must be one of not-a-knot, physical"),
])
def test_bad_surrogate_settings_are_refused(kwargs, match):
    tables = [p for p in load_builtin_polars("naca4412") if p.reynolds in (5e5, 1e6)]
    with pytest.raises(ValueError, match=match):
        TabulatedPolar(tables, **kwargs)


def test_physical_low_end_on_a_polar_without_a_split():
    # low_end='physical' alone (no split): lift flat below the lowest table, drag rising as Re drops.
    tables = [p for p in load_builtin_polars("naca4412") if p.reynolds in (1e5, 2e5, 5e5)]
    polar = TabulatedPolar(tables, low_end="physical")
    alpha = np.radians(np.linspace(0.0, 8.0, 9))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        edge, below = polar.evaluate(alpha, 1e5), polar.evaluate(alpha, 2e4)
    np.testing.assert_allclose(below.cl, edge.cl, atol=1e-12)
    assert np.all(below.cd > edge.cd) and np.all(below.cd < LOW_REYNOLDS_DRAG_FACTOR * edge.cd)
