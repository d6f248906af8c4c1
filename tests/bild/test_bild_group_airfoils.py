"""BILDGroup with a Mach-dependent polar and with several airfoils along the span (Assumption 2 per station)."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.airfoil.analytic import AnalyticPolar
from bild_mdo.airfoil.compressibility import CompressiblePolar
from bild_mdo.airfoil.spanwise import SpanwisePolar
from bild_mdo.atmosphere import isa
from bild_mdo.bild import BILDGroup
from bild_mdo.constants import angular_velocity
from bild_mdo.utils.testing import check_group_totals
from tests.bild.test_bild_group import NR_REF, OPERATING, REF_STATION

TIP = AnalyticPolar(reynolds_exponent=0.2)
# A thicker root section: more zero-lift drag, less camber, lower maximum L/D.
ROOT = AnalyticPolar(cl0=0.25, cd0=0.012, k=0.012, cl_cd_min=0.3, reynolds_exponent=0.15)
SPANWISE = SpanwisePolar([ROOT, TIP], [0.3, 0.8])
COMPRESSIBLE = CompressiblePolar(TIP, correction="karman-tsien")
SPANWISE_MACH = SpanwisePolar([CompressiblePolar(ROOT), COMPRESSIBLE], [0.3, 0.8])
# Tip Mach numbers 0.55-0.67 (R = 1.5 m): compressibility matters, below the corrections' 0.7 warning.
SETTINGS = dict(ref_chord=[0.1, 0.2, 0.3], rpm=[1200.0, 1300.0, 1400.0], altitude=[0.0, 1000.0, 2500.0])
OF = ["thrust", "torque", "efficiency", "chord", "twist", "mach", "tip_mach"]
WRT = ["v_axial", "rpm", "radius", "ref_chord", "ref_radius_ratio", "hub_radius_ratio", "altitude"]


def _values(kind):
    return dict(OPERATING[kind], **SETTINGS)


def _run(kind, polar, num_radial=NR_REF):
    prob = om.Problem(BILDGroup(num_nodes=3, num_radial=num_radial, polar=polar), reports=False)
    prob.setup()
    for name, value in _values(kind).items():
        prob.set_val(name, value)
    prob.run_model()
    return prob


def test_two_identical_airfoils_reproduce_the_single_airfoil_design(kind):
    # A blend of a polar with itself is that polar at every r/R, so the per-station points all equal the
    # reference point and the spanwise chain must give the one-airfoil design to round-off.
    single = _run(kind, TIP)
    blended = _run(kind, SpanwisePolar([TIP, TIP], [0.3, 0.8]))
    for name in ("thrust", "torque", "chord", "twist", "eta2", "u_axial"):
        np.testing.assert_allclose(blended.get_val(name), single.get_val(name), rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(blended.get_val("cl_star"),
                               np.repeat(single.get_val("cl_star")[:, None], NR_REF, axis=1), rtol=1e-13)


@pytest.mark.parametrize("polar", [SPANWISE, SPANWISE_MACH], ids=["spanwise", "spanwise_mach"])
def test_chord_at_reference_radius_is_reference_chord_with_two_airfoils(kind, polar):
    # Algorithm 1's invariant holds per station: at r_ref the station's airfoil is the reference station's.
    prob = _run(kind, polar)
    np.testing.assert_allclose(prob.get_val("radii")[:, REF_STATION] / prob.get_val("radius"), 0.5, rtol=1e-14)
    np.testing.assert_allclose(prob.get_val("chord")[:, REF_STATION], SETTINGS["ref_chord"], rtol=1e-9)
    np.testing.assert_allclose(prob.get_val("cl_star")[:, REF_STATION], prob.get_val("cl_star_ref"), rtol=1e-13)
    # The root airfoil's lower L/D shows inboard: C_l*/C_d* rises from root to tip.
    ratio = prob.get_val("cl_star") / prob.get_val("cd_star")
    assert np.all(np.diff(ratio, axis=1) >= -1e-12) and np.all(ratio[:, -1] > 1.2 * ratio[:, 0])


@pytest.mark.parametrize("kind, polar", [("cruise", SPANWISE), ("cruise", COMPRESSIBLE), ("hover", SPANWISE_MACH)],
                         ids=["cruise_spanwise", "cruise_mach", "hover_spanwise_mach"])
def test_totals_complex_step(kind, polar):
    check_group_totals(lambda: BILDGroup(num_nodes=3, num_radial=NR_REF, polar=polar), of=OF, wrt=WRT,
                       values=_values(kind), atol=1e-10, rtol=1e-6)


def test_totals_complex_step_exact_loading_with_an_airfoil_per_station(kind):
    # The exact ideal loading with each station's own airfoil point (ExactEta2Comp(varies_along_span=True)) in
    # the group (the local section point with the exact loading has its own station component).
    check_group_totals(lambda: BILDGroup(num_nodes=3, num_radial=NR_REF, polar=SPANWISE, ideal_loading="exact"),
                       of=OF, wrt=WRT, values=_values(kind), atol=1e-10, rtol=1e-6)


def test_mach_outputs(kind):
    # M = W / a per station; M_tip = sqrt(V_x^2 + (Omega R)^2) / a; M_ref = sqrt(V_x^2 + (Omega r_ref)^2) / a.
    prob = _run(kind, COMPRESSIBLE)
    a = isa(np.array(SETTINGS["altitude"])).speed_of_sound
    v_x = np.array(OPERATING[kind]["v_axial"])
    omega = angular_velocity(np.array(SETTINGS["rpm"]))
    radius = prob.get_val("radius")
    np.testing.assert_allclose(prob.get_val("mach"), prob.get_val("inflow_speed") / a[:, None], rtol=1e-14)
    np.testing.assert_allclose(prob.get_val("tip_mach"), np.hypot(v_x, omega * radius) / a, rtol=1e-14)
    np.testing.assert_allclose(prob.get_val("mach_ref"), np.hypot(v_x, omega * 0.5 * radius) / a, rtol=1e-14)
    # The airfoil point is taken at M_ref (Karman-Tsien raises C_l* over the incompressible section's).
    assert np.all(prob.get_val("cl_star") > _run(kind, TIP).get_val("cl_star"))
