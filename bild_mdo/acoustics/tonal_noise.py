"""TonalNoiseComp: loading and thickness noise of the blade-passing harmonics (compact Hanson / Gutin / Deming)."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.acoustics.hanson import AREA_COEFFICIENT, observer_coordinates, retarded_geometry, tonal_amplitudes
from bild_mdo.utils.options import add_inputs, declare_size_options

#: Station inputs of the component (shared interface names), shape (nn, nr).
STATION_INPUTS = ("radii", "dr", "chord", "thickness_ratio", "dthrust_dr", "dtorque_dr")
#: Per-design inputs, shape (nn,).
NODE_INPUTS = ("rpm", "v_axial", "rho", "speed_of_sound")
#: Which amplitude each mean-square output is made of.
_OUTPUT_AMPLITUDES = {"loading_pressure_squared": ("loading",), "thickness_pressure_squared": ("thickness",),
                      "tonal_pressure_squared": ("loading", "thickness")}
#: The inputs each amplitude depends on.
_DEPENDS = {"loading": ("radii", "dr", "dthrust_dr", "dtorque_dr", "rpm", "v_axial", "speed_of_sound",
                        "observer_position"),
            "thickness": ("radii", "dr", "chord", "thickness_ratio", "rpm", "v_axial", "rho", "speed_of_sound",
                          "observer_position")}


def _dependencies(amps):
    """Inputs (in declaration order) that an output made of the amplitudes ``amps`` depends on."""
    return [name for name in (*STATION_INPUTS, *NODE_INPUTS, "observer_position")
            if any(name in _DEPENDS[amp] for amp in amps)]
_RPM_TO_RAD_S = np.pi / 30.0


class TonalNoiseComp(om.ExplicitComponent):
    """Mean-square pressure of the tones ``m B Omega`` (loading, thickness and both) at far-field observers.

    The model, its frame and its limits are those of :mod:`bild_mdo.acoustics.hanson`: Hanson's
    helicoidal-surface theory in the compact-chord limit, for axial flight and hover, with the
    observer moving with the rotor (so each tone is heard at ``m B Omega / (2 pi)``, no Doppler shift
    of frequency; the flight Mach number enters the amplitudes through the Doppler factor
    ``1 - M cos(theta_e)`` in emission coordinates).  A harmonic's mean square is that of the real tone
    ``p_m(t) = 2 Re(P_m exp(-i m B Omega t))`` of complex amplitude ``P_m``: ``2 |P_m|**2`` (Pa**2); the
    total sums loading and thickness as complex amplitudes (in quadrature in the compact limit).

    Options
    -------
    num_nodes, num_radial : int
        Designs (axis 0) and stations (axis 1).
    num_observers : int
        Observers per design.
    num_harmonics : int
        Harmonics ``m = 1 ... num_harmonics`` of the blade-passing frequency (default 10).
    num_blades : int
        Number of blades ``B``.
    area_coefficient : float
        Section area / (t c**2); default 0.685, the NACA four-digit thickness form.

    Inputs
    ------
    radii[nn, nr] (m), dr[nn, nr] (m), chord[nn, nr] (m), thickness_ratio[nn, nr]
        Stations, their widths, chord and thickness-to-chord ratio.
    dthrust_dr[nn, nr] (N/m), dtorque_dr[nn, nr] (N*m/m)
        Thrust and torque per unit span, all blades.
    rpm[nn] (rpm), v_axial[nn] (m/s), rho[nn] (kg/m**3), speed_of_sound[nn] (m/s)
        Rotor speed, flight speed along +x (``v_axial / speed_of_sound < 1``), density and speed of sound.
    observer_position[nn, no, 3] (m)
        Observers relative to the rotor centre (x along the thrust).

    Outputs
    -------
    loading_pressure_squared[nn, no, nh] (Pa**2), thickness_pressure_squared[nn, no, nh] (Pa**2),
    tonal_pressure_squared[nn, no, nh] (Pa**2)
        Mean-square pressure of each harmonic.
    tonal_frequency[nn, nh] (Hz)
        ``m B Omega / (2 pi)``.
    """

    def initialize(self):
        declare_size_options(self.options)
        self.options.declare("num_observers", types=int, default=1, lower=1, desc="observers per design")
        self.options.declare("num_harmonics", types=int, default=10, lower=1,
                             desc="harmonics m = 1 ... num_harmonics of the blade-passing frequency")
        self.options.declare("num_blades", types=int, default=2, lower=1, desc="number of blades B")
        self.options.declare("area_coefficient", types=float, default=AREA_COEFFICIENT, lower=0.0,
                             desc="section area / (thickness_ratio * chord**2)")

    def setup(self):
        nn, no, nh = self.options["num_nodes"], self.options["num_observers"], self.options["num_harmonics"]
        add_inputs(self, ("radii", "dr", "chord", "dthrust_dr", "dtorque_dr") + NODE_INPUTS)
        self.add_input("thickness_ratio", val=np.full((nn, self.options["num_radial"]), 0.12), units=None,
                       desc="section thickness-to-chord ratio t/c")
        default_observer = np.zeros((nn, no, 3))
        default_observer[..., 0] = -10.0
        default_observer[..., 1] = 10.0
        self.add_input("observer_position", val=default_observer, units="m",
                       desc="observer positions in the rotor frame (x along the thrust, rotor centre at 0)")
        for name in _OUTPUT_AMPLITUDES:
            self.add_output(name, val=np.zeros((nn, no, nh)), units="Pa**2",
                            desc="mean-square pressure of each harmonic m B Omega")
        self.add_output("tonal_frequency", val=np.zeros((nn, nh)), units="Hz",
                        desc="frequency m B Omega / (2 pi) of each harmonic (observer moving with the rotor)")

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        no, nh = self.options["num_observers"], self.options["num_harmonics"]
        out = np.arange(nn * no * nh).reshape(nn, no * nh)
        # Each output entry of node i depends on every station of node i.
        rows_st = np.repeat(out, nr, axis=1).ravel()
        cols_st = np.tile(np.arange(nn * nr).reshape(nn, 1, nr), (1, no * nh, 1)).ravel()
        rows_nd, cols_nd = out.ravel(), np.repeat(np.arange(nn), no * nh)
        obs = np.arange(nn * no * 3).reshape(nn, no, 1, 3)
        rows_ob = np.repeat(out.reshape(nn, no, nh, 1), 3, axis=3).ravel()
        cols_ob = np.broadcast_to(obs, (nn, no, nh, 3)).ravel()
        patterns = {**{wrt: (rows_st, cols_st) for wrt in STATION_INPUTS},
                    **{wrt: (rows_nd, cols_nd) for wrt in NODE_INPUTS}, "observer_position": (rows_ob, cols_ob)}
        for name, amps in _OUTPUT_AMPLITUDES.items():
            for wrt in _dependencies(amps):
                rows, cols = patterns[wrt]
                self.declare_partials(name, wrt, rows=rows, cols=cols)
        harmonics = np.arange(1, nh + 1)
        self.declare_partials("tonal_frequency", "rpm", rows=np.arange(nn * nh), cols=np.repeat(np.arange(nn), nh),
                              val=np.tile(harmonics * self.options["num_blades"] * _RPM_TO_RAD_S / (2.0 * np.pi), nn))

    def _evaluate(self, inputs, partials):
        nb = self.options["num_blades"]
        orders = nb * np.arange(1, self.options["num_harmonics"] + 1)
        c = inputs["speed_of_sound"]
        mach = inputs["v_axial"] / c
        if np.any(np.abs(np.real(mach)) >= 1.0):
            raise om.AnalysisError(f"{self.msginfo}: flight Mach number v_axial / speed_of_sound must be below 1 "
                                   f"for the far-field tonal model, got {np.real(mach).max():.3g}")
        x, rho_o, drho_dy, drho_dz = observer_coordinates(inputs["observer_position"])
        geometry = retarded_geometry(x, rho_o, mach[:, None])
        result = tonal_amplitudes(*(inputs[name] for name in STATION_INPUTS), inputs["rpm"] * _RPM_TO_RAD_S, c,
                                  inputs["rho"], mach, geometry, orders, nb, self.options["area_coefficient"],
                                  partials=partials)
        return result, mach, drho_dy, drho_dz

    def compute(self, inputs, outputs):
        (a_l, a_t), _, _, _ = self._evaluate(inputs, partials=False)
        outputs["loading_pressure_squared"] = 2.0 * a_l * a_l
        outputs["thickness_pressure_squared"] = 2.0 * a_t * a_t
        outputs["tonal_pressure_squared"] = 2.0 * (a_l * a_l + a_t * a_t)
        harmonics = np.arange(1, self.options["num_harmonics"] + 1)
        omega = inputs["rpm"] * _RPM_TO_RAD_S
        outputs["tonal_frequency"] = harmonics[None, :] * self.options["num_blades"] * omega[:, None] / (2.0 * np.pi)

    def compute_partials(self, inputs, partials):
        (a_l, a_t, d), mach, drho_dy, drho_dz = self._evaluate(inputs, partials=True)
        c = inputs["speed_of_sound"][:, None, None]
        amplitude = {"loading": a_l, "thickness": a_t}
        for name, amps in _OUTPUT_AMPLITUDES.items():
            def total(key, amps=amps):
                # d(2 a^2) = 4 a da, summed over the amplitudes of the output.
                terms = []
                for amp in amps:
                    if key in d[amp]:
                        da = d[amp][key]
                        scale = 4.0 * amplitude[amp]
                        terms.append((scale[..., None] if da.ndim == 4 else scale) * da)
                return sum(terms)

            wrts = _dependencies(amps)
            for wrt in STATION_INPUTS:
                if wrt in wrts:
                    partials[name, wrt] = total(wrt).ravel()
            dmach = total("mach")
            partials[name, "rpm"] = (total("omega") * _RPM_TO_RAD_S).ravel()
            partials[name, "v_axial"] = (dmach / c).ravel()
            partials[name, "speed_of_sound"] = (total("speed_of_sound") - dmach * mach[:, None, None] / c).ravel()
            if "rho" in wrts:
                partials[name, "rho"] = total("rho").ravel()
            d_rho = total("rho_o")
            jac = np.stack([total("x"), d_rho * drho_dy[:, :, None], d_rho * drho_dz[:, :, None]], axis=-1)
            partials[name, "observer_position"] = jac.ravel()
