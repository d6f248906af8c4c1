"""BroadbandNoiseComp: BPM airfoil self-noise of a rotor at far-field observers, in one-third-octave bands.

Every station of a blade is a BPM segment (NASA RP-1218; :mod:`bild_mdo.acoustics.bpm`) of chord ``c``,
span ``dr``, flow speed ``W`` (``inflow_speed``), angle of attack ``alpha`` and chord Reynolds number
``R_c = rho W c / mu``, NACA 0012 boundary-layer fits (tripped or untripped).  The blade is sampled at
``num_azimuth`` equally spaced azimuths; at each the segment's observer distance, directivity angles and
Doppler factor follow from its position and velocity (:mod:`bild_mdo.acoustics.bpm.rotor_geometry`), and the
directivities carry Brooks and Burley's convective amplification of a source moving through still air,
``(1 - M_tot cos xi_r)^-4`` with the segment's velocity ``W`` relative to the local air along the inflow
angle ``phi`` (AIAA 2001-2210, Eqs. 14, 19-20), not BPM's wind-tunnel factors of Eqs. (B1)-(B2).  Each
source spectrum, analytic in Strouhal number, is evaluated at the source frequency ``f (1 - M_r)`` for
the observer band of centre ``f``.  The rotor's broadband mean-square pressure is the incoherent average
over azimuth, summed over stations and times the number of blades::

    p2[b] = B / N_psi  sum_psi sum_stations p2_segment(f_b (1 - M_r), r_e, D_h, D_l)

Trailing-edge bluntness vortex shedding (TEB-VS, Eq. 70) needs the trailing-edge thickness ``h`` of each
station (input ``trailing_edge_thickness``, m; default 0, a sharp edge, which makes no bluntness noise: the
level vanishes as ``h -> 0``, faster than ``h^2.75``; measured exponents 4.3 at ``Psi = 14``, 21 at 0) and
the solid angle ``Psi`` of the edge (option ``trailing_edge_angle``, deg, default 14, a NACA 0012's);
:mod:`~bild_mdo.acoustics.bpm.bluntness`.

The tip vortex (Eq. 61, a rounded or flat tip) takes the chord, ``W``, ``phi`` and ``alpha`` of the
outermost station (``alpha'_TIP = tip_alpha_correction * alpha``, Eq. 65) and sits at the tip radius ``R``.
LBL-VS exists only with an untripped boundary layer.

An observer on the rotor axis hears every azimuth alike (the rotor, its flow and the observer are symmetric
about the axis): where every observer of every design is on the axis (``y = z = 0`` exactly) and
``num_azimuth >= 2``, one azimuth is evaluated for all, the same mean to rounding, and the partials with
respect to the observers' ``y`` and ``z`` are their exact value there, 0 (the azimuth sum of a first-order
change is a sum of ``cos`` and ``sin`` over equal steps).

Approximations: far field per segment (point-source directivities at ``r_e``); the azimuths are averaged
uniformly in source time (the observer-time weight ``1 - M_r`` of each emission interval is left out); the
source sits on the blade's pitch-change axis (the quarter chord) with BPM's chord axis along the section's
chord, pitched ``theta = phi + alpha`` from the disc plane (:mod:`~bild_mdo.acoustics.bpm.rotor_geometry`); the source
amplitude and Strouhal numbers use the flow speed ``W`` (no Prandtl-Glauert factor); observers move with
the rotor; a Doppler-shifted band keeps its 1/3-octave energy (no band re-binning).

Partials are exact: the BPM functions are evaluated once more with :class:`~bild_mdo.utils.jet.Jet`
values seeded at the segment and geometric quantities, and chained to the inputs.
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo import validation
from bild_mdo.acoustics.bands import THIRD_OCTAVE_CENTRES
from bild_mdo.acoustics.bpm.bluntness import (MAX_TRAILING_EDGE_ANGLE, NACA0012_TRAILING_EDGE_ANGLE,
                                              bluntness_pressure_squared)
from bild_mdo.acoustics.bpm.jet_math import value, where
from bild_mdo.acoustics.bpm.laminar_vortex_shedding import lbl_vs_pressure_squared
from bild_mdo.acoustics.bpm.rotor_geometry import GEOMETRY_NAMES, segment_geometry
from bild_mdo.acoustics.bpm.tip_vortex import TIP_ALPHA_CORRECTION, TIP_SHAPES, tip_vortex_pressure_squared
from bild_mdo.acoustics.bpm.turbulent_trailing_edge import tbl_te_pressure_squared
from bild_mdo.utils.jet import Jet
from bild_mdo.utils.options import add_inputs, declare_size_options

#: The broadband mechanisms, in the order of the ``ns`` axis of ``broadband_source_pressure_squared``.
BROADBAND_SOURCES = ("tbl_te_pressure", "tbl_te_suction", "separation", "lbl_vs", "tip_vortex", "bluntness")
_TIP = BROADBAND_SOURCES.index("tip_vortex")
_LBL = BROADBAND_SOURCES.index("lbl_vs")
_BLUNT = BROADBAND_SOURCES.index("bluntness")
_RPM_TO_RAD_S = np.pi / 30.0
#: Peak memory per segment, azimuth and band (bytes) of a run and of the partials, measured (30 stations, 24
#: azimuths, 31 bands, one observer, 20 designs: 137 and 705 B with sharp trailing edges, 225 and 939 B with
#: the bluntness noise) and rounded up.
RUN_BYTES, PARTIALS_BYTES = 300.0, 1200.0
_DIST = ("radii", "dr", "chord", "alpha", "inflow_speed", "phi")
#: Every per-station input (the distributions and the trailing-edge thickness).
_STATION = _DIST + ("trailing_edge_thickness",)
_NODE = ("rpm", "radius", "rho", "mu", "speed_of_sound")
_GEOMETRY_SEEDS = ("r", "pitch", "w", "inflow_angle", "rpm", "speed_of_sound", "ox", "oy", "oz")


def _seed(x, name, jets):
    return Jet(x, {name: 1.0}) if jets else x


class BroadbandNoiseComp(om.ExplicitComponent):
    """Broadband self-noise (BPM) of a rotor per mechanism and in total (module docstring for the model).

    Options
    -------
    num_nodes, num_radial : int
        Designs (nn) and radial stations (nr).
    num_observers : int
        Observers per design (no).
    num_blades : int
        Number of blades ``B``.
    band_frequencies : array
        One-third-octave centre frequencies (Hz), nb of them (default ``bands.THIRD_OCTAVE_CENTRES``).
    boundary_layer : str
        ``'tripped'`` (default) or ``'untripped'`` (then LBL-VS is predicted).
    num_azimuth : int
        Azimuth samples of the blade around the disc (default 24).
    tip_shape : str
        ``'rounded'`` (default, Eq. 63) or ``'flat'`` (Eq. 67).
    tip_alpha_correction : float
        ``alpha'_TIP / alpha_TIP`` of the tip vortex (Eq. 65); default 0.71, BPM's untwisted wing (Eq. 66).
    trailing_edge_angle : float
        Solid angle ``Psi`` (deg) between the surfaces at the trailing edge, of the bluntness noise (Eq. 70);
        default 14 (NACA 0012), 0 for a flat plate.

    Inputs
    ------
    radii[nn, nr] (m), dr[nn, nr] (m), chord[nn, nr] (m), alpha[nn, nr] (rad), inflow_speed[nn, nr] (m/s)
        Station radius, width, chord, angle of attack and inflow speed ``W``.
    phi[nn, nr] (rad)
        Inflow angle of each station: the direction of ``W`` (convective amplification) and, with ``alpha``,
        the pitch ``phi + alpha`` of its chord.  The flight speed enters through ``W`` and ``phi``.
    rpm[nn] (rpm), radius[nn] (m)
        Rotor speed and tip radius.
    rho[nn] (kg/m**3), mu[nn] (Pa*s), speed_of_sound[nn] (m/s)
        The air.
    observer_position[nn, no, 3] (m)
        Observers in the rotor frame.
    trailing_edge_thickness[nn, nr] (m)
        Trailing-edge thickness ``h`` of each station (>= 0; 0, the default, is a sharp edge: no bluntness noise).

    Outputs
    -------
    broadband_source_pressure_squared[nn, no, ns, nb] (Pa**2)
        Mean-square pressure per mechanism, ``ns = len(BROADBAND_SOURCES)``.
    broadband_pressure_squared[nn, no, nb] (Pa**2)
        Their sum.
    """

    def initialize(self):
        declare_size_options(self.options)
        self.options.declare("num_observers", types=int, default=1, lower=1, desc="observers per design (no)")
        self.options.declare("num_blades", types=int, default=2, lower=1, desc="number of blades B")
        self.options.declare("band_frequencies", default=THIRD_OCTAVE_CENTRES,
                             desc="one-third-octave band centre frequencies (Hz)")
        self.options.declare("boundary_layer", default="tripped", values=("tripped", "untripped"),
                             desc="BPM boundary-layer fits: tripped (no LBL-VS) or untripped")
        self.options.declare("num_azimuth", types=int, default=24, lower=1,
                             desc="azimuth samples of the blade around the disc")
        self.options.declare("tip_shape", default="rounded", values=TIP_SHAPES,
                             desc="tip shape of the tip-vortex model: rounded (Eq. 63) or flat (Eq. 67)")
        self.options.declare("tip_alpha_correction", types=float, default=TIP_ALPHA_CORRECTION, lower=0.0,
                             desc="alpha'_TIP / alpha_TIP of the tip vortex (Eq. 65; 0.71 is BPM's Eq. 66)")
        self.options.declare("trailing_edge_angle", types=float, default=NACA0012_TRAILING_EDGE_ANGLE, lower=0.0,
                             upper=MAX_TRAILING_EDGE_ANGLE,
                             desc="solid angle Psi (deg) of the trailing edge, bluntness noise (Eq. 70)")

    def _sizes(self):
        o = self.options
        return (o["num_nodes"], o["num_radial"], o["num_observers"], len(BROADBAND_SOURCES),
                len(np.atleast_1d(o["band_frequencies"])))

    def _check_memory(self, bytes_per_value, what):
        """ValueError (one line) before a run whose arrays of every segment, azimuth and band would not fit."""
        nn, nr, no, _, nb = self._sizes()
        validation.memory_bound(f"{what} of {nn} designs x {no} observers", nn * no, nr,
                                bytes_per_value=bytes_per_value * self.options["num_azimuth"] * nb,
                                hint="compute the noise of fewer designs at a time (a smaller num_nodes), or with "
                                     "fewer observers, azimuths or bands")

    def setup(self):
        nn, nr, no, ns, nb = self._sizes()
        self._check_memory(RUN_BYTES, "the broadband noise")
        add_inputs(self, [n for n in _DIST + _NODE if n != "alpha"])
        self.add_input("alpha", val=np.full((nn, nr), 0.05), units="rad", desc="angle of attack of each station")
        self.add_input("observer_position", val=np.tile([-10.0, 0.0, 0.0], (nn, no, 1)), units="m",
                       desc="observer positions in the rotor frame (x along the thrust)")
        self.add_input("trailing_edge_thickness", val=np.zeros((nn, nr)), units="m",
                       desc="trailing-edge thickness of each station (0: a sharp edge, no bluntness noise)")
        self.add_output("broadband_source_pressure_squared", val=np.zeros((nn, no, ns, nb)), units="Pa**2",
                        desc="BPM mean-square pressure per mechanism (BROADBAND_SOURCES) and band")
        self.add_output("broadband_pressure_squared", val=np.zeros((nn, no, nb)), units="Pa**2",
                        desc="broadband mean-square pressure per band (all mechanisms)")

    # ----- dependency patterns --------------------------------------------------------------------------
    def _dependencies(self):
        """``{input: mask}``: ``mask[ns, nr]`` (station inputs) or ``mask[ns]`` which sources depend on it."""
        nr, ns = self.options["num_radial"], len(BROADBAND_SOURCES)
        segment = np.ones(ns, dtype=bool)
        segment[_TIP] = False
        if self.options["boundary_layer"] == "tripped":
            segment[_LBL] = False
        tip = np.zeros(ns, dtype=bool)
        tip[_TIP] = True
        last = np.zeros(nr, dtype=bool)
        last[-1] = True
        seg_all = np.outer(segment, np.ones(nr, dtype=bool))
        seg_tip = seg_all | np.outer(tip, last)
        blunt = np.zeros((ns, nr), dtype=bool)
        blunt[_BLUNT] = True
        return {"trailing_edge_thickness": blunt,
                "radii": seg_all, "dr": seg_all, "chord": seg_tip, "alpha": seg_tip, "inflow_speed": seg_tip,
                "phi": seg_tip,
                "rpm": segment | tip, "speed_of_sound": segment | tip,
                "rho": segment, "mu": segment, "radius": tip, "observer_position": segment | tip}

    def _patterns(self):
        """``{(output, input): (rows, cols, mask_of_full_array)}`` with the full arrays as in compute_partials."""
        nn, nr, no, ns, nb = self._sizes()
        patterns = {}
        for name, dep in self._dependencies().items():
            if name in _STATION:
                full = (nn, no, ns, nb, nr)
                mask = np.broadcast_to(dep[None, None, :, None, :], full)
                col = np.broadcast_to(np.arange(nn)[:, None, None, None, None] * nr + np.arange(nr), full)
            elif name == "observer_position":
                full = (nn, no, ns, nb, 3)
                mask = np.broadcast_to(dep[None, None, :, None, None], full)
                col = np.broadcast_to((np.arange(nn)[:, None] * no + np.arange(no))[:, :, None, None, None] * 3
                                      + np.arange(3), full)
            else:
                full = (nn, no, ns, nb)
                mask = np.broadcast_to(dep[None, None, :, None], full)
                col = np.broadcast_to(np.arange(nn)[:, None, None, None], full)
            row = np.broadcast_to(np.arange(nn * no * ns * nb).reshape(nn, no, ns, nb)[(...,) + (None,) *
                                                                                     (len(full) - 4)], full)
            patterns["broadband_source_pressure_squared", name] = (row[mask], col[mask], mask)
            # The total: the same per-band pattern without the source axis.
            mask_t = mask.any(axis=2)
            row_t = np.broadcast_to(np.arange(nn * no * nb).reshape(nn, no, nb)[(...,) + (None,) * (len(full) - 4)],
                                    mask_t.shape)
            patterns["broadband_pressure_squared", name] = (row_t[mask_t], np.take(col, 0, axis=2)[mask_t], mask_t)
        return patterns

    def setup_partials(self):
        self._pattern_cache = self._patterns()
        for (of, wrt), (rows, cols, _) in self._pattern_cache.items():
            if rows.size:
                self.declare_partials(of, wrt, rows=rows, cols=cols)

    # ----- the model ------------------------------------------------------------------------------------
    def _evaluate(self, inputs, jets, azimuths):
        """Per-station spectra (arrays or jets) of the segment sources and the tip, and their geometry jets, at
        the first ``azimuths`` of the ``num_azimuth`` equal steps (:meth:`_azimuths`)."""
        o = self.options
        nr = o["num_radial"]
        tripped = o["boundary_layer"] == "tripped"
        psi = 2.0 * np.pi * np.arange(azimuths) / o["num_azimuth"]
        azimuth = psi[None, None, None, :, None]
        freq = np.asarray(o["band_frequencies"], dtype=float)
        per_node = {k: inputs[k][:, None, None, None, None] for k in _NODE}
        pos = inputs["observer_position"]
        obs = [_seed(pos[:, :, k][:, :, None, None, None], n, jets) for k, n in enumerate(("ox", "oy", "oz"))]
        omega = per_node["rpm"] * _RPM_TO_RAD_S
        omega = Jet(omega, {"rpm": _RPM_TO_RAD_S}) if jets else omega
        c0 = per_node["speed_of_sound"]
        c0_geo = _seed(c0, "speed_of_sound", jets)

        def station(x, j=slice(None)):
            return x[:, j][:, None, :, None, None] if isinstance(j, slice) else x[:, j][:, None, None, None, None]

        def segment(j):
            chord, speed = station(inputs["chord"], j), station(inputs["inflow_speed"], j)
            values = {"chord": chord, "span": station(inputs["dr"], j), "speed": speed, "mach": speed / c0,
                      "alpha": station(inputs["alpha"], j),
                      "reynolds": per_node["rho"] * speed * chord / per_node["mu"]}
            seeds = {k: _seed(v, k, jets) for k, v in values.items()}
            values.update(rho=per_node["rho"], mu=per_node["mu"])
            return values, seeds

        seg_values, seg = segment(slice(None))
        pitch = inputs["phi"] + inputs["alpha"]
        geo = segment_geometry(_seed(station(inputs["radii"]), "r", jets), omega,
                               _seed(station(inputs["inflow_speed"]), "w", jets),
                               _seed(station(inputs["phi"]), "inflow_angle", jets), c0_geo, obs, azimuth,
                               _seed(station(pitch), "pitch", jets))
        g = {k: _seed(value(v), k, jets) for k, v in geo.items()}
        f_src = freq * g["shift"]
        p2_p, p2_s, p2_a = tbl_te_pressure_squared(f_src, seg["chord"], seg["span"], seg["speed"], seg["mach"],
                                                   seg["alpha"], seg["reynolds"], g["distance"], g["d_high"],
                                                   g["d_low"], tripped)
        p2_l = None if tripped else lbl_vs_pressure_squared(f_src, seg["chord"], seg["span"], seg["speed"],
                                                            seg["mach"], seg["alpha"], seg["reynolds"],
                                                            g["distance"], g["d_high"])
        p2_b = self._bluntness(inputs, station, seg, g, f_src, tripped, jets)
        tip_values, tip = segment(nr - 1)
        geo_tip = segment_geometry(_seed(per_node["radius"], "r", jets), omega,
                                   _seed(station(inputs["inflow_speed"], nr - 1), "w", jets),
                                   _seed(station(inputs["phi"], nr - 1), "inflow_angle", jets), c0_geo, obs,
                                   azimuth, _seed(station(pitch, nr - 1), "pitch", jets))
        gt = {k: _seed(value(v), k, jets) for k, v in geo_tip.items()}
        c0_tip = _seed(c0, "c0_tip", jets)
        p2_t = tip_vortex_pressure_squared(freq * gt["shift"], tip["chord"], tip["mach"], c0_tip, tip["alpha"],
                                           gt["distance"], gt["d_high"], tip_shape=o["tip_shape"],
                                           alpha_correction=o["tip_alpha_correction"])
        return ([p2_p, p2_s, p2_a, p2_l, p2_t, p2_b], (seg_values, geo), (tip_values, geo_tip))

    def _bluntness(self, inputs, station, seg, g, f_src, tripped, jets):
        """TEB-VS of the stations with a blunt trailing edge (``h > 0``), zero at the others; None if none is."""
        h = inputs["trailing_edge_thickness"]
        bad = np.argwhere(~(np.isfinite(h) & (np.real(h) >= 0.0)))
        if bad.size:
            raise om.AnalysisError(f"{self.msginfo}: trailing_edge_thickness must be finite and >= 0 (m), got "
                                   f"{np.real(h[tuple(bad[0])]):.6g} m at node {bad[0][0]}, station {bad[0][1]}")
        blunt = np.real(h) > 0.0
        if not np.any(blunt):
            return None
        thickness = _seed(station(np.where(blunt, h, 1.0)), "thickness", jets)
        p2 = bluntness_pressure_squared(f_src, seg["chord"], seg["span"], seg["speed"], seg["mach"], seg["alpha"],
                                        seg["reynolds"], g["distance"], g["d_high"], thickness,
                                        self.options["trailing_edge_angle"], tripped)
        return where(station(blunt), p2, 0.0 * p2)

    def _azimuths(self, inputs):
        """Azimuths evaluated: 1 where every observer is on the rotor axis (module docstring), else num_azimuth."""
        n = self.options["num_azimuth"]
        return 1 if n >= 2 and np.all(inputs["observer_position"][..., 1:] == 0.0) else n

    def compute(self, inputs, outputs):
        nn, _, no, ns, nb = self._sizes()
        azimuths = self._azimuths(inputs)
        scale = self.options["num_blades"] / azimuths
        spectra, _, _ = self._evaluate(inputs, False, azimuths)
        out = np.zeros((nn, no, ns, nb), dtype=inputs["chord"].dtype)
        for s, p2 in enumerate(spectra):
            if p2 is not None:
                out[:, :, s] = scale * np.sum(p2, axis=(2, 3))
        outputs["broadband_source_pressure_squared"] = out
        outputs["broadband_pressure_squared"] = out.sum(axis=2)

    def compute_partials(self, inputs, partials):
        self._check_memory(PARTIALS_BYTES, "the broadband noise's partials")
        nn, nr, no, ns, nb = self._sizes()
        azimuths = self._azimuths(inputs)
        on_axis = azimuths != self.options["num_azimuth"]
        scale = self.options["num_blades"] / azimuths
        spectra, (seg, geo), (tip, geo_tip) = self._evaluate(inputs, True, azimuths)
        full = {name: np.zeros((nn, no, ns, nb, nr)) for name in _STATION}
        full.update({name: np.zeros((nn, no, ns, nb)) for name in _NODE})
        full["observer_position"] = np.zeros((nn, no, ns, nb, 3))
        for s, p2 in enumerate(spectra):
            if p2 is None:
                continue
            values, geometry = (tip, geo_tip) if s == _TIP else (seg, geo)
            for name, x in self._chain(p2, values, geometry, s == _TIP, scale).items():
                if name in _STATION and s == _TIP:
                    full[name][:, :, s, :, -1] = x[:, :, 0, :]  # the tip's one station is the outermost
                elif name in _STATION:
                    full[name][:, :, s] = np.moveaxis(x, 2, 3)  # [nn, no, nr, nb] -> [nn, no, nb, nr]
                else:
                    full[name][:, :, s] = x
        if on_axis:
            full["observer_position"][..., 1:] = 0.0  # their exact value on the axis (module docstring)
        for (of, wrt), (_, _, mask) in self._pattern_cache.items():
            if np.any(mask):
                values = full[wrt] if of == "broadband_source_pressure_squared" else full[wrt].sum(axis=2)
                partials[of, wrt] = values[mask]

    @staticmethod
    def _chain(p2, values, geometry, is_tip, scale):
        """Partials of one source, summed over azimuth, with respect to the inputs.

        Station inputs come back as ``[nn, no, nr, nb]`` (``nr = 1`` for the tip), per-design inputs as
        ``[nn, no, nb]`` (summed over stations) and the observer as ``[nn, no, nb, 3]``.
        """
        shape = p2.v.shape

        def total(name, factor=1.0):
            """``scale * sum_psi dp2/dname * factor`` -> [nn, no, nr, nb]."""
            return scale * np.sum(np.real(np.broadcast_to(p2.partial(name), shape) * factor), axis=3)

        def over_stations(x):
            return np.sum(np.broadcast_to(x, shape[:3] + shape[4:]), axis=2)

        speed, mach = values["speed"], values["mach"]
        geo_d = {seed: 0.0 for seed in _GEOMETRY_SEEDS}
        for g in GEOMETRY_NAMES:
            dp = np.broadcast_to(p2.partial(g), shape)
            for seed in _GEOMETRY_SEEDS:
                dg = geometry[g].partial(seed)
                if not (np.isscalar(dg) and dg == 0.0):
                    geo_d[seed] = geo_d[seed] + scale * np.sum(np.real(dp * dg), axis=3)

        def per_station(x):
            return np.broadcast_to(x, shape[:3] + shape[4:])

        # M = W / c0: dM/dW = M / W, dM/dc0 = -M^2 / W.
        # The chord's pitch is phi + alpha; W and phi also set the convection velocity of the directivities.
        d_pitch = per_station(geo_d["pitch"])
        out = {"chord": total("chord"), "alpha": total("alpha") + d_pitch,
               "phi": d_pitch + per_station(geo_d["inflow_angle"]),
               "inflow_speed": total("speed") + total("mach", mach / speed) + per_station(geo_d["w"])}
        d_c0 = over_stations(total("mach", -mach * mach / speed))
        if is_tip:
            d_c0 = d_c0 + over_stations(total("c0_tip"))
            out["radius"] = over_stations(geo_d["r"])
        else:
            # R_c = rho W c / mu.
            re = values["reynolds"]
            out["chord"] = out["chord"] + total("reynolds", re / values["chord"])
            out["inflow_speed"] = out["inflow_speed"] + total("reynolds", re / speed)
            out["dr"] = total("span")
            if "thickness" in p2.d:
                out["trailing_edge_thickness"] = total("thickness")
            out["radii"] = per_station(geo_d["r"])
            out["rho"] = over_stations(total("reynolds", re / values["rho"]))
            out["mu"] = over_stations(total("reynolds", -re / values["mu"]))
        out["speed_of_sound"] = d_c0 + over_stations(geo_d["speed_of_sound"])
        out["rpm"] = over_stations(geo_d["rpm"])
        out["observer_position"] = np.stack([over_stations(geo_d[k]) for k in ("ox", "oy", "oz")], axis=-1)
        return out
