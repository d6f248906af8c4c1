"""A closed-form, twice continuously differentiable polar for tests and quick studies."""
from __future__ import annotations

import dataclasses

import numpy as np

from bild_mdo.airfoil.polar import Polar, PolarSecondDerivatives, PolarValues
from bild_mdo.airfoil.viterna import DEFAULT_CD_MAX, DEFAULT_CD_REVERSE, post_stall


def _smoothstep(t):
    """Quintic smooth step on [0, 1] (value, d/dt, d2/dt2); C^2 where it meets 0 and 1."""
    t = np.where(np.real(t) < 0.0, 0.0, np.where(np.real(t) > 1.0, 1.0, t))
    w = t**3 * (10.0 - 15.0 * t + 6.0 * t**2)
    dw = 30.0 * t**2 * (1.0 - t) ** 2
    d2w = 60.0 * t * (1.0 - t) * (1.0 - 2.0 * t)
    return w, dw, d2w


# eq=False keeps identity hashing: models are cached per polar object.
@dataclasses.dataclass(eq=False, repr=False)
class AnalyticPolar(Polar):
    """Linear lift and quadratic drag, blended C^2 into Viterna post-stall flow to +-180 deg.

    Attached flow::

        cl_att = cl0 + cl_alpha * alpha
        cd_att = cd0 * (Re / reynolds_ref)**(-reynolds_exponent) + k * (cl_att - cl_cd_min)**2

    Each stall side has a Viterna-Corrigan extrapolation
    (:func:`bild_mdo.airfoil.viterna.post_stall`) matched to the attached
    curves (at the reference Reynolds number) at ``alpha_stall -
    stall_half_width``, and the polar is ``cl = cl_att + w (cl_viterna -
    cl_att)`` (same for cd), where ``w`` is a quintic smooth step rising from 0
    to 1 over ``alpha_stall +- stall_half_width``.  The lift maximum is near
    ``alpha_stall``.  Every piece is C^2, and so is the blend, so the polar is C^2 on the whole
    circle (angles are wrapped to ``[-pi, pi)``; the two Viterna sides meet C^2
    at ``+-pi``).

    The maximum lift-to-drag point has the closed form
    ``cl* = sqrt(cl_cd_min^2 + cd0 f(Re) / k)``, ``alpha* = (cl* - cl0) / cl_alpha``,
    ``cd* = 2 k cl* (cl* - cl_cd_min)`` (see :meth:`max_lift_to_drag_closed_form`)
    as long as ``alpha*`` lies below the stall blend: always with the defaults
    (``alpha* = 5.9 deg``), and for ``Re >= 3e4`` with ``reynolds_exponent=0.2``.

    Parameters
    ----------
    cl0 : float
        Lift coefficient at zero angle of attack.  The default 0.4 is that of a
        NACA 4412 (4 % camber).
    cl_alpha : float
        Lift-curve slope (per rad); default ``0.9 * 2 pi``.
    cd0 : float
        Minimum drag coefficient at ``reynolds_ref``.
    k : float
        Quadratic drag factor.
    cl_cd_min : float
        Lift coefficient of minimum drag.
    alpha_stall : float
        Positive stall angle (rad), centre of the upper blend; default 13 deg.
    alpha_stall_negative : float
        Negative stall angle (rad); default -12 deg.
    stall_half_width : float
        Half width of each stall blend (rad); default 3 deg.
    cd_max : float
        Flat-plate drag coefficient at +-90 deg.
    cd_reverse : float
        Drag coefficient at +-180 deg.
    reynolds_exponent : float
        Exponent ``n`` of the Reynolds scaling ``(Re/reynolds_ref)**(-n)`` of
        ``cd0``; 0 (default) makes the polar independent of Reynolds number.
        0.2 is the turbulent flat-plate skin-friction scaling.
    reynolds_ref : float
        Reference Reynolds number of ``cd0`` and of the Viterna matching.
    """

    name = "analytic"
    # Its defaults are those of a NACA 4412 (cl0, slope), so it stands for a 12 % thick section.
    _thickness_ratio = 0.12

    cl0: float = 0.4
    cl_alpha: float = 0.9 * 2.0 * np.pi
    cd0: float = 0.008
    k: float = 0.01
    cl_cd_min: float = 0.4
    alpha_stall: float = np.radians(13.0)
    alpha_stall_negative: float = np.radians(-12.0)
    stall_half_width: float = np.radians(3.0)
    cd_max: float = DEFAULT_CD_MAX
    cd_reverse: float = DEFAULT_CD_REVERSE
    reynolds_exponent: float = 0.0
    reynolds_ref: float = 1.0e6

    def __post_init__(self):
        for field in dataclasses.fields(self):
            setattr(self, field.name, float(getattr(self, field.name)))
        dw = self.stall_half_width
        if not (self.cl_alpha > 0 and self.cd0 > 0 and self.k > 0 and dw > 0
                and self.cd_max > 0 and self.cd_reverse > 0 and self.reynolds_ref > 0):
            raise ValueError("cl_alpha, cd0, k, stall_half_width, cd_max, cd_reverse and "
                             "reynolds_ref must all be positive")
        if not (self.alpha_stall_negative + dw < 0.0 < self.alpha_stall - dw
                and self.alpha_stall + dw < 0.5 * np.pi
                and self.alpha_stall_negative - dw > -0.5 * np.pi):
            raise ValueError(
                "need -pi/2 < alpha_stall_negative +- stall_half_width < 0 < "
                "alpha_stall +- stall_half_width < pi/2; got alpha_stall="
                f"{np.degrees(self.alpha_stall):g} deg, alpha_stall_negative="
                f"{np.degrees(self.alpha_stall_negative):g} deg, stall_half_width="
                f"{np.degrees(dw):g} deg")
        self._sides = []
        # Viterna is matched where the blend starts, so it is only ever used on its
        # post-stall side: matching at the blend centre would let the Viterna curve
        # (falling lift, low drag) leak into the attached side and raise L/D there.
        for a_s in (self.alpha_stall - dw, self.alpha_stall_negative + dw):
            cl_s = self.cl0 + self.cl_alpha * a_s
            cd_s = self.cd0 + self.k * (cl_s - self.cl_cd_min) ** 2
            self._sides.append((a_s, cl_s, cd_s))

    @property
    def alpha_scan_range(self):
        """Attached-flow range ``(alpha_stall_negative, alpha_stall)`` (rad) of the max-L/D search."""
        return (self.alpha_stall_negative, self.alpha_stall)

    def __repr__(self):
        return (f"AnalyticPolar(cl0={self.cl0:g}, cl_alpha={self.cl_alpha:g}, cd0={self.cd0:g}, "
                f"k={self.k:g}, alpha_stall={np.degrees(self.alpha_stall):g} deg, "
                f"reynolds_exponent={self.reynolds_exponent:g})")

    def _reynolds_factor(self, reynolds):
        """``f = (Re/Re_ref)^-n``, ``df/dRe = -n f / Re`` and ``d2f/dRe2 = n (n + 1) f / Re^2``."""
        if self.reynolds_exponent == 0.0:
            return np.ones_like(reynolds), np.zeros_like(reynolds), np.zeros_like(reynolds)
        if np.any(~(np.real(reynolds) > 0)):
            raise ValueError("AnalyticPolar with reynolds_exponent != 0 needs positive "
                             f"Reynolds numbers; got min {np.min(reynolds)!r}")
        n = self.reynolds_exponent
        f = (reynolds / self.reynolds_ref) ** (-n)
        return f, -n * f / reynolds, n * (n + 1.0) * f / reynolds**2

    def _all(self, alpha, reynolds):
        """Values, first and second derivatives of cl and cd.

        Complex-step safe (branches on real parts), which the tests use to check
        the hand-written derivatives.
        """
        alpha = alpha - 2.0 * np.pi * np.floor((np.real(alpha) + np.pi) / (2.0 * np.pi))
        alpha, reynolds = np.broadcast_arrays(alpha, reynolds)
        f, df, d2f = self._reynolds_factor(reynolds)

        cl_att = self.cl0 + self.cl_alpha * alpha
        dcl_att = self.cl_alpha
        cd_att = self.cd0 * f + self.k * (cl_att - self.cl_cd_min) ** 2
        dcd_att = 2.0 * self.k * (cl_att - self.cl_cd_min) * self.cl_alpha
        d2cd_att = 2.0 * self.k * self.cl_alpha**2
        cd_att_re = self.cd0 * df
        cd_att_rere = self.cd0 * d2f

        cl, cd, dcd = cl_att.copy(), cd_att.copy(), dcd_att.copy()
        dcl = np.full_like(cl, dcl_att)
        d2cl = np.zeros_like(cl)
        d2cd = np.full_like(cl, d2cd_att)
        cd_re = cd_att_re * np.ones_like(cl)
        cd_are = np.zeros_like(cl)
        cd_rere = cd_att_rere * np.ones_like(cl)
        two_dw = 2.0 * self.stall_half_width
        for sign, (a_s, cl_s, cd_s) in zip((1.0, -1.0), self._sides):
            # Only the points past the matching point need the Viterna branch.
            idx = np.nonzero(sign * (np.real(alpha) - a_s) > 0.0)
            if idx[0].size == 0:
                continue
            a = alpha[idx]
            # t runs from 0 at the matching point to 1 on the stalled side.
            w, dw, d2w = _smoothstep(sign * (a - a_s) / two_dw)
            dw = dw * sign / two_dw
            d2w = d2w / two_dw**2
            v_cl, v_cd = post_stall(a, a_s, cl_s, cd_s, self.cd_max, self.cd_reverse)
            # g = g_att + w (g_v - g_att): product rule to second order.
            e_cl = v_cl.value - cl_att[idx]
            de_cl = v_cl.slope - dcl_att
            d2e_cl = v_cl.curvature
            e_cd = v_cd.value - cd_att[idx]
            de_cd = v_cd.slope - dcd_att[idx]
            d2e_cd = v_cd.curvature - d2cd_att
            cl[idx] += w * e_cl
            dcl[idx] += dw * e_cl + w * de_cl
            d2cl[idx] += d2w * e_cl + 2.0 * dw * de_cl + w * d2e_cl
            cd[idx] += w * e_cd
            dcd[idx] += dw * e_cd + w * de_cd
            d2cd[idx] += d2w * e_cd + 2.0 * dw * de_cd + w * d2e_cd
            # The Viterna side does not depend on Re: the blend scales the attached Re terms by 1 - w.
            re_idx = cd_att_re[idx] if np.ndim(cd_att_re) else cd_att_re
            cd_re[idx] -= w * re_idx
            cd_are[idx] -= dw * re_idx
            cd_rere[idx] -= w * (cd_att_rere[idx] if np.ndim(cd_att_rere) else cd_att_rere)
        zeros = np.zeros_like(cl)
        return (cl, cd, dcl, zeros, dcd, cd_re), (d2cl, zeros, d2cd, cd_are, zeros, cd_rere)

    def _evaluate_real(self, alpha, reynolds):
        return PolarValues(*self._all(alpha, reynolds)[0])

    def _second_derivatives_real(self, alpha, reynolds):
        return PolarSecondDerivatives(*self._all(alpha, reynolds)[1])

    def max_lift_to_drag_closed_form(self, reynolds):
        """Closed-form maximum-L/D point ``(alpha*, cl*, cd*)`` of the attached-flow model.

        Minimising ``cd/cl`` with ``cd = cd0 f + k (cl - cl_cd_min)^2`` gives
        ``k cl*^2 = k cl_cd_min^2 + cd0 f``.  Valid while ``alpha*`` lies below
        the stall blend (true for the defaults).

        Parameters
        ----------
        reynolds : array_like
            Chord Reynolds number.

        Returns
        -------
        tuple of ndarray
            ``alpha*`` (rad), ``cl*``, ``cd*``.
        """
        reynolds = np.asarray(reynolds, dtype=float)
        f = self._reynolds_factor(reynolds)[0]
        cl = np.sqrt(self.cl_cd_min**2 + self.cd0 * f / self.k)
        cd = self.cd0 * f + self.k * (cl - self.cl_cd_min) ** 2
        return (cl - self.cl0) / self.cl_alpha, cl, cd
