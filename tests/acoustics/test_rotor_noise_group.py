"""RotorNoiseGroup and its small components: partials, totals, options and the observer checks."""
import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_no_approx_partials

from bild_mdo.acoustics.bands import THIRD_OCTAVE_CENTRES
from bild_mdo.acoustics.noise_options import check_observers
from bild_mdo.acoustics.rotor_noise_group import RotorNoiseGroup
from bild_mdo.acoustics.section_thickness import SectionThicknessComp
from bild_mdo.acoustics.station_angle import StationAngleComp
from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.airfoil.spanwise import SpanwisePolar
from bild_mdo.airfoil.thickness import ThicknessWarning
from bild_mdo.utils.testing import assert_totals_match, check_component_partials

NN, NR, NO, NH = 2, 5, 3, 4
BANDS = THIRD_OCTAVE_CENTRES[10::4]         # 100 Hz ... 16 kHz, 6 bands: a fast spectrum
OBSERVERS = np.array([[-12.0, 0.0, 3.0], [-6.0, 8.0, 0.0], [2.0, 0.0, -9.0]])


def _spanwise():
    thick, thin = AnalyticPolar(), AnalyticPolar(cl0=0.3)
    thick.thickness_ratio, thin.thickness_ratio = 0.21, 0.09
    return SpanwisePolar([thick, thin], [0.3, 0.9])


def _rotor(nn=NN, nr=NR):
    """A plausible hovering / climbing rotor (R = 0.6 m, 4000-4500 rpm), loads peaking outboard."""
    radius = np.array([0.6, 0.65])[:nn]
    x = 0.2 + (np.arange(nr) + 0.5) * 0.8 / nr
    radii = radius[:, None] * x
    load = 150.0 * x ** 2 * np.sqrt(1.0 - 0.9 * x)
    return {"rpm": np.array([4000.0, 4500.0])[:nn], "v_axial": np.array([0.0, 6.0])[:nn], "radius": radius,
            "hub_radius": 0.2 * radius, "radii": radii, "dr": np.broadcast_to(0.8 * radius[:, None] / nr, (nn, nr)),
            "chord": 0.06 - 0.02 * x + 0.0 * radii, "dthrust_dr": load * radius[:, None] / 0.6,
            "dtorque_dr": 0.12 * load * radii, "alpha": np.full((nn, nr), np.radians(5.0)) + 0.01 * x,
            "inflow_speed": 2.0 * np.pi / 60.0 * np.array([4000.0, 4500.0])[:nn, None] * radii + 3.0,
            "observer_position": np.broadcast_to(OBSERVERS, (nn, NO, 3))}


def test_section_thickness_spanwise_partials():
    """A spanwise set blends t/c in r/R: exact partials with respect to radii and radius."""
    values = _rotor()
    check_component_partials(SectionThicknessComp(num_nodes=NN, num_radial=NR, polar=_spanwise()), values,
                             atol=1e-12, rtol=1e-10)


def test_section_thickness_values():
    """t/c of the members at their stations (0.21 at r/R <= 0.3, 0.09 at r/R >= 0.9); NACA 4412 is 0.12."""
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("span", SectionThicknessComp(num_nodes=1, num_radial=3, polar=_spanwise()),
                             promotes=["*"])
    prob.model.add_subsystem("naca", SectionThicknessComp(num_nodes=1, num_radial=3),
                             promotes_outputs=[("thickness_ratio", "naca_ratio")])
    prob.setup()
    prob.set_val("radius", [1.0])
    prob.set_val("radii", [[0.2, 0.6, 0.95]])
    prob.run_model()
    # Midway (t = 0.5) the quintic smooth step is 0.5: (0.21 + 0.09) / 2 = 0.15.
    np.testing.assert_allclose(prob.get_val("thickness_ratio"), [[0.21, 0.15, 0.09]], rtol=1e-12)
    np.testing.assert_allclose(prob.get_val("naca_ratio"), 0.12, rtol=1e-12)


def test_section_thickness_default_warns_once_at_setup():
    class Unknown(AnalyticPolar):
        name = "mystery foil"
        _thickness_ratio = None

    prob = om.Problem(reports=False)
    prob.model.add_subsystem("t", SectionThicknessComp(num_nodes=1, num_radial=3, polar=Unknown()))
    with pytest.warns(ThicknessWarning, match="mystery foil"):
        prob.setup()
    prob.run_model()
    np.testing.assert_allclose(prob.get_val("t.thickness_ratio"), 0.12)


