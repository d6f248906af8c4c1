"""The polar interface every airfoil model in bild-mdo implements.

A polar maps angle of attack ``alpha`` (rad) and chord Reynolds number ``Re``
to lift and drag coefficients, together with their first derivatives.  Users
may supply their own polar: subclass :class:`Polar` and implement
:meth:`Polar._evaluate_real` (and :meth:`Polar._second_derivatives_real`, which
returns a :class:`PolarSecondDerivatives`, if the polar is used for BILD's
maximum-L/D point or its local section point).

Two optional arguments extend every query (``evaluate``, ``second_derivatives``,
``max_lift_to_drag``); left out, the result and its cost are exactly those of
the two-argument call:

``mach``
    Local Mach number.  The result gains ``d/dmach`` fields
    (:class:`MachPolarValues`).  A polar whose data do not depend on Mach
    number ignores it (zero derivatives); Mach-dependent polars are
    :class:`~bild_mdo.airfoil.mach_surrogate.MachTabulatedPolar` (tables at
    several Mach numbers) and
    :class:`~bild_mdo.airfoil.compressibility.CompressiblePolar` (a
    Prandtl-Glauert or Karman-Tsien correction of single-Mach data).
    Subclasses implement :meth:`Polar._evaluate_mach_real`.
``radial_fraction``
    ``r/R`` of the blade station.  The result gains ``d/dmach`` and
    ``d/d(r/R)`` fields (:class:`StationPolarValues`).  A polar that is the
    same along the span ignores it; :class:`~bild_mdo.airfoil.spanwise.SpanwisePolar`
    blends airfoils placed along the span.  Subclasses implement
    :meth:`Polar._evaluate_station_real`.

Complex step
------------
OpenMDAO's complex-step checks push complex inputs through ``compute``.
Spline libraries do not accept complex numbers, so :meth:`Polar.evaluate`
evaluates the model at the real parts and carries the imaginary parts with the
analytic first derivatives, ``f(x + ih) = f(x) + i h f'(x) + O(h^2)``
(for ``alpha``, ``reynolds``, ``mach`` and ``radial_fraction`` alike).  With
OpenMDAO's step of 1e-40 the neglected term is far below round-off, so the
result is exactly what a complex-capable polar would give.
"""
from __future__ import annotations

import abc
from typing import NamedTuple

import numpy as np

from bild_mdo.airfoil.max_lift_to_drag import max_lift_to_drag
from bild_mdo.airfoil.thickness import checked_thickness_ratio, naca_thickness_ratio
from bild_mdo.utils.complex_step import real_part as _real


class PolarValues(NamedTuple):
    """Lift and drag coefficients and their first derivatives (alpha in rad, Re nondimensional)."""

    cl: np.ndarray
    cd: np.ndarray
    dcl_dalpha: np.ndarray
    dcl_dre: np.ndarray
    dcd_dalpha: np.ndarray
    dcd_dre: np.ndarray


def _extended(name, base, extra, doc):
    """A NamedTuple with the fields of ``base`` followed by ``extra`` (arrays)."""
    kind = NamedTuple(name, [(f, np.ndarray) for f in base._fields + extra])
    kind.__doc__ = doc
    return kind


_MACH = ("dcl_dmach", "dcd_dmach")
_STATION = ("dcl_dradial_fraction", "dcd_dradial_fraction")
MachPolarValues = _extended("MachPolarValues", PolarValues, _MACH, """\
:class:`PolarValues`, then ``dcl_dmach, dcd_dmach`` (``evaluate(..., mach=M)``).""")
StationPolarValues = _extended("StationPolarValues", PolarValues, _MACH + _STATION, """\
:class:`MachPolarValues`, then ``dcl_dradial_fraction, dcd_dradial_fraction``
(``evaluate(..., radial_fraction=x)``); the Mach derivatives are zero when no Mach number was given.""")


