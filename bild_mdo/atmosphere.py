"""International Standard Atmosphere (troposphere): density, viscosity and speed of sound.

ISA (ISO 2533:1975 / ICAO Doc 7488) below the tropopause, from *geometric*
altitude ``h`` in 0 ... 11,000 m:

* geopotential altitude ``H = r0 h / (r0 + h)``, ``r0 = 6,356,766 m``;
* temperature ``T = T0 - L H``, ``T0 = 288.15 K``, ``L = 0.0065 K/m``;
* pressure ``p = p0 (T/T0)^(g0/(L R))``, ``p0 = 101,325 Pa``, ``g0 = 9.80665 m/s^2``,
  ``R = 287.05287 J/(kg K)`` (specific gas constant of dry air);
* density ``rho = p / (R T)``;
* dynamic viscosity (Sutherland) ``mu = beta_s T^1.5 / (T + S)``,
  ``beta_s = 1.458e-6 kg/(m s K^0.5)``, ``S = 110.4 K``;
* speed of sound ``a = sqrt(gamma R T)``, ``gamma = 1.4``.

At sea level: rho = 1.2250 kg/m^3, mu = 1.7894e-5 Pa s, a = 340.29 m/s.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
import openmdao.api as om

from bild_mdo.utils.options import declare_size_options
from bild_mdo.utils.sparsity import node_wrt_node

EARTH_RADIUS = 6356766.0          # m, r0 of the geopotential altitude
T0 = 288.15                       # K
P0 = 101325.0                     # Pa
LAPSE_RATE = 0.0065               # K/m
G0 = 9.80665                      # m/s^2
R_AIR = 287.05287                 # J/(kg K)
GAMMA = 1.4
SUTHERLAND_BETA = 1.458e-6        # kg/(m s K^0.5)
SUTHERLAND_S = 110.4              # K
MAX_ALTITUDE = 11000.0            # m, geometric; the tropopause is at 11,000 m geopotential

_EXPONENT = G0 / (LAPSE_RATE * R_AIR)


class IsaState(NamedTuple):
    """ISA values and their derivatives with respect to geometric altitude (per metre)."""

    rho: np.ndarray
    mu: np.ndarray
    speed_of_sound: np.ndarray
    temperature: np.ndarray
    pressure: np.ndarray
    drho_dh: np.ndarray
    dmu_dh: np.ndarray
    dspeed_of_sound_dh: np.ndarray
    dtemperature_dh: np.ndarray
    dpressure_dh: np.ndarray


def isa(altitude, derivatives=True):
    """ISA troposphere at geometric altitude.

    Parameters
    ----------
    altitude : array_like
        Geometric altitude (m), 0 ... 11,000 (real or complex-step).
    derivatives : bool
        False: the derivative fields are None (a run without derivatives).

    Returns
    -------
    IsaState
        rho (kg/m^3), mu (Pa s), speed_of_sound (m/s), temperature (K), pressure (Pa)
        and their derivatives with respect to altitude.

    Raises
    ------
    ValueError
        If any altitude is outside 0 ... 11,000 m or not finite.
    """
    h = np.asarray(altitude)
    h_real = np.real(h)
    # One reduction (NaN fails both comparisons, so this also rejects values that are not finite).
    if not ((h_real >= 0.0) & (h_real <= MAX_ALTITUDE)).all():
        raise ValueError(
            f"altitude must be within 0 ... {MAX_ALTITUDE:g} m (ISA troposphere); got "
            f"min {np.min(h_real):g} m, max {np.max(h_real):g} m")
    H = EARTH_RADIUS * h / (EARTH_RADIUS + h)
    T = T0 - LAPSE_RATE * H
    theta = T / T0
    p = P0 * theta**_EXPONENT
    rho = p / (R_AIR * T)
    mu = SUTHERLAND_BETA * T**1.5 / (T + SUTHERLAND_S)
    a = np.sqrt(GAMMA * R_AIR * T)
    if not derivatives:
        return IsaState(rho, mu, a, T, p, None, None, None, None, None)

    dT_dh = -LAPSE_RATE * (EARTH_RADIUS / (EARTH_RADIUS + h)) ** 2
    dp_dh = _EXPONENT * p / T * dT_dh
    drho_dh = (_EXPONENT - 1.0) * rho / T * dT_dh
    dmu_dh = mu * (1.5 / T - 1.0 / (T + SUTHERLAND_S)) * dT_dh
    da_dh = 0.5 * a / T * dT_dh
    real = np.real if np.iscomplexobj(h) else (lambda x: x)
    return IsaState(rho, mu, a, T, p, real(drho_dh), real(dmu_dh), real(da_dh), real(dT_dh), real(dp_dh))


class AtmosphereComp(om.ExplicitComponent):
    """ISA troposphere: density, viscosity and speed of sound from geometric altitude.

    Options
    -------
    num_nodes : int
        Number of designs / operating points.

    Inputs
    ------
    altitude[nn] (m)
        Geometric altitude, 0 ... 11,000 m.

    Outputs
    -------
    rho[nn] (kg/m**3), mu[nn] (Pa*s), speed_of_sound[nn] (m/s)

    Raises
    ------
    openmdao.api.AnalysisError
        When an altitude is outside 0 ... 11,000 m or not finite, so that an
        optimiser can back off (the plain :func:`isa` raises ``ValueError``).
    """

    def initialize(self):
        declare_size_options(self.options, radial=False)

    def setup(self):
        nn = self.options["num_nodes"]
        self.add_input("altitude", val=np.zeros(nn), units="m", desc="geometric altitude (0 ... 11 km)")
        self.add_output("rho", val=np.full(nn, 1.225), units="kg/m**3", desc="air density (ISA)")
        self.add_output("mu", val=np.full(nn, 1.789e-5), units="Pa*s", desc="air dynamic viscosity (Sutherland)")
        self.add_output("speed_of_sound", val=np.full(nn, 340.3), units="m/s", desc="speed of sound (ISA)")

    def setup_partials(self):
        rows, cols = node_wrt_node(self.options["num_nodes"])
        for name in ("rho", "mu", "speed_of_sound"):
            self.declare_partials(name, "altitude", rows=rows, cols=cols)

    def _isa(self, altitude, derivatives=True):
        try:
            return isa(altitude, derivatives)
        except ValueError as err:
            raise om.AnalysisError(f"{self.msginfo}: {err}") from err

    def compute(self, inputs, outputs):
        state = self._isa(inputs["altitude"], derivatives=False)
        outputs["rho"] = state.rho
        outputs["mu"] = state.mu
        outputs["speed_of_sound"] = state.speed_of_sound

    def compute_partials(self, inputs, partials):
        state = self._isa(inputs["altitude"])
        partials["rho", "altitude"] = state.drho_dh
        partials["mu", "altitude"] = state.dmu_dh
        partials["speed_of_sound", "altitude"] = state.dspeed_of_sound_dh
