"""The polar interface every airfoil model in bild-mdo implements.

A polar maps angle of attack ``alpha`` (rad) and chord Reynolds number ``Re``
to lift and drag coefficients, together with their first derivatives.  Users
may supply their own polar: subclass :class:`Polar` and implement
:meth:`Polar._evaluate_real` (and :meth:`Polar._second_derivatives_real` if the
polar is used for the maximum-L/D point of BILD).

Complex step
------------
OpenMDAO's complex-step checks push complex inputs through ``compute``.
Spline libraries do not accept complex numbers, so :meth:`Polar.evaluate`
evaluates the model at the real parts and carries the imaginary parts with the
analytic first derivatives, ``f(x + ih) = f(x) + i h f'(x) + O(h^2)``.  With
OpenMDAO's step of 1e-40 the neglected term is far below round-off, so the
result is exactly what a complex-capable polar would give.
"""
from __future__ import annotations

import abc
from typing import NamedTuple

import numpy as np

from bild_mdo.airfoil.max_lift_to_drag import max_lift_to_drag


class PolarValues(NamedTuple):
    """Lift and drag coefficients and their first derivatives (alpha in rad, Re nondimensional)."""

    cl: np.ndarray
    cd: np.ndarray
    dcl_dalpha: np.ndarray
    dcl_dre: np.ndarray
    dcd_dalpha: np.ndarray
    dcd_dre: np.ndarray


class PolarSecondDerivatives(NamedTuple):
    """Second derivatives needed by the implicit-function derivative of the max-L/D point."""

    d2cl_dalpha2: np.ndarray
    d2cl_dalpha_dre: np.ndarray
    d2cd_dalpha2: np.ndarray
    d2cd_dalpha_dre: np.ndarray


def _real(x):
    return np.real(x) if np.iscomplexobj(x) else x


class Polar(abc.ABC):
    """Base class of airfoil polars: ``C_l(alpha, Re)``, ``C_d(alpha, Re)`` with derivatives."""

    #: Short human-readable name, used in messages and result files.
    name = "polar"

    def evaluate(self, alpha, reynolds):
        """Lift and drag coefficients with first derivatives.

        Parameters
        ----------
        alpha : array_like
            Angle of attack (rad).  Real or complex (complex step).
        reynolds : array_like
            Chord Reynolds number.  Broadcast against ``alpha``.

        Returns
        -------
        PolarValues
            ``cl, cd`` (complex when an input is) and real first derivatives,
            all with the broadcast shape of the inputs.
        """
        alpha = np.asarray(alpha)
        reynolds = np.asarray(reynolds)
        alpha, reynolds = np.broadcast_arrays(alpha, reynolds)
        shape = alpha.shape
        vals = self._evaluate_real(np.require(np.atleast_1d(_real(alpha)), float, "C"),
                                   np.require(np.atleast_1d(_real(reynolds)), float, "C"))
        vals = PolarValues(*(np.reshape(v, shape) for v in vals))
        if not (np.iscomplexobj(alpha) or np.iscomplexobj(reynolds)):
            return vals
        ia = np.imag(alpha)
        ire = np.imag(reynolds)
        cl = vals.cl + 1j * (vals.dcl_dalpha * ia + vals.dcl_dre * ire)
        cd = vals.cd + 1j * (vals.dcd_dalpha * ia + vals.dcd_dre * ire)
        return vals._replace(cl=cl, cd=cd)

    def second_derivatives(self, alpha, reynolds):
        """Second derivatives of ``cl`` and ``cd`` (real inputs only).

        Returns
        -------
        PolarSecondDerivatives
        """
        alpha, reynolds = np.broadcast_arrays(np.asarray(_real(alpha), dtype=float),
                                              np.asarray(_real(reynolds), dtype=float))
        second = self._second_derivatives_real(np.require(np.atleast_1d(alpha), float, "C"),
                                               np.require(np.atleast_1d(reynolds), float, "C"))
        return PolarSecondDerivatives(*(np.reshape(v, alpha.shape) for v in second))

    def max_lift_to_drag(self, reynolds):
        """Maximum-L/D point ``alpha*(Re), cl*(Re), cd*(Re)`` with Re derivatives.

        Exact on this polar (a Newton solve of d(cl/cd)/d(alpha) = 0), not a
        grid scan.  Complex ``reynolds`` is carried to first order like
        :meth:`evaluate`.

        Parameters
        ----------
        reynolds : array_like
            Chord Reynolds numbers, any shape.

        Returns
        -------
        MaxLiftToDrag
            See :func:`bild_mdo.airfoil.max_lift_to_drag.max_lift_to_drag`.
        """
        return max_lift_to_drag(self, reynolds)

    @abc.abstractmethod
    def _evaluate_real(self, alpha, reynolds):
        """Evaluate at real, broadcast, contiguous float arrays; return :class:`PolarValues`."""

    def _second_derivatives_real(self, alpha, reynolds):
        raise NotImplementedError(
            f"{type(self).__name__} does not provide second derivatives, which the "
            "maximum-L/D point needs; implement _second_derivatives_real")
