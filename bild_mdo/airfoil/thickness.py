"""Section thickness ratio ``t/c`` of an airfoil: part of the airfoil description, used by the noise models.

Thickness noise (the volume the blade displaces) and the BPM self-noise need the section's maximum
thickness over its chord.  Where it comes from, first match wins
(:attr:`bild_mdo.airfoil.polar.Polar.thickness_ratio`):

* set on the polar (``polar.thickness_ratio = 0.15``), or the ``"thickness_ratio"`` of its description
  in a geometry or polar file (:mod:`bild_mdo.airfoil.serialize`), or a comment line
  ``# thickness_ratio = 0.15`` in a polar table file (:func:`thickness_from_header`);
* a polar built on another (compressibility correction, frozen Reynolds number): its base's;
* a polar generated from a Selig coordinates file (XFOIL, NeuralFoil): the shape's largest thickness
  normal to its chord (:func:`coordinates_thickness_ratio`);
* a NACA 4- or 5-digit designation in the polar's name: its last two digits (``naca4412`` -> 0.12,
  ``'NACA 0012'`` -> 0.12, ``naca23015`` -> 0.15), so the built-in NACA 4412 and XFOIL polars of NACA
  designations carry it;
* otherwise unknown: :func:`section_thickness_ratio` then uses :data:`DEFAULT_THICKNESS_RATIO` (0.12)
  with a :class:`ThicknessWarning` naming the airfoil.

A :class:`~bild_mdo.airfoil.spanwise.SpanwisePolar` has one thickness per station, blended in ``r/R``
with the same smooth step as its coefficients.
"""
from __future__ import annotations

import re
import warnings

import numpy as np

__all__ = ["DEFAULT_THICKNESS_RATIO", "ThicknessWarning", "checked_thickness_ratio", "coordinates_thickness_ratio",
           "naca_thickness_ratio", "section_thickness_ratio", "thickness_from_header"]

#: Thickness ratio assumed (with a warning) for an airfoil that does not give one.
DEFAULT_THICKNESS_RATIO = 0.12

_NACA = re.compile(r"naca[\s_-]*(\d{4,5})(?!\d)", re.IGNORECASE)
_HEADER = re.compile(r"^\s*#\s*thickness_ratio\s*=\s*(\S+)", re.IGNORECASE)


class ThicknessWarning(UserWarning):
    """An airfoil without a thickness ratio: the noise models use :data:`DEFAULT_THICKNESS_RATIO`."""


def checked_thickness_ratio(value, where="thickness_ratio"):
    """``value`` as a float in (0, 1), or ``ValueError`` (one line naming ``where``)."""
    try:
        ratio = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{where} must be a number t/c in (0, 1), got {value!r}") from None
    if not 0.0 < ratio < 1.0:
        raise ValueError(f"{where} must be a number t/c in (0, 1), got {value!r}")
    return ratio


def naca_thickness_ratio(name):
    """Thickness ratio of the NACA 4- or 5-digit designation in ``name`` (its last two digits), or None."""
    match = _NACA.search(str(name or ""))
    if match is None:
        return None
    ratio = int(match.group(1)[-2:]) / 100.0
    return ratio if ratio > 0.0 else None


def coordinates_thickness_ratio(xy, where="coordinates"):
    """Largest thickness over chord of a Selig shape ``xy[n, 2]`` (trailing edge, upper surface, leading edge,
    lower surface): both surfaces interpolated in ``x`` on 2001 cosine-spaced points between the leading edge
    (the point of least ``x``) and the trailing edge, the thickness normal to the chord (``x`` axis).  For a
    NACA 4-digit section that is its last two digits (its half-thickness distribution peaks at 30 % chord).
    ``ValueError`` (naming ``where``) for a shape whose surfaces cross or are not single-valued in ``x``."""
    xy = np.asarray(xy, dtype=float)
    lead = int(np.argmin(xy[:, 0]))
    upper, lower = xy[:lead + 1][::-1], xy[lead:]
    x0, chord = xy[lead, 0], float(np.max(xy[:, 0]) - xy[lead, 0])
    if not (chord > 0.0 and np.all(np.diff(upper[:, 0]) > 0.0) and np.all(np.diff(lower[:, 0]) > 0.0)):
        raise ValueError(f"{where}: the surfaces must each run once from the leading edge (least x) to the "
                         "trailing edge to give a thickness ratio")
    x = x0 + chord * 0.5 * (1.0 - np.cos(np.linspace(0.0, np.pi, 2001)))
    gap = np.interp(x, upper[:, 0], upper[:, 1]) - np.interp(x, lower[:, 0], lower[:, 1])
    ratio = float(np.max(gap)) / chord
    if not 0.0 < ratio < 1.0 or np.min(gap[1:-1]) < 0.0:
        raise ValueError(f"{where}: the upper surface must lie above the lower one (thickness ratio {ratio:.4g})")
    return ratio


def thickness_from_header(path):
    """The ``# thickness_ratio = VALUE`` comment line of a polar table file, or None (unreadable file: None)."""
    try:
        with open(path, encoding="utf-8", errors="replace") as handle:
            for line in handle:
                match = _HEADER.match(line)
                if match:
                    return checked_thickness_ratio(match.group(1), f"{path}: thickness_ratio")
    except OSError:
        return None
    return None


def _known(polar):
    """The thickness ratio ``polar`` gives (None if unknown); members of a spanwise set by their own rule."""
    return getattr(polar, "thickness_ratio", None)


def section_thickness_ratio(polar, radial_fraction):
    """Thickness ratio at each ``r/R`` and its derivative with respect to ``r/R`` (complex-step safe).

    Parameters
    ----------
    polar : Polar
        The blade's airfoil (a spanwise set blends its members' thickness ratios).
    radial_fraction : array_like
        ``r/R`` of each station, any shape.

    Returns
    -------
    tuple of ndarray
        ``t/c`` and ``d(t/c)/d(r/R)``, each of the shape of ``radial_fraction``.

    Warns
    -----
    ThicknessWarning
        Once per call for an airfoil (or member) without a thickness ratio: 0.12 is used.
    """
    x = np.asarray(radial_fraction)
    members = getattr(polar, "polars", None) if getattr(polar, "varies_along_span", False) else None
    if members is None:
        ratio = _known(polar)
        if ratio is None:
            _warn_default([polar])
            ratio = DEFAULT_THICKNESS_RATIO
        return np.full(x.shape, ratio, dtype=x.dtype if np.iscomplexobj(x) else float), np.zeros(x.shape)
    ratios = [_known(p) for p in members]
    _warn_default([p for p, t in zip(members, ratios) if t is None])
    ratios = np.array([DEFAULT_THICKNESS_RATIO if t is None else t for t in ratios])
    j, s, ds = polar.weights(x)
    step = ratios[j + 1] - ratios[j]
    return (ratios[j] + s * step).reshape(x.shape), np.real(ds * step).reshape(x.shape)


def _warn_default(polars):
    if polars:
        names = ", ".join(repr(getattr(p, "name", p)) for p in polars)
        warnings.warn(f"airfoil {names} gives no section thickness ratio; the noise models use t/c = "
                      f"{DEFAULT_THICKNESS_RATIO} (set polar.thickness_ratio, or 'thickness_ratio' in its polar "
                      "file)", ThicknessWarning, stacklevel=3)
