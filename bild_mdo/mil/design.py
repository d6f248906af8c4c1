"""design_mil: a minimum-induced-loss design (Adkins & Liebeck 1994) as plain arrays."""
from __future__ import annotations

import functools
from typing import NamedTuple

import numpy as np
import openmdao.api as om

from bild_mdo import validation
from bild_mdo.atmosphere import MAX_ALTITUDE
from bild_mdo.fluid import resolve_fluid
from bild_mdo.mil.kernel import LOSS_FORMS
from bild_mdo.mil.mil_group import MILGroup
from bild_mdo.utils.options import DEFAULT_NUM_RADIAL


class MILDesign(NamedTuple):
    """A minimum-induced-loss design; per-design values have shape ``(nn,)``, distributions ``(nn, nr)``.

    Attributes
    ----------
    radii, chord, twist, phi : ndarray
        Stations (m), chord (m), twist and flow angle (rad).
    zeta : ndarray
        Displacement velocity ratio ``v'/V``.
    thrust, torque, power, efficiency : ndarray
        Performance from A&L's integrals (N, N m, W, -).
    """

    radii: np.ndarray
    chord: np.ndarray
    twist: np.ndarray
    phi: np.ndarray
    zeta: np.ndarray
    thrust: np.ndarray
    torque: np.ndarray
    power: np.ndarray
    efficiency: np.ndarray


@functools.lru_cache(maxsize=8)
def _problem(num_nodes, num_radial, num_blades, design_for, loss_form, use_atmosphere=True):
    prob = om.Problem(MILGroup(num_nodes=num_nodes, num_radial=num_radial, num_blades=num_blades,
                               design_for=design_for, loss_form=loss_form, use_atmosphere=use_atmosphere),
                      reports=False)
    prob.setup()
    prob.final_setup()
    return prob


def design_mil(thrust=None, *, v_axial, rpm, radius, hub_radius, cl_star, cd_star, alpha_star, num_blades=2,
               altitude=0.0, power=None, num_radial=DEFAULT_NUM_RADIAL, loss_form="adkins_liebeck", fluid=None):
    """Design minimum-induced-loss propellers for a thrust (or a power) target.

    Per-design arguments are scalars or 1-D sequences of one common length
    (a batch of designs, solved together).

    Parameters
    ----------
    thrust : float or array_like, optional
        Thrust target (N, > 0); give exactly one of ``thrust`` and ``power``.
    v_axial : float or array_like
        Flight speed (m/s, > 0: forward flight only).
    rpm, radius, hub_radius : float or array_like
        Rotor speed (rpm), tip and hub radius (m), ``0 <= hub_radius < radius``.
    cl_star, cd_star, alpha_star : float or array_like
        Airfoil point of every section (``alpha_star`` in rad), e.g. BILD's reference point.
    num_blades : int
        Number of blades.
    altitude : float or array_like
        Geometric altitude (m) for the ISA.
    fluid : Fluid, str or (rho, mu, speed_of_sound), optional
        Any fluid instead of the ISA (:mod:`bild_mdo.fluid`: ``'water'``,
        ``'seawater'``, ``'air'`` or your own); then ``altitude`` must stay 0.
    power : float or array_like, optional
        Shaft power target (W, > 0) instead of ``thrust``.
    num_radial : int
        Stations (midpoints of equal annuli).
    loss_form : {'adkins_liebeck', 'local', 'qmil'}
        Prandtl exponent (see :class:`~bild_mdo.mil.mil_group.MILGroup`).

    Returns
    -------
    MILDesign

    Raises
    ------
    ValueError
        For an invalid argument (one line naming it), e.g. ``v_axial <= 0`` (hover).
    openmdao.api.AnalysisError
        Where the target cannot be reached at the operating point.
    """
    if (thrust is None) == (power is None):
        raise ValueError("give exactly one of thrust and power (the design target)")
    design_for, target = ("thrust", thrust) if power is None else ("power", power)
    values = {
        "v_axial": validation.positive("v_axial", v_axial, units="m/s",
                                       hint="minimum-induced-loss design is for forward flight, J > 0"),
        "rpm": validation.positive("rpm", rpm, units="rpm"),
        "radius": validation.positive("radius", radius, units="m"),
        "hub_radius": validation.non_negative("hub_radius", hub_radius, units="m"),
        "cl_star": validation.positive("cl_star", cl_star),
        "cd_star": validation.non_negative("cd_star", cd_star),
        "alpha_star": validation.real_array("alpha_star", alpha_star, units="rad"),
        f"design_{design_for}": validation.positive(design_for, target, units="N" if power is None else "W"),
    }
    validation.smaller("hub_radius", values["hub_radius"], "radius", values["radius"])
    num_blades = validation.integer("num_blades", num_blades, minimum=1)
    num_radial = validation.integer("num_radial", num_radial, minimum=1)
    loss_form = validation.choice("loss_form", loss_form, LOSS_FORMS)
    if fluid is None:
        values["altitude"] = validation.in_range("altitude", altitude, 0.0, MAX_ALTITUDE, units="m")
    else:
        fluid = resolve_fluid(fluid)
        if np.any(np.asarray(altitude) != 0.0):
            raise ValueError("give either altitude [m] (the ISA) or fluid, not both")
        values["rho"] = np.asarray(fluid.rho)  # MIL's relations need no viscosity
    nn = validation.batch_size({name: value.size for name, value in values.items() if value.ndim == 1})
    prob = _problem(nn, num_radial, num_blades, design_for, loss_form, fluid is None)
    for name, value in values.items():
        prob.set_val(name, np.broadcast_to(value, (nn,)))
    prob.run_model()
    get = lambda name: np.array(prob.get_val(name))  # noqa: E731
    return MILDesign(get("radii"), get("chord"), get("twist"), get("phi"), get("zeta"), get("thrust"),
                     get("torque"), get("power"), get("efficiency"))
