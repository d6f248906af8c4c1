"""The station relations of minimum-induced-loss design (Adkins & Liebeck 1994) with their exact partials.

Adkins & Liebeck, "Design of optimum propellers", J. Propulsion and Power
10(5), 1994 (A&L below).  With the speed ratio ``lambda = V/(Omega R)``, the
nondimensional radius ``xi = r/R``, the displacement velocity ratio
``zeta = v'/V`` and the drag-to-lift ratio ``eps = C_d/C_l``, every quantity
of the design at a station is a closed-form function of ``(lambda, xi, zeta,
eps)``::

    tan(phi)   = lambda (1 + zeta/2) / xi                flow angle (constant-pitch wake, Betz)
    tan(phi_t) = lambda (1 + zeta/2)                     flow angle at the tip
    F          = 2/pi acos(exp(-f)),  f = (B/2)(1 - xi)/sin(phi_t)   Prandtl's momentum loss factor
    G          = F x cos(phi) sin(phi),  x = xi/lambda   circulation function
    a          = (zeta/2) cos^2(phi) (1 - eps tan(phi))  axial interference factor
    I1'        = 4 xi G (1 - eps tan(phi))
    I2'        = lambda (I1'/(2 xi)) (1 + eps/tan(phi)) sin(phi) cos(phi)
    J1'        = 4 xi G (1 + eps/tan(phi))
    J2'        = (J1'/2) (1 - eps tan(phi)) cos^2(phi)

and the design integrals give ``T_c = I1 zeta - I2 zeta^2`` and ``P_c = J1
zeta + J2 zeta^2`` (``T_c = 2T/(rho V^2 pi R^2)``, ``P_c = 2P/(rho V^3 pi
R^2)``).  ``loss_form='local'`` uses instead the tip factor of the package's
BEM analysis, ``f = (B/2)(1 - xi)/(xi sin(phi))`` (Prandtl with the local flow
angle), so that a BEM analysis with ``loss_model='tip'`` reproduces the design
exactly (A&L's "exact agreement of design and analysis").  ``loss_form='qmil'``
is the factor of Drela's QMIL (QPROP distribution: the local formulation of
``src/gvcalc.f`` that QMIL's design iteration uses; ``src/tpdes.f``, its initial
guess, has the same form): Prandtl's exponent with the wake advance ratio
``lambda_w = tan(phi_t)``, ``f = (B/2)(1 - xi)/lambda_w``, times the root
self-induction factor ``sqrt(1 + (4 lambda_w/(pi B xi))**2)``; with it the
design reproduces QMIL's (tests/mil/test_qmil_example.py).

Partials are carried forward through these closed forms by the chain rule
(:class:`Jet`): each quantity holds its value and its exact gradient with
respect to ``(lambda, xi, zeta, eps)``, evaluated at the real part of complex
inputs so that complex-step checks of the components see exact partials.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from bild_mdo.bem.prandtl import acos_factor
from bild_mdo.utils.complex_step import real_part as _real

#: Prandtl tip factor forms: A&L's (tip flow angle), the BEM analysis's (local flow angle) or QMIL's.
LOSS_FORMS = ("adkins_liebeck", "local", "qmil")
#: Order of the gradient entries of a :class:`Jet`.
VARIABLES = ("speed_ratio", "radius_fraction", "zeta", "drag_to_lift")
#: Nondimensional variables shared by the MIL components: name -> (radial, description).
MIL_VARIABLES = {
    "speed_ratio": (False, "speed ratio lambda = V/(Omega R)"),
    "radius_fraction": (True, "station radius xi = r/R"),
    "width_fraction": (True, "station width dr/R"),
    "zeta": (False, "displacement velocity ratio v'/V"),
}


def declare_design_options(options):
    """Declare ``num_blades`` and ``loss_form`` (besides the sizes) on a MIL component's or group's options."""
    options.declare("num_blades", types=int, default=2, desc="number of blades B")
    options.declare("loss_form", default="adkins_liebeck", values=LOSS_FORMS,
                    desc="Prandtl factor with the tip ('adkins_liebeck') or local flow angle, or QMIL's ('qmil')")


def add_mil_inputs(component, names):
    """Declare the :data:`MIL_VARIABLES` ``names`` as nondimensional inputs of ``component``."""
    nn, nr = component.options["num_nodes"], component.options["num_radial"]
    defaults = {"speed_ratio": 0.2, "zeta": 0.1, "width_fraction": 1.0 / nr,
                "radius_fraction": (np.arange(nr) + 0.5) / nr}
    for name in names:
        radial, desc = MIL_VARIABLES[name]
        shape = (nn, nr) if radial else (nn,)
        component.add_input(name, val=np.broadcast_to(defaults[name], shape).copy(), units=None, desc=desc)


class Jet:
    """A value with its exact gradient ``grad[k]`` with respect to :data:`VARIABLES` (chain rule forward).

    Only the operations the design relations need are defined.  ``grad`` is
    always real (partials are evaluated at the real part of complex-step
    inputs); ``value`` may be complex.
    """

    __slots__ = ("value", "grad")
    # numpy arrays on the left of an operator defer to the Jet's reflected operators.
    __array_ufunc__ = None

    def __init__(self, value, grad):
        self.value = value
        self.grad = grad

    @classmethod
    def variable(cls, value, index, shape):
        grad = np.zeros((len(VARIABLES),) + shape)
        grad[index] = 1.0
        return cls(np.broadcast_to(value, shape), grad)

    def apply(self, value, derivative):
        """``g(self)`` given ``g``'s value and its derivative at ``self``."""
        return Jet(value, _real(derivative) * self.grad)

    def __add__(self, other):
        if isinstance(other, Jet):
            return Jet(self.value + other.value, self.grad + other.grad)
        return Jet(self.value + other, self.grad)

    __radd__ = __add__

    def __neg__(self):
        return Jet(-self.value, -self.grad)

    def __sub__(self, other):
        return self + (-other)

    def __rsub__(self, other):
        return (-self) + other

    def __mul__(self, other):
        if isinstance(other, Jet):
            return Jet(self.value * other.value,
                       _real(other.value) * self.grad + _real(self.value) * other.grad)
        return Jet(self.value * other, _real(other) * self.grad)

    __rmul__ = __mul__

    def reciprocal(self):
        return self.apply(1.0 / self.value, -1.0 / _real(self.value) ** 2)

    def __truediv__(self, other):
        if isinstance(other, Jet):
            return self * other.reciprocal()
        return self * (1.0 / other)

    def __rtruediv__(self, other):
        return self.reciprocal() * other

    def sqrt(self):
        root = np.sqrt(self.value)
        return self.apply(root, 0.5 / _real(root))


