"""Airfoils named by text: the form a sweep, a geometry file and the command line keep, and its polar.

A sweep names its airfoil by a string, so that the results store can hold it
(column ``airfoil``), the sweep fingerprint includes it and worker processes
rebuild the same polar from it.  :func:`sweep_polar` turns that string into the
polar BILD, the BEM optimisation and the optimality check all use.  It accepts
everything :func:`bild_mdo.airfoil.builtin.resolve_polar` accepts (a built-in
name, a NACA designation, polar files or a folder, a coordinates file,
``neuralfoil:NAME``) and two forms of its own:

``AIRFOIL@re=RE``
    The polar of ``AIRFOIL`` frozen at the one Reynolds number ``RE``
    (:class:`FixedReynoldsPolar`): lift and drag do not vary with Re.  With
    ``naca4412@re=1e6`` BILD's one-Reynolds-number airfoil point (paper
    Assumption 2) is exact for the optimiser as well, so the sweep measures
    the method's geometry error without the optimiser's freedom to run
    sections at other Reynolds numbers (the clean geometry verification).
``X:AIRFOIL;X:AIRFOIL...``
    Airfoils placed at radial fractions ``X = r/R`` and blended along the
    span (:func:`bild_mdo.airfoil.builtin.spanwise_polar`), for example
    ``0.2:naca4415;1:naca4412``.  Each member may carry its own ``@re=``.
"""
from __future__ import annotations

import re

import numpy as np

from bild_mdo.airfoil.builtin import resolve_polar, spanwise_polar
from bild_mdo.airfoil.polar import Polar

#: The sweep's default airfoil (the paper's NACA 4412, Reynolds-dependent XFOIL surrogate).
DEFAULT_AIRFOIL = "naca4412"
#: The Reynolds-independent reference airfoil of the clean geometry verification.
REYNOLDS_INDEPENDENT_AIRFOIL = "naca4412@re=1e6"

_FIXED_RE = re.compile(r"^(?P<airfoil>.+?)\s*@\s*re\s*=\s*(?P<re>.*?)\s*$", re.IGNORECASE)
_STATION = re.compile(r"^\s*(?P<x>[0-9.eE+-]+)\s*:\s*(?P<airfoil>.+?)\s*$")
_STATION_SEPARATOR = ";"

# Polars resolved in this process, by their text: one object per airfoil, so the set-up
# models (cached per polar object) are reused from case to case.
_POLARS = {}


class FixedReynoldsPolar(Polar):
    """A polar frozen at one Reynolds number: ``c(alpha, Re, ...) = base(alpha, Re_0, ...)``.

    Every Reynolds derivative is zero; the Mach and ``r/R`` dependence of
    ``base`` is kept.  Unlike a surrogate of a single table, it never warns
    about Reynolds numbers outside a table: there is no Reynolds range, by
    construction.

    Parameters
    ----------
    base : Polar
        The polar to freeze.
    reynolds : float
        The Reynolds number it is evaluated at (> 0).
    name : str, optional
        Default ``'{base.name}@re={reynolds:g}'``.
    """

    def __init__(self, base, reynolds, name=None):
        if not isinstance(base, Polar):
            raise ValueError(f"FixedReynoldsPolar needs a Polar, got {type(base).__name__}")
        reynolds = float(reynolds)
        if not (np.isfinite(reynolds) and reynolds > 0.0):
            raise ValueError(f"the fixed Reynolds number must be finite and > 0, got {reynolds!r}")
        self.base = base
        self.reynolds = reynolds
        self.name = name or f"{base.name}@re={reynolds:g}"
        self.varies_with_mach = base.varies_with_mach
        self.varies_along_span = base.varies_along_span
        if hasattr(base, "alpha_scan_range"):
            self.alpha_scan_range = base.alpha_scan_range

    def __repr__(self):
        return f"FixedReynoldsPolar({self.base!r}, reynolds={self.reynolds:g})"

    def _frozen(self, alpha):
        return np.full(alpha.shape, self.reynolds)

    @staticmethod
    def _values(values):
        zero = np.zeros_like(values.cl)
        return values._replace(dcl_dre=zero, dcd_dre=zero)

    @staticmethod
    def _second(values):
        zero = np.zeros_like(values.d2cl_dalpha2)
        return values._replace(d2cl_dalpha_dre=zero, d2cd_dalpha_dre=zero, d2cl_dre2=zero, d2cd_dre2=zero)

    def _evaluate_real(self, alpha, reynolds):
        return self._values(self.base._evaluate_real(alpha, self._frozen(alpha)))

    def _second_derivatives_real(self, alpha, reynolds):
        return self._second(self.base._second_derivatives_real(alpha, self._frozen(alpha)))

    def _evaluate_mach_real(self, alpha, reynolds, mach):
        return self._values(self.base._evaluate_mach_real(alpha, self._frozen(alpha), mach))

    def _second_derivatives_mach_real(self, alpha, reynolds, mach):
        return self._second(self.base._second_derivatives_mach_real(alpha, self._frozen(alpha), mach))

    def _evaluate_station_real(self, alpha, reynolds, mach, radial_fraction):
        return self._values(self.base._evaluate_station_real(alpha, self._frozen(alpha), mach, radial_fraction))

    def _second_derivatives_station_real(self, alpha, reynolds, mach, radial_fraction):
        return self._second(self.base._second_derivatives_station_real(alpha, self._frozen(alpha), mach,
                                                                       radial_fraction))


