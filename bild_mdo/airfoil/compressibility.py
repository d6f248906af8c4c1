"""Compressibility corrections of lift for polars measured at one low Mach number.

Two classical corrections of subsonic thin-airfoil theory, applied to the lift
coefficient as a whole (Anderson, *Fundamentals of Aerodynamics*, Sec. 11.4
and 11.6), with ``beta = sqrt(1 - M^2)``:

``'prandtl-glauert'`` (Glauert 1928; Prandtl)
    ``cl = cl_inc / beta``: the lift slope scales with ``1/sqrt(1 - M^2)``.
``'karman-tsien'`` (von Karman 1941; Tsien 1939)
    ``cl = cl_inc / (beta + M^2 / (1 + beta) * cl_inc / 2)``: the pressure
    rule of Karman and Tsien applied to ``cl``; close to Prandtl-Glauert at
    small lift, stronger at large positive lift.

``cl_inc`` is the incompressible lift.  Data measured at a low but non-zero
Mach number ``M_data`` (a wind tunnel at M = 0.1, XFOIL at M = 0.2) are first
taken back to ``M = 0`` with the inverse rule, so that the correction at
``M = M_data`` returns the data unchanged.

Drag is left unchanged.  Below the critical Mach number the skin friction
and the form drag of an attached boundary layer change little with Mach
number; neither rule predicts wave drag, so the correction does not model
drag divergence or the loss of lift past it.

Validity.  Both rules are linearised subsonic theory: they hold up to the
critical Mach number of the section (about 0.6 to 0.75 for 9-15 % thick
sections at moderate lift).  Above ``MACH_WARNING`` (0.7) a warning is issued
once per polar; Mach numbers above ``MACH_LIMIT`` (0.9) are evaluated at 0.9
(zero Mach derivative there), as Reynolds numbers outside a table are
clamped, so that a solver that strays there still gets finite numbers.  For
transonic blades use XFOIL tables at several Mach numbers
(:class:`~bild_mdo.airfoil.mach_surrogate.MachTabulatedPolar`).
"""
from __future__ import annotations

import warnings

import numpy as np

from bild_mdo.airfoil.polar import MachPolarSecondDerivatives, MachPolarValues, Polar

__all__ = ["CORRECTIONS", "MACH_LIMIT", "MACH_WARNING", "CompressiblePolar", "karman_tsien", "prandtl_glauert"]

#: Names accepted by :class:`CompressiblePolar` (and ``resolve_polar(..., compressibility=...)``).
CORRECTIONS = ("prandtl-glauert", "karman-tsien")
#: Mach number above which a warning says the correction is outside its validity.
MACH_WARNING = 0.7
#: Mach numbers above this are evaluated at it.
MACH_LIMIT = 0.9


def _beta(mach):
    """``beta``, ``dbeta/dM`` and the Karman-Tsien ``k = M^2 / (2 (1 + beta))`` with ``dk/dM``."""
    beta = np.sqrt(1.0 - mach * mach)
    dbeta = -mach / beta
    k = mach * mach / (2.0 * (1.0 + beta))
    dk = mach / (1.0 + beta) - mach * mach * dbeta / (2.0 * (1.0 + beta) ** 2)
    return beta, dbeta, k, dk


def prandtl_glauert(cl_data, mach, reference_mach=0.0):
    """Prandtl-Glauert lift ``cl = cl_data beta(M_data) / beta(M)`` and its derivatives.

    Parameters
    ----------
    cl_data : array_like
        Lift coefficient measured at ``reference_mach``.
    mach : array_like
        Mach number, ``0 <= M < 1`` (real or complex: the formula is complex-step safe).
    reference_mach : float
        Mach number of the data.

    Returns
    -------
    tuple of ndarray
        ``cl``, ``dcl/dcl_data``, ``d2cl/dcl_data2`` (zero), ``dcl/dM``, ``d2cl/(dcl_data dM)``.
    """
    beta_ref = np.sqrt(1.0 - reference_mach ** 2)
    beta, dbeta, _, _ = _beta(mach)
    scale = beta_ref / beta
    dscale = -scale * dbeta / beta
    cl_data = np.asarray(cl_data)
    return cl_data * scale, scale + 0.0 * cl_data, 0.0 * cl_data, cl_data * dscale, dscale + 0.0 * cl_data


def karman_tsien(cl_data, mach, reference_mach=0.0):
    """Karman-Tsien lift ``cl = cl_inc / (beta + k cl_inc)`` and its derivatives.

    ``k = M^2 / (2 (1 + beta))``; ``cl_inc = beta_d cl_data / (1 - k_d cl_data)``
    takes the data back from ``reference_mach`` to M = 0 (the inverse rule).

    Parameters
    ----------
    cl_data, mach, reference_mach
        As in :func:`prandtl_glauert`.

    Returns
    -------
    tuple of ndarray
        ``cl``, ``dcl/dcl_data``, ``d2cl/dcl_data2``, ``dcl/dM``, ``d2cl/(dcl_data dM)``.

    Raises
    ------
    ValueError
        Where a denominator is not positive (very large negative lift at high
        Mach number, outside the rule's validity).
    """
    cl_data = np.asarray(cl_data)
    beta_r, _, k_r, _ = _beta(np.asarray(reference_mach, dtype=float))
    den_r = 1.0 - k_r * cl_data
    beta, dbeta, k, dk = _beta(mach)
    u = beta_r * cl_data / den_r
    den = beta + k * u
    if np.any(np.real(den_r) <= 0.0) or np.any(np.real(den) <= 0.0):
        raise ValueError("Karman-Tsien correction undefined (denominator <= 0) for lift coefficients "
                         f"{np.real(cl_data).min():.3g}..{np.real(cl_data).max():.3g} at Mach "
                         f"{np.real(mach).max():.3g}; use 'prandtl-glauert' or Mach-dependent tables")
    u_c = beta_r / den_r ** 2
    u_cc = 2.0 * beta_r * k_r / den_r ** 3
    g_u = beta / den ** 2
    g_uu = -2.0 * beta * k / den ** 3
    dden = dbeta + dk * u
    g_m = -u * dden / den ** 2
    g_um = dbeta / den ** 2 - 2.0 * beta * dden / den ** 3
    return u / den, g_u * u_c, g_uu * u_c ** 2 + g_u * u_cc, g_m, g_um * u_c


