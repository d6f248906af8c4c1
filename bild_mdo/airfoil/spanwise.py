"""Several airfoils along the span: one polar that blends smoothly between airfoils placed at ``r/R``.

Real blades use thick sections at the root and thin ones at the tip.  A
:class:`SpanwisePolar` places polars at radial fractions ``x_0 < x_1 < ...``
and, between two neighbours, blends their coefficients with the quintic
smooth step ``s(t) = 10 t^3 - 15 t^4 + 6 t^5``, ``t = (x - x_j)/(x_{j+1} - x_j)``::

    c(alpha, Re, M, x) = (1 - s(t)) c_j(alpha, Re, M) + s(t) c_{j+1}(alpha, Re, M)

for ``cl`` and ``cd`` alike (inboard of ``x_0`` the first polar, outboard of
the last the last one).  Why this blend:

* it is twice continuously differentiable in ``r/R`` everywhere, including
  at the stations and at the ends (``s' = s'' = 0`` at ``t = 0, 1``), so the
  derivatives with respect to ``r/R`` are continuous for an optimiser that
  moves the radius;
* the weights are between 0 and 1 and sum to 1, so the blend of positive
  drags stays positive and never overshoots the two airfoils (a global
  spline in ``r/R`` could);
* at a station the polar is exactly that airfoil's, and only two airfoils
  are evaluated at any point.

Use it wherever a polar is used, with ``radial_fraction=r/R`` of each point:
:meth:`~bild_mdo.airfoil.polar.Polar.evaluate` (BEM: the blended polar of each
station) and :meth:`~bild_mdo.airfoil.polar.Polar.max_lift_to_drag` (BILD:
``alpha*, cl*, cd*`` of each station at given Reynolds and Mach numbers,
with derivatives with respect to ``Re``, ``M`` and ``r/R``).  Calls without
``radial_fraction`` raise ``ValueError``: there is no single polar to use.
"""
from __future__ import annotations

import numpy as np

from bild_mdo.airfoil.polar import MachPolarSecondDerivatives, Polar, StationPolarSecondDerivatives, StationPolarValues

__all__ = ["SpanwisePolar", "smooth_step"]


def smooth_step(t):
    """Quintic smooth step ``s(t)`` clipped to [0, 1], with ``ds/dt`` (complex-step safe).

    Returns
    -------
    tuple of ndarray
        ``s``, ``ds/dt``.
    """
    t = np.where(np.real(t) < 0.0, 0.0, np.where(np.real(t) > 1.0, 1.0, t))
    return t ** 3 * (10.0 - 15.0 * t + 6.0 * t ** 2), 30.0 * t ** 2 * (1.0 - t) ** 2


def _flat(*arrays):
    """The common shape and the raveled arrays (``None`` stays ``None``)."""
    return arrays[0].shape, [None if a is None else a.ravel() for a in arrays]