class PolarSecondDerivatives(NamedTuple):
    """Second derivatives of ``cl`` and ``cd`` (alpha in rad, Re nondimensional).

    The implicit-function derivatives of the max-L/D point use the first four;
    the local section point of the Reynolds-aware BILD
    (:mod:`bild_mdo.airfoil.load_path`) also uses ``d2cl_dre2, d2cd_dre2``.
    """

    d2cl_dalpha2: np.ndarray
    d2cl_dalpha_dre: np.ndarray
    d2cd_dalpha2: np.ndarray
    d2cd_dalpha_dre: np.ndarray
    d2cl_dre2: np.ndarray
    d2cd_dre2: np.ndarray


MachPolarSecondDerivatives = _extended(
    "MachPolarSecondDerivatives", PolarSecondDerivatives, ("d2cl_dalpha_dmach", "d2cd_dalpha_dmach"), """\
:class:`PolarSecondDerivatives`, then the mixed alpha-Mach derivatives ``d2cl_dalpha_dmach, d2cd_dalpha_dmach``.""")
StationPolarSecondDerivatives = _extended(
    "StationPolarSecondDerivatives", MachPolarSecondDerivatives,
    ("d2cl_dalpha_dradial_fraction", "d2cd_dalpha_dradial_fraction"), """\
:class:`MachPolarSecondDerivatives`, then the mixed alpha-``r/R`` derivatives
``d2cl_dalpha_dradial_fraction, d2cd_dalpha_dradial_fraction``.""")


def _flat(x):
    return np.require(np.atleast_1d(_real(x)), float, "C")


def _checked_mach(mach):
    real = np.asarray(_real(mach), dtype=float)
    if not np.all(np.isfinite(real)) or np.any(real < 0.0):
        bad = real[~(np.isfinite(real) & (real >= 0.0))].ravel()[0]
        raise ValueError(f"Mach number must be finite and >= 0, got {bad!r}")
    return mach


def _checked_fraction(radial_fraction):
    real = np.asarray(_real(radial_fraction), dtype=float)
    if not np.all(np.isfinite(real)):
        raise ValueError("radial_fraction (r/R) must be finite")
    return radial_fraction