_RULES = {"prandtl-glauert": prandtl_glauert, "karman-tsien": karman_tsien}


class CompressiblePolar(Polar):
    """A polar measured at one Mach number, with a compressibility correction of its lift.

    Without a Mach number (``evaluate(alpha, Re)``) it is the base polar,
    unchanged.  With ``mach`` the lift follows the chosen rule (module
    docstring) and the drag is the base polar's; all derivatives, including
    ``d/dM`` and the mixed ``d2/(dalpha dM)`` that the maximum-L/D point
    needs, are exact.

    Parameters
    ----------
    base : Polar
        A polar that does not depend on Mach number or span position.
    correction : {'prandtl-glauert', 'karman-tsien'}
        The rule.
    reference_mach : float, optional
        Mach number of the base data; default: ``base.data_mach`` if the
        base has it (tabulated polars), else 0.
    name : str, optional
        Default ``'<base name>+<correction>'``.
    """

    varies_with_mach = True

    def __init__(self, base, correction="prandtl-glauert", reference_mach=None, name=None):
        if not isinstance(base, Polar) or base.varies_with_mach or base.varies_along_span:
            raise ValueError("CompressiblePolar needs a Polar that varies neither with Mach number nor "
                             "along the span")
        key = str(correction).strip().lower().replace("_", "-").replace(" ", "-")
        if key not in _RULES:
            raise ValueError(f"unknown compressibility correction {correction!r}; choose from "
                             f"{', '.join(CORRECTIONS)}")
        if reference_mach is None:
            reference_mach = getattr(base, "data_mach", 0.0)
        reference_mach = float(reference_mach)
        if not 0.0 <= reference_mach <= 0.5:
            raise ValueError(f"reference_mach must be in [0, 0.5] (data at a low Mach number), got "
                             f"{reference_mach}")
        self.base = base
        self.correction = key
        self.reference_mach = reference_mach
        self.name = name or f"{base.name}+{key}"
        self._rule = _RULES[key]
        self._warned = False
        if hasattr(base, "alpha_scan_range"):
            self.alpha_scan_range = base.alpha_scan_range

    def __repr__(self):
        return f"CompressiblePolar({self.base!r}, {self.correction!r}, reference_mach={self.reference_mach:g})"

    def _clamped(self, mach):
        if not self._warned and np.any(mach > MACH_WARNING):
            self._warned = True
            warnings.warn(f"{self.name}: Mach numbers up to {np.max(mach):.3g} exceed {MACH_WARNING}, beyond "
                          f"the validity of the {self.correction} correction (critical Mach number, no wave "
                          f"drag); Mach numbers above {MACH_LIMIT} are evaluated at {MACH_LIMIT} (warned once "
                          "per polar)", RuntimeWarning, stacklevel=5)
        inside = mach <= MACH_LIMIT
        return np.minimum(mach, MACH_LIMIT), inside

    def _evaluate_real(self, alpha, reynolds):
        return self.base._evaluate_real(alpha, reynolds)

    def _second_derivatives_real(self, alpha, reynolds):
        return self.base._second_derivatives_real(alpha, reynolds)

    def _evaluate_mach_real(self, alpha, reynolds, mach):
        v = self.base._evaluate_real(alpha, reynolds)
        m, inside = self._clamped(mach)
        f, f_c, _, f_m, _ = self._rule(v.cl, m, self.reference_mach)
        zero = np.zeros_like(f)
        return MachPolarValues(f, v.cd, f_c * v.dcl_dalpha, f_c * v.dcl_dre, v.dcd_dalpha, v.dcd_dre,
                               np.where(inside, f_m, 0.0), zero)

    def _second_derivatives_mach_real(self, alpha, reynolds, mach):
        v = self.base._evaluate_real(alpha, reynolds)
        s = self.base._second_derivatives_real(alpha, reynolds)
        m, inside = self._clamped(mach)
        _, f_c, f_cc, _, f_cm = self._rule(v.cl, m, self.reference_mach)
        zero = np.zeros_like(f_c)
        # cl = F(cl_base, M): the chain rule to second order; cd is not corrected.
        return MachPolarSecondDerivatives(
            d2cl_dalpha2=f_cc * v.dcl_dalpha ** 2 + f_c * s.d2cl_dalpha2,
            d2cl_dalpha_dre=f_cc * v.dcl_dalpha * v.dcl_dre + f_c * s.d2cl_dalpha_dre,
            d2cd_dalpha2=s.d2cd_dalpha2, d2cd_dalpha_dre=s.d2cd_dalpha_dre,
            d2cl_dre2=f_cc * v.dcl_dre ** 2 + f_c * s.d2cl_dre2, d2cd_dre2=s.d2cd_dre2,
            d2cl_dalpha_dmach=np.where(inside, f_cm * v.dcl_dalpha, 0.0), d2cd_dalpha_dmach=zero)
