"""Frequency bands, A-weighting and decibels: the conventions every noise component of bild-mdo shares.

* One-third-octave bands: the base-ten exact centre frequencies of ANSI S1.11 /
  IEC 61260, ``f_c = 1000 * 10**(n / 10)`` Hz, with band edges
  ``f_c * 10**(+-1/20)``; :data:`THIRD_OCTAVE_CENTRES` holds the 31 bands from
  20 Hz (``n = -17``) to 20 kHz (``n = 13``), and :data:`NOMINAL_CENTRES` their
  nominal labels (20, 25, 31.5, ... Hz).
* A-weighting: the analytic form of IEC 61672-1:2013 (Annex E), normalised to
  0 dB at 1 kHz (:func:`a_weighting_db`, with its derivative).
* Decibels: sound pressure level ``SPL = 10 log10(p2 / p_ref**2 + floor)`` of a
  mean-square pressure ``p2`` (Pa**2) with ``p_ref = 20 uPa``.  The floor
  (:data:`PRESSURE_SQUARED_FLOOR`, ``1e-10``, i.e. -100 dB) keeps the level of a
  silent source finite and differentiable (``d SPL / d p2`` bounded) and changes
  any audible level (above 0 dB) by less than 5e-10 dB.
"""
from __future__ import annotations

import numpy as np

#: Reference pressure of sound in air, Pa.
REFERENCE_PRESSURE = 20e-6
#: Added to ``p2 / p_ref**2`` before the logarithm (documented above): a silent source reads -100 dB.
PRESSURE_SQUARED_FLOOR = 1e-10
#: Band numbers ``n`` of the 31 one-third-octave bands 20 Hz ... 20 kHz (``f_c = 1000 * 10**(n/10)``).
BAND_NUMBERS = np.arange(-17, 14)
#: Exact (base-ten) centre frequencies of those bands, Hz.
THIRD_OCTAVE_CENTRES = 1000.0 * 10.0 ** (BAND_NUMBERS / 10.0)
#: Their nominal labels (ANSI S1.11 Table A1), Hz.
NOMINAL_CENTRES = np.array([20, 25, 31.5, 40, 50, 63, 80, 100, 125, 160, 200, 250, 315, 400, 500, 630, 800,
                            1000, 1250, 1600, 2000, 2500, 3150, 4000, 5000, 6300, 8000, 10000, 12500, 16000,
                            20000], dtype=float)
#: Ratio of a band's upper (lower) edge to its centre frequency.
BAND_EDGE_RATIO = 10.0 ** (1.0 / 20.0)

# IEC 61672-1 Annex E pole frequencies (Hz) and the 1-kHz normalisation A1000 (dB).
_F1, _F2, _F3, _F4 = 20.598997, 107.65265, 737.86223, 12194.217
_A1000 = -2.000


def band_edges(centres=THIRD_OCTAVE_CENTRES):
    """``(lower, upper)`` edge frequencies (Hz) of one-third-octave bands with the given centres."""
    centres = np.asarray(centres, dtype=float)
    return centres / BAND_EDGE_RATIO, centres * BAND_EDGE_RATIO


def a_weighting_db(frequency):
    """A-weighting ``A(f)`` in dB (IEC 61672-1 Annex E; 0 dB at 1 kHz), for real or complex ``f`` in Hz."""
    f2 = np.asarray(frequency) ** 2
    ratio = _F4 ** 2 * f2 ** 2 / ((f2 + _F1 ** 2) * np.sqrt((f2 + _F2 ** 2) * (f2 + _F3 ** 2)) * (f2 + _F4 ** 2))
    return 20.0 * np.log10(ratio) - _A1000


def a_weighting_db_derivative(frequency):
    """``d A / d f`` in dB/Hz (the analytic derivative of :func:`a_weighting_db`)."""
    f = np.asarray(frequency)
    f2 = f ** 2
    # d ln(ratio) / d f2, term by term, then chain d f2 / d f = 2 f.
    dlog = 2.0 / f2 - 1.0 / (f2 + _F1 ** 2) - 0.5 / (f2 + _F2 ** 2) - 0.5 / (f2 + _F3 ** 2) - 1.0 / (f2 + _F4 ** 2)
    return 20.0 / np.log(10.0) * dlog * 2.0 * f


def spl_db(pressure_squared):
    """Sound pressure level (dB re 20 uPa) of a mean-square pressure (Pa**2), with the documented floor."""
    return 10.0 * np.log10(np.asarray(pressure_squared) / REFERENCE_PRESSURE ** 2 + PRESSURE_SQUARED_FLOOR)


def spl_db_derivative(pressure_squared):
    """``d SPL / d p2`` in dB/Pa**2 (finite at ``p2 = 0`` thanks to the floor)."""
    scaled = np.asarray(pressure_squared) / REFERENCE_PRESSURE ** 2 + PRESSURE_SQUARED_FLOOR
    return 10.0 / np.log(10.0) / (scaled * REFERENCE_PRESSURE ** 2)


def pressure_squared_from_spl(spl):
    """Mean-square pressure (Pa**2) of a level in dB re 20 uPa (the inverse without the floor)."""
    return REFERENCE_PRESSURE ** 2 * 10.0 ** (np.asarray(spl) / 10.0)


def incoherent_sum_db(*levels):
    """Level (dB) of incoherent sources of the given levels (dB), e.g. several rotors of one vehicle."""
    total = sum(pressure_squared_from_spl(level) for level in levels)
    return spl_db(total)
