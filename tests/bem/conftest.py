"""Shared fixtures of the BEM tests: polars and seeded blade geometries."""
import numpy as np
import pytest

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.airfoil.compressibility import CompressiblePolar
from bild_mdo.airfoil.spanwise import SpanwisePolar
from bild_mdo.airfoil.polar import Polar, PolarValues


class SmoothTestPolar(Polar):
    """Smooth, 2pi-periodic polar in which both cl and cd depend on Reynolds number.

    ``cl = f (2 sin 2a) + 0.15 (1 + cos a)``, ``cd = 0.01 g + sin^2 a`` with
    ``f = (Re/1e6)^0.05`` and ``g = (Re/1e6)^-0.2``.  Not a real airfoil: it
    exists so the partial-derivative checks exercise every term of the chain
    rule (the analytic polar's lift does not depend on Re).
    """

    name = "smooth-test"

    def _evaluate_real(self, alpha, reynolds):
        x = reynolds / 1e6
        f, df = x**0.05, 0.05 * x**0.05 / reynolds
        g, dg = x**-0.2, -0.2 * x**-0.2 / reynolds
        s2 = np.sin(2.0 * alpha)
        cl = f * 2.0 * s2 + 0.15 * (1.0 + np.cos(alpha))
        dcl_da = 4.0 * f * np.cos(2.0 * alpha) - 0.15 * np.sin(alpha)
        cd = 0.01 * g + np.sin(alpha) ** 2
        dcd_da = s2
        return PolarValues(cl, cd, dcl_da, 2.0 * s2 * df, dcd_da, 0.01 * dg * np.ones_like(alpha))


@pytest.fixture(scope="session")
def smooth_polar():
    """Polar with Reynolds dependence in lift and drag (for derivative checks)."""
    return SmoothTestPolar()


@pytest.fixture(scope="session")
def analytic_polar():
    """The library's analytic polar (NACA 4412-like, Viterna post-stall), Re-dependent drag."""
    return AnalyticPolar(reynolds_exponent=0.2)


def blade_inputs(num_nodes, num_radial, hover_first=True, seed=0):
    """Seeded operating points and a tapered, twisted blade per node (values well inside the valid range).

    Node 0 hovers (V_x = 0) when ``hover_first``; the others are in cruise.
    """
    rng = np.random.default_rng(seed)
    x = np.linspace(0.0, 1.0, num_radial)
    radius = rng.uniform(0.6, 1.4, num_nodes)
    hub = radius * rng.uniform(0.12, 0.2, num_nodes)
    rpm = rng.uniform(1500.0, 3000.0, num_nodes)
    v_axial = rng.uniform(8.0, 40.0, num_nodes)
    if hover_first:
        v_axial[0] = 0.0
    chord = radius[:, None] * (0.12 - 0.06 * x) * rng.uniform(0.8, 1.2, (num_nodes, 1))
    twist = np.radians(35.0 - 22.0 * x)[None, :] * rng.uniform(0.9, 1.2, (num_nodes, 1))
    twist = twist + np.arctan(v_axial / (rpm * np.pi / 30.0 * radius))[:, None] * 0.5
    return dict(v_axial=v_axial, rpm=rpm, radius=radius, hub_radius=hub, chord=chord, twist=twist,
                altitude=rng.uniform(0.0, 3000.0, num_nodes))


@pytest.fixture(scope="session")
def make_blade():
    """Factory ``make_blade(num_nodes, num_radial, hover_first=True, seed=0)`` -> input dict."""
    return blade_inputs


@pytest.fixture(scope="session")
def mach_polar():
    """Mach-dependent polar: Karman-Tsien lift correction of the Re-dependent smooth test polar."""
    return CompressiblePolar(SmoothTestPolar(), correction="karman-tsien")


@pytest.fixture(scope="session")
def spanwise_polar():
    """Two analytic airfoils of different lift slope (5.0 and 6.2 per rad) blended along r/R 0.3 -> 0.9."""
    return SpanwisePolar([AnalyticPolar(cl_alpha=5.0, reynolds_exponent=0.2),
                          AnalyticPolar(cl_alpha=6.2, cl0=0.3, reynolds_exponent=0.2)], [0.3, 0.9])
