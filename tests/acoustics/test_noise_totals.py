"""NoiseTotalsComp: levels, overall levels, A-weighting, the dB floor, and complex-step partials."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.acoustics.bands import REFERENCE_PRESSURE, THIRD_OCTAVE_CENTRES, pressure_squared_from_spl
from bild_mdo.acoustics.noise_totals import NoiseTotalsComp, a_weight_factor
from bild_mdo.utils.testing import check_component_partials

NN, NO, NH = 3, 2, 4
BANDS = THIRD_OCTAVE_CENTRES[2::3]         # 10 bands, 31.5 Hz ... 16 kHz
NB = BANDS.size


def _values(seed=0):
    rng = np.random.default_rng(seed)
    return {"tonal_pressure_squared": rng.uniform(1e-4, 1.0, (NN, NO, NH)),
            "tonal_frequency": rng.uniform(50.0, 400.0, (NN, 1)) * np.arange(1, NH + 1),
            "broadband_pressure_squared": rng.uniform(1e-6, 1e-2, (NN, NO, NB))}


def _run(values, **options):
    prob = om.Problem(reports=False)
    comp = NoiseTotalsComp(num_nodes=NN, num_observers=NO, num_harmonics=NH, band_frequencies=BANDS, **options)
    prob.model.add_subsystem("totals", comp, promotes=["*"])
    prob.setup(force_alloc_complex=True)
    for name, value in values.items():
        if name in comp._var_rel_names["input"]:
            prob.set_val(name, value)
    prob.run_model()
    return prob


@pytest.mark.parametrize("include_broadband", [True, False])
def test_partials(include_broadband):
    comp = NoiseTotalsComp(num_nodes=NN, num_observers=NO, num_harmonics=NH, band_frequencies=BANDS,
                           include_broadband=include_broadband)
    values = _values()
    if not include_broadband:
        values.pop("broadband_pressure_squared")
    check_component_partials(comp, values, atol=1e-10, rtol=1e-9)


def test_partials_of_a_silent_source_are_finite():
    """Silent tones and bands (p2 = 0): -100 dB by the floor of bands.py, with finite derivatives."""
    values = {k: (np.zeros_like(v) if "pressure" in k else v) for k, v in _values().items()}
    prob = check_component_partials(NoiseTotalsComp(num_nodes=NN, num_observers=NO, num_harmonics=NH,
                                                    band_frequencies=BANDS), values, atol=1e-6, rtol=1e-9)
    for name in ("tonal_spl", "band_spl", "oaspl", "oaspl_dba"):
        np.testing.assert_allclose(prob.get_val(name), -100.0, atol=1e-9)
    jac = prob.compute_totals(of=["oaspl_dba"], wrt=["tonal_pressure_squared"])
    assert np.all(np.isfinite(jac["oaspl_dba", "tonal_pressure_squared"]))


def test_levels_of_known_pressures():
    """Hand derivation: p_rms = 1 Pa is 20 log10(1 / 20e-6) = 93.9794 dB; 2 Pa**2 is 3.0103 dB more."""
    values = _values()
    values["tonal_pressure_squared"][:] = 1.0
    values["tonal_pressure_squared"][:, :, 1] = 2.0
    prob = _run(values)
    np.testing.assert_allclose(prob.get_val("tonal_spl")[..., 0], 93.9794, atol=1e-4)
    np.testing.assert_allclose(prob.get_val("tonal_spl")[..., 1], 93.9794 + 3.0103, atol=1e-4)


def test_two_equal_incoherent_sources_add_3_dB():
    """Hand derivation: two equal incoherent sources, 10 log10(2) = 3.0103 dB above one of them."""
    tonal = np.zeros((NN, NO, NH))
    tonal[..., 0] = 0.5
    one = _run({"tonal_pressure_squared": tonal}, include_broadband=False).get_val("oaspl")
    tonal[..., 2] = 0.5
    two = _run({"tonal_pressure_squared": tonal}, include_broadband=False).get_val("oaspl")
    np.testing.assert_allclose(two - one, 3.0103, atol=1e-4)


def test_overall_levels_sum_tones_and_bands():
    """oaspl is the level of the sum of every tone and band; oaspl_dba weights each by 10**(A(f)/10)."""
    values = _values(1)
    prob = _run(values)
    p2 = values["tonal_pressure_squared"].sum(-1) + values["broadband_pressure_squared"].sum(-1)
    np.testing.assert_allclose(prob.get_val("oaspl"), 10 * np.log10(p2 / REFERENCE_PRESSURE ** 2), rtol=1e-12)
    weighted = (values["tonal_pressure_squared"] * a_weight_factor(values["tonal_frequency"])[:, None]).sum(-1)
    weighted += (values["broadband_pressure_squared"] * a_weight_factor(BANDS)).sum(-1)
    np.testing.assert_allclose(prob.get_val("oaspl_dba"), 10 * np.log10(weighted / REFERENCE_PRESSURE ** 2),
                               rtol=1e-12)


# IEC 61672-1:2013 Table 3, A-weighting at the nominal frequencies (exact base-ten frequencies), to 0.1 dB.
IEC_TABLE = {-20: -70.4, -15: -39.4, -12: -26.2, -10: -19.1, -9: -16.1, -6: -8.6, -3: -3.2, 0: 0.0,
             3: 1.2, 6: 1.0, 9: -1.1, 12: -6.6}


@pytest.mark.parametrize("band_number, expected", sorted(IEC_TABLE.items()))
def test_a_weighted_level_of_one_tone_follows_iec_61672(band_number, expected):
    """One tone of 94 dB at f: oaspl_dba - oaspl = A(f), IEC 61672-1 Table 3 (0 dB at 1 kHz)."""
    frequency = 1000.0 * 10.0 ** (band_number / 10.0)
    tonal = np.zeros((NN, NO, NH))
    tonal[..., 0] = pressure_squared_from_spl(94.0)
    prob = _run({"tonal_pressure_squared": tonal, "tonal_frequency": np.full((NN, NH), frequency)},
                include_broadband=False)
    np.testing.assert_allclose(prob.get_val("oaspl"), 94.0, atol=1e-9)
    np.testing.assert_allclose(prob.get_val("oaspl_dba") - prob.get_val("oaspl"), expected, atol=0.051)


def test_a_weighted_band_at_its_centre():
    """A band of 94 dB at the 1-kHz centre reads 94 dBA (A(1 kHz) = 0, IEC 61672-1); at 125 Hz 94 - 16.1."""
    band = np.zeros((NN, NO, NB))
    k1000 = int(np.argmin(np.abs(BANDS - 1000.0)))
    band[..., k1000] = pressure_squared_from_spl(94.0)
    prob = _run({"tonal_pressure_squared": np.zeros((NN, NO, NH)), "broadband_pressure_squared": band})
    # IEC 61672-1 normalises with A1000 = -2.000 dB (rounded), so A(1 kHz) is 0 to within 0.001 dB.
    np.testing.assert_allclose(prob.get_val("oaspl_dba"), 94.0, atol=1e-3)
    np.testing.assert_allclose(prob.get_val("band_spl")[..., k1000], 94.0, atol=1e-6)
    band[:] = 0.0
    band[..., int(np.argmin(np.abs(BANDS - 125.0)))] = pressure_squared_from_spl(94.0)
    prob = _run({"tonal_pressure_squared": np.zeros((NN, NO, NH)), "broadband_pressure_squared": band})
    np.testing.assert_allclose(prob.get_val("oaspl_dba"), 94.0 - 16.1, atol=0.051)


def test_bad_band_frequencies():
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("t", NoiseTotalsComp(band_frequencies=[100.0, -1.0]))
    with pytest.raises(ValueError, match="band_frequencies"):
        prob.setup()
