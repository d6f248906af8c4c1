"""Compact Hanson tonal noise: Gutin's closed form, the physical limits and an independent time-domain solution.

Sources named per test: a hand derivation of Gutin's formula (L. Gutin 1936, NACA TM 1195), the limits
of the model (no thickness without thickness, silence on the axis, spherical spreading, the flight
Mach number -> 0), and the exact retarded-time (Lienard-Wiechert) field of moving point forces and
volumes, sampled in time and Fourier analysed, for axial flight.
"""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.acoustics.hanson import AREA_COEFFICIENT, bessel_j, bessel_j_derivative, retarded_geometry
from bild_mdo.acoustics.tonal_noise import TonalNoiseComp

C0, RHO0 = 340.0, 1.2


def _tonal(stations, rpm, v_axial, observers, num_blades, num_harmonics=4):
    """Run TonalNoiseComp on one design; ``stations`` maps station inputs to 1-d arrays."""
    nr, no = len(stations["radii"]), len(observers)
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("tonal", TonalNoiseComp(num_nodes=1, num_radial=nr, num_observers=no,
                                                     num_harmonics=num_harmonics, num_blades=num_blades),
                             promotes=["*"])
    prob.setup()
    for name, val in stations.items():
        prob.set_val(name, np.reshape(val, (1, nr)))
    for name, val in (("rpm", rpm), ("v_axial", v_axial), ("rho", RHO0), ("speed_of_sound", C0)):
        prob.set_val(name, [val])
    prob.set_val("observer_position", np.reshape(observers, (1, no, 3)))
    prob.run_model()
    return {name: prob.get_val(name)[0] for name in ("loading_pressure_squared", "thickness_pressure_squared",
                                                     "tonal_pressure_squared", "tonal_frequency")}


def _ring(r_e=0.4, thrust=80.0, torque=4.0, width=0.02, chord=0.05, thickness_ratio=0.12):
    """One station of width ``width`` carrying thrust ``thrust`` (N) and torque ``torque`` (N m) in total."""
    return {"radii": [r_e], "dr": [width], "chord": [chord], "thickness_ratio": [thickness_ratio],
            "dthrust_dr": [thrust / width], "dtorque_dr": [torque / width]}


def _on_arc(distance, theta_deg, azimuth_deg=30.0):
    theta, phi = np.deg2rad(np.asarray(theta_deg, dtype=float)), np.deg2rad(azimuth_deg)
    return np.stack([distance * np.cos(theta), distance * np.sin(theta) * np.cos(phi),
                     distance * np.sin(theta) * np.sin(phi)], axis=-1)


