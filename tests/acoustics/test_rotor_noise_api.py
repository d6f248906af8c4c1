"""rotor_noise, NoiseResult and combine_noise: designs, analyses, sums of rotors, the summary and the plots."""
import numpy as np
import pytest

from bild_mdo import NoiseResult, analyze_rotor, combine_noise, design_rotor, rotor_noise
from bild_mdo.acoustics.bands import THIRD_OCTAVE_CENTRES
from bild_mdo.acoustics.broadband_noise import BROADBAND_SOURCES
from bild_mdo.results.noise import MODEL, VALIDITY

OBSERVERS = np.array([[-10.0, 0.0, 2.0], [-7.0, 7.0, 0.0], [0.5, 0.0, 10.0]])
BANDS = THIRD_OCTAVE_CENTRES[8::3]


@pytest.fixture(scope="module")
def design():
    """A small two-blade hover rotor (R = 0.5 m, 2000 rpm) designed by BILD."""
    return design_rotor(v_axial=0.0, rpm=2000.0, radius=0.5, ref_chord=0.05, num_radial=8, num_blades=2,
                        bem_analysis=False)


@pytest.fixture(scope="module")
def noise(design):
    return rotor_noise(design, OBSERVERS, num_harmonics=4, band_frequencies=BANDS)


def test_shapes_and_levels(noise):
    assert isinstance(noise, NoiseResult) and not noise.is_batch
    assert noise.oaspl.shape == noise.oaspl_dba.shape == (3,)
    assert noise.tonal_spl.shape == (3, 4) and noise.tonal_frequency.shape == (4,)
    assert noise.band_spl.shape == (3, BANDS.size) and set(noise.source_spl) == set(BROADBAND_SOURCES)
    # B Omega / (2 pi) = 2 * 2000 / 60 Hz, and its multiples (Hanson's harmonics m B Omega).
    np.testing.assert_allclose(noise.tonal_frequency, 2 * 2000.0 / 60.0 * np.arange(1, 5), rtol=1e-12)
    # The overall level is at least the loudest of its parts, and the parts add up (incoherent sum).
    assert np.all(noise.oaspl >= np.max(noise.tonal_spl, axis=1) - 1e-9)
    total = (10 ** (noise.tonal_spl / 10)).sum(-1) + (10 ** (noise.band_spl / 10)).sum(-1)
    np.testing.assert_allclose(noise.oaspl, 10 * np.log10(total), atol=1e-6)


def test_batch_matches_single_designs(design):
    """A batch of designs gives, per design, the noise of that design alone."""
    batch = design_rotor(v_axial=[0.0, 3.0], rpm=[2000.0, 2200.0], radius=0.5, ref_chord=0.05, num_radial=8,
                         num_blades=2, bem_analysis=False)
    noise = rotor_noise(batch, OBSERVERS, num_harmonics=3, band_frequencies=BANDS)
    assert noise.is_batch and noise.oaspl.shape == (2, 3) and len(noise) == 2
    single = rotor_noise(batch[1], OBSERVERS, num_harmonics=3, band_frequencies=BANDS)
    np.testing.assert_allclose(noise.oaspl_dba[1], single.oaspl_dba, rtol=1e-12)


def test_analysis_result(design):
    """The BEM analysis of the design's own blade: its noise is that of the design to within the model change."""
    bem = analyze_rotor(chord=design.chord, twist=design.twist, radius=0.5, hub_radius=design.hub_radius,
                        rpm=2000.0, v_axial=0.0, num_blades=2, polar="naca4412", radii=design.radii)
    kwargs = dict(chord=design.chord, rpm=2000.0, v_axial=0.0, radius=0.5, hub_radius=design.hub_radius,
                  num_blades=2)
    noise = rotor_noise(bem, OBSERVERS, num_harmonics=4, band_frequencies=BANDS, **kwargs)
    reference = rotor_noise(design, OBSERVERS, num_harmonics=4, band_frequencies=BANDS)
    # BILD and BEM thrusts of this blade agree to 0.2 % (design summary): loading tones within 0.1 dB.
    np.testing.assert_allclose(noise.tonal_spl[:2, 0], reference.tonal_spl[:2, 0], atol=0.1)
    with pytest.raises(ValueError, match="give chord, rpm"):
        rotor_noise(bem, OBSERVERS)


def test_two_equal_rotors_add_3_dB(noise):
    """Hand derivation: two equal incoherent sources read 10 log10(2) = 3.0103 dB above one."""
    both = combine_noise(noise, noise)
    np.testing.assert_allclose(both.oaspl - noise.oaspl, 3.0103, atol=1e-4)
    np.testing.assert_allclose(both.oaspl_dba - noise.oaspl_dba, 3.0103, atol=1e-4)
    np.testing.assert_allclose((noise + noise).oaspl, both.oaspl)
    assert both.tonal_frequency.size == 8 and "2 rotors" in both.description


def test_combine_needs_the_same_observers(noise, design):
    other = rotor_noise(design, OBSERVERS[:2], num_harmonics=2, band_frequencies=BANDS)
    with pytest.raises(ValueError, match="same number of observers"):
        combine_noise(noise, other)


def test_hover_loading_tones_vanish_on_the_axis(design):
    """Gutin: in hover the loading harmonics m B >= 1 vanish on the rotor axis (floor: -100 dB, finite)."""
    axis = rotor_noise(design, [[-10.0, 0.0, 0.0]], num_harmonics=3, include_broadband=False)
    assert np.all(axis.tonal_spl < -50.0) and np.all(np.isfinite(axis.oaspl))
    assert np.all(axis.band_spl == -100.0)


@pytest.mark.parametrize("observers, message", [
    ([[0.1, 0.1, 0.0]], "inside the rotor"), ([[np.nan, 0.0, -5.0]], "not finite"), ([[1.0, 2.0]], "shape")])
