"""BPM segment spectra against the report's predictions for its NACA 0012 sections (NASA RP-1218, 1989).

The report's wind-tunnel cases: span L = 45.72 cm (30.48 cm for the tip-vortex blade of figure 91),
observer at r_e = 1.22 m, Theta_e = Phi_e = 90 deg, kinematic viscosity 1.4529e-5 m**2/s, speed of sound
340.46 m/s; the spectra figures have one panel per tunnel speed, (a) U = 71.3, (b) 55.5, (c) 39.6 and
(d) 31.7 m/s (M = 0.209, 0.163, 0.116, 0.093; figure 12 has only (a) 71.3 and (b) 39.6).  Chord, U, alpha*
and the trip per figure are in the case tables below (which numbers belong to which figure was read from
the AcousticAnalogies.jl tests and docs, numbers only).  The curves are the report's one-third-octave
predictions, digitized by the AcousticAnalogies.jl project (data/bpm/README.md); each digitized point is
compared with the model at the nearest nominal band centre, where the report evaluated it (the exact
base-ten centres change the errors by at most 0.3 dB either way and explain nothing below).

Acceptance (issue 26): within 1 dB in every band the report plots.  Met at 71.3 and 31.7 m/s, measured
largest errors (dB): 11a 0.33, 11d 0.32, 12a 0.38 / 0.30 / 0.61 (suction / pressure / separation),
26a 0.36, 26d 0.28, 28a 0.39 / 0.29 / 0.40, 28d 0.42 / 0.47 / 0.46, 38d 0.27, 39d 0.49 / 0.51 / 0.36,
45a 0.63 / 0.64 / 0.76 and LBL-VS 0.25, 54a 0.49, 60d 0.61, 65d 0.46, 69a 0.53, tip vortex 91: 0.56.

Not met at the printed 55.5 and 39.6 m/s, for every mechanism, chord and angle (largest errors, dB):
11b 1.46, 26b 1.51, 28b 3.57 (separation) at 55.5 m/s; 11c 1.06, 12b 1.55, 26c 1.96, 28c 2.35, 48c 1.75,
59c 2.70, 60c 2.85, 66b 3.86, 69b 1.01 at 39.6 m/s.  The cause is the speed the report's curves were
computed for, not Eqs. (53)-(60) or the TBL-TE and separation terms here:

* Same formulas, same chords, angles and trips: panels (a) and (d) agree at the printed speeds, and a
  least-squares fit of the speed per panel gives 0.994-1.011 times the printed one.  Panels (b) and (c)
  give 1.037-1.050 and 1.024-1.041 times it, for TBL-TE, separation and LBL-VS alike.
* Fitted jointly over all panels of one speed, the Mach numbers U / c_0 are 0.2104, 0.1697, 0.1199 and
  0.0931, i.e. 0.21, 0.17, 0.12 and 0.093: the two-figure Mach numbers, not the printed 0.163 and 0.116.
  With U = M c_0 for those (71.5, 57.9, 40.9, 31.7 m/s) every digitized band of every panel is within
  0.86 dB (60c); the (b) and (c) panels read 0.37, 0.33, 0.54 / 0.28, 0.45, 0.44, 0.51, 0.49, 0.34, 0.86,
  0.08, 0.31 dB in the order above.
* A speed changes the level (M^5, +0.64 dB for 3 %) and the frequency (St = f delta / U) together.  On
  those panels a level offset alone leaves 1.1-1.8 dB rms (LBL-VS), a frequency scale alone 0.3-1.0 dB
  rms (TBL-TE, separation); the speed alone leaves 0.06-0.44 dB rms.  The digitized frequencies sit on
  the nominal band centres to about 1 % in every panel (panel means -1.3 % ... +1.2 %, the (b) and (c)
  panels' -1.2 % ... +0.9 %), so no panel's frequency axis is off by 3 %.
* AcousticAnalogies.jl, an independent implementation, misses the same panels by similar amounts: its
  tests (relative to each curve's range) allow 2.0, 3.0, 3.8 and 4.2 dB on 48c, 59c, 60c and 66b against
  0.7-0.8 dB on 54a, 60d, 65d, and it asserts none of the (b) and (c) TBL-TE or separation panels.

The printed speeds are kept (the report's text), the model is not tuned, and the (b) and (c) panels are
asserted twice: within their measured error at the printed speed, and within 1 dB at U = M c_0.
"""
from pathlib import Path

import numpy as np
import pytest

