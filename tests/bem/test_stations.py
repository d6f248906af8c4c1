"""StationsComp: midpoint stations, user stations, and partials."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.bem.stations import StationsComp
from bild_mdo.utils.testing import check_component_partials


# User stations start at r/R = 0.198 (0.2 * 0.99), so their hub must be smaller than the default 0.2 m at node 1.
USER_HUB = [0.1, 0.15, 0.15]


def _run(nn=3, nr=7, hub_radius=(0.1, 0.2, 0.15), **options):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("st", StationsComp(num_nodes=nn, num_radial=nr, **options), promotes=["*"])
    prob.setup(force_alloc_complex=True)
    prob.set_val("radius", [0.8, 1.0, 1.5])
    prob.set_val("hub_radius", hub_radius)
    prob.run_model()
    return prob


def test_midpoints_of_equal_annuli():
    prob = _run()
    radii, dr = prob.get_val("radii"), prob.get_val("dr")
    R, rh = prob.get_val("radius"), prob.get_val("hub_radius")
    # Hand: dr = (R - r_hub)/7, r_j = r_hub + (j + 1/2) dr; widths tile the span exactly.
    np.testing.assert_allclose(dr, np.tile(((R - rh) / 7)[:, None], 7), rtol=1e-15)
    np.testing.assert_allclose(radii, rh[:, None] + (np.arange(7) + 0.5) * dr, rtol=1e-15)
    np.testing.assert_allclose(dr.sum(axis=1), R - rh, rtol=1e-14)
    # The midpoint rule integrates linear functions exactly: sum(r dr) = (R^2 - r_hub^2)/2.
    np.testing.assert_allclose((radii * dr).sum(axis=1), (R**2 - rh**2) / 2, rtol=1e-14)


@pytest.mark.parametrize("per_node", [False, True])
def test_user_stations(per_node):
    frac = np.linspace(0.2, 0.95, 7)
    width = np.full(7, 0.1)
    if per_node:
        frac = np.vstack([frac, frac * 0.99, frac * 1.01])
        width = np.vstack([width] * 3)
    prob = _run(hub_radius=USER_HUB, radial_fractions=frac, width_fractions=width)
    R = prob.get_val("radius")[:, None]
    np.testing.assert_allclose(prob.get_val("radii"), np.broadcast_to(frac, (3, 7)) * R, rtol=1e-15)
    np.testing.assert_allclose(prob.get_val("dr"), np.broadcast_to(width, (3, 7)) * R, rtol=1e-15)


@pytest.mark.parametrize("user", [False, True])
def test_partials(user):
    options = dict(radial_fractions=np.linspace(0.2, 0.95, 7), width_fractions=np.full(7, 0.1),
                   hub_radius=USER_HUB) if user else {}
    hub = options.pop("hub_radius", (0.1, 0.2, 0.15))
    check_component_partials(StationsComp(num_nodes=3, num_radial=7, **options),
                             {"radius": [0.8, 1.0, 1.5], "hub_radius": hub}, atol=1e-12, rtol=1e-12)


def test_fraction_options_validated():
    with pytest.raises(ValueError, match="width_fractions"):
        _run(radial_fractions=np.linspace(0.2, 0.9, 7))
    with pytest.raises(ValueError, match="radial_fractions must have shape"):
        _run(radial_fractions=np.linspace(0.2, 0.9, 6), width_fractions=np.full(6, 0.1))


EQUAL = ((np.arange(7) + 0.5) / 7, np.full(7, 1.0 / 7))  # 7 equal annuli on [0, 1]: r/R +- dr/(2R) tiles it


@pytest.mark.parametrize("centred", [False, True])
@pytest.mark.parametrize("change, name, what", [
    (dict(radial_fractions=EQUAL[0] + [0, 0, 0, 0, 0, 0, 0.2]), "radial_fractions", "not on the blade"),
    (dict(radial_fractions=EQUAL[0] - [0.1, 0, 0, 0, 0, 0, 0]), "radial_fractions", "not on the blade"),
    (dict(radial_fractions=EQUAL[0] * [1, 1, np.nan, 1, 1, 1, 1]), "radial_fractions", "not finite"),
    (dict(width_fractions=EQUAL[1] * [1, 1, 1, 0, 1, 1, 1]), "width_fractions", "not positive"),
    (dict(width_fractions=EQUAL[1] * [1, 1, 1, -1, 1, 1, 1]), "width_fractions", "not positive"),
    (dict(width_fractions=EQUAL[1] * [1, 1, 1, 1, np.inf, 1, 1]), "width_fractions", "not finite"),
    (dict(width_fractions=np.array([1, 1.4, 1.4, 1.4, 1.4, 1.4, 1]) / 7), "width_fractions", "add up to"),
])
def test_invalid_user_stations_raise_in_setup(centred, change, name, what):
    options = {**dict(radial_fractions=EQUAL[0], width_fractions=EQUAL[1], centred_annuli=centred), **change}
    with pytest.raises(ValueError, match=rf"{name}: .*{what}"):
        _run(hub_radius=[0.0, 0.0, 0.0], **options)


def test_centred_annuli_must_lie_on_the_disk():
    # r/R +- dr/(2R) must stay inside [0, 1]: a station at the tip, or one whose annulus crosses the axis
    # or the tip, is rejected with centred_annuli (each case is accepted without it, where only r/R counts).
    tip = (np.linspace(0.1, 1.0, 7), np.full(7, 0.1))  # a rectangle rule with the last station at the tip
    crosses_tip = (EQUAL[0], EQUAL[1] * [0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 1.5])
    crosses_axis = (EQUAL[0], EQUAL[1] * [1.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5])
    for (rf, wf), what in ((tip, r"not inside the blade .*"), (crosses_tip, r"annulus .* is not inside \[0, 1\]"),
                           (crosses_axis, r"annulus .* is not inside \[0, 1\]")):
        with pytest.raises(ValueError, match=rf"(radial|width)_fractions: .*{what} at node 0, station "):
            _run(hub_radius=[0.0, 0.0, 0.0], radial_fractions=rf, width_fractions=wf, centred_annuli=True)
        np.testing.assert_allclose(_run(hub_radius=[0.0, 0.0, 0.0], radial_fractions=rf, width_fractions=wf)
                                   .get_val("dr")[0], 0.8 * wf, rtol=1e-15)


def test_equal_annuli_pass_the_centred_checks_to_round_off():
    # r/R + dr/(2R) = 1 and r - dr/2 = r_hub hold only to round-off for user-given equal annuli (hand).
    hub = np.array([0.1, 0.2, 0.15])
    R = np.array([0.8, 1.0, 1.5])
    ratio = hub / R
    rf = ratio[:, None] + (1.0 - ratio[:, None]) * EQUAL[0]
    wf = (1.0 - ratio[:, None]) * EQUAL[1]
    prob = _run(hub_radius=hub, radial_fractions=rf, width_fractions=wf, centred_annuli=True)
    default = _run(hub_radius=hub)
    np.testing.assert_allclose(prob.get_val("radii"), default.get_val("radii"), rtol=1e-14)
    np.testing.assert_allclose(prob.get_val("dr"), default.get_val("dr"), rtol=1e-14)


@pytest.mark.parametrize("centred, hub, node, station", [(False, [0.1, 0.25, 0.15], 1, 0),
                                                         (False, [0.1, 0.2, 0.55], 2, 0),
                                                         (True, [0.1, 0.2, 0.15], 1, 0)])
def test_stations_inside_the_hub_raise_naming_node_and_station(centred, hub, node, station):
    # User stations r/R = 0.2 + 0.125 j, dr/R = 0.1 (hand): node 1 (R = 1 m) has r_0 = 0.2 m, inside a 0.25 m
    # hub; node 2 (R = 1.5 m) has r_0 = 0.3 m and r_1 = 0.4875 m inside a 0.55 m hub (the first is named);
    # with centred annuli the inner edge r_0 - dr/2 = 0.15 m of node 1 is inside its 0.2 m hub, though
    # r_0 = 0.2 m itself is not (node 0: 0.12 m >= 0.1 m).
    options = dict(radial_fractions=np.linspace(0.2, 0.95, 7), width_fractions=np.full(7, 0.1),
                   centred_annuli=centred)
    with pytest.raises(om.AnalysisError, match=rf"node {node}, station {station} lies inside the hub"):
        _run(hub_radius=hub, **options)


@pytest.mark.parametrize("centred", [False, True])
def test_midpoint_stations_of_a_hub_beyond_the_tip_raise_naming_the_first_station(centred):
    # Node 1: hub 1.2 m outside its 1.0 m tip, so the width (R - r_hub)/nr < 0 puts every midpoint inside the hub;
    # without centring the first (r_0 = r_hub + width/2) is named; centred, r_0 - dr/2 = r_hub is on the hub
    # edge (allowed to round-off) and r_1 - dr/2 = r_hub + width is the first inside it (hand derivation).
    station = 1 if centred else 0
    with pytest.raises(om.AnalysisError, match=rf"node 1, station {station} lies inside the hub"):
        _run(hub_radius=[0.1, 1.2, 0.15], centred_annuli=centred)
