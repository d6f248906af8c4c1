"""TonalNoiseComp: complex-step partials (hover and axial flight), shapes, frequencies and the summed total."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.acoustics.hanson import AREA_COEFFICIENT
from bild_mdo.acoustics.tonal_noise import TonalNoiseComp
from bild_mdo.utils.testing import check_component_partials

NN, NR, NO, NH, B = 2, 3, 2, 3, 3


def _values(seed=0, v_axial=(0.0, 25.0)):
    """Seeded, non-singular inputs: two designs (hover and climb), observers off the axis and the disc."""
    rng = np.random.default_rng(seed)
    radius = np.array([0.6, 0.9])
    fractions = np.sort(rng.uniform(0.3, 0.95, size=(NN, NR)), axis=1)
    observers = np.array([[[-8.0, 5.0, 2.0], [6.0, 4.0, -3.0]], [[-3.0, -7.0, 1.5], [2.0, 9.0, 4.0]]])
    return {"radii": fractions * radius[:, None], "dr": rng.uniform(0.05, 0.1, size=(NN, NR)),
            "chord": rng.uniform(0.05, 0.1, size=(NN, NR)), "thickness_ratio": rng.uniform(0.08, 0.15, (NN, NR)),
            "dthrust_dr": rng.uniform(50.0, 300.0, size=(NN, NR)), "dtorque_dr": rng.uniform(5.0, 30.0, (NN, NR)),
            "rpm": np.array([3000.0, 2200.0]), "v_axial": np.array(v_axial), "rho": np.array([1.225, 1.1]),
            "speed_of_sound": np.array([340.3, 336.0]), "observer_position": observers}


def _comp():
    return TonalNoiseComp(num_nodes=NN, num_radial=NR, num_observers=NO, num_harmonics=NH, num_blades=B)


@pytest.mark.filterwarnings("ignore:(?s).*zero derivatives")
@pytest.mark.parametrize("v_axial", [(0.0, 25.0), (0.0, 0.0)], ids=["hover+climb", "hover"])
def test_partials_complex_step(v_axial):
    check_component_partials(_comp(), _values(v_axial=v_axial), atol=1e-10, rtol=1e-8)


def _run(values, **options):
    kw = dict(num_nodes=NN, num_radial=NR, num_observers=NO, num_harmonics=NH, num_blades=B)
    kw.update(options)
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("tonal", TonalNoiseComp(**kw), promotes=["*"])
    prob.setup()
    for name, val in values.items():
        prob.set_val(name, val)
    prob.run_model()
    return prob


def test_shapes_frequency_and_total():
    """tonal = loading + thickness (compact limit: the two are in quadrature); f_m = m B Omega / (2 pi)."""
    values = _values()
    prob = _run(values)
    g = prob.get_val
    for name in ("loading_pressure_squared", "thickness_pressure_squared", "tonal_pressure_squared"):
        assert g(name).shape == (NN, NO, NH) and np.all(g(name) > 0.0)
    np.testing.assert_allclose(g("tonal_pressure_squared"),
                               g("loading_pressure_squared") + g("thickness_pressure_squared"), rtol=1e-14)
    expected = np.arange(1, NH + 1)[None, :] * B * values["rpm"][:, None] / 60.0
    np.testing.assert_allclose(g("tonal_frequency"), expected, rtol=1e-14)


def test_units_and_area_coefficient():
    """Thickness noise scales with the square of the section area coefficient; loading does not see it."""
    values = _values()
    base, half = _run(values), _run(values, area_coefficient=0.5 * AREA_COEFFICIENT)
    np.testing.assert_allclose(half.get_val("thickness_pressure_squared"),
                               0.25 * base.get_val("thickness_pressure_squared"), rtol=1e-12)
    np.testing.assert_allclose(half.get_val("loading_pressure_squared"), base.get_val("loading_pressure_squared"),
                               rtol=1e-15)