from bild_mdo.acoustics import bpm
from bild_mdo.acoustics.bands import NOMINAL_CENTRES, spl_db

DATA = Path(__file__).resolve().parent / "data" / "bpm"
NU, C0 = 1.4529e-5, 340.46
R_E, SPAN = 1.22, 0.4572
# Digitized curve name -> segment mechanism (figure 12b's separation file is named "TBL-TE-separation").
COMPONENTS = {"TBL-TE-suction": "tbl_te_suction", "TBL-TE-pressure": "tbl_te_pressure", "separation": "separation",
              "TBL-TE-separation": "separation", "LBL-VS": "lbl_vs"}

# figure panel -> (chord m, U m/s, alpha* deg, tripped, digitized curves)
CASES = {
    "figure11-a": (0.3048, 71.3, 0.0, True, ["TBL-TE-suction"]),
    "figure11-d": (0.3048, 31.7, 0.0, True, ["TBL-TE-suction"]),
    "figure12-U71.3": (0.3048, 71.3, 1.5, True, ["TBL-TE-suction", "TBL-TE-pressure", "separation"]),
    "figure26-a": (0.1016, 71.3, 0.0, True, ["TBL-TE-suction"]),
    "figure26-d": (0.1016, 31.7, 0.0, True, ["TBL-TE-suction"]),
    "figure28-a": (0.1016, 71.3, 6.7, True, ["TBL-TE-suction", "TBL-TE-pressure", "separation"]),
    "figure28-d": (0.1016, 31.7, 6.7, True, ["TBL-TE-suction", "TBL-TE-pressure", "separation"]),
    "figure38-d": (0.0254, 31.7, 0.0, True, ["TBL-TE-suction"]),
    "figure39-d": (0.0254, 31.7, 4.8, True, ["TBL-TE-suction", "TBL-TE-pressure", "separation"]),
    "figure45-a": (0.3048, 71.3, 1.5, False, ["TBL-TE-suction", "TBL-TE-pressure", "separation", "LBL-VS"]),
    "figure54-a": (0.1524, 71.3, 2.7, False, ["LBL-VS"]),
    "figure60-d": (0.1016, 31.7, 3.3, False, ["LBL-VS"]),
    "figure65-d": (0.0508, 31.7, 0.0, False, ["LBL-VS"]),
}
# The panels at 55.5 and 39.6 m/s (module docstring): the CASES columns, then the measured largest error (dB)
# over the panel's curves at the printed speed.
PRINTED_SPEED_MISSES = {
    "figure11-b": (0.3048, 55.5, 0.0, True, ["TBL-TE-suction"], 1.46),
    "figure26-b": (0.1016, 55.5, 0.0, True, ["TBL-TE-suction"], 1.51),
    "figure28-b": (0.1016, 55.5, 6.7, True, ["TBL-TE-suction", "TBL-TE-pressure", "separation"], 3.57),
    "figure11-c": (0.3048, 39.6, 0.0, True, ["TBL-TE-suction"], 1.06),
    "figure12-b": (0.3048, 39.6, 1.5, True, ["TBL-TE-suction", "TBL-TE-pressure", "TBL-TE-separation"], 1.55),
    "figure26-c": (0.1016, 39.6, 0.0, True, ["TBL-TE-suction"], 1.96),
    "figure28-c": (0.1016, 39.6, 6.7, True, ["TBL-TE-suction", "TBL-TE-pressure", "separation"], 2.35),
    "figure48-c": (0.2286, 39.6, 0.0, False, ["LBL-VS"], 1.75),
    "figure59-c": (0.1016, 39.6, 0.0, False, ["LBL-VS"], 2.70),
    "figure60-c": (0.1016, 39.6, 3.3, False, ["LBL-VS"], 2.85),
    "figure66-b": (0.0508, 39.6, 4.2, False, ["LBL-VS"], 3.86),
    "figure69-b": (0.0508, 39.6, 15.4, False, ["separation"], 1.01),
}
# Printed speed -> the Mach number the report's curves fit (module docstring).
CURVE_MACH = {55.5: 0.17, 39.6: 0.12}


def load(name):
    return np.loadtxt(DATA / f"19890016302-{name}.csv", delimiter=",", ndmin=2).T


