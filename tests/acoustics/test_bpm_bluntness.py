"""Trailing-edge bluntness noise (TEB-VS) against the report's figures (NASA RP-1218, 1989, Sec. 5.4).

Digitized curves (data/bpm/README.md): figure 95, ``St'''_peak`` against ``h / delta*_avg`` for ``Psi`` = 0
and 14 deg (Eq. 72); figure 96, ``G_4`` (Eq. 74); figure 97, the shape ``G_5`` for ``Psi = 14`` deg at six
ratios (Eqs. 76-81) and for ``Psi = 0`` at five (Eq. 82); figures 98 and 99, the predicted TEB-VS spectra of the 60.96-cm NACA 0012 with blunt
trailing edges, h = 1.1, 1.9 and 2.5 mm (panels b, c, d), Psi = 14 deg, alpha* = 0, tripped, at U = 69.5
(98) and 38.6 m/s (99), span 45.72 cm, r_e = 1.22 m, Theta_e = Phi_e = 90 deg (which numbers belong to which
panel was read from the AcousticAnalogies.jl docs, numbers only).

Measured (model - report): figure 95 within 0.006; figure 96 within 0.96 dB (Psi = 0) and 0.66 dB (14).
Figure 97: the curves as digitized peak at St'''/St'''_peak = 1.02-1.05, not at 1 where Eq. (76) puts the
peak (G_5 = 0 there), and fall beyond it as -163 eta (-155.5 eta in Eq. 76): the figure's frequency axis is
about 3-5 % off, which on the steep sides is up to 2.1 dB.  The slopes below the peak, which do not depend
on that offset, follow Eq. (79)'s m within 1.6-4.2 % for h / delta*_avg = 0.25-0.62; the curve labelled 1.20
rises at 183 per decade, not Eq. (79)'s 268.3 (the value of m for 1.13-1.15), so the figure's curve was not
drawn from the printed equation there.  Figures 98, 99: every band below the report's peak band within
1.1 dB (the rising flank); the peak in the same band on four panels (there within 0.99-1.45 dB), one band
lower on 98c and 99b (there 2.7 and 3.0 dB below); the bands past the peak, on the falling flank (-15.5 dB
per band), 2.8-5.7 dB below the report: on that slope, as if the peak frequency were a few per cent lower.  AcousticAnalogies.jl, an independent implementation of the same equations, shows the same
("last two points are off", its test/broadband_source_element_tests.jl).
"""
import numpy as np
import pytest

from bild_mdo.acoustics.bands import spl_db
from bild_mdo.acoustics.bpm.bluntness import (bluntness_pressure_squared, peak_strouhal_3, shape_g4, shape_g5,
                                              shape_g5_psi14)
from bild_mdo.acoustics.bpm.bluntness import _slope
from bild_mdo.acoustics.bpm.directivity import high_frequency_directivity
from tests.acoustics.test_bpm_spectra import C0, NU, R_E, SPAN, largest_error, load, nearest_band

CHORD = 0.6096
# panel -> (U m/s, h m)
PANELS = {"figure98-b": (69.5, 1.1e-3), "figure98-c": (69.5, 1.9e-3), "figure98-d": (69.5, 2.5e-3),
          "figure99-b": (38.6, 1.1e-3), "figure99-c": (38.6, 1.9e-3), "figure99-d": (38.6, 2.5e-3)}


@pytest.mark.parametrize("psi", [0.0, 14.0])
def test_peak_strouhal_and_level_figures_95_96(psi):
    x, y = load(f"figure95-{psi:g}Psi")
    assert np.max(np.abs(peak_strouhal_3(x, psi) - y)) < 0.01
    x, y = load(f"figure96-{psi:g}Psi")
    assert np.max(np.abs(shape_g4(x, psi) - y)) < 1.0


@pytest.mark.parametrize("label", ["0p25", "0p43", "0p50", "0p54", "0p62"])
def test_shape_g5_figure97(label):
    """Below the peak the digitized slope dG_5/d(eta) is Eq. (79)'s m within 5 %; the digitized peak lies within
    0.4 dB of 0 dB at 1.00-1.06 times St'''_peak (the model: exactly 0 dB at 1)."""
    ratio = float(label.replace("p", "."))
    x, y = load(f"figure97-Psi14-h_over_deltastar{label}")
    eta = np.log10(x)
    low = eta < -0.05
    slope = np.polyfit(eta[low], y[low], 1)[0]
    assert slope == pytest.approx(_slope(np.array([ratio]))[0], rel=0.05)
    assert abs(np.max(y)) < 0.4 and 1.0 <= x[np.argmax(y)] <= 1.06
    assert shape_g5_psi14(np.array([ratio]), np.array([0.0]))[0] == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("label", ["0p25", "0p43", "0p50", "0p54", "1p20"])