class StationState(NamedTuple):
    """Design relations at the stations (each a :class:`Jet`)."""

    phi: Jet
    loss_factor: Jet
    circulation: Jet
    axial_interference: Jet
    sin_phi: Jet
    cos_phi: Jet
    i1: Jet
    i2: Jet
    j1: Jet
    j2: Jet


def _prandtl(f):
    """``2/pi acos(exp(-f))`` with the exponent clipped as in :mod:`bild_mdo.bem.prandtl`."""
    return f.apply(*acos_factor(f.value))


def station_state(speed_ratio, radius_fraction, zeta, drag_to_lift, num_blades, loss_form="adkins_liebeck"):
    """The A&L design relations at every station, with their gradients.

    Parameters
    ----------
    speed_ratio : array_like
        ``lambda = V/(Omega R)``, shape ``(nn, 1)`` or broadcastable.
    radius_fraction : array_like
        ``xi = r/R``, shape ``(nn, nr)``.
    zeta : array_like
        Displacement velocity ratio ``v'/V``, shape ``(nn, 1)``.
    drag_to_lift : array_like
        ``eps = C_d/C_l``, shape ``(nn, 1)``.
    num_blades : int
        Number of blades B.
    loss_form : {'adkins_liebeck', 'local', 'qmil'}
        Prandtl exponent with the tip flow angle (A&L), the local flow angle (BEM analysis), or QMIL's
        factor (the module docstring).

    Returns
    -------
    StationState
    """
    shape = np.broadcast(speed_ratio, radius_fraction, zeta, drag_to_lift).shape
    lam, xi, zeta, eps = (Jet.variable(v, k, shape)
                          for k, v in enumerate((speed_ratio, radius_fraction, zeta, drag_to_lift)))
    tan_tip = lam * (1.0 + 0.5 * zeta)
    tan_phi = tan_tip / xi
    secant = (1.0 + tan_phi * tan_phi).sqrt()
    cos_phi = secant.reciprocal()
    sin_phi = tan_phi * cos_phi
    phi = tan_phi.apply(np.arctan(tan_phi.value), _real(cos_phi.value) ** 2)
    if loss_form == "adkins_liebeck":
        sin_tip = tan_tip / (1.0 + tan_tip * tan_tip).sqrt()
        exponent = (0.5 * num_blades) * (1.0 - xi) / sin_tip
    elif loss_form == "qmil":
        exponent = (0.5 * num_blades) * (1.0 - xi) / tan_tip
    else:
        exponent = (0.5 * num_blades) * (1.0 - xi) / (xi * sin_phi)
    loss = _prandtl(exponent)
    if loss_form == "qmil":
        root = tan_tip * (4.0 / (np.pi * num_blades)) / xi
        loss = loss * (1.0 + root * root).sqrt()
    sin_cos = sin_phi * cos_phi
    circulation = loss * (xi / lam) * sin_cos
    thrust_drag = 1.0 - eps * tan_phi
    torque_drag = 1.0 + eps / tan_phi
    i1 = 4.0 * xi * circulation * thrust_drag
    i2 = lam * (i1 / (2.0 * xi)) * torque_drag * sin_cos
    j1 = 4.0 * xi * circulation * torque_drag
    j2 = 0.5 * j1 * thrust_drag * cos_phi * cos_phi
    axial = 0.5 * zeta * cos_phi * cos_phi * thrust_drag
    return StationState(phi, loss, circulation, axial, sin_phi, cos_phi, i1, i2, j1, j2)


