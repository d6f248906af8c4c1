"""DisplacementVelocityComp: partials, the solved zeta meets its target, an unreachable target is rejected."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.mil.displacement_velocity import DisplacementVelocityComp
from bild_mdo.mil.kernel import LOSS_FORMS
from bild_mdo.mil.performance import MILPerformanceComp
from bild_mdo.utils.testing import check_component_partials

from .conftest import NN, NR, station_values


@pytest.mark.parametrize("loss_form", LOSS_FORMS)
@pytest.mark.parametrize("design_for, target", [("thrust", "design_thrust"), ("power", "design_power")])
def test_displacement_velocity_partials_and_solve(design_for, target, loss_form):
    values = station_values(3)
    values[target] = np.array([800.0, 1500.0, 300.0]) * (1.0 if design_for == "thrust" else 40.0)
    comp = DisplacementVelocityComp(num_nodes=NN, num_radial=NR, num_blades=2, design_for=design_for,
                                    loss_form=loss_form)
    prob = check_component_partials(comp, values)
    # The solved zeta reproduces the target through the performance integrals (A&L's two forms).
    perf = om.Problem(reports=False)
    perf.model.add_subsystem("comp", MILPerformanceComp(num_nodes=NN, num_radial=NR, num_blades=2,
                                                        loss_form=loss_form), promotes=["*"])
    perf.setup()
    for name, value in values.items():
        if name in ("alpha_star", target):
            continue
        perf.set_val(name, value)
    perf.set_val("zeta", prob.get_val("zeta"))
    perf.run_model()
    np.testing.assert_allclose(perf.get_val(design_for), values[target], rtol=1e-10)


def test_displacement_velocity_unreachable_target():
    values = station_values(4)
    values["design_thrust"] = np.array([1e3, 1e9, 1e3])
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("comp", DisplacementVelocityComp(num_nodes=NN, num_radial=NR), promotes=["*"])
    prob.setup()
    for name in ("speed_ratio", "radius_fraction", "width_fraction", "cl_star", "cd_star", "rho", "v_axial",
                 "radius", "design_thrust"):
        prob.set_val(name, values[name])
    with pytest.raises(om.AnalysisError, match="node 1: the thrust target"):
        prob.run_model()
