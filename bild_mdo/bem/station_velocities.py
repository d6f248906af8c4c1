"""Per-station freestream velocities of the BEM section components (inclined flow), named once.

With option ``station_velocities=True``, :class:`~bild_mdo.bem.inflow.InflowComp` and
:class:`~bild_mdo.bem.loads.BladeElementLoadsComp` take the freestream velocity of every station,
``v_axial_local[nn, nr]`` and ``v_theta_local[nn, nr]`` (m/s, from
:class:`~bild_mdo.bem.wind_components.WindComponentsComp`), instead of ``v_axial[nn]`` and
``rpm[nn]`` (``V_theta = Omega r``).  The blade-element formulas are the same.
"""
from __future__ import annotations

#: Per-station freestream velocities of inclined flow (option ``station_velocities``): input name ->
#: (the kernel's argument and partial key, description).  They replace the inputs ``v_axial`` and ``rpm``.
STATION_VELOCITIES = {
    "v_axial_local": ("v_axial", "freestream velocity normal to the rotor plane at the station (blade frame x_b)"),
    "v_theta_local": ("v_theta", "tangential freestream velocity at the station, Omega r cos(precone) plus the "
                                 "in-plane wind (blade frame y_b)"),
}


def declare_station_velocity_option(options):
    """Declare ``station_velocities`` (bool, default False) on a BEM section component."""
    options.declare("station_velocities", types=bool, default=False,
                    desc="per-station inputs v_axial_local, v_theta_local[nn, nr] instead of v_axial, rpm[nn]")


def station_mode(options):
    """Whether a section component takes per-station freestream velocities."""
    return "station_velocities" in options and options["station_velocities"]


def kernel_key(name):
    """The key of an input's partials in :func:`~bild_mdo.bem.blade_element.evaluate_section`.

    ``v_axial_local`` -> ``v_axial``, ``v_theta_local`` -> ``v_theta``; other names are their own keys.
    """
    return STATION_VELOCITIES[name][0] if name in STATION_VELOCITIES else name
