"""ChordAtReferenceComp and the Reynolds-aware exact loading's thrust target, which solves lambda.

Sources: complex step (partials and totals), linear interpolation (a hand derivation: exact for a chord linear
in r, and the station's own chord where r_ref is a station), Re = rho W0 c / mu (the BEM convention).
"""
import numpy as np

from bild_mdo.airfoil import naca4412
from bild_mdo.bild import BILDGroup
from bild_mdo.bild.variants.reynolds_exact.chord_at_reference import ChordAtReferenceComp
from bild_mdo.utils.testing import check_component_partials, check_group_totals

NN, NR = 3, 5
RADII = np.array([np.linspace(0.3, 1.4, NR), np.linspace(0.2, 0.9, NR), np.linspace(0.4, 2.0, NR)])


def _values(chord, ref_radius):
    return dict(chord_raw=chord, radii=RADII, ref_radius=ref_radius, v_axial=[0.0, 10.0, 30.0],
                v_theta_ref=[50.0, 60.0, 70.0], rho=[1.2, 1.1, 1.0], mu=[1.8e-5, 1.75e-5, 1.7e-5])


def test_partials_and_values():
    # r_ref inside an interval, on the last interval, and beyond the first station (the end interval extended).
    chord = 0.2 - 0.05 * RADII + 0.01 * np.sin(7.0 * RADII)
    ref_radius = np.array([0.71, 0.85, 0.3])
    prob = check_component_partials(ChordAtReferenceComp(num_nodes=NN, num_radial=NR), _values(chord, ref_radius))
    linear = 0.2 - 0.05 * RADII  # a chord linear in r is interpolated exactly, also outside the stations
    prob.set_val("chord_raw", linear)
    prob.run_model()
    np.testing.assert_allclose(prob.get_val("ref_chord"), 0.2 - 0.05 * ref_radius, rtol=1e-14)
    w0 = np.hypot([0.0, 10.0, 30.0], [50.0, 60.0, 70.0])
    np.testing.assert_allclose(prob.get_val("reynolds_ref"),
                               np.array([1.2, 1.1, 1.0]) * w0 * (0.2 - 0.05 * ref_radius) / [1.8e-5, 1.75e-5, 1.7e-5],
                               rtol=1e-14)
    prob.set_val("chord_raw", chord)
    prob.set_val("ref_radius", RADII[:, 2])  # on a station: its chord
    prob.run_model()
    np.testing.assert_allclose(prob.get_val("ref_chord"), chord[:, 2], rtol=1e-15)


def test_thrust_target_totals_through_lambda():
    # BILDGroup(thrust_target=True) with the Reynolds-aware exact loading: lambda is the state of the balance,
    # ref_chord and Re_ref outputs of the design; totals on every (of, wrt) pair, both modes.
    values = dict(v_axial=[0.0, 15.0], rpm=[800.0, 900.0], thrust_target=[900.0, 700.0], altitude=[0.0, 1000.0])
    check_group_totals(lambda: BILDGroup(num_nodes=2, num_radial=6, polar=naca4412(), section_point="local",
                                         ideal_loading="exact", thrust_target=True),
                       of=["ideal_loading_constant", "ref_chord", "reynolds_ref", "torque", "chord", "twist"],
                       wrt=["thrust_target", "rpm", "radius", "v_axial", "ref_radius_ratio", "altitude"],
                       values=values, atol=1e-10, rtol=1e-6)
