"""RotorGeometry: its checks, the station widths (cells between station midpoints), the file checks on them."""
import numpy as np
import pytest

from bild_mdo.io.file_checks import check_stations, check_version, twist_to_radians
from bild_mdo.io.geometry import FORMAT_VERSION, RotorGeometry, as_geometry, station_widths

BLADE = dict(radii=[0.3, 0.6, 0.9], chord=[0.1, 0.09, 0.05], twist=[0.4, 0.3, 0.2], radius=1.0, hub_radius=0.2,
             num_blades=2)


@pytest.mark.parametrize("change, message", [
    (dict(radii=[0.5, 0.4, 0.9]), "strictly increasing"),
    (dict(radii=[0.5, 0.6, 1.4]), "within hub and tip"),
    (dict(chord=[0.1, -0.1, 0.1]), "chord must be non-negative"),
    (dict(twist=[0.1, 0.2]), "the same length"),
    (dict(num_blades=True), "num_blades must be an integer >= 1, got True"),
    (dict(num_blades=2.5), "num_blades must be an integer >= 1, got 2.5"),
    (dict(hub_radius=1.2), "need 0 <= hub_radius < radius"),
])
def test_invalid_geometry(change, message):
    with pytest.raises(ValueError, match=message):
        RotorGeometry(**{**BLADE, **change})


def test_as_geometry_sources(design):
    geometry = as_geometry(BLADE)
    assert as_geometry(geometry) is geometry
    np.testing.assert_allclose(geometry.radial_fractions, [0.3, 0.6, 0.9])
    assert geometry.num_radial == 3
    # A BILD design hands over its blade and the polar it was designed with.
    from_design = as_geometry(design)
    np.testing.assert_array_equal(from_design.chord, design.chord)
    assert from_design.polar is design.polar
    with pytest.raises(ValueError, match="cannot make a rotor geometry from int"):
        as_geometry(3)


def test_station_widths_of_equal_annuli_are_the_annuli():
    # Hand derivation: 4 equal annuli of 0.2 m from 0.2 m to 1.0 m have their midpoints at 0.3, 0.5, 0.7, 0.9 m;
    # the midpoints between these stations are the annulus edges 0.4, 0.6, 0.8 m, so every cell is 0.2 m.
    geometry = RotorGeometry(**{**BLADE, "radii": [0.3, 0.5, 0.7, 0.9], "chord": [0.1] * 4, "twist": [0.3] * 4})
    np.testing.assert_allclose(geometry.dr, [0.2, 0.2, 0.2, 0.2], rtol=1e-15)
    np.testing.assert_allclose(station_widths([0.3, 0.5, 0.7, 0.9], 0.2, 1.0), geometry.dr, rtol=0.0)


def test_station_widths_tile_hub_to_tip():
    # Invariant: the cells end where the next begins, so they add up to R - r_hub for any stations.
    radii = np.sort(np.random.default_rng(4).uniform(0.25, 1.45, 17))
    widths = station_widths(radii, 0.25, 1.5)
    assert np.all(widths > 0.0)
    assert np.sum(widths) == pytest.approx(1.25, rel=1e-14)


@pytest.mark.parametrize("version, message", [
    (99, r"^blade\.csv: format version 99 is newer than this bild-mdo reads \(1 \.\.\. 2\); update bild-mdo "),
    (0, r"^blade\.csv: the format version must be a whole number >= 1, got 0$"),
    ("x", r"^blade\.csv: the format version must be a whole number >= 1, got 'x'$"),
    (True, r"^blade\.csv: the format version must be a whole number >= 1, got True$"),
])
def test_check_version(version, message):
    with pytest.raises(ValueError, match=message):
        check_version("blade.csv", version)
    assert check_version("blade.csv", FORMAT_VERSION) == FORMAT_VERSION == 2


@pytest.mark.parametrize("radii", [
    [0.3, 0.5, 0.7, 0.9],  # midpoints of equal annuli: half a spacing to hub and tip
    [0.2, 0.4, 0.6, 0.8, 1.0],  # CCBlade/QPROP-style: stations at hub and tip
    [0.4, 0.6, 0.8],  # gap to the hub exactly one spacing: the limit, accepted
])
def test_end_gaps_of_honest_stations_pass(radii):
    geometry = RotorGeometry(**{**BLADE, "radii": radii, "chord": [0.1] * len(radii), "twist": [0.3] * len(radii)})
    assert check_stations("old.csv", geometry) is geometry


@pytest.mark.parametrize("radii, message", [
    # One station cut from the tip of 4 equal annuli: the gap is 1.5 spacings (1.0 - 0.7 = 0.3 m against 0.2 m),
    # and the last cell (0.1 + 0.3 = 0.4 m) twice its neighbour's (0.2 m).
    ([0.3, 0.5, 0.7], r"^old\.csv: the last station \(r = 0\.7 m\) is 0\.3 m from the tip \(R = 1 m\), more than the "
                      r"0\.2 m to its neighbour: its annulus would stretch to the tip, 2 times as wide as its "
                      r"neighbour's, so stations are missing \(a cut file\?\); FIX$"),
    ([0.5, 0.7, 0.9], r"^old\.csv: the first station \(r = 0\.5 m\) is 0\.3 m from the hub \(hub radius 0\.2 m\), "),
])
def test_end_gaps_of_cut_stations_are_refused(radii, message):
    geometry = RotorGeometry(**{**BLADE, "radii": radii, "chord": [0.1] * 3, "twist": [0.3] * 3})
    with pytest.raises(ValueError, match=message):
        check_stations("old.csv", geometry, fix="FIX")


@pytest.mark.parametrize("dr, message", [
    ([0.2, 0.2, 0.2], r"^new\.csv: 4 stations but 3 widths 'dr \[m\]': the file was cut or edited; "),
    ([0.2, 0.2, 0.2, 0.1], r"^new\.csv: the station widths 'dr \[m\]' add up to 0\.7 m, but hub to tip is 0\.8 m "
                           r"\(0\.2 \.\.\. 1 m\): stations are missing \(a cut file\?\); "),
    ([0.2, 0.25, 0.15, 0.2], r"^new\.csv: station 1 \(r = 0\.5 m\) has the width dr = 0\.25 m, but its annulus "
                             r"between the midpoints to its neighbours, which the analysis integrates over, is 0\.2 m"),
    ([0.2, np.nan, 0.2, 0.2], r"^new\.csv: the station widths 'dr \[m\]' must be finite numbers$"),
])
def test_widths_that_do_not_tile_are_refused(dr, message):
    geometry = RotorGeometry(**{**BLADE, "radii": [0.3, 0.5, 0.7, 0.9], "chord": [0.1] * 4, "twist": [0.3] * 4})
    assert check_stations("new.csv", geometry, [0.2, 0.2, 0.2, 0.2]) is geometry
    with pytest.raises(ValueError, match=message):
        check_stations("new.csv", geometry, dr)


def test_twist_in_rad_that_looks_like_degrees():
    np.testing.assert_allclose(twist_to_radians("b.json", "twist [deg]", [30.0, 12.0], "deg"), np.radians([30, 12]))
    np.testing.assert_array_equal(twist_to_radians("b.json", "twist [rad]", [0.5, -6.2], "rad"), [0.5, -6.2])
    with pytest.raises(ValueError, match=r"^b\.json: 'twist \[rad\]' holds 30, more than one turn \(2 pi = 6\.28319 "
                                         r"rad\): the values look like degrees, but the file gives them in rad; write "
                                         r"the key as 'twist \[deg\]' or give the twist in radians$"):
        twist_to_radians("b.json", "twist [rad]", [30.0, 12.0], "rad")
