"""10,000 random blades in one vectorised analysis: no failure, residual at round-off at every solved station."""
import numpy as np

from bild_mdo.bem import analyze_rotor
from bild_mdo.bem.flow_states import NO_SOLUTION

NUM_BLADES_TESTED = 10_000
NUM_RADIAL = 10


def test_random_blades_all_converge(analytic_polar):
    rng = np.random.default_rng(20230901)
    nn, nr = NUM_BLADES_TESTED, NUM_RADIAL
    v_axial = rng.uniform(0.0, 100.0, nn)
    v_axial[rng.random(nn) < 0.1] = 0.0  # exact hover cases
    rpm = rng.uniform(200.0, 8000.0, nn)
    radius = rng.uniform(0.1, 3.0, nn)
    hub = radius * rng.uniform(0.05, 0.25, nn)
    # Independent random chord and twist at every station (harsher than any smooth blade).
    chord = radius[:, None] * rng.uniform(0.01, 0.3, (nn, nr))
    twist = np.radians(rng.uniform(-10.0, 89.0, (nn, nr)))
    res = analyze_rotor(chord, twist, radius, hub, rpm, v_axial, 3, analytic_polar,
                        altitude=rng.uniform(0.0, 5000.0, nn), on_invalid="ignore")
    assert np.count_nonzero(v_axial == 0.0) > 500
    # Residual re-evaluated at the returned phi (independent of the solver's own bookkeeping), at every
    # station with a momentum solution (code 0 takes the zero-loading fallback instead).
    solved = res.flow_state != NO_SOLUTION
    assert np.max(np.abs(res.residual[solved])) < 1e-10
    for name, value in res.to_dict().items():
        assert np.all(np.isfinite(value)), name
    # The blades span every search region of the solve: regions 1, 2 and 3 all occur.
    phi = res.phi
    assert np.any((phi > 0) & (phi < np.pi / 2)) and np.any(phi < 0) and np.any(phi > np.pi / 2)