def test_gutin_closed_form_single_station():
    r"""Gutin's loading noise of a thin annulus in hover, derived by hand, against TonalNoiseComp to 1e-10.

    Derivation.  B blades turn about +x at Omega; each carries, at radius r_e, the force on the fluid
    f = -(T/B) e_x + (Q/(B r_e)) e_psi (the reaction to thrust along +x and to the drag torque).  The far
    field of a point force, p = -div[F G], G = exp(ikR)/(4 pi R), R ~ r - n.y, has the harmonic
    n = m B of a blade (period 2 pi/Omega; psi = Omega tau - psi_o):
        p_n = -(i k / (4 pi r)) exp(ikr) (1/2pi) int (n.f) exp(i n psi - i z cos psi) dpsi,
    z = k r_e sin(theta), with n.f = -(T/B) cos(theta) - (Q/(B r_e)) sin(theta) sin(psi).  Jacobi-Anger gives
    (1/2pi) int exp(i n psi - i z cos psi) dpsi = (-i)^n J_n(z) and, with sin psi = (e^{i psi} - e^{-i psi})/2i
    and J_{n-1} + J_{n+1} = 2n J_n / z, (1/2pi) int sin(psi) exp(...) dpsi = -(-i)^n (n/z) J_n(z).
    So p_n = (i k/(4 pi r)) exp(ikr) (-i)^n J_n(z) (T cos(theta) - Q n/(z r_e) sin(theta)) / B per blade;
    the B blades multiply by B, and n sin(theta)/(z r_e) = c0 / (Omega r_e**2).  The real tone
    2 Re(p_n e^{-i n Omega t}) has the mean square 2 |p_n|**2:
        p_rms = (m B Omega / (2 sqrt(2) pi c0 r)) |T cos(theta) - Q c0 / (Omega r_e**2)|
                * |J_mB(m B Omega r_e sin(theta) / c0)|.
    theta is measured from +x (the thrust direction): behind the disc the two terms add.
    """
    thrust, torque, r_e, num_blades, rpm, distance = 80.0, 4.0, 0.4, 3, 3000.0, 25.0
    theta = np.array([20.0, 60.0, 95.0, 120.0, 165.0])
    out = _tonal(_ring(r_e, thrust, torque), rpm, 0.0, _on_arc(distance, theta), num_blades)
    omega = rpm * np.pi / 30.0
    m = np.arange(1, 5)[None, :]
    n = m * num_blades
    th = np.deg2rad(theta)[:, None]
    p_rms = (n * omega / (2.0 * np.sqrt(2.0) * np.pi * C0 * distance)
             * np.abs(thrust * np.cos(th) - torque * C0 / (omega * r_e ** 2))
             * np.abs(bessel_j(n, n * omega * r_e * np.sin(th) / C0)))
    np.testing.assert_allclose(out["loading_pressure_squared"], p_rms ** 2, rtol=1e-10)
    np.testing.assert_allclose(out["tonal_frequency"], n[0] * omega / (2.0 * np.pi), rtol=1e-14)


def test_deming_thickness_single_station():
    r"""Deming's thickness noise of the same annulus (hand derivation as for Gutin, for a point volume).

    A blade section of area A = kappa (t/c) c**2 over the width dr displaces the volume V = A dr; its field is
    p = rho0 d^2/dt^2 [V G] (FW-H thickness source rho0 d^2 H / dt^2 of a compact body).  The harmonic n = m B
    of B blades: p_n = -rho0 B (n Omega)^2 V exp(ikr) (-i)^n J_n(z) / (4 pi r), so
        p_rms = rho0 B (m B Omega)^2 V |J_mB(m B Omega r_e sin(theta)/c0)| / (2 sqrt(2) pi r),
    i.e. the mean square 2 |p_n|**2 = (rho0 B (n Omega)^2 V J_n)^2 / (8 pi^2 r^2).
    """
    r_e, num_blades, rpm, distance, chord, tc, width = 0.4, 3, 3000.0, 25.0, 0.05, 0.12, 0.02
    theta = np.array([30.0, 90.0, 140.0])
    out = _tonal(_ring(r_e, chord=chord, thickness_ratio=tc, width=width), rpm, 0.0, _on_arc(distance, theta),
                 num_blades)
    omega = rpm * np.pi / 30.0
    n = np.arange(1, 5)[None, :] * num_blades
    volume = AREA_COEFFICIENT * tc * chord ** 2 * width
    z = n * omega * r_e * np.sin(np.deg2rad(theta))[:, None] / C0
    amplitude = RHO0 * num_blades * (n * omega) ** 2 * volume * bessel_j(n, z)
    expected = amplitude ** 2 / (8.0 * np.pi ** 2 * distance ** 2)
    np.testing.assert_allclose(out["thickness_pressure_squared"], expected, rtol=1e-10)
    assert AREA_COEFFICIENT == pytest.approx(0.685083, abs=1e-6)   # 2 * 5 * int y_t/(t c) dx (NACA 4-digit)


def test_no_thickness_noise_without_thickness():
    """Limit: a section of zero thickness displaces nothing, so thickness noise vanishes; loading is unchanged."""
    obs = _on_arc(30.0, [45.0, 100.0])
    thin = _tonal(_ring(thickness_ratio=0.0), 2500.0, 10.0, obs, 2)
    thick = _tonal(_ring(thickness_ratio=0.12), 2500.0, 10.0, obs, 2)
    assert np.all(thin["thickness_pressure_squared"] == 0.0)
    np.testing.assert_allclose(thin["tonal_pressure_squared"], thick["loading_pressure_squared"], rtol=1e-14)


