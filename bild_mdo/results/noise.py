"""Rotor noise of a design or an analysis: :func:`rotor_noise`, :class:`NoiseResult`, :func:`combine_noise`.

:func:`rotor_noise` runs :class:`~bild_mdo.acoustics.rotor_noise_group.RotorNoiseGroup` on the loads and
blade of a :class:`~bild_mdo.results.design_result.DesignResult` (:func:`~bild_mdo.results.design.design_rotor`)
or of a :class:`~bild_mdo.bem.analyze.BEMResult` (:func:`~bild_mdo.bem.analyze.analyze_rotor`, with the blade
and operating point it was given) at observers in the rotor frame (x along the rotor axis in the direction
of the thrust, so an observer below a hovering lift rotor has x < 0; y, z in the disc plane; metres).
"""
from __future__ import annotations

import dataclasses
import textwrap

import numpy as np
import openmdao.api as om

from bild_mdo import validation
from bild_mdo.acoustics.bands import NOMINAL_CENTRES, THIRD_OCTAVE_CENTRES, spl_db
from bild_mdo.acoustics.bpm.bluntness import MAX_TRAILING_EDGE_ANGLE, NACA0012_TRAILING_EDGE_ANGLE
from bild_mdo.acoustics.broadband_noise import BROADBAND_SOURCES
from bild_mdo.acoustics.noise_totals import a_weight_factor
from bild_mdo.acoustics.rotor_noise_group import BOUNDARY_LAYERS, RotorNoiseGroup, check_observers
from bild_mdo.atmosphere import isa
from bild_mdo.io.airfoil import resolve_airfoil

__all__ = ["MODEL", "VALIDITY", "NoiseResult", "combine_noise", "rotor_noise"]

#: What the noise models are, for summaries.
MODEL = ("tonal: Hanson's helicoidal-surface far field in its compact-chord limit (Gutin's loading and "
         "Deming's thickness noise in hover), harmonics m B Omega; broadband: Brooks-Pope-Marcolini self-noise "
         "(NASA RP-1218, 1989: TBL-TE pressure and suction side, separation, LBL-VS, tip vortex, trailing-edge "
         "bluntness where a trailing-edge thickness is given) per blade "
         "element in 1/3-octave bands; levels dB re 20 uPa, A-weighting IEC 61672-1")
#: Where the models stop holding.
VALIDITY = ("far field only (observers many radii and wavelengths away), axial flight and hover, tip Mach "
            "well below 1 (compact, subsonic sections); BPM fits from NACA 0012 sections at Re <= 1.5e6 and "
            "alpha <= 25 deg; broadband and tonal levels are incoherent sums")
# Rows of the summary where the model's limits are near: observer distance / radius, tip Mach number.
_NEAR_FIELD_RADII = 3.0
_HIGH_TIP_MACH = 0.8
# Width of the wrapped text lines of a summary.
_WIDTH = 110