def nearest_band(frequency_khz):
    """The nominal one-third-octave centre (Hz, 2 Hz ... 200 kHz) nearest to each digitized frequency."""
    centres = np.concatenate([NOMINAL_CENTRES / 10.0, NOMINAL_CENTRES, NOMINAL_CENTRES * 10.0])
    f = np.asarray(frequency_khz) * 1e3
    return centres[np.argmin(np.abs(np.log(centres[None, :] / f[:, None])), axis=1)]


def spectrum(frequency, chord, speed, alpha_deg, tripped, component):
    spectra = bpm.segment_spectra(frequency, chord, SPAN, speed, np.deg2rad(alpha_deg), speed * chord / NU, R_E,
                                  np.pi / 2, np.pi / 2, C0, tripped)
    return spl_db(spectra[COMPONENTS[component]])


def largest_error(figure, curves, chord, speed, alpha, tripped):
    """Largest |model - report| (dB) over every digitized band of the panel's curves."""
    errors = []
    for curve in curves:
        f_khz, level = load(f"{figure}-{curve}")
        errors.append(np.max(np.abs(spectrum(nearest_band(f_khz), chord, speed, alpha, tripped, curve) - level)))
    return max(errors)


@pytest.mark.parametrize("figure, curve", [(f, c) for f, case in CASES.items() for c in case[4]])
def test_report_spectra_within_1_db(figure, curve):
    """Every digitized band of the report's prediction within 1 dB (figure and panel in the test id)."""
    chord, speed, alpha, tripped, _ = CASES[figure]
    assert largest_error(figure, [curve], chord, speed, alpha, tripped) < 1.0


@pytest.mark.parametrize("figure", list(PRINTED_SPEED_MISSES))
def test_report_spectra_at_55_5_and_39_6_m_per_s(figure):
    """Panels (b) and (c): not within 1 dB at the printed speed (the point of issue 26 this leaves open), and
    within 1 dB at U = M c_0 with the Mach numbers 0.17 and 0.12.  Those two numbers are a FIT (one per printed
    speed, jointly over all twelve panels and their mechanisms: the module docstring gives the evidence), so the
    second assertion is a fit residual (the shapes of the spectra agree), not an independent check."""
    chord, speed, alpha, tripped, curves, _ = PRINTED_SPEED_MISSES[figure]
    assert largest_error(figure, curves, chord, speed, alpha, tripped) > 1.0
    assert largest_error(figure, curves, chord, CURVE_MACH[speed] * C0, alpha, tripped) < 1.0


def test_curves_fit_the_printed_speed_at_71_3_and_31_7_m_per_s():
    """The counter-check: no panel (a) or (d) fits such a shift; 3 % faster makes every one worse (0.8-4.0 dB)."""
    for figure, (chord, speed, alpha, tripped, curves) in CASES.items():
        printed = largest_error(figure, curves, chord, speed, alpha, tripped)
        assert printed < largest_error(figure, curves, chord, 1.03 * speed, alpha, tripped)


def test_tip_vortex_figure91():
    """Figure 91: rounded tip, chord 15.24 cm, U = 71.3 m/s, alpha_TIP = 10.8 deg with BPM's 0.71 correction
    (Eq. 66); measured max 0.56 dB."""
    f_khz, level = load("figure91-tip")
    p2 = bpm.tip_vortex_pressure_squared(nearest_band(f_khz), 0.1524, 71.3 / C0, C0, np.deg2rad(10.8), R_E, 1.0)
    assert np.max(np.abs(spl_db(p2) - level)) < 1.0


def test_separation_takes_over_above_stall():
    """Sec. 5.1.1: above alpha*_0 = min(gamma_0, 12.5 deg) the pressure and suction terms vanish and the
    separation term uses D_l and A at 3 R_c; below, the separation term uses D_h and B."""
    f = NOMINAL_CENTRES
    stalled = bpm.segment_spectra(f, 0.0508, SPAN, 71.3, np.deg2rad(15.4), 71.3 * 0.0508 / NU, R_E, np.pi / 2,
                                  np.pi / 2, C0, tripped=False)
    assert np.all(stalled["tbl_te_pressure"] == 0.0) and np.all(stalled["tbl_te_suction"] == 0.0)
    assert np.all(stalled["separation"] > 0.0)
    # Figure 69a (chord 5.08 cm, U = 71.3 m/s, alpha* = 15.4 deg, untripped): the stalled spectrum within 1 dB.
    f_khz, level = load("figure69-a-separation")
    model = spectrum(nearest_band(f_khz), 0.0508, 71.3, 15.4, False, "separation")
    assert np.max(np.abs(model - level)) < 1.0