def test_bad_observers(design, observers, message):
    with pytest.raises(ValueError, match=message):
        rotor_noise(design, observers)


def test_summary(noise, design):
    text = noise.summary()
    assert text.startswith("Rotor noise: B = 2, 2000 rpm")
    flat = " ".join(text.split())
    assert " ".join(MODEL.split()) in flat and " ".join(VALIDITY.split()) in flat
    rows = [line for line in text.splitlines() if line.split()[:2] in (["0", "0"], ["0", "1"], ["0", "2"])]
    assert len(rows) == 3
    assert f"{noise.oaspl_dba[1]:.2f}" in rows[1]
    near = rotor_noise(design, [[-1.2, 0.0, 0.0]], num_harmonics=2, band_frequencies=BANDS)
    assert "within 3 rotor radii" in near.summary()


def test_plots(noise, design, tmp_path):
    pytest.importorskip("matplotlib")
    from bild_mdo.plots.noise import arc_observers, plot_directivity, plot_noise_spectrum

    arc = arc_observers(10.0, 7)
    np.testing.assert_allclose(np.linalg.norm(arc, axis=1), 10.0)
    plot_noise_spectrum(noise, tmp_path / "spectrum.png")
    plot_directivity(rotor_noise(design, arc, num_harmonics=2, band_frequencies=BANDS), tmp_path / "arc.png")
    assert (tmp_path / "spectrum.png").stat().st_size > 1000 and (tmp_path / "arc.png").stat().st_size > 1000


def test_blunt_trailing_edge(design):
    """A trailing-edge thickness adds BPM's bluntness noise and nothing else; 0 (the default) adds none; per
    station or one value alike; bad values are one line."""
    sharp = rotor_noise(design, OBSERVERS, num_harmonics=2, band_frequencies=BANDS)
    assert np.all(sharp.source_pressure_squared["bluntness"] == 0.0)
    blunt = rotor_noise(design, OBSERVERS, num_harmonics=2, band_frequencies=BANDS, trailing_edge_thickness=5e-4)
    assert np.all(blunt.source_pressure_squared["bluntness"] > 0.0)
    for name in BROADBAND_SOURCES[:-1]:
        np.testing.assert_array_equal(blunt.source_pressure_squared[name], sharp.source_pressure_squared[name])
    per_station = rotor_noise(design, OBSERVERS, num_harmonics=2, band_frequencies=BANDS,
                              trailing_edge_thickness=np.full(design.chord.size, 5e-4))
    np.testing.assert_array_equal(per_station.band_spl, blunt.band_spl)
    assert "trailing edge 0.5 mm, Psi 14 deg" in blunt.summary()
    for bad, message in ((-1e-3, "trailing_edge_thickness must be a finite number >= 0 in m"),
                         (np.ones(3) * 1e-3, "one value or one per station")):
        with pytest.raises(ValueError, match=message):
            rotor_noise(design, OBSERVERS, trailing_edge_thickness=bad)
    for angle in (-2.0, "16", np.nan):
        with pytest.raises(ValueError, match=r"trailing_edge_angle must be a finite number in deg within \[0, 30\]"):
            rotor_noise(design, OBSERVERS, trailing_edge_thickness=1e-3, trailing_edge_angle=angle)
    with pytest.raises(ValueError, match=r"got inf \(design 0, station 2\)"):
        rotor_noise(design, OBSERVERS, trailing_edge_thickness=[1e-3, 1e-3, np.inf] + [1e-3] * (design.chord.size - 3))


def test_azimuths(design):
    """num_azimuth reaches the broadband noise.  The azimuth mean converges geometrically, slowest near the disc
    plane, where the Doppler factor and the directivity change most around the disc: on this rotor (tip Mach
    0.31) the default 24 azimuths are within 0.0004 dB of 96 at the observers below it and 0.10 dB at the
    third, 3 deg above the disc plane (measured); 12 azimuths within 0.003 dB below, but 1.35 dB off there.
    0 is one line."""
    def bands(n):
        return rotor_noise(design, OBSERVERS, num_harmonics=2, band_frequencies=BANDS, num_azimuth=n).band_spl
    reference, default, coarse = bands(96), bands(24), bands(12)
    np.testing.assert_allclose(default[:2], reference[:2], atol=1e-3)
    np.testing.assert_allclose(coarse[:2], reference[:2], atol=5e-3)
    assert np.max(np.abs(default[2] - reference[2])) < 0.12 < 1.0 < np.max(np.abs(coarse[2] - reference[2]))
    with pytest.raises(ValueError, match="num_azimuth must be an integer >= 1"):
        rotor_noise(design, OBSERVERS, num_azimuth=0)


def test_mechanism_levels(design):
    """The overall level of each BPM mechanism: their incoherent sum is the broadband level of the observer
    (a physical invariant); the summary names the mechanisms heard (a tripped layer has no LBL-VS)."""
    noise = rotor_noise(design, OBSERVERS, num_harmonics=2, band_frequencies=BANDS, trailing_edge_thickness=5e-4)
    for k in range(len(OBSERVERS)):
        levels = noise.mechanism_levels(observer=k)
        assert set(levels) == set(BROADBAND_SOURCES) and levels["lbl_vs"] == -100.0
        total = 10 * np.log10(sum(10 ** (level / 10) for name, level in levels.items() if name != "lbl_vs"))
        assert total == pytest.approx(10 * np.log10(noise.broadband_pressure_squared[k].sum() / 4e-10), abs=1e-9)
    text = noise.summary()
    notes = text[text.index("broadband by mechanism"):]
    assert "separation" in notes and "bluntness" in notes and "lbl_vs" not in notes