def nondimensional_load(state, zeta, width_fraction, design_for):
    """``T_c`` (``design_for='thrust'``) or ``P_c`` (``'power'``) of the design and its gradients.

    Parameters
    ----------
    state : StationState
        From :func:`station_state`, shape ``(nn, nr)``.
    zeta : array_like
        ``(nn,)``.
    width_fraction : array_like
        ``dr/R`` of the stations, ``(nn, nr)`` (the integrals are midpoint sums).
    design_for : {'thrust', 'power'}

    Returns
    -------
    value : ndarray
        ``(nn,)``.
    dvalue : ndarray
        ``(4, nn, nr)`` partials with respect to the :data:`VARIABLES` at each station
        (the ``zeta`` row summed over stations gives d/dzeta, the others are per station).
    dvalue_dwidth : ndarray
        ``(nn, nr)`` partials with respect to ``width_fraction``.
    """
    z = np.asarray(zeta)[:, None]
    zr = _real(z)
    if design_for == "thrust":
        first, second, sign = state.i1, state.i2, -1.0
    else:
        first, second, sign = state.j1, state.j2, 1.0
    local = first.value * z + sign * second.value * z * z
    grad = (first.grad * zr + sign * second.grad * zr * zr) * _real(width_fraction)
    grad[2] += (_real(first.value) + 2.0 * sign * _real(second.value) * zr) * _real(width_fraction)
    return np.sum(local * width_fraction, axis=1), grad, _real(local)