class SpanwisePolar(Polar):
    """Airfoil polars placed at radial fractions, blended C^2-smoothly in ``r/R`` (module docstring).

    Parameters
    ----------
    polars : sequence of Polar
        One polar per station, root to tip (not spanwise polars themselves).
    radial_fractions : sequence of float
        ``r/R`` of each polar, strictly increasing, in [0, 1].
    name : str, optional
        Default: the member names joined by ``'>'``.

    Attributes
    ----------
    polars : tuple of Polar
    radial_fractions : ndarray
    """

    def __init__(self, polars, radial_fractions, name=None):
        polars = tuple(polars)
        fractions = np.asarray(radial_fractions, dtype=float).ravel()
        if not polars or len(polars) != fractions.size:
            raise ValueError(f"SpanwisePolar needs one radial fraction per polar, got {len(polars)} polars and "
                             f"{fractions.size} fractions")
        for p in polars:
            if not isinstance(p, Polar) or p.varies_along_span:
                raise ValueError(f"SpanwisePolar members must be polars that are the same along the span, "
                                 f"got {p!r}")
        if not (np.all(np.isfinite(fractions)) and np.all(np.diff(fractions) > 0.0)
                and fractions[0] >= 0.0 and fractions[-1] <= 1.0):
            raise ValueError(f"radial_fractions must increase strictly within [0, 1], got {fractions.tolist()}")
        self.polars = polars
        self.radial_fractions = fractions
        self.name = name or ">".join(p.name for p in polars)
        self.varies_along_span = len(polars) > 1
        self.varies_with_mach = any(p.varies_with_mach for p in polars)
        ranges = [getattr(p, "alpha_scan_range", None) for p in polars]
        if all(r is not None for r in ranges):
            self.alpha_scan_range = (min(r[0] for r in ranges), max(r[1] for r in ranges))

    def __repr__(self):
        places = ", ".join(f"{p.name}@{x:g}" for p, x in zip(self.polars, self.radial_fractions))
        return f"SpanwisePolar({places})"

    def weights(self, radial_fraction):
        """Segment index, the blend ``s`` and ``ds/d(r/R)`` at each ``r/R`` (complex-step safe).

        Returns
        -------
        tuple of ndarray
            ``j`` (the blend is ``(1 - s) polar_j + s polar_{j+1}``), ``s``, ``ds/dx``;
            flat (the inputs are raveled).
        """
        x = np.asarray(radial_fraction).ravel()
        f = self.radial_fractions
        if f.size == 1:
            zero = np.zeros(x.shape)
            return np.zeros(x.shape, dtype=np.intp), zero, zero
        j = np.clip(np.searchsorted(f, np.real(x), side="right") - 1, 0, f.size - 2)
        width = f[j + 1] - f[j]
        s, ds = smooth_step((x - f[j]) / width)
        return j, s, ds / width

    def _blend(self, radial_fraction, call, n_fields):
        """Weighted sums of the members' ``call(polar, idx)`` fields and of their ``r/R`` slopes."""
        j, s, ds = self.weights(radial_fraction)
        total = np.zeros((n_fields, j.size))
        slope = np.zeros((n_fields, j.size))
        last_segment = max(len(self.polars) - 2, 0)
        for k, _ in enumerate(self.polars):
            for seg, w, dw in ((k, 1.0 - s, -ds), (k - 1, s, ds)):
                if not 0 <= seg <= last_segment:
                    continue
                idx = np.flatnonzero(j == seg)
                if idx.size == 0:
                    continue
                vals = np.asarray(call(self.polars[k], idx))
                total[:, idx] += w[idx] * vals
                slope[:, idx] += dw[idx] * vals
        return total, slope

    def _evaluate_real(self, alpha, reynolds):
        raise ValueError(f"{self.name}: pass radial_fraction")  # unreachable: evaluate() checks first

    def _evaluate_station_real(self, alpha, reynolds, mach, radial_fraction):
        shape, (alpha, reynolds, mach, radial_fraction) = _flat(alpha, reynolds, mach, radial_fraction)

        def call(polar, idx):
            if mach is None:
                v = polar._evaluate_real(alpha[idx], reynolds[idx])
                return [*v, np.zeros(idx.size), np.zeros(idx.size)]
            return list(polar._evaluate_mach_real(alpha[idx], reynolds[idx], mach[idx]))

        total, slope = self._blend(radial_fraction, call, 8)
        return StationPolarValues(*(v.reshape(shape) for v in (*total, slope[0], slope[1])))

    def _second_derivatives_station_real(self, alpha, reynolds, mach, radial_fraction):
        shape, (alpha, reynolds, mach, radial_fraction) = _flat(alpha, reynolds, mach, radial_fraction)

        def call(polar, idx):
            if mach is None:
                s = polar._second_derivatives_real(alpha[idx], reynolds[idx])
                v = polar._evaluate_real(alpha[idx], reynolds[idx])
                return [*s, np.zeros(idx.size), np.zeros(idx.size), v.dcl_dalpha, v.dcd_dalpha]
            s = polar._second_derivatives_mach_real(alpha[idx], reynolds[idx], mach[idx])
            v = polar._evaluate_mach_real(alpha[idx], reynolds[idx], mach[idx])
            return [*s, v.dcl_dalpha, v.dcd_dalpha]

        n_mach = len(MachPolarSecondDerivatives._fields)
        total, slope = self._blend(radial_fraction, call, n_mach + 2)
        # d2c/(dalpha dx) = sum_k w_k'(x) dc_k/dalpha: the slopes of the last two fields.
        return StationPolarSecondDerivatives(*(v.reshape(shape) for v in (*total[:n_mach], slope[n_mach],
                                                                            slope[n_mach + 1])))