def _member(text):
    """One airfoil, with an optional ``@re=``."""
    match = _FIXED_RE.match(text)
    if match is None:
        return resolve_polar(text)
    try:
        reynolds = float(match["re"])
    except ValueError:
        raise ValueError(f"airfoil {text!r}: {match['re']!r} after '@re=' is not a number") from None
    return FixedReynoldsPolar(resolve_polar(match["airfoil"].strip()), reynolds, name=text.strip())


def _stations(text):
    """``[(r/R, member text)]`` of a spanwise spec, or None when ``text`` is not one."""
    parts = [p for p in text.split(_STATION_SEPARATOR) if p.strip()]
    matches = [_STATION.match(p) for p in parts]
    if not parts or not all(matches):
        if len(parts) > 1 or any(matches):
            raise ValueError(f"airfoil {text!r}: a spanwise set is 'r/R:AIRFOIL;r/R:AIRFOIL...' "
                             "(for example '0.2:naca4415;1:naca4412')")
        return None
    try:
        stations = [(float(m["x"]), m["airfoil"]) for m in matches]
    except ValueError:
        raise ValueError(f"airfoil {text!r}: each station of a spanwise set starts with its r/R, a number") from None
    if len({x for x, _ in stations}) != len(stations):
        raise ValueError(f"airfoil {text!r}: two stations of the spanwise set have the same r/R")
    return stations


def sweep_polar(airfoil):
    """The polar of a sweep's ``airfoil`` text (see the module docstring), one object per text in a process.

    Parameters
    ----------
    airfoil : str or Polar
        A :class:`Polar` is returned as is.

    Returns
    -------
    Polar

    Raises
    ------
    ValueError
        One line, for text that names no airfoil (the message of
        :func:`~bild_mdo.airfoil.builtin.resolve_polar` or of the forms above).
    """
    if isinstance(airfoil, Polar):
        return airfoil
    if not isinstance(airfoil, str) or not airfoil.strip():
        raise ValueError(f"a sweep's airfoil must be a non-empty string, got {airfoil!r}")
    key = airfoil.strip()
    polar = _POLARS.get(key)
    if polar is None:
        stations = _stations(key)
        if stations is None:
            polar = _member(key)
        else:
            members = [(x, _member(text)) for x, text in stations]
            polar = spanwise_polar(members) if len(members) > 1 else members[0][1]
            if len(members) > 1 and any(_FIXED_RE.match(text) for _, text in stations):
                # A member frozen at one Reynolds number has no name resolve_polar knows: the set is named by
                # its text, which this function reads back (a geometry file stores the name).
                polar.name = key
        _POLARS[key] = polar
    return polar


def polar_from(airfoil):
    """The polar of any airfoil argument of the analysis and optimisation entry points: text in every form of
    :func:`sweep_polar` (spanwise sets, ``@re=``), anything else as
    :func:`~bild_mdo.airfoil.builtin.resolve_polar` takes it (a Polar, None for the built-in NACA 4412)."""
    return sweep_polar(airfoil) if isinstance(airfoil, str) else resolve_polar(airfoil)
