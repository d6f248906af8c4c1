"""The Ideally Twisted Rotor in hover: first blade-passing tone against Fig. 21a of Pettingill et al. (AIAA 2021-1928).

Fig. 21a (digitized in AcousticAnalogies.jl's test data, copied to data/itr/) is read as the directivity
of the predicted loading and thickness noise of the first blade-passing harmonic (BPF = 364 Hz) on the
microphone arc, SPL against the elevation angle from the rotor plane (-45 ... +45 deg, positive above
the plane): the loading curve is louder below the plane than above it, the thickness curve symmetric
about it, as the physics of a lifting rotor says.  The case (geometry, 5465 rpm, 2.27 m, standard day)
and the loads from bild-mdo's BEM are those of :mod:`tests.acoustics.itr_case`.

Measured differences (this model minus the figure, dB, at the 32 / 33 digitized points):

* thickness: -2.39 ... -2.65 (mean -2.48) at every elevation: the shape agrees to 0.3 dB, the level is
  2.5 dB lower; the case's inputs that set the level (section area, distance, rpm) are as published,
  so the offset is left as it is and stated, not tuned away;
* loading at and below the plane (elevation <= +15 deg): -0.92 ... -1.73 (mean -1.08); peak at -14 deg
  (43.1 dB) where the figure peaks at -14 ... -19 deg (44.1 dB);
* loading above the plane (> +15 deg): -2.2 at +17.6 deg growing to -36 dB near +39 deg.  The compact
  model cancels the thrust term against the torque term where ``T cos(theta) = Q c0 / (Omega r**2)``
  (a null near +39 deg for the ITR's loads); the paper's prediction keeps the chordwise extent of the
  loading and does not cancel as deeply.  There only the ordering is asserted (the model is not louder).
"""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.acoustics.bands import spl_db
from bild_mdo.acoustics.tonal_noise import TonalNoiseComp
from tests.acoustics.itr_case import NUM_RADIAL, itr_stations, observer_positions, read_figure

_INPUTS = ("radii", "dr", "chord", "thickness_ratio", "dthrust_dr", "dtorque_dr", "rpm", "v_axial", "rho",
           "speed_of_sound")


def _bpf_spl(elevation_deg, output):
    """SPL (dB re 20 uPa) of the first blade-passing harmonic at the elevations, from TonalNoiseComp."""
    case = itr_stations()
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("tonal", TonalNoiseComp(num_nodes=1, num_radial=NUM_RADIAL,
                                                     num_observers=len(elevation_deg), num_harmonics=2,
                                                     num_blades=case["num_blades"]), promotes=["*"])
    prob.setup()
    for name in _INPUTS:
        prob.set_val(name, case[name])
    prob.set_val("observer_position", observer_positions(elevation_deg)[None])
    prob.run_model()
    return spl_db(prob.get_val(output))[0, :, 0], prob.get_val("tonal_frequency")[0, 0]


def test_itr_case_is_the_published_rotor():
    """Table 1 of the paper: 4 blades, R = 0.1588 m, c = 0.2 R; the BEM thrust is positive and C_T plausible."""
    case = itr_stations()
    assert case["num_blades"] == 4 and case["radius"][0] == pytest.approx(0.1588)
    np.testing.assert_allclose(case["chord"], 0.2 * 0.1588)
    tip_speed = case["rpm"][0] * np.pi / 30.0 * case["radius"][0]
    thrust_coefficient = case["thrust"][0] / (case["rho"][0] * np.pi * case["radius"][0] ** 2 * tip_speed ** 2)
    assert 0.005 < thrust_coefficient < 0.02
    np.testing.assert_allclose(np.sum(case["dthrust_dr"] * case["dr"]), case["thrust"][0], rtol=1e-12)


def test_figure21a_thickness_noise():
    """Fig. 21a thickness: within 3 dB everywhere (measured -2.39 ... -2.65 dB), shape within 0.3 dB."""
    spl_figure, elevation = read_figure("figure21a-thickness")
    spl, frequency = _bpf_spl(elevation, "thickness_pressure_squared")
    np.testing.assert_allclose(frequency, 4 * 5465.0 / 60.0, rtol=1e-14)
    error = spl - spl_figure
    assert np.max(np.abs(error)) < 3.0
    assert np.ptp(error) < 0.3


def test_figure21a_loading_noise():
    """Fig. 21a loading: within 2 dB at and below the plane (measured -0.92 ... -1.73 dB), same peak angle."""
    spl_figure, elevation = read_figure("figure21a-loading")
    spl, _ = _bpf_spl(elevation, "loading_pressure_squared")
    error = spl - spl_figure
    near = elevation <= 15.0
    assert np.max(np.abs(error[near])) < 2.0
    assert abs(elevation[np.argmax(spl)] - elevation[np.argmax(spl_figure)]) <= 5.0
    # Above the plane: the compact model's thrust-torque cancellation (see the module docstring).
    assert np.all(error[~near] < 0.0)