def test_shape_g5_psi0_figure97(label):
    """The Psi = 0 shapes (Eq. 75 at Psi = 0: Eq. 82's modified ratio): within 1.3 dB of the digitized curves,
    measured 0.74-1.29 dB (medians 0.22-0.43 dB), their peaks at 1.005-1.022 times St'''_peak."""
    ratio = float(label.replace("p", "."))
    x, y = load(f"figure97-Psi0-h_over_deltastar{label}")
    assert np.max(np.abs(shape_g5(np.full_like(x, ratio), 0.0, x) - y)) < 1.3


def test_figure97_curve_at_1_20_does_not_follow_eq_79():
    """The documented exception: the 1.20 curve rises at about 183 per decade, Eq. (79) gives m = 268.344."""
    x, y = load("figure97-Psi14-h_over_deltastar1p20")
    eta = np.log10(x)
    low = eta < -0.05
    assert np.polyfit(eta[low], y[low], 1)[0] < 0.75 * _slope(np.array([1.2]))[0]


def test_shape_g5_caps_and_interpolation():
    """Eq. (75): G_5 is linear in Psi between the Psi = 0 (Eq. 82) and Psi = 14 shapes; the report's code listing
    caps it at 0 dB and at the Psi = 14 shape of h / delta*_avg = 0.25."""
    e = np.geomspace(0.3, 3.0, 41)
    for ratio in (0.1, 0.4, 0.9, 2.0):
        r = np.full_like(e, ratio)
        g14 = shape_g5(r, 14.0, e)
        g0 = shape_g5(r, 0.0, e)
        # The cap: the Psi = 14 shape at 0.25 on the listing's branch 'ratio >= 0.25' of Eq. (78).
        cap = shape_g5_psi14(np.full_like(e, np.nextafter(0.25, 1.0)), np.log10(e))
        assert np.all(g14 <= 0.0) and np.all(g0 <= 0.0) and np.all(g14 <= cap + 1e-12)
        raw = shape_g5_psi14(r, np.log10(e)), shape_g5_psi14(6.724 * r * r - 4.019 * r + 1.107, np.log10(e))
        uncapped = raw[1] + 0.0714 * 7.0 * (raw[0] - raw[1])
        np.testing.assert_allclose(shape_g5(r, 7.0, e), np.minimum(np.minimum(uncapped, 0.0), cap), atol=1e-12)


def _panel(name):
    speed, h = PANELS[name]
    f_khz, level = load(f"{name}-bluntness")
    order = np.argsort(f_khz)
    f_khz, level = f_khz[order], level[order]
    mach = speed / C0
    d_high = high_frequency_directivity(np.pi / 2, np.pi / 2, mach)
    model = spl_db(bluntness_pressure_squared(nearest_band(f_khz), CHORD, SPAN, speed, mach, 0.0, speed * CHORD / NU,
                                              R_E, d_high, h))
    return f_khz, level, model


@pytest.mark.parametrize("name", list(PANELS))
def test_spectra_figures_98_99(name):
    f_khz, level, model = _panel(name)
    peak = int(np.argmax(level))
    err = model - level
    assert np.max(np.abs(err[:peak])) < 1.15
    same_band = int(np.argmax(model)) == peak
    assert same_band or int(np.argmax(model)) == peak - 1
    assert abs(err[peak]) < (1.5 if same_band else 3.1)
    # The falling flank: below the report by 2.8-5.7 dB (module docstring), one or two bands per panel.
    assert np.all((err[peak + 1:] < -2.5) & (err[peak + 1:] > -6.0))


@pytest.mark.parametrize("name, speed, bound", [("figure98-a", 69.5, 1.1), ("figure99-b", 38.6, 1.7)])
def test_tbl_te_of_the_bluntness_cases(name, speed, bound):
    """The TBL-TE suction-side curve the report plots beside the bluntness (the same section, alpha* = 0,
    tripped): within 1.07 and 1.65 dB at the printed 69.5 and 38.6 m/s.  Like the (b) and (c) panels of
    tests/acoustics/test_bpm_spectra.py they fit a faster flow better (0.33 dB at 71.6, 0.91 dB at 39.8 m/s,
    3 % faster), so the bluntness panels' small negative offsets may share that cause; the printed speeds
    are kept."""
    assert largest_error(name, ["TBL-TE-suction"], CHORD, speed, 0.0, True) < bound
    assert largest_error(name, ["TBL-TE-suction"], CHORD, 1.03 * speed, 0.0, True) < 0.95


def test_sharp_edge_is_refused():
    with pytest.raises(ValueError, match="trailing-edge thickness h must be positive"):
        bluntness_pressure_squared(1000.0, 0.1, 0.1, 50.0, 0.15, 0.0, 3e5, 1.0, 2.0, 0.0)