@dataclasses.dataclass(frozen=True, eq=False)
class NoiseResult:
    """Noise of one rotor (or several, :func:`combine_noise`) at observers: spectra and overall levels.

    A single design holds arrays whose first axis is the observer; a batch of ``nn`` designs has one more
    axis in front.  Levels are dB re 20 uPa; mean-square pressures Pa**2; frequencies Hz.

    Attributes
    ----------
    observers : ndarray, shape (no, 3)
        Observer positions (m, rotor frame).
    tonal_frequency : ndarray, shape ([nn,] nt)
        Frequency of each tonal line (harmonics ``m B Omega / (2 pi)``; several rotors: all their lines).
    tonal_spl, loading_spl, thickness_spl : ndarray, shape ([nn,] no, nt)
        Level of each tonal line: total, loading part, thickness part.
    band_frequencies : ndarray, shape (nb,)
        Centre frequencies of the one-third-octave bands.
    band_spl : ndarray, shape ([nn,] no, nb)
        Broadband level per band (all mechanisms); -100 dB (the floor) without broadband.
    source_spl : dict of str to ndarray, shape ([nn,] no, nb)
        Broadband level per band of each BPM mechanism (:data:`BROADBAND_SOURCES`).
    oaspl, oaspl_dba : ndarray, shape ([nn,] no)
        Overall and A-weighted overall level.
    pressure_squared, weighted_pressure_squared : ndarray, shape ([nn,] no)
        Total and A-weighted mean-square pressure (what :func:`combine_noise` adds).
    tonal_pressure_squared, broadband_pressure_squared : ndarray
        Mean-square pressure of each tonal line and band.
    description : str
        The rotor(s): blades, rotor speed, tip Mach number.
    tip_mach, radius : ndarray, shape ([nn,] k)
        Tip Mach number and radius of each of the k rotors summed.
    is_batch : bool
    """

    observers: np.ndarray
    tonal_frequency: np.ndarray
    tonal_pressure_squared: np.ndarray
    loading_pressure_squared: np.ndarray
    thickness_pressure_squared: np.ndarray
    band_frequencies: np.ndarray
    broadband_pressure_squared: np.ndarray
    source_pressure_squared: dict
    description: str
    tip_mach: np.ndarray
    radius: np.ndarray
    is_batch: bool = False
    boundary_layer: str = "tripped"

    @property
    def tonal_spl(self):
        return spl_db(self.tonal_pressure_squared)

    @property
    def loading_spl(self):
        return spl_db(self.loading_pressure_squared)

    @property
    def thickness_spl(self):
        return spl_db(self.thickness_pressure_squared)

    @property
    def band_spl(self):
        return spl_db(self.broadband_pressure_squared)

    @property
    def source_spl(self):
        return {name: spl_db(value) for name, value in self.source_pressure_squared.items()}

    @property
    def pressure_squared(self):
        return self.tonal_pressure_squared.sum(-1) + self.broadband_pressure_squared.sum(-1)

    @property
    def weighted_pressure_squared(self):
        tones = self.tonal_pressure_squared * a_weight_factor(self.tonal_frequency)[..., None, :]
        return tones.sum(-1) + (self.broadband_pressure_squared * a_weight_factor(self.band_frequencies)).sum(-1)

    @property
    def oaspl(self):
        return spl_db(self.pressure_squared)

    @property
    def oaspl_dba(self):
        return spl_db(self.weighted_pressure_squared)

    @property
    def distance(self):
        """Distance of each observer from the rotor centre (m)."""
        return np.linalg.norm(self.observers, axis=1)

    @property
    def polar_angle(self):
        """Angle of each observer from the rotor axis +x (deg): 0 ahead along the thrust, 180 behind."""
        return np.degrees(np.arccos(np.clip(self.observers[:, 0] / self.distance, -1.0, 1.0)))

    def __len__(self):
        return self.oaspl.shape[0] if self.is_batch else 1

    def __add__(self, other):
        return combine_noise(self, other)

    def summary(self, max_rows=20):
        """Readable text: the model and its limits, then one row per observer (per design of a batch)."""
        lines = [f"Rotor noise: {self.description}",
                 textwrap.fill(f"model: {MODEL}", _WIDTH, subsequent_indent="  "),
                 textwrap.fill(f"validity: {VALIDITY}", _WIDTH, subsequent_indent="  "),
                 f"{'design':>6} {'observer':>8} {'x [m]':>9} {'y [m]':>9} {'z [m]':>9} {'angle':>7} "
                 f"{'OASPL':>8} {'dBA':>8} {'tonal':>8} {'broadband':>9} {'loudest':>12}",
                 f"{'':>6} {'':>8} {'':>9} {'':>9} {'':>9} {'[deg]':>7} {'[dB]':>8} {'[dBA]':>8} {'[dB]':>8} "
                 f"{'[dB]':>9} {'[Hz]':>12}"]
        oaspl, dba = np.atleast_2d(self.oaspl), np.atleast_2d(self.oaspl_dba)
        tonal = np.atleast_2d(spl_db(self.tonal_pressure_squared.sum(-1)))
        broadband = np.atleast_2d(spl_db(self.broadband_pressure_squared.sum(-1)))
        loudest = self._loudest()
        rows = [(i, k) for i in range(oaspl.shape[0]) for k in range(oaspl.shape[1])]
        shown = rows if len(rows) <= max_rows else rows[:max_rows // 2] + [None] + rows[-(max_rows // 2):]
        for row in shown:
            if row is None:
                lines.append(f"{'...':>6}")
                continue
            i, k = row
            x, y, z = self.observers[k]
            lines.append(f"{i:>6d} {k:>8d} {x:>9.4g} {y:>9.4g} {z:>9.4g} {self.polar_angle[k]:>7.1f} "
                         f"{oaspl[i, k]:>8.2f} {dba[i, k]:>8.2f} {tonal[i, k]:>8.2f} {broadband[i, k]:>9.2f} "
                         f"{loudest[i, k]:>12s}")
        lines += self._notes()
        return "\n".join(lines)

    def _loudest(self):
        """The loudest tonal line or band of each observer, as text."""
        tones = self.tonal_pressure_squared if self.is_batch else self.tonal_pressure_squared[None]
        bands = self.broadband_pressure_squared if self.is_batch else self.broadband_pressure_squared[None]
        freq = np.atleast_2d(self.tonal_frequency)
        text = np.empty(tones.shape[:2], dtype=object)
        for i in range(tones.shape[0]):
            for k in range(tones.shape[1]):
                h, b = int(np.argmax(tones[i, k])), int(np.argmax(bands[i, k]))
                if tones[i, k, h] >= bands[i, k, b]:
                    text[i, k] = f"tone {freq[i, h]:.4g}"
                else:
                    text[i, k] = f"band {_nominal(self.band_frequencies[b]):g}"
        return text

    def _at(self, value, design=0, observer=0):
        """``value`` (per observer, or per design and observer of a batch) of one design and observer."""
        return value[design, observer] if self.is_batch else value[observer]

    def mechanism_levels(self, design=0, observer=0):
        """Overall broadband level (dB) of each BPM mechanism at one observer: ``{name: dB}``, sums over bands."""
        return {name: float(spl_db(self._at(value, design, observer).sum(-1)))
                for name, value in self.source_pressure_squared.items()}

    def _notes(self):
        notes = []
        if self.source_pressure_squared and np.any(self._at(self.broadband_pressure_squared) > 0.0):
            levels = self.mechanism_levels()
            heard = ", ".join(f"{name} {level:.1f}" for name, level in levels.items()
                              if np.any(self._at(self.source_pressure_squared[name]) > 0.0))
            notes.append(textwrap.fill(f"broadband by mechanism, design 0, observer 0 [dB]: {heard}", _WIDTH,
                                       subsequent_indent="  "))
        near = np.flatnonzero(self.distance < _NEAR_FIELD_RADII * np.max(self.radius))
        if near.size:
            notes.append(textwrap.fill(f"note: observer(s) {', '.join(map(str, near))} within {_NEAR_FIELD_RADII:g} "
                                       "rotor radii: the far-field models do not hold there", _WIDTH,
                                       subsequent_indent="  "))
        if np.max(self.tip_mach) > _HIGH_TIP_MACH:
            notes.append(textwrap.fill(f"note: tip Mach number {np.max(self.tip_mach):.3g} > {_HIGH_TIP_MACH}: the "
                                       "compact, subsonic tonal model loses accuracy as the tip Mach number nears 1",
                                       _WIDTH, subsequent_indent="  "))
        return notes


def _nominal(frequency):
    k = int(np.argmin(np.abs(THIRD_OCTAVE_CENTRES - frequency)))
    return NOMINAL_CENTRES[k] if np.isclose(THIRD_OCTAVE_CENTRES[k], frequency, rtol=1e-6) else frequency


def _rotor_of_design(result):
    """Inputs of the noise group from a DesignResult (every array 2-D / 1-D over designs)."""
    if not np.all(result.feasible):
        raise ValueError("rotor_noise needs feasible designs; pass result.feasible_designs()")
    values = result.values
    node = {name: np.atleast_1d(np.asarray(values[name], dtype=float))
            for name in ("rpm", "v_axial", "radius", "hub_radius", "rho", "mu")}
    if result.fluid is not None:
        node["speed_of_sound"] = np.full(node["rpm"].shape, float(result.fluid.speed_of_sound))
    else:
        node["speed_of_sound"] = np.atleast_1d(isa(np.atleast_1d(np.asarray(values["altitude"], float))).speed_of_sound)
    station = {name: np.atleast_2d(np.asarray(values[name], dtype=float))
               for name in ("radii", "dr", "chord", "dthrust_dr", "dtorque_dr", "phi")}
    # BILD's local Mach number is W / a with the induced inflow speed W.
    station["inflow_speed"] = np.atleast_2d(values["mach"]) * node["speed_of_sound"][:, None]
    # alpha* per design (one section point) or per station (spanwise airfoils, local section points).
    alpha = np.asarray(values["alpha_star"], dtype=float)
    if result.is_batch and alpha.ndim == 1:
        alpha = alpha[:, None]
    station["alpha"] = np.broadcast_to(np.atleast_2d(alpha), station["radii"].shape).copy()
    return node, station, result.num_blades, result.polar, np.atleast_1d(values["tip_mach"]), result.is_batch


_BEM_ROTOR = ("chord", "rpm", "v_axial", "radius", "hub_radius", "num_blades")


def _rotor_of_analysis(result, rotor):
    """Inputs of the noise group from a BEMResult and the blade it was analysed with."""
    missing = [name for name in _BEM_ROTOR if rotor.get(name) is None]
    if missing:
        raise ValueError(f"rotor_noise of an analyze_rotor result needs the blade and operating point it was "
                         f"analysed with: give {', '.join(missing)}")
    radii = np.asarray(result.radii, dtype=float)
    batch = radii.ndim == 2
    radii = np.atleast_2d(radii)
    nn = radii.shape[0]
    node = {name: np.broadcast_to(np.asarray(rotor[name], dtype=float), (nn,)).copy()
            for name in ("rpm", "v_axial", "radius", "hub_radius")}
    for name in ("rho", "mu", "speed_of_sound"):
        node[name] = np.broadcast_to(np.asarray(getattr(result, name), dtype=float), (nn,)).copy()
    station = {name: np.atleast_2d(np.asarray(getattr(result, name), dtype=float))
               for name in ("radii", "dr", "dthrust_dr", "dtorque_dr", "alpha", "inflow_speed", "phi")}
    station["chord"] = np.broadcast_to(np.asarray(rotor["chord"], dtype=float), radii.shape).copy()
    polar = rotor.get("polar")
    polar = resolve_airfoil("naca4412" if polar is None else polar)
    tip_mach = np.atleast_1d(np.asarray(result.tip_mach, dtype=float))
    return node, station, int(rotor["num_blades"]), polar, tip_mach, batch


def rotor_noise(result, observers, num_harmonics=10, boundary_layer="tripped", include_broadband=True,
                band_frequencies=THIRD_OCTAVE_CENTRES, trailing_edge_thickness=0.0,
                trailing_edge_angle=NACA0012_TRAILING_EDGE_ANGLE, num_azimuth=24, **rotor):
    """Tonal and broadband noise of a rotor design or analysis at observers.

    Parameters
    ----------
    result : DesignResult or BEMResult
        A design of :func:`~bild_mdo.results.design.design_rotor` (single or batch, feasible), or an
        analysis of :func:`~bild_mdo.bem.analyze.analyze_rotor`.
    observers : array_like, shape (n, 3)
        Observer positions (m) in the rotor frame: x along the rotor axis in the direction of the thrust
        (an observer below a hovering lift rotor has x < 0), y and z in the disc plane.  Each observer must
        lie outside the sphere through the blade tips.
    num_harmonics : int
        Blade-passage harmonics of the tonal noise (default 10).
    boundary_layer : {'tripped', 'untripped'}
        BPM's boundary-layer thickness fits.
    include_broadband : bool
        False: tonal noise only.
    band_frequencies : array_like
        Band centre frequencies (Hz), default the 31 one-third-octave bands 20 Hz - 20 kHz.
    trailing_edge_thickness : float or array_like
        Trailing-edge thickness ``h`` (m), one value or one per station (``[nr]`` or ``[nn, nr]``); 0, the
        default, is a sharp edge, which makes no bluntness noise.
    trailing_edge_angle : float
        Solid angle ``Psi`` (deg) between the surfaces at the trailing edge (default 14, a NACA 0012's).
    num_azimuth : int
        Azimuth samples of the broadband noise (default 24): the mean converges geometrically, slowest near
        the disc plane (the docs' Noise page gives the errors of 6, 12 and 24 azimuths).
    **rotor
        For a BEMResult: ``chord``, ``rpm``, ``v_axial``, ``radius``, ``hub_radius``, ``num_blades`` as
        given to ``analyze_rotor``, and ``polar`` (its airfoil, for the section thickness; default NACA 4412).

    Returns
    -------
    NoiseResult

    Raises
    ------
    ValueError
        One line: observers of the wrong shape, not finite or inside the rotor; a missing rotor argument.
    """
    if boundary_layer not in BOUNDARY_LAYERS:
        raise ValueError(f"boundary_layer must be 'tripped' or 'untripped', got {boundary_layer!r}")
    if hasattr(result, "values") and hasattr(result, "feasible"):
        if rotor:
            raise ValueError(f"rotor_noise of a design takes no rotor arguments, got {', '.join(sorted(rotor))}")
        node, station, blades, polar, tip_mach, batch = _rotor_of_design(result)
    else:
        node, station, blades, polar, tip_mach, batch = _rotor_of_analysis(result, rotor)
    positions = check_observers(observers, radius=np.max(node["radius"]))
    nn, nr = station["radii"].shape
    thickness = _trailing_edge(trailing_edge_thickness, trailing_edge_angle, (nn, nr))
    num_azimuth = validation.integer("num_azimuth", num_azimuth, minimum=1)
    no = positions.shape[0]
    bands = np.asarray(band_frequencies, dtype=float).ravel()
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("noise", RotorNoiseGroup(
        num_nodes=nn, num_radial=nr, num_observers=no, num_harmonics=int(num_harmonics), num_blades=blades,
        band_frequencies=bands, boundary_layer=boundary_layer, include_broadband=include_broadband, polar=polar,
        trailing_edge_angle=float(trailing_edge_angle), num_azimuth=num_azimuth), promotes=["*"])
    prob.setup(check=False)
    inputs = {meta["prom_name"] for meta in prob.model.get_io_metadata(iotypes="input").values()}
    for name, value in {**node, **station}.items():
        if name in inputs:
            prob.set_val(name, value)
    prob.set_val("observer_position", np.broadcast_to(positions, (nn, no, 3)))
    if include_broadband:
        prob.set_val("trailing_edge_thickness", thickness)
    prob.run_model()

    def take(name, shape):
        value = prob.get_val(name).copy() if include_broadband or "broadband" not in name else np.zeros(shape)
        return value if batch else value[0]

    band_shape = (nn, no, bands.size)
    sources = take("broadband_source_pressure_squared", (nn, no, len(BROADBAND_SOURCES), bands.size))
    rpm = node["rpm"]
    rpm_text = f"{rpm[0]:.6g} rpm" if np.ptp(rpm) == 0 else f"{rpm.min():.6g}-{rpm.max():.6g} rpm"
    description = (f"B = {blades}, {rpm_text}, tip Mach {np.max(tip_mach):.3g}, radius {np.max(node['radius']):.4g} m, "
                   f"{int(num_harmonics)} harmonics, "
                   + (f"{bands.size} bands ({boundary_layer} boundary layer" + (
                       f", trailing edge {'up to ' if np.ptp(thickness) > 0 else ''}{np.max(thickness) * 1e3:.3g} mm, "
                       f"Psi {float(trailing_edge_angle):g} deg)"
                       if np.any(thickness > 0.0) else ")") if include_broadband else "no broadband"))
    return NoiseResult(
        observers=positions, tonal_frequency=take("tonal_frequency", None),
        tonal_pressure_squared=take("tonal_pressure_squared", None),
        loading_pressure_squared=take("loading_pressure_squared", None),
        thickness_pressure_squared=take("thickness_pressure_squared", None), band_frequencies=bands,
        broadband_pressure_squared=take("broadband_pressure_squared", band_shape),
        source_pressure_squared={name: sources[..., k, :] for k, name in enumerate(BROADBAND_SOURCES)},
        description=description, tip_mach=(tip_mach[:, None] if batch else tip_mach[:1]),
        radius=(node["radius"][:, None] if batch else node["radius"][:1]), is_batch=batch,
        boundary_layer=boundary_layer)


def _trailing_edge(thickness, angle, shape):
    """The trailing-edge thickness as ``[nn, nr]`` (m), or ValueError (one line)."""
    try:
        h = np.array(thickness, dtype=float)
        h = np.broadcast_to(h, shape).copy()
    except (TypeError, ValueError):
        raise ValueError(f"trailing_edge_thickness must be one value or one per station (shape {shape[1:]} or "
                         f"{shape}) in metres, got {np.shape(thickness)}") from None
    validation.non_negative("trailing_edge_thickness", h, units="m", ndim=(2,))
    validation.in_range("trailing_edge_angle", angle, 0.0, MAX_TRAILING_EDGE_ANGLE, units="deg", ndim=(0,))
    return h


def combine_noise(*results):
    """Incoherent sum of the noise of several rotors of one vehicle at the same observers.

    The mean-square pressures add (rotors turning at independent phases): the bands band by band, the
    tonal lines of every rotor are kept side by side (``tonal_frequency`` holds them all), so two equal
    rotors read 10 log10(2) = 3.01 dB above one.  ``a + b`` is ``combine_noise(a, b)``.

    Parameters
    ----------
    *results : NoiseResult
        Results at the same observers (positions in each rotor's own frame are the caller's business: give
        each rotor the observers as seen from its own centre) and the same bands and batch size.

    Returns
    -------
    NoiseResult
    """
    if not results:
        raise ValueError("combine_noise needs at least one NoiseResult")
    first = results[0]
    for other in results[1:]:
        if not isinstance(other, NoiseResult):
            return NotImplemented
        if other.observers.shape != first.observers.shape or other.is_batch != first.is_batch or \
                other.oaspl.shape != first.oaspl.shape:
            raise ValueError("combine_noise needs results at the same number of observers and designs")
        if not np.array_equal(other.band_frequencies, first.band_frequencies):
            raise ValueError("combine_noise needs results in the same bands")

    def cat(name):
        return np.concatenate([getattr(r, name) for r in results], axis=-1)

    return dataclasses.replace(
        first, tonal_frequency=cat("tonal_frequency"), tonal_pressure_squared=cat("tonal_pressure_squared"),
        loading_pressure_squared=cat("loading_pressure_squared"),
        thickness_pressure_squared=cat("thickness_pressure_squared"),
        broadband_pressure_squared=sum(r.broadband_pressure_squared for r in results),
        source_pressure_squared={k: sum(r.source_pressure_squared[k] for r in results)
                                 for k in first.source_pressure_squared},
        description=f"{len(results)} rotors, summed incoherently: " + "; ".join(r.description for r in results),
        tip_mach=cat("tip_mach"), radius=cat("radius"))

