"""NoiseTotalsComp: levels of the tones and bands, overall and A-weighted overall level at every observer.

The sources deliver mean-square pressures (Pa**2); this component is the only place where they become
decibels (:mod:`bild_mdo.acoustics.bands`: ``SPL = 10 log10(p2 / p_ref**2 + floor)``, the floor giving a
silent source -100 dB with a bounded derivative).  Tones and bands are incoherent with one another, so the
overall level adds their mean-square pressures::

    oaspl     = SPL( sum_m p2_m + sum_b p2_b )
    oaspl_dba = SPL( sum_m p2_m 10**(A(f_m)/10) + sum_b p2_b 10**(A(f_b)/10) )

with ``A`` the IEC 61672-1 A-weighting, taken for each tone at its own frequency ``f_m``
(``tonal_frequency``, an input: it moves with the rotor speed) and for each one-third-octave band at its
centre frequency ``f_b`` (a constant).
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.acoustics.bands import (THIRD_OCTAVE_CENTRES, a_weighting_db, a_weighting_db_derivative, spl_db,
                                      spl_db_derivative)
from bild_mdo.utils.options import declare_size_options

_LN10_OVER_10 = np.log(10.0) / 10.0


def a_weight_factor(frequency):
    """``10**(A(f)/10)``: the factor that A-weights a mean-square pressure at frequency ``f`` (Hz)."""
    return 10.0 ** (a_weighting_db(frequency) / 10.0)


def _sum_pattern(leading, inner):
    """rows/cols of ``out[k] = sum_j x[k, j]`` for ``leading`` k and ``inner`` j (row-major flattening)."""
    return np.repeat(np.arange(leading), inner), np.arange(leading * inner)


class NoiseTotalsComp(om.ExplicitComponent):
    """Sound pressure levels of every tone and band and the overall levels (module docstring for the formulas).

    Options
    -------
    num_nodes : int
        Designs or operating points (axis 0).
    num_observers : int
        Observers per node.
    num_harmonics : int
        Blade-passage harmonics ``m = 1 ... nh``.
    band_frequencies : array_like
        Centre frequencies of the broadband bands (Hz); default the 31 one-third-octave bands
        20 Hz - 20 kHz (:data:`~bild_mdo.acoustics.bands.THIRD_OCTAVE_CENTRES`).
    include_broadband : bool
        True (default): the bands are inputs and enter the overall levels; False: tones only.

    Inputs
    ------
    tonal_pressure_squared[nn, no, nh] (Pa**2)
        Mean-square pressure of each harmonic (loading and thickness summed coherently).
    tonal_frequency[nn, nh] (Hz)
        Frequency of each harmonic, ``m B Omega / (2 pi)``.
    broadband_pressure_squared[nn, no, nb] (Pa**2)
        Mean-square pressure in each band (all mechanisms); only with ``include_broadband``.

    Outputs
    -------
    tonal_spl[nn, no, nh] (dB re 20 uPa; OpenMDAO units None)
        Level of each harmonic.
    band_spl[nn, no, nb] (dB)
        Level in each band (only with ``include_broadband``).
    oaspl[nn, no] (dB)
        Overall sound pressure level (tones and bands).
    oaspl_dba[nn, no] (dBA)
        A-weighted overall level.
    """

    def initialize(self):
        declare_size_options(self.options, radial=False)
        self.options.declare("num_observers", types=int, default=1, lower=1, desc="observers per node")
        self.options.declare("num_harmonics", types=int, default=10, lower=1, desc="blade-passage harmonics")
        self.options.declare("band_frequencies", default=THIRD_OCTAVE_CENTRES,
                             desc="centre frequencies of the broadband bands (Hz)")
        self.options.declare("include_broadband", types=bool, default=True,
                             desc="bands as inputs, in the overall levels (False: tones only)")

    def setup(self):
        nn, no, nh = self.options["num_nodes"], self.options["num_observers"], self.options["num_harmonics"]
        self.add_input("tonal_pressure_squared", val=np.zeros((nn, no, nh)), units="Pa**2",
                       desc="mean-square pressure of each harmonic (loading and thickness, coherent)")
        self.add_input("tonal_frequency", val=np.ones((nn, nh)) * 100.0, units="Hz",
                       desc="frequency of each harmonic m B Omega / (2 pi)")
        self.add_output("tonal_spl", val=np.zeros((nn, no, nh)), units=None,
                        desc="level of each harmonic, dB re 20 uPa")
        if self.options["include_broadband"]:
            nb = self._band_count()
            self.add_input("broadband_pressure_squared", val=np.zeros((nn, no, nb)), units="Pa**2",
                           desc="mean-square pressure in each band (all broadband mechanisms)")
            self.add_output("band_spl", val=np.zeros((nn, no, nb)), units=None,
                            desc="level in each band, dB re 20 uPa")
        self.add_output("oaspl", val=np.zeros((nn, no)), units=None,
                        desc="overall sound pressure level, dB re 20 uPa")
        self.add_output("oaspl_dba", val=np.zeros((nn, no)), units=None,
                        desc="A-weighted overall level, dBA re 20 uPa")

    def _band_count(self):
        centres = np.asarray(self.options["band_frequencies"], dtype=float).ravel()
        if centres.size < 1 or not np.all(np.isfinite(centres) & (centres > 0.0)):
            raise ValueError(f"{self.msginfo}: band_frequencies must be positive finite frequencies (Hz)")
        return centres.size

    def setup_partials(self):
        nn, no, nh = self.options["num_nodes"], self.options["num_observers"], self.options["num_harmonics"]
        n_tone = nn * no * nh
        self.declare_partials("tonal_spl", "tonal_pressure_squared", rows=np.arange(n_tone), cols=np.arange(n_tone))
        rows, cols = _sum_pattern(nn * no, nh)
        for out in ("oaspl", "oaspl_dba"):
            self.declare_partials(out, "tonal_pressure_squared", rows=rows, cols=cols)
        # d oaspl_dba / d f_m: observer (i, o) depends on the harmonics of its node i.
        obs, harm = np.meshgrid(np.arange(no), np.arange(nh), indexing="ij")
        node = np.arange(nn)[:, None, None]
        self.declare_partials("oaspl_dba", "tonal_frequency", rows=(node * no + obs[None]).ravel(),
                              cols=(node * nh + harm[None]).ravel())
        if self.options["include_broadband"]:
            nb = self._band_count()
            n_band = nn * no * nb
            self.declare_partials("band_spl", "broadband_pressure_squared", rows=np.arange(n_band),
                                  cols=np.arange(n_band))
            rows, cols = _sum_pattern(nn * no, nb)
            for out in ("oaspl", "oaspl_dba"):
                self.declare_partials(out, "broadband_pressure_squared", rows=rows, cols=cols)

    def _sums(self, inputs):
        """Total and A-weighted mean-square pressures per observer, and the weights of tones and bands."""
        tonal = inputs["tonal_pressure_squared"]
        tone_weight = a_weight_factor(inputs["tonal_frequency"])[:, None, :]
        total = np.sum(tonal, axis=-1)
        weighted = np.sum(tonal * tone_weight, axis=-1)
        band_weight = None
        if self.options["include_broadband"]:
            band = inputs["broadband_pressure_squared"]
            band_weight = a_weight_factor(np.asarray(self.options["band_frequencies"], dtype=float).ravel())
            total = total + np.sum(band, axis=-1)
            weighted = weighted + np.sum(band * band_weight, axis=-1)
        return total, weighted, tone_weight, band_weight

    def compute(self, inputs, outputs):
        total, weighted, _, _ = self._sums(inputs)
        outputs["tonal_spl"] = spl_db(inputs["tonal_pressure_squared"])
        if self.options["include_broadband"]:
            outputs["band_spl"] = spl_db(inputs["broadband_pressure_squared"])
        outputs["oaspl"] = spl_db(total)
        outputs["oaspl_dba"] = spl_db(weighted)

    def compute_partials(self, inputs, partials):
        total, weighted, tone_weight, band_weight = self._sums(inputs)
        tonal = inputs["tonal_pressure_squared"]
        d_total = spl_db_derivative(total)[..., None]
        d_weighted = spl_db_derivative(weighted)[..., None]
        partials["tonal_spl", "tonal_pressure_squared"] = spl_db_derivative(tonal).ravel()
        partials["oaspl", "tonal_pressure_squared"] = np.broadcast_to(d_total, tonal.shape).ravel()
        partials["oaspl_dba", "tonal_pressure_squared"] = (d_weighted * tone_weight).ravel()
        # d weight / d f = weight * ln(10)/10 * dA/df.
        dweight_df = tone_weight * _LN10_OVER_10 * a_weighting_db_derivative(inputs["tonal_frequency"])[:, None, :]
        partials["oaspl_dba", "tonal_frequency"] = (d_weighted * tonal * dweight_df).ravel()
        if self.options["include_broadband"]:
            band = inputs["broadband_pressure_squared"]
            partials["band_spl", "broadband_pressure_squared"] = spl_db_derivative(band).ravel()
            partials["oaspl", "broadband_pressure_squared"] = np.broadcast_to(d_total, band.shape).ravel()
            partials["oaspl_dba", "broadband_pressure_squared"] = (d_weighted * band_weight).ravel()
