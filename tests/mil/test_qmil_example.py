"""A published minimum-induced-loss design reproduced: QMIL's example propeller ``runs/test.mil``.

Source: M. Drela, QMIL 1.13 (10 Nov 2007) and QPROP 1.21, the QPROP/QMIL distribution
(web.mit.edu/drela/Public/web/qprop), as redistributed in github.com/gviolato/nemo at commit
faea3e4241e607b13e6196f3c7acec1c2036a47c, folder ``utils/QpropN`` (the run files, ``qmil.f``, ``tpdes.f`` and
the documents as distributed; some other sources there are modified):

* ``runs/test.mil``, the design input: "Test prop", 4 blades, CL0 = 0, CL_a = 6.2832 /rad, CD0 = CD2u =
  CD2l = 0 (no profile drag), design cl = 1.0 at r/R = 0, 0.5, 1 (constant), hub radius 0.05 m, tip
  radius 1.0 m, speed 1.00 m/s, 40 rpm, thrust 1.0 N, Ldes = 0 (minimum induced loss), 19 output
  stations;
* ``runs/qcon.def``, the fluid: rho = 1.225 kg/m^3, speed of sound a = 340 m/s (the ISA at sea level has
  the same rho to 1.5e-8);
* ``runs/test1``, QMIL's output for it: r (m), chord (m) and beta (deg) at 19 stations, the midpoints of
  19 equal annuli from hub to tip (``XI(I) = XI0 + DXI*(I - 0.5)`` in ``src/qmil.f``, our stations too),
  printed to 5 significant digits (chord) and 1e-4 deg (beta); its 20th line (r = R) is QMIL's tip
  extrapolation, not a design station.

QMIL designs with Prandtl's factor in the exponent form of QPROP's local formulation (wake advance ratio
``lambda_w = tan(phi_t)``; ``src/gvcalc.f``, and ``src/tpdes.f`` for QMIL's initial guess) times a root
self-induction factor: ``MILGroup(loss_form='qmil')``.  Its lift
line carries the Prandtl-Glauert factor: ``CL = (CL0 + CL_a alpha)/sqrt(1 - M^2)`` (``qprop_doc.txt``,
prop file lines 3-4, ``M = W/a``), so the angle of attack for cl = 1 is ``alpha = sqrt(1 - M^2)/CL_a``
at the station's speed W; MIL design (as A&L) takes one incompressible angle of attack, so the test adds
QMIL's compressibility to our inflow angle by hand: ``beta = phi + sqrt(1 - (W/a)^2)/CL_a``.
"""
import numpy as np
import openmdao.api as om

from bild_mdo.mil import MILGroup

#: runs/test1: r (m), chord (m), beta (deg) at the 19 design stations, verbatim.
QMIL_TEST1 = np.array([
    [0.075, 0.030374, 84.1388], [0.125, 0.055401, 75.0839], [0.175, 0.077928, 67.1405],
    [0.225, 0.094117, 60.3638], [0.275, 0.10360, 54.6651], [0.325, 0.10771, 49.8947],
    [0.375, 0.10809, 45.8951], [0.425, 0.10607, 42.5242], [0.475, 0.10258, 39.6633],
    [0.525, 0.098227, 37.2162], [0.575, 0.093349, 35.1064], [0.625, 0.088114, 33.2734],
    [0.675, 0.082558, 31.6692], [0.725, 0.076608, 30.2556], [0.775, 0.070088, 29.0020],
    [0.825, 0.062682, 27.8836], [0.875, 0.053844, 26.8805], [0.925, 0.042461, 25.9762],
    [0.975, 0.024981, 25.1572]])
LIFT_SLOPE = 6.2832  # CL_a (1/rad), CL0 = 0
SPEED_OF_SOUND = 340.0  # runs/qcon.def (m/s)


def _design(loss_form):
    prob = om.Problem(MILGroup(num_nodes=1, num_radial=19, num_blades=4, loss_form=loss_form), reports=False)
    prob.setup()
    for name, value in dict(v_axial=1.0, rpm=40.0, radius=1.0, hub_radius=0.05, altitude=0.0, design_thrust=1.0,
                            cl_star=1.0, cd_star=0.0, alpha_star=1.0 / LIFT_SLOPE).items():
        prob.set_val(name, value)  # SI units, MILGroup's own
    prob.run_model()
    return {name: prob.get_val(name)[0] for name in ("radii", "chord", "phi", "inflow_speed", "twist")}


def _last_digit(values, significant=5):
    """One unit in the last printed digit of ``values`` printed to ``significant`` digits."""
    return 10.0 ** (np.floor(np.log10(np.abs(values))) - (significant - 1))


def test_qmil_example_is_reproduced_to_its_printed_digits():
    design = _design("qmil")
    np.testing.assert_allclose(design["radii"], QMIL_TEST1[:, 0], rtol=0.0, atol=1e-12)
    # Chord: within half a unit of QMIL's last printed digit at every station (rounding), plus a tenth of one
    # unit for QMIL's single-precision iteration.
    chord_error = np.abs(design["chord"] - QMIL_TEST1[:, 1]) / _last_digit(QMIL_TEST1[:, 1])
    assert np.all(chord_error <= 0.6), np.round(chord_error, 2)
    # Blade angle: our inflow angle plus QMIL's compressible angle of attack for cl = 1 (module docstring).
    mach = design["inflow_speed"] / SPEED_OF_SOUND
    beta = np.degrees(design["phi"] + np.sqrt(1.0 - mach**2) / LIFT_SLOPE)
    np.testing.assert_allclose(beta, QMIL_TEST1[:, 2], rtol=0.0, atol=0.6e-4)
    # The incompressible twist is phi + alpha: the Prandtl-Glauert term is the whole difference at the tip.
    np.testing.assert_allclose(design["twist"], design["phi"] + 1.0 / LIFT_SLOPE, rtol=1e-14)
    assert np.degrees(design["twist"][-1]) - QMIL_TEST1[-1, 2] > 5e-4


def test_adkins_liebeck_factor_differs_from_qmil_where_the_root_factor_acts():
    # The test can fail: A&L's own factor (sin(phi_t) in the exponent, no root factor) misses QMIL's chord by
    # tens of percent at the root, where QMIL's root self-induction factor sqrt(1 + (4 lambda_w/(pi B xi))**2)
    # is largest, and by about 2 % at the tip, where F is most sensitive to its exponent.
    design = _design("adkins_liebeck")
    relative = design["chord"] / QMIL_TEST1[:, 1] - 1.0
    assert relative[0] < -0.3
    assert 0.01 < relative[-1] < 0.03
