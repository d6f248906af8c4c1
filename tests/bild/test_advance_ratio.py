import numpy as np

from bild_mdo.bild.advance_ratio import AdvanceRatioComp
from bild_mdo.utils.testing import check_component_partials
from tests.bild.conftest import NN, state


def test_partials_and_values(kind):
    values = state(kind)
    values["advance_ratio"] = np.array([0.0, 0.5, 1.0]) if kind == "hover" else np.array([0.3, 1.5, 3.0])
    prob = check_component_partials(AdvanceRatioComp(num_nodes=NN), values)
    # Table 2: J = V_x / (n D), n in rev/s, D = 2R.
    expected = values["advance_ratio"] * values["rpm"] / 60.0 * 2.0 * values["radius"]
    np.testing.assert_allclose(prob.get_val("v_axial", units="m/s"), expected, rtol=1e-14)


def test_paper_case():
    # Sec. 5.2: R = 1.5 m, 800 rpm; J = 1 -> V_x = (800/60) * 3 m = 40 m/s.
    prob = check_component_partials(AdvanceRatioComp(num_nodes=1),
                           dict(advance_ratio=[1.0], rpm=[800.0], radius=[1.5]))
    assert abs(prob.get_val("v_axial")[0] - 40.0) < 1e-12
