"""TurbinePolar: a wind-turbine airfoil's polar seen in the BEM's propeller convention.

The BEM kernel (:mod:`bild_mdo.bem.blade_element`) measures the angle of attack as
``alpha_p = twist + pitch - phi`` and its lift as pushing the air downstream (thrust against the
freestream).  A turbine blade section is the same airfoil turned over: it lifts toward the
rotation and downwind, with CCBlade's angle of attack ``alpha = phi - theta`` (``theta`` the twist
plus pitch; Ning 2014).  With ``alpha_p = -alpha`` the lift flips sign and the drag does not::

    cl_p(alpha_p) = -cl(-alpha_p),    cd_p(alpha_p) = cd(-alpha_p),

so a turbine is the kernel's rotor with this polar and ``twist`` equal to the turbine's ``theta``
(the same sign: a positive pitch lowers the turbine's angle of attack, toward feather).  Then
``C_x = -C_n`` and ``C_theta = -C_t`` (CCBlade's normal and tangential coefficients): the kernel's
thrust and torque are minus the turbine's, ``dT/dr < 0`` and ``dQ/dr < 0`` in the windmill state.
"""
from __future__ import annotations

import numpy as np

from bild_mdo.airfoil.polar import Polar

#: Fields of the polar values that keep their sign in the mirror (the others flip).
_KEPT = ("cd", "dcd_dre", "dcd_dmach", "dcd_dradial_fraction", "dcl_dalpha")


def _mirrored(values):
    return type(values)(*(v if name in _KEPT else -v for name, v in zip(values._fields, values)))


class TurbinePolar(Polar):
    """The polar of a turbine airfoil (its own convention, ``alpha = phi - theta``) for the BEM kernel.

    Parameters
    ----------
    base : Polar
        The airfoil's polar as published for the turbine (AeroDyn / CCBlade tables), any
        :class:`~bild_mdo.airfoil.polar.Polar` (also one that varies along the span or with Mach number).

    Attributes
    ----------
    base : Polar
    """

    def __init__(self, base):
        if not isinstance(base, Polar):
            raise ValueError(f"TurbinePolar needs a Polar, got {type(base).__name__}")
        if isinstance(base, TurbinePolar):
            raise ValueError("the polar is already a TurbinePolar; pass the airfoil's own polar")
        self.base = base
        self.name = f"{base.name} (turbine)"
        self.varies_with_mach = base.varies_with_mach
        self.varies_along_span = base.varies_along_span

    def _evaluate_real(self, alpha, reynolds):
        return _mirrored(self.base._evaluate_real(np.negative(alpha), reynolds))

    def _evaluate_mach_real(self, alpha, reynolds, mach):
        return _mirrored(self.base._evaluate_mach_real(np.negative(alpha), reynolds, mach))

    def _evaluate_station_real(self, alpha, reynolds, mach, radial_fraction):
        return _mirrored(self.base._evaluate_station_real(np.negative(alpha), reynolds, mach, radial_fraction))
