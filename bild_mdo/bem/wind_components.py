"""WindComponentsComp: the freestream velocity at every blade station and azimuth sector (inclined flow).

Conventions (those CCBlade documents for its coordinate systems, ``docs/csystem.rst``, angles here in rad):

* wind frame ``w``: ``x_w`` along the wind, ``z_w`` up; the wind at height ``z`` above the hub is
  ``V(z) x_w`` with the power law ``V(z) = V_hub (1 + z / H)**alpha_s`` (``H`` the hub height above
  the ground, ``alpha_s`` the shear exponent; ``alpha_s = 0``: uniform wind);
* yaw ``psi``: the yaw frame is the wind frame turned by ``+psi`` about ``z_w``;
* tilt ``theta_t``: the hub frame is the yaw frame turned by ``+theta_t`` about ``y``; ``x_h`` is the
  shaft (downwind for zero yaw and tilt); a positive tilt raises the rotor of an upwind machine;
* azimuth ``Lambda``: the azimuth frame is the hub frame turned by ``+Lambda`` about ``x_h``
  (``Lambda = 0``: blade pointing up, ``z_a = z_h``); the rotor turns about ``+x_h``;
* precone ``phi_c``: the blade frame is the azimuth frame turned by ``phi_c`` about ``-y_a``; the
  blade axis is ``z_b = -sin(phi_c) x_a + cos(phi_c) z_a`` (a positive precone moves the blade
  upwind, away from the tower of an upwind rotor), and the station at distance ``r`` along the blade
  is at ``(-r sin phi_c, 0, r cos phi_c)`` in the azimuth frame.

Derivation.  With ``c_`` and ``s_`` for cosine and sine, the wind ``(V, 0, 0)`` in the wind frame is
``(V c_psi, -V s_psi, 0)`` in the yaw frame, ``(V c_psi c_t, -V s_psi, V c_psi s_t)`` in the hub frame,
``(V c_psi c_t, V (c_psi s_t s_L - s_psi c_L), V (s_psi s_L + c_psi s_t c_L))`` in the azimuth frame
and, projected on the blade frame (``x_b = c_c x_a + s_c z_a``, ``y_b = y_a``),

    V_x,wind = V [c_c c_psi c_t + s_c (s_psi s_L + c_psi s_t c_L)]
    V_y,wind = V (c_psi s_t s_L - s_psi c_L).

The station moves with ``Omega x_h x p = -Omega r c_c y_a``, so the air meets it with ``+Omega r c_c``
along ``y_b`` (which points against the rotation).  The station's height above the hub, the ``z``
of its position in the yaw frame, is ``h = r (s_c s_t + c_c c_t c_L)``.  Hence, at station ``j`` and
sector ``k`` (``Lambda_k = 2 pi k / ns``, :mod:`bild_mdo.bem.sectors`)::

    V       = V_hub (1 + h / H)**alpha_s
    V_x     = V [c_c c_psi c_t + s_c (s_psi s_L + c_psi s_t c_L)]      -> output v_axial_local
    V_theta = Omega r c_c + V (c_psi s_t s_L - s_psi c_L)               -> output v_theta_local

``V_x`` is the propeller convention's ``V_x`` (the freestream through the disk, from ahead) and
``V_theta`` its tangential speed: the inflow and loads components take them per station
(``station_velocities=True``).  These are the velocity components CCBlade's documentation defines
(its ``Vx``, ``Vy``); the derivation above is this module's own.  With ``precone = tilt = yaw = 0``,
``alpha_s = 0`` and one sector they are exactly ``V_x = V_hub`` and ``V_theta = Omega r``.
The momentum balance of each sector is the axial one with these components (CCBlade's model: no
skewed-wake correction).
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.bem.sectors import declare_sector_option, sector_azimuths, sector_wrt_station
from bild_mdo.constants import RPM_TO_RAD_PER_S
from bild_mdo.utils.complex_step import real_part as _real
from bild_mdo.utils.options import add_inputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_node

#: The geometry and inflow inputs of inclined flow: name -> (default, units, description).
INFLOW_GEOMETRY = {
    "precone": (0.0, "rad", "precone angle: blade axis tilted upwind from the rotor plane (CCBlade's precone)"),
    "tilt": (0.0, "rad", "shaft tilt angle, positive raises an upwind rotor (CCBlade's tilt)"),
    "yaw": (0.0, "rad", "yaw angle of the shaft from the wind about the vertical (CCBlade's yaw)"),
    "hub_height": (100.0, "m", "hub height above the ground, for the wind shear"),
    "shear_exponent": (0.0, None, "power-law wind shear exponent alpha_s, V = V_hub (1 + z/H)**alpha_s"),
}


def add_geometry_inputs(component, names=tuple(INFLOW_GEOMETRY)):
    """Declare the per-node inputs ``names`` of :data:`INFLOW_GEOMETRY`, shape ``(nn,)``."""
    nn = component.options["num_nodes"]
    for name in names:
        default, units, desc = INFLOW_GEOMETRY[name]
        component.add_input(name, val=np.full(nn, default), units=units, desc=desc)


def wind_terms(values, azimuth):
    """Every factor of the module docstring's formulas, shape (nn, ns, nr) (complex with the inputs).

    ``values`` maps the inputs of :class:`WindComponentsComp` (``v_axial, rpm, radii`` and
    :data:`INFLOW_GEOMETRY`) to arrays ``(nn,)`` and ``(nn, nr)``; ``azimuth`` holds the sector angles (rad).

    Raises
    ------
    openmdao.api.AnalysisError
        Where a station reaches the ground (``1 + h / H <= 0``) or ``hub_height <= 0``.
    """
    def node(name):
        return np.asarray(values[name])[:, None, None]
    radii = np.asarray(values["radii"])
    sin_az, cos_az = np.sin(azimuth)[None, :, None], np.cos(azimuth)[None, :, None]
    cone, tilt, yaw = node("precone"), node("tilt"), node("yaw")
    t = dict(r=radii[:, None, :], sc=np.sin(cone), cc=np.cos(cone), st=np.sin(tilt), ct=np.cos(tilt),
             sy=np.sin(yaw), cy=np.cos(yaw), sa=sin_az, ca=cos_az, v=node("v_axial"),
             omega=node("rpm") * RPM_TO_RAD_PER_S, height=node("hub_height"), shear=node("shear_exponent"))
    t["e"] = t["sc"] * t["st"] + t["cc"] * t["ct"] * t["ca"]  # h / r
    t["g"] = 1.0 + t["r"] * t["e"] / t["height"]
    bad = ~(np.real(t["g"]) > 0.0) | ~(np.real(t["height"]) > 0.0)
    if np.any(bad):
        node_index = int(np.argmax(bad.reshape(bad.shape[0], -1).any(axis=1)))
        raise om.AnalysisError(
            f"node {node_index}: a blade station reaches the ground or hub_height <= 0 (hub_height = "
            f"{np.real(t['height'][node_index, 0, 0]):.6g} m); the wind shear needs 1 + z / hub_height > 0")
    t["f"] = t["g"] ** t["shear"]
    t["ax"] = t["cc"] * t["cy"] * t["ct"] + t["sc"] * (t["sy"] * t["sa"] + t["cy"] * t["st"] * t["ca"])
    t["ay"] = t["cy"] * t["st"] * t["sa"] - t["sy"] * t["ca"]
    t["shape"] = (radii.shape[0], azimuth.size * radii.shape[1])
    return t


def _velocities(t):
    speed = t["v"] * t["f"]
    # Omega r c_c + V a_y, in this order: exactly Omega r (the axial BEM's) when c_c = 1 and a_y = 0.
    return ((speed * t["ax"]).reshape(t["shape"]),
            (t["omega"] * t["r"] * t["cc"] + speed * t["ay"]).reshape(t["shape"]))


def wind_components(values, num_sectors):
    """``(v_axial_local, v_theta_local)`` of :class:`WindComponentsComp`, shape (nn, ns*nr) (m/s), without OpenMDAO.

    ``values`` as in :func:`wind_terms`.
    """
    return _velocities(wind_terms(values, sector_azimuths(num_sectors)))


class WindComponentsComp(om.ExplicitComponent):
    """Freestream velocity components of every station in every azimuth sector (module docstring).

    Options
    -------
    num_nodes, num_radial : int
        Designs or operating points (axis 0) and blade stations.
    num_sectors : int
        Azimuth sectors ``ns`` (default 1).

    Inputs
    ------
    v_axial[nn] (m/s)
        Wind (or flight) speed at hub height, >= 0.
    rpm[nn] (rpm), radii[nn, nr] (m)
        Rotor speed and the stations' distances from the rotor axis along the blade.
    precone[nn] (rad), tilt[nn] (rad), yaw[nn] (rad), hub_height[nn] (m), shear_exponent[nn]
        Geometry and inflow (:data:`INFLOW_GEOMETRY`).

    Outputs
    -------
    v_axial_local[nn, ns*nr] (m/s), v_theta_local[nn, ns*nr] (m/s)
        ``V_x`` and ``V_theta`` of every sector and station (sector-major, :mod:`bild_mdo.bem.sectors`).
    """

    def initialize(self):
        declare_size_options(self.options)
        declare_sector_option(self.options)

    def setup(self):
        nn, nr, ns = self.options["num_nodes"], self.options["num_radial"], self.options["num_sectors"]
        add_inputs(self, ("v_axial", "rpm", "radii"))
        add_geometry_inputs(self)
        self.add_output("v_axial_local", val=np.ones((nn, ns * nr)), units="m/s",
                        desc="freestream velocity normal to the rotor plane at each sector and station")
        self.add_output("v_theta_local", val=np.ones((nn, ns * nr)), units="m/s",
                        desc="tangential freestream velocity at each sector and station")
        self._azimuth = sector_azimuths(ns)

    def setup_partials(self):
        nn, nr, ns = self.options["num_nodes"], self.options["num_radial"], self.options["num_sectors"]
        rows_n, cols_n = dist_wrt_node(nn, ns * nr)
        rows_r, cols_r = sector_wrt_station(nn, ns, nr)
        for out, node_inputs in (("v_axial_local", ("v_axial",) + tuple(INFLOW_GEOMETRY)),
                                 ("v_theta_local", ("v_axial", "rpm") + tuple(INFLOW_GEOMETRY))):
            for name in node_inputs:
                self.declare_partials(out, name, rows=rows_n, cols=cols_n)
            self.declare_partials(out, "radii", rows=rows_r, cols=cols_r)

    def _terms(self, inputs):
        try:
            return wind_terms(inputs, self._azimuth)
        except om.AnalysisError as err:
            raise om.AnalysisError(f"{self.msginfo}: {err}") from err

    def compute(self, inputs, outputs):
        outputs["v_axial_local"], outputs["v_theta_local"] = _velocities(self._terms(inputs))

    def compute_partials(self, inputs, partials):
        t = {k: (_real(v) if k != "shape" else v) for k, v in self._terms(inputs).items()}
        r, f, g, shear, height, v = t["r"], t["f"], t["g"], t["shear"], t["height"], t["v"]
        speed = v * f
        sc, cc, st, ct, sy, cy, sa, ca = (t[k] for k in ("sc", "cc", "st", "ct", "sy", "cy", "sa", "ca"))
        # The shear factor f = g**alpha_s, g = 1 + h / H, h = r e.
        df_dh = shear * f / (g * height)
        dh = {"radii": t["e"], "precone": r * (cc * st - sc * ct * ca), "tilt": r * (sc * ct - cc * st * ca)}
        d_speed = {"v_axial": f, "hub_height": -v * shear * f * (g - 1.0) / (g * height),
                   "shear_exponent": v * f * np.log(g)}
        for name, value in dh.items():
            d_speed[name] = v * df_dh * value
        d_ax = {"precone": -sc * cy * ct + cc * (sy * sa + cy * st * ca),
                "tilt": -cc * cy * st + sc * cy * ct * ca,
                "yaw": -cc * sy * ct + sc * (cy * sa - sy * st * ca)}
        d_ay = {"tilt": cy * ct * sa, "yaw": -sy * st * sa - cy * ca}
        d_rot = {"rpm": RPM_TO_RAD_PER_S * r * cc, "radii": t["omega"] * cc, "precone": -t["omega"] * r * sc}
        ones = np.ones(t["shape"]).reshape(-1, sa.shape[1], r.shape[2])
        for out, factor, d_factor, extra in (("v_axial_local", t["ax"], d_ax, {}),
                                             ("v_theta_local", t["ay"], d_ay, d_rot)):
            names = ("v_axial", "radii") + tuple(INFLOW_GEOMETRY) + (("rpm",) if extra else ())
            for name in names:
                value = d_speed.get(name, 0.0) * factor + speed * d_factor.get(name, 0.0) + extra.get(name, 0.0)
                partials[out, name] = (value * ones).ravel()