class Polar(abc.ABC):
    """Base class of airfoil polars: ``C_l(alpha, Re[, M, r/R])``, ``C_d`` with derivatives."""

    #: Short human-readable name, used in messages and result files.
    name = "polar"
    #: Whether the coefficients change with Mach number (False: ``mach`` is ignored).
    varies_with_mach = False
    #: Whether the coefficients change along the span (True: ``radial_fraction`` is required).
    varies_along_span = False

    @property
    def thickness_ratio(self):
        """Section thickness over chord ``t/c``, or None when the airfoil does not give it.

        Set explicitly (``polar.thickness_ratio = 0.15``, or by a polar file), else the base polar's
        (a compressibility correction, a frozen Reynolds number), else that of a NACA designation in
        :attr:`name` (``naca4412`` -> 0.12); None for a polar that varies along the span (one per
        station: :func:`bild_mdo.airfoil.thickness.section_thickness_ratio`).
        """
        explicit = getattr(self, "_thickness_ratio", None)
        if explicit is not None:
            return explicit
        if self.varies_along_span:
            return None
        members = getattr(self, "polars", None)
        base = members[0] if members is not None and len(members) == 1 else getattr(self, "base", None)
        if isinstance(base, Polar):
            return base.thickness_ratio
        return naca_thickness_ratio(getattr(self, "name", None))

    @thickness_ratio.setter
    def thickness_ratio(self, value):
        # None removes an explicit value: the airfoil's own (base, NACA designation) applies again.
        if value is None:
            vars(self).pop("_thickness_ratio", None)
        else:
            self._thickness_ratio = checked_thickness_ratio(value)

    def evaluate(self, alpha, reynolds, mach=None, radial_fraction=None):
        """Lift and drag coefficients with first derivatives.

        Parameters
        ----------
        alpha : array_like
            Angle of attack (rad).  Real or complex (complex step).
        reynolds : array_like
            Chord Reynolds number.  Broadcast against ``alpha``.
        mach : array_like, optional
            Local Mach number (>= 0), broadcast.  ``None`` (default): no
            compressibility, exactly the two-argument polar.
        radial_fraction : array_like, optional
            ``r/R`` of each point, broadcast; needed by polars that vary along
            the span, ignored (zero derivatives) by the others.

        Returns
        -------
        PolarValues, MachPolarValues or StationPolarValues
            ``cl, cd`` (complex when an input is) and real first derivatives,
            all with the broadcast shape of the inputs: :class:`PolarValues`
            without ``mach`` and ``radial_fraction``, :class:`MachPolarValues`
            with ``mach`` only, :class:`StationPolarValues` with ``radial_fraction``.
        """
        if mach is None and radial_fraction is None:
            self._require_station()
            alpha = np.asarray(alpha)
            reynolds = np.asarray(reynolds)
            alpha, reynolds = np.broadcast_arrays(alpha, reynolds)
            vals = self._evaluate_real(_flat(alpha), _flat(reynolds))
            return _carry(vals, alpha.shape, (alpha, reynolds), ((2, 3), (4, 5)))
        if radial_fraction is None:
            self._require_station()
            args = np.broadcast_arrays(np.asarray(alpha), np.asarray(reynolds), np.asarray(_checked_mach(mach)))
            vals = self._evaluate_mach_real(*(_flat(a) for a in args))
            return _carry(vals, args[0].shape, args, ((2, 3, 6), (4, 5, 7)))
        args = [np.asarray(alpha), np.asarray(reynolds),
                np.asarray(0.0 if mach is None else _checked_mach(mach)),
                np.asarray(_checked_fraction(radial_fraction))]
        args = np.broadcast_arrays(*args)
        flat = [_flat(a) for a in args]
        vals = self._evaluate_station_real(flat[0], flat[1], None if mach is None else flat[2], flat[3])
        return _carry(vals, args[0].shape, args, ((2, 3, 6, 8), (4, 5, 7, 9)))

    def second_derivatives(self, alpha, reynolds, mach=None, radial_fraction=None):
        """Second derivatives of ``cl`` and ``cd`` (real inputs only).

        ``mach`` and ``radial_fraction`` as in :meth:`evaluate`.

        Returns
        -------
        PolarSecondDerivatives, MachPolarSecondDerivatives or StationPolarSecondDerivatives
        """
        if mach is None and radial_fraction is None:
            self._require_station()
            alpha, reynolds = np.broadcast_arrays(np.asarray(_real(alpha), dtype=float),
                                                  np.asarray(_real(reynolds), dtype=float))
            second = self._second_derivatives_real(_flat(alpha), _flat(reynolds))
            return type(second)(*(np.reshape(v, alpha.shape) for v in second))
        if radial_fraction is None:
            self._require_station()
            args = np.broadcast_arrays(*(np.asarray(_real(a), dtype=float)
                                         for a in (alpha, reynolds, _checked_mach(mach))))
            second = self._second_derivatives_mach_real(*(_flat(a) for a in args))
        else:
            args = np.broadcast_arrays(*(np.asarray(_real(a), dtype=float) for a in (
                alpha, reynolds, 0.0 if mach is None else _checked_mach(mach), _checked_fraction(radial_fraction))))
            flat = [_flat(a) for a in args]
            second = self._second_derivatives_station_real(flat[0], flat[1], None if mach is None else flat[2],
                                                           flat[3])
        return type(second)(*(np.reshape(v, args[0].shape) for v in second))

    def evaluate_with_second_derivatives(self, alpha, reynolds):
        """:meth:`evaluate` and :meth:`second_derivatives` at real ``alpha``, ``reynolds`` (no Mach number,
        not along the span), in one evaluation where the polar shares the work of the two (a
        :class:`~bild_mdo.airfoil.surrogate.TabulatedPolar`: one spline evaluation for both).

        Returns
        -------
        tuple of PolarValues and PolarSecondDerivatives
        """
        self._require_station()
        alpha, reynolds = np.broadcast_arrays(np.asarray(_real(alpha), dtype=float),
                                              np.asarray(_real(reynolds), dtype=float))
        values, second = self._evaluate_with_second_real(_flat(alpha), _flat(reynolds))
        return (type(values)(*(np.reshape(v, alpha.shape) for v in values)),
                type(second)(*(np.reshape(v, alpha.shape) for v in second)))

    @property
    def shares_second_derivatives(self):
        """Whether :meth:`evaluate_with_second_derivatives` costs less than its two calls (the polar overrides
        ``_evaluate_with_second_real``)."""
        return type(self)._evaluate_with_second_real is not Polar._evaluate_with_second_real

    def max_lift_to_drag(self, reynolds, mach=None, radial_fraction=None):
        """Maximum-L/D point ``alpha*, cl*, cd*`` with derivatives.

        Exact on this polar (a Newton solve of d(cl/cd)/d(alpha) = 0), not a
        grid scan.  Complex inputs are carried to first order like
        :meth:`evaluate`.

        Parameters
        ----------
        reynolds : array_like
            Chord Reynolds numbers, any shape.
        mach : array_like, optional
            Mach numbers, broadcast against ``reynolds``.
        radial_fraction : array_like, optional
            ``r/R`` of each station (BILD's per-station point), broadcast.

        Returns
        -------
        MaxLiftToDrag or StationMaxLiftToDrag
            See :func:`bild_mdo.airfoil.max_lift_to_drag.max_lift_to_drag`.
        """
        return max_lift_to_drag(self, reynolds, mach=mach, radial_fraction=radial_fraction)

    def _require_station(self):
        if self.varies_along_span:
            raise ValueError(f"{self.name}: this polar varies along the span; pass radial_fraction=r/R "
                             "(the station's radius over the tip radius)")

    @abc.abstractmethod
    def _evaluate_real(self, alpha, reynolds):
        """Evaluate at real, broadcast, contiguous float arrays; return :class:`PolarValues`."""

    def _second_derivatives_real(self, alpha, reynolds):
        raise NotImplementedError(
            f"{type(self).__name__} does not provide second derivatives, which the "
            "maximum-L/D point needs; implement _second_derivatives_real")

    def _evaluate_with_second_real(self, alpha, reynolds):
        """``(PolarValues, PolarSecondDerivatives)`` at real flat arrays; default: the two calls."""
        return self._evaluate_real(alpha, reynolds), self._second_derivatives_real(alpha, reynolds)

    def _evaluate_mach_real(self, alpha, reynolds, mach):
        """:class:`MachPolarValues` at real flat arrays; default: independent of Mach number."""
        return _padded(MachPolarValues, self._evaluate_real(alpha, reynolds))

    def _second_derivatives_mach_real(self, alpha, reynolds, mach):
        return _padded(MachPolarSecondDerivatives, self._second_derivatives_real(alpha, reynolds))

    def _evaluate_station_real(self, alpha, reynolds, mach, radial_fraction):
        """:class:`StationPolarValues` (``mach`` may be None); default: the same along the span."""
        if mach is None:
            return _padded(StationPolarValues, self._evaluate_real(alpha, reynolds))
        return _padded(StationPolarValues, self._evaluate_mach_real(alpha, reynolds, mach))

    def _second_derivatives_station_real(self, alpha, reynolds, mach, radial_fraction):
        if mach is None:
            return _padded(StationPolarSecondDerivatives, self._second_derivatives_real(alpha, reynolds))
        return _padded(StationPolarSecondDerivatives, self._second_derivatives_mach_real(alpha, reynolds, mach))


def _padded(kind, values):
    """``values`` extended to the fields of ``kind`` with zero derivatives (a parameter the polar ignores)."""
    zero = np.zeros_like(values[0])
    return kind(*values, *(zero for _ in range(len(kind._fields) - len(values))))


def _carry(vals, shape, inputs, slopes):
    """Reshape ``vals`` and carry the imaginary parts of complex ``inputs`` with the first derivatives.

    ``slopes`` gives, for cl and for cd, the field index of the derivative with
    respect to each input after the first two (``alpha`` and ``reynolds`` first).
    """
    vals = type(vals)(*(np.reshape(v, shape) for v in vals))
    if not any(np.iscomplexobj(x) for x in inputs):
        return vals
    imag = [np.imag(x) for x in inputs]
    cl = vals.cl + 1j * sum(vals[k] * h for k, h in zip(slopes[0], imag))
    cd = vals.cd + 1j * sum(vals[k] * h for k, h in zip(slopes[1], imag))
    return vals._replace(cl=cl, cd=cd)
