import numpy as np
import pytest

from bild_mdo.bild.root_chord_correction import RootChordCorrectionComp
from bild_mdo.utils.testing import check_component_partials
from tests.bild.conftest import NN, NR, state


def _values(kind):
    values = state(kind)
    values["chord_raw"] = 0.05 + 0.1 * np.random.default_rng(2).random((NN, NR))
    return values


@pytest.mark.parametrize("k", [None, 3.0, 12.0])
def test_partials(kind, k):
    check_component_partials(RootChordCorrectionComp(num_nodes=NN, num_radial=NR, correction_constant=k), _values(kind))


def test_off_is_identity():
    values = _values("cruise")
    prob = check_component_partials(RootChordCorrectionComp(num_nodes=NN, num_radial=NR), values)
    np.testing.assert_array_equal(prob.get_val("chord"), values["chord_raw"])


def test_eq32_by_hand():
    # Eq. (32) on r/R: k = 10, r/R = 0.2 -> w = exp(-2); c = w c_ref + (1 - w) c_bc.
    values = dict(chord_raw=np.full((1, 2), 0.02), ref_chord=[0.2], radii=[[0.3, 1.5]], radius=[1.5])
    prob = check_component_partials(RootChordCorrectionComp(num_nodes=1, num_radial=2, correction_constant=10.0),
                           values)
    w = np.exp(-10.0 * np.array([0.2, 1.0]))
    np.testing.assert_allclose(prob.get_val("chord")[0], w * 0.2 + (1.0 - w) * 0.02, rtol=1e-14)
    # The root chord rises from 0.02 m towards c_ref; the tip is almost untouched.
    assert prob.get_val("chord")[0, 0] > 0.04 and abs(prob.get_val("chord")[0, 1] - 0.02) < 1e-5


@pytest.mark.parametrize("k", [0.0, -1.0, "10", True])
def test_invalid_constant(k):
    with pytest.raises(ValueError, match="correction_constant"):
        RootChordCorrectionComp(correction_constant=k)
