"""The fluid a rotor works in, as an alternative to the ISA: density, dynamic viscosity and speed of sound.

Every design and analysis entry point takes ``fluid=`` instead of ``altitude``
(:func:`~bild_mdo.results.design.design_rotor`, :func:`~bild_mdo.mil.design_mil`,
:func:`~bild_mdo.bem.analyze_rotor`, :func:`~bild_mdo.results.off_design.off_design_sweep`,
``bild-mdo design/analyze --fluid``); the OpenMDAO groups take
``use_atmosphere=False`` and then have ``rho``, ``mu`` and ``speed_of_sound``
as inputs.  A fluid is a :class:`Fluid` or the name of one of :data:`FLUIDS`.

The named fluids, at 15 deg C and atmospheric pressure:

* ``'air'``: the ISA at sea level (ISO 2533:1975), rho = 1.2250 kg/m**3,
  mu = 1.7894e-5 Pa s, a = 340.29 m/s;
* ``'water'``: fresh water, rho = 999.10 kg/m**3 (the UNESCO 1981 pure-water
  density polynomial), mu = 1.1382e-3 Pa s (Kestin, Sokolov and Wakeham 1978:
  log10(mu / 1.002e-3) = (1.1709 (20 - t) - 0.001827 (t - 20)**2) / (t + 89.93)),
  a = 1465.9 m/s (Del Grosso and Mader 1972);
* ``'seawater'``: salinity 35 g/kg, rho = 1025.97 kg/m**3 (UNESCO EOS-80 at the
  surface), mu = 1.2125e-3 Pa s (the fresh-water value times the salinity
  factor of Landolt-Boernstein New Series V/3a, 1986), a = 1506.7 m/s
  (Mackenzie 1981, at the surface).

The blade-element model knows nothing of cavitation: a water propeller design
is the ideal loading of the non-cavitating flow, and its Reynolds numbers are
about fifteen times those in air at the same speed and chord (often beyond a
polar's data: the results flag those stations).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from bild_mdo import validation
from bild_mdo.atmosphere import isa


class Fluid(NamedTuple):
    """Density ``rho`` (kg/m**3), dynamic viscosity ``mu`` (Pa s) and speed of sound (m/s) of the fluid."""

    rho: float
    mu: float
    speed_of_sound: float
    name: str = "fluid"

    def __str__(self):
        return (f"{self.name} (rho {self.rho:.6g} kg/m^3, mu {self.mu:.5g} Pa s, "
                f"a {self.speed_of_sound:.5g} m/s)")


#: The properties a fluid gives the models, by their input names.
PROPERTIES = ("rho", "mu", "speed_of_sound")

_SEA_LEVEL = isa(0.0, derivatives=False)

#: The named fluids (module docstring for their sources).
FLUIDS = {
    "air": Fluid(float(_SEA_LEVEL.rho), float(_SEA_LEVEL.mu), float(_SEA_LEVEL.speed_of_sound), "air"),
    "water": Fluid(999.10, 1.1382e-3, 1465.9, "water"),
    "seawater": Fluid(1025.97, 1.2125e-3, 1506.7, "seawater"),
}


def resolve_fluid(fluid):
    """A :class:`Fluid` from a Fluid, a name of :data:`FLUIDS`, or a ``(rho, mu, speed_of_sound)`` triple.

    ValueError in one line for anything else, or for a non-positive property.
    """
    if isinstance(fluid, str):
        key = fluid.strip().lower()
        if key not in FLUIDS:
            raise ValueError(f"fluid must be one of {sorted(FLUIDS)} or (rho [kg/m^3], mu [Pa s], speed of sound "
                             f"[m/s]), got {fluid!r}")
        return FLUIDS[key]
    if not isinstance(fluid, Fluid):
        try:
            values = tuple(fluid)
        except TypeError:
            values = ()
        if len(values) not in (3, 4):
            raise ValueError(f"fluid must be one of {sorted(FLUIDS)}, a Fluid or (rho [kg/m^3], mu [Pa s], speed of "
                             f"sound [m/s]), got {fluid!r}")
        fluid = Fluid(*values)
    rho = float(validation.positive("fluid density rho", fluid.rho, units="kg/m**3", ndim=(0,)))
    mu = float(validation.positive("fluid viscosity mu", fluid.mu, units="Pa*s", ndim=(0,)))
    speed = float(validation.positive("fluid speed of sound", fluid.speed_of_sound, units="m/s", ndim=(0,)))
    return Fluid(rho, mu, speed, str(fluid.name))


#: What the command line's ``--fluid`` accepts.
FLUID_HELP = (f"the fluid instead of the ISA at --altitude: {', '.join(FLUIDS)} (15 deg C, see bild_mdo.fluid) or "
              "RHO,MU,A: density [kg/m^3], dynamic viscosity [Pa s] and speed of sound [m/s]")


def fluid_from_text(text):
    """The :class:`Fluid` of a ``--fluid`` text: a name of :data:`FLUIDS` or ``'RHO,MU,A'``."""
    parts = [part.strip() for part in str(text).split(",")]
    if len(parts) == 1:
        return resolve_fluid(parts[0])
    try:
        values = [float(part) for part in parts]
    except ValueError:
        values = ()
    if len(values) != 3:
        raise ValueError(f"--fluid takes a name ({', '.join(FLUIDS)}) or RHO,MU,A (three numbers: kg/m^3, Pa s, "
                         f"m/s), got {text!r}")
    return resolve_fluid(Fluid(*values, name=f"fluid {text}"))


def fluid_point(fluid):
    """The design-point entries of a geometry file that keep a fluid (``rho``, ``mu``, ``speed_of_sound``)."""
    return {name: float(getattr(fluid, name)) for name in PROPERTIES}


def point_fluid(design_point):
    """The :class:`Fluid` a geometry's design point keeps (None where it keeps an altitude or nothing)."""
    if "altitude" in design_point or not set(PROPERTIES) <= set(design_point):
        return None
    return resolve_fluid(Fluid(design_point["rho"], design_point["mu"], design_point["speed_of_sound"],
                               "the design's fluid"))


def fluid_arrays(fluid, size):
    """``{'rho', 'mu', 'speed_of_sound'}`` of a resolved fluid as arrays of ``size`` (for the groups' inputs)."""
    return {name: np.full(size, value) for name, value in fluid_point(fluid).items()}