@pytest.mark.parametrize("x", [-20.0, 20.0])
def test_silent_on_the_axis_in_hover(x):
    """Limit: on the axis z = 0 and J_mB(0) = 0 for m B >= 1, so loading and thickness tones vanish (hover)."""
    out = _tonal(_ring(), 3000.0, 0.0, [[x, 0.0, 0.0]], 2)
    assert np.all(out["loading_pressure_squared"] == 0.0) and np.all(out["thickness_pressure_squared"] == 0.0)


@pytest.mark.parametrize("v_axial", [0.0, 40.0])
def test_spherical_spreading(v_axial):
    """Limit: far away the mean square falls as 1/r**2 along a ray (hover and flight: r_e grows with r)."""
    obs = np.concatenate([_on_arc(100.0, [50.0, 110.0]), _on_arc(400.0, [50.0, 110.0])])
    out = _tonal(_ring(), 3000.0, v_axial, obs, 2)
    for name in ("loading_pressure_squared", "thickness_pressure_squared"):
        np.testing.assert_allclose(out[name][2:] * 16.0, out[name][:2], rtol=1e-12)


def test_flight_tends_to_hover():
    """Limit: the Doppler factors 1 - M cos(theta_e) -> 1 as M_x -> 0: the flight result is continuous at hover."""
    obs = _on_arc(20.0, [40.0, 90.0, 130.0])
    hover = _tonal(_ring(), 3000.0, 0.0, obs, 2)
    slow = _tonal(_ring(), 3000.0, 1e-5, obs, 2)
    for name in ("loading_pressure_squared", "thickness_pressure_squared"):
        np.testing.assert_allclose(slow[name], hover[name], rtol=1e-6)


def _time_domain_harmonics(r_e, thrust, torque, volume, num_blades, omega, v_axial, observer, harmonics, samples=96):
    """Exact field of B rotating point forces and point volumes translating along +x (medium at rest).

    A point source of strength q moving on y(tau) radiates phi = [q / (4 pi R (1 - M_R))]_ret (Lienard-Wiechert);
    the force F on the fluid gives p = -div phi_F, the volume V gives p = rho0 d^2 phi_V / dt^2.  The observer
    moves with the rotor: at time t it is at ``observer + (V t, 0, 0)``.  Derivatives by central differences.
    """
    period = 2.0 * np.pi / omega
    t = np.arange(samples) * period / samples

    def potentials(xo, t):
        """(phi_Fx, phi_Fy, phi_Fz, phi_V) at observer points xo[..., 3] and times t[...], summed over blades."""
        total = 0.0
        for k in range(num_blades):
            tau = t - np.linalg.norm(xo, axis=-1) / C0
            for _ in range(200):   # contraction, rate |M_R| < 1
                psi = omega * tau + 2.0 * np.pi * k / num_blades
                ys = np.stack([v_axial * tau, r_e * np.cos(psi), r_e * np.sin(psi)], axis=-1)
                tau = t - np.linalg.norm(xo - ys, axis=-1) / C0
            psi = omega * tau + 2.0 * np.pi * k / num_blades
            ys = np.stack([v_axial * tau, r_e * np.cos(psi), r_e * np.sin(psi)], axis=-1)
            vs = np.stack([np.full_like(psi, v_axial), -r_e * omega * np.sin(psi), r_e * omega * np.cos(psi)], -1)
            sep = xo - ys
            dist = np.linalg.norm(sep, axis=-1)
            factor = 1.0 / (4.0 * np.pi * dist * (1.0 - np.sum(vs * sep, axis=-1) / (C0 * dist)))
            e_psi = np.stack([np.zeros_like(psi), -np.sin(psi), np.cos(psi)], axis=-1)
            force = -thrust / num_blades * np.array([1.0, 0.0, 0.0]) + torque / (num_blades * r_e) * e_psi
            total = total + np.concatenate([force * factor[..., None], (volume * factor)[..., None]], axis=-1)
        return total

    def position(t):
        return np.asarray(observer)[None, :] + np.outer(t, [v_axial, 0.0, 0.0])

    dx, dt = 1e-3, 1e-3 / (omega * num_blades * max(harmonics))
    p_load = 0.0
    for i in range(3):
        step = np.zeros(3)
        step[i] = dx
        p_load = p_load - (potentials(position(t) + step, t)[:, i] - potentials(position(t) - step, t)[:, i]) / (2 * dx)
    phi_v = [potentials(position(t), t + s)[:, 3] for s in (-dt, 0.0, dt)]
    p_thick = RHO0 * (phi_v[0] - 2.0 * phi_v[1] + phi_v[2]) / dt ** 2
    idx = num_blades * np.asarray(harmonics)
    return (2.0 * np.abs(np.fft.fft(p_load)[idx] / samples) ** 2, 2.0 * np.abs(np.fft.fft(p_thick)[idx] / samples) ** 2)