def test_station_angle_partials():
    check_component_partials(StationAngleComp(num_nodes=NN, num_radial=NR), {"alpha_star": [0.1, 0.12]})


def _group_problem(mode="fwd", **options):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("noise", RotorNoiseGroup(num_nodes=NN, num_radial=NR, num_observers=NO,
                                                      num_harmonics=NH, num_blades=3, band_frequencies=BANDS,
                                                      **options), promotes=["*"])
    prob.setup(force_alloc_complex=True, mode=mode)
    inputs = {meta["prom_name"] for meta in prob.model.get_io_metadata(iotypes="input").values()}
    for name, value in _rotor().items():
        if name in inputs:      # the sources use what they need (hub_radius: none of them)
            prob.set_val(name, value)
    prob.run_model()
    return prob


WRT = ["rpm", "v_axial", "radius", "radii", "dr", "chord", "dthrust_dr", "dtorque_dr", "alpha", "inflow_speed",
       "observer_position"]


@pytest.mark.parametrize("mode", ["fwd", "rev"])
def test_group_totals(mode):
    """Totals of the levels against complex step, every (of, wrt) pair (the sources' and totals' partials)."""
    prob = _group_problem(mode, polar=_spanwise())
    assert_no_approx_partials(prob.model)
    data = prob.check_totals(of=["oaspl", "oaspl_dba"], wrt=WRT, method="cs", out_stream=None)
    assert_totals_match(data, atol=1e-9, rtol=1e-7)


def test_levels_are_consistent_with_the_pressures():
    """oaspl is the level of the sum of the tones and bands of each observer (incoherent sum)."""
    prob = _group_problem()
    p2 = prob.get_val("tonal_pressure_squared").sum(-1) + prob.get_val("broadband_pressure_squared").sum(-1)
    np.testing.assert_allclose(prob.get_val("oaspl"), 10 * np.log10(p2 / 4e-10 + 1e-10), rtol=1e-12)
    np.testing.assert_allclose(prob.get_val("broadband_source_pressure_squared").sum(2),
                               prob.get_val("broadband_pressure_squared"), rtol=1e-12)
    assert np.all(np.isfinite(prob.get_val("oaspl_dba")))


def test_tones_only():
    """include_broadband=False: no BPM subsystem, and oaspl is the level of the tones alone."""
    prob = _group_problem(include_broadband=False)
    assert prob.model.noise._get_subsystem("broadband") is None
    with pytest.raises(KeyError):
        prob.get_val("band_spl")
    p2 = prob.get_val("tonal_pressure_squared").sum(-1)
    np.testing.assert_allclose(prob.get_val("oaspl"), 10 * np.log10(p2 / 4e-10 + 1e-10), rtol=1e-12)


def test_observers_option_sets_the_default_positions():
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("noise", RotorNoiseGroup(num_nodes=NN, num_radial=NR, num_observers=NO,
                                                      band_frequencies=BANDS, observers=OBSERVERS), promotes=["*"])
    prob.setup()
    np.testing.assert_array_equal(prob.get_val("observer_position"), np.broadcast_to(OBSERVERS, (NN, NO, 3)))
    bad = om.Problem(reports=False)
    bad.model.add_subsystem("noise", RotorNoiseGroup(num_observers=2, observers=OBSERVERS))
    with pytest.raises(ValueError, match="3 positions but num_observers is 2"):
        bad.setup()


@pytest.mark.parametrize("observers, message", [
    ([[1.0, 2.0]], "shape"), ([[np.nan, 0.0, 0.0]], "not finite"), ("far away", "numbers"),
    ([[-0.3, 0.2, 0.0]], "inside the rotor")])
def test_check_observers_refuses(observers, message):
    with pytest.raises(ValueError, match=message):
        check_observers(observers, radius=0.5)


def test_check_observers_accepts_one_position():
    np.testing.assert_array_equal(check_observers([-5.0, 0.0, 0.0], radius=0.5), [[-5.0, 0.0, 0.0]])
