"""SingleTablePolar: one table of ``alpha, cl, cd`` at one Reynolds number, interpolated as CCBlade does.

Wind-turbine airfoil data usually come as one table per airfoil (AeroDyn's
files, already extended to +-180 deg), not as a Reynolds sweep.  This polar
reads such a table (whitespace columns ``alpha`` in degrees, ``cl``, ``cd``;
``#`` comments; a repeated angle keeps its first row) and interpolates it the
way one of the two CCBlade codes does, so that a turbine analysis can be put
next to theirs:

* ``interpolation='akima'`` (default): Akima splines in ``alpha``, as
  CCBlade.jl (``byuflowlab/CCBlade.jl``) does;
* ``'smoothing'``: smoothing cubic splines (``s = 0.1`` for ``cl``, ``0.001`` for
  ``cd``), as CCBlade (``WISDEM/CCBlade``, Python) fits its tables.

The coefficients do not depend on the Reynolds number (their Reynolds
derivatives are zero).  A table of at most three rows (a cylinder's constant
drag) gives its first row's ``cl, cd`` at every angle.
"""
from pathlib import Path

import numpy as np

from bild_mdo.airfoil.polar import Polar, PolarSecondDerivatives, PolarValues

INTERPOLATIONS = ("akima", "smoothing")


class SingleTablePolar(Polar):
    """A single-Reynolds ``alpha (deg), cl, cd`` table (module docstring).

    Parameters
    ----------
    path : str or Path
        The table.
    interpolation : {'akima', 'smoothing'}
        CCBlade.jl's Akima splines or CCBlade's smoothing splines.
    name : str, optional
        Default: the file's stem.
    """

    def __init__(self, path, interpolation="akima", name=None):
        from scipy.interpolate import Akima1DInterpolator, RectBivariateSpline

        if interpolation not in INTERPOLATIONS:
            raise ValueError(f"interpolation must be one of {', '.join(INTERPOLATIONS)}, got {interpolation!r}")
        path = Path(path)
        data = np.atleast_2d(np.loadtxt(path))
        if data.shape[1] < 3 or data.shape[0] < 1:
            raise ValueError(f"{path}: expected columns alpha (deg), cl, cd, got {data.shape[1]} column(s)")
        _, keep = np.unique(data[:, 0], return_index=True)
        data = data[keep]
        alpha = np.radians(data[:, 0])
        self.name = path.stem if name is None else str(name)
        self.interpolation = interpolation
        self.constant = alpha.size <= 3
        if self.constant:
            self.cl_value, self.cd_value = data[0, 1], data[0, 2]
        elif interpolation == "smoothing":
            order = min(3, alpha.size - 1)
            self.cl = RectBivariateSpline(alpha, [1e1, 1e15], np.c_[data[:, 1], data[:, 1]], kx=order, ky=1, s=0.1)
            self.cd = RectBivariateSpline(alpha, [1e1, 1e15], np.c_[data[:, 2], data[:, 2]], kx=order, ky=1,
                                          s=0.001)
        else:
            self.cl, self.cd = Akima1DInterpolator(alpha, data[:, 1]), Akima1DInterpolator(alpha, data[:, 2])

    def _evaluate_real(self, alpha, reynolds):
        zero = np.zeros_like(alpha)
        if self.constant:
            return PolarValues(zero + self.cl_value, zero + self.cd_value, zero, zero, zero, zero)
        if self.interpolation == "smoothing":
            re = np.full_like(alpha, 1e6)
            return PolarValues(self.cl.ev(alpha, re), self.cd.ev(alpha, re), self.cl.ev(alpha, re, dx=1), zero,
                               self.cd.ev(alpha, re, dx=1), zero)
        return PolarValues(self.cl(alpha), self.cd(alpha), self.cl(alpha, 1), zero, self.cd(alpha, 1), zero)

    def _second_derivatives_real(self, alpha, reynolds):
        zero = np.zeros_like(alpha)
        if self.constant:
            return PolarSecondDerivatives(zero, zero, zero, zero, zero, zero)
        if self.interpolation == "smoothing":
            re = np.full_like(alpha, 1e6)
            return PolarSecondDerivatives(self.cl.ev(alpha, re, dx=2), zero, self.cd.ev(alpha, re, dx=2), zero, zero,
                                          zero)
        return PolarSecondDerivatives(self.cl(alpha, 2), zero, self.cd(alpha, 2), zero, zero, zero)