@pytest.mark.parametrize("theta_deg", [45.0, 115.0])
def test_axial_flight_against_time_domain_solution(theta_deg):
    """Doppler factors of flight (M_x = 0.25) against the exact moving-source field, far away (r = 2000 m).

    Independent of the frequency-domain derivation: retarded times solved numerically, the pressure sampled
    over a revolution and Fourier analysed.  Agreement to 0.01 % in mean square (measured: 3.3e-5 at most; the
    far-field terms dropped are of order R/r and 1/(k r), 2e-4 and 1e-4 here); the hover value differs by
    tens of per cent, so the test sees the Doppler factors 1/(1 - M cos(theta_e))**2 (loading) and **3 (thickness).
    """
    r_e, thrust, torque, width, num_blades, rpm, v_axial = 0.4, 80.0, 4.0, 0.02, 2, 3000.0, 0.25 * C0
    ring = _ring(r_e, thrust, torque, width)
    volume = AREA_COEFFICIENT * 0.12 * 0.05 ** 2 * width
    observer = _on_arc(2000.0, theta_deg)
    harmonics = [1, 2, 3]
    loading, thickness = _time_domain_harmonics(r_e, thrust, torque, volume, num_blades, rpm * np.pi / 30.0,
                                                v_axial, observer, harmonics)
    out = _tonal(ring, rpm, v_axial, [observer], num_blades, num_harmonics=3)
    np.testing.assert_allclose(out["loading_pressure_squared"][0], loading, rtol=1e-4)
    np.testing.assert_allclose(out["thickness_pressure_squared"][0], thickness, rtol=1e-4)
    hover = _tonal(ring, rpm, 0.0, [observer], num_blades, num_harmonics=3)
    assert np.all(np.abs(hover["loading_pressure_squared"][0] / loading - 1.0) > 0.1)


def test_retarded_geometry_and_complex_safe_bessel():
    """Emission point: the sound leaves the hub's past position (x + M r_e, rho_o) at distance r_e; J' recurrence."""
    x, rho_o, mach = np.array([-30.0, 5.0, 40.0]), np.array([10.0, 25.0, 3.0]), 0.3
    g = retarded_geometry(x, rho_o, mach)
    np.testing.assert_allclose(np.hypot(g["axial"], rho_o), g["r_e"], rtol=1e-14)
    np.testing.assert_allclose(g["axial"], x + mach * g["r_e"], rtol=1e-14)
    np.testing.assert_allclose(g["sigma"], g["r_e"] * (1.0 - mach * g["axial"] / g["r_e"]), rtol=1e-14)
    h = 1e-40
    z = np.array([0.3, 2.0, 7.5])
    np.testing.assert_allclose(bessel_j(4, z + 1j * h).imag / h, bessel_j_derivative(4, z), rtol=1e-14)
    step = 1e-6
    np.testing.assert_allclose(bessel_j_derivative(4, z), (bessel_j(4, z + step) - bessel_j(4, z - step)) / (2 * step),
                               rtol=1e-7)
