"""Fuzzing the Python API's argument checks: any value either works (finite results) or gives one ValueError line.

design_rotor and analyze_rotor take random values for one argument at a time (strings, booleans, None,
non-finite, negative, nested or mixed lists); the property: a ValueError (or om.AnalysisError) with a
one-line message (an AnalysisError of an infeasible batch may list designs on further lines), or a result
whose per-design values are all finite.
"""
import os

import numpy as np
import openmdao.api as om
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.bem.analyze import analyze_rotor
from bild_mdo.results.design import design_rotor
from bild_mdo.results.off_design import off_design_sweep

# NumPy's overflow warnings at 1e300-sized inputs come from the BEM and BILD kernels; what is asserted here is
# the outcome (a clean error or finite values).
pytestmark = pytest.mark.filterwarnings("ignore::RuntimeWarning")

SCALE = int(os.environ.get("BILD_MDO_FUZZ_SCALE", "1"))
FUZZ = settings(max_examples=40 * SCALE, deadline=None, database=None, suppress_health_check=[HealthCheck.too_slow])

ODD = st.one_of(
    st.sampled_from(["1.5", "", "abc", True, False, None, float("nan"), float("inf"), -float("inf"), -1.0, 0.0,
                     1e300, 1e-300, 1j, [], [[]], [1.0, "2"], [1.0, True], [[1.0, 2.0]], {"a": 1}, (1.0, 2.0),
                     np.array([1.0, np.nan]), np.array(["1"]), np.bool_(True), 2**70]),
    st.floats(allow_nan=True, allow_infinity=True),
    st.lists(st.floats(min_value=-10, max_value=10), min_size=0, max_size=3),
    st.integers(min_value=-3, max_value=5),
)
DESIGN_ARGS = ["v_axial", "advance_ratio", "rpm", "radius", "hub_radius_ratio", "ref_radius_ratio", "ref_chord",
               "altitude", "num_blades", "airfoil", "num_radial", "loss_model", "chord_form", "root_chord_correction",
               "thrust"]
SWEEP_ARGS = ["design", "collective_pitch", "advance_ratios", "rpm", "altitude", "polar"]
ANALYZE_ARGS = ["chord", "twist", "radius", "hub_radius", "rpm", "v_axial", "num_blades", "altitude", "loss_model",
                "radii"]


def _expect_clean(call):
    try:
        result = call()
    except ValueError as err:
        assert "\n" not in str(err).strip(), str(err)
        return None
    except om.AnalysisError:
        return None
    return result


@FUZZ
@given(name=st.sampled_from(DESIGN_ARGS), value=ODD)
def test_design_rotor_arguments(name, value):
    kwargs = {"airfoil": "analytic", "num_radial": 5, name: value}
    if name == "thrust":
        kwargs["ref_chord"] = None
    if name == "num_radial" and isinstance(value, int) and value > 50:
        return
    result = _expect_clean(lambda: design_rotor(**kwargs))
    if result is not None:
        for field in ("thrust", "torque", "power", "chord", "twist"):
            assert np.all(np.isfinite(getattr(result, field))), (name, value, field)


@FUZZ
@given(name=st.sampled_from(ANALYZE_ARGS), value=ODD)
def test_analyze_rotor_arguments(name, value):
    args = dict(chord=[0.1, 0.09, 0.07, 0.05], twist=np.radians([25.0, 18.0, 14.0, 11.0]), radius=1.0,
                hub_radius=0.2, rpm=1000.0, v_axial=5.0, num_blades=2)
    args[name] = value
    result = _expect_clean(lambda: analyze_rotor(**{k: v for k, v in args.items() if k in (
        "chord", "twist", "radius", "hub_radius", "rpm", "v_axial", "num_blades")}, polar=AnalyticPolar(),
        **{k: v for k, v in args.items() if k in ("altitude", "loss_model", "radii")}, on_invalid="ignore"))
    if result is not None:
        for field in ("thrust", "torque", "power"):
            assert np.all(np.isfinite(getattr(result, field))), (name, value, field)


@pytest.fixture(scope="module")
def batch():
    return design_rotor(advance_ratio=[0.5, 1.0], airfoil="analytic", num_radial=5)


@FUZZ
@given(name=st.sampled_from(SWEEP_ARGS), value=ODD)
def test_off_design_sweep_arguments(batch, name, value):
    kwargs = {"design": 1, "advance_ratios": [0.5, 1.0], name: value}
    result = _expect_clean(lambda: off_design_sweep(batch, **kwargs))
    if result is not None:
        # Failed points are NaN by documentation (result.status says why); the others are finite.
        assert np.all(np.isfinite(result.thrust[result.ok])), (name, value)
