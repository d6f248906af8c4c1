"""Jet: a value with its first partial derivatives, for residuals whose partials are long chain rules.

A :class:`Jet` holds a value (array, real or complex) and a dict ``name ->
partial derivative`` with respect to named variables.  Sums, products and
quotients of jets apply the rules of differentiation exactly (first-order
forward mode, no step size), so a residual written once with jets gives its
value and every analytic partial together.  A name missing from the dict has a
zero partial; plain numbers and arrays are constants.

Used where a residual chains many terms whose second derivatives the partials
need (:mod:`bild_mdo.bild.variants.local_point.load_path_model`); the primitives (the
polar's first and second derivatives, the Prandtl factor's jet) are seeded by
the caller from their own analytic derivatives.
"""
from __future__ import annotations

import numpy as np


class Jet:
    """Value ``v`` and partials ``d`` (dict of arrays broadcastable against ``v``)."""

    __slots__ = ("v", "d")
    # NumPy arrays on the left defer to the jet's reflected operators (instead of making object arrays).
    __array_ufunc__ = None

    def __init__(self, value, partials=None):
        self.v = value
        self.d = dict(partials) if partials else {}

    def partial(self, name):
        """``d v / d name`` (0.0 where the jet does not depend on ``name``)."""
        return self.d.get(name, 0.0)

    def __neg__(self):
        return Jet(-self.v, {k: -x for k, x in self.d.items()})

    def __add__(self, other):
        if not isinstance(other, Jet):
            return Jet(self.v + other, self.d)
        d = dict(self.d)
        for k, x in other.d.items():
            d[k] = d[k] + x if k in d else x
        return Jet(self.v + other.v, d)

    __radd__ = __add__

    def __sub__(self, other):
        return self + (-other)

    def __rsub__(self, other):
        return (-self) + other

    def __mul__(self, other):
        if not isinstance(other, Jet):
            return Jet(self.v * other, {k: x * other for k, x in self.d.items()})
        d = {k: x * other.v for k, x in self.d.items()}
        for k, x in other.d.items():
            d[k] = d[k] + self.v * x if k in d else self.v * x
        return Jet(self.v * other.v, d)

    __rmul__ = __mul__

    def __truediv__(self, other):
        if not isinstance(other, Jet):
            return Jet(self.v / other, {k: x / other for k, x in self.d.items()})
        quotient = self.v / other.v
        d = {k: x / other.v for k, x in self.d.items()}
        for k, x in other.d.items():
            term = -quotient * x / other.v
            d[k] = d[k] + term if k in d else term
        return Jet(quotient, d)

    def __rtruediv__(self, other):
        return Jet(np.asarray(other) * np.ones_like(self.v)) / self


def variable(value, name):
    """The independent variable ``name`` at ``value`` (partial 1 with respect to itself)."""
    return Jet(value, {name: 1.0})


def jacobian(jets, names, size, real=True):
    """The partials of ``jets`` with respect to ``names`` as one array ``[size, len(jets), len(names)]``.

    Each partial is broadcast to ``size`` elements (a missing name gives zeros); with ``real`` the real parts.
    """
    jets = list(jets)
    dtype = float if real else np.result_type(*(x for jet in jets for x in jet.d.values()), float)
    out = np.zeros((size, len(jets), len(names)), dtype=dtype)
    for i, jet in enumerate(jets):
        for j, name in enumerate(names):
            x = jet.d.get(name)
            if x is not None:
                out[:, i, j] = np.real(x) if real else x
    return out


def eliminate(outputs, states, names, sens, size):
    """Total partials ``[size, len(outputs), len(names)]`` of ``outputs`` with the states eliminated:
    ``d out / d name + d out / d states @ sens`` (``sens[size, states, names]`` = ``d states / d names``)."""
    outputs = list(outputs)
    return jacobian(outputs, names, size) + jacobian(outputs, states, size) @ sens
