"""StationsComp: midpoint stations, user stations, and partials."""
import numpy as np
import openmdao.api as om
import pytest
from openmdao.utils.assert_utils import assert_check_partials

from bild_mdo.bem.stations import StationsComp


def _run(nn=3, nr=7, **options):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("st", StationsComp(num_nodes=nn, num_radial=nr, **options), promotes=["*"])
    prob.setup(force_alloc_complex=True)
    prob.set_val("radius", [0.8, 1.0, 1.5])
    prob.set_val("hub_radius", [0.1, 0.2, 0.15])
    prob.run_model()
    return prob


def test_midpoints_of_equal_annuli():
    prob = _run()
    radii, dr = prob.get_val("radii"), prob.get_val("dr")
    R, rh = prob.get_val("radius"), prob.get_val("hub_radius")
    # Hand: dr = (R - r_hub)/7, r_j = r_hub + (j + 1/2) dr; widths tile the span exactly.
    np.testing.assert_allclose(dr, np.tile(((R - rh) / 7)[:, None], 7), rtol=1e-15)
    np.testing.assert_allclose(radii, rh[:, None] + (np.arange(7) + 0.5) * dr, rtol=1e-15)
    np.testing.assert_allclose(dr.sum(axis=1), R - rh, rtol=1e-14)
    # The midpoint rule integrates linear functions exactly: sum(r dr) = (R^2 - r_hub^2)/2.
    np.testing.assert_allclose((radii * dr).sum(axis=1), (R**2 - rh**2) / 2, rtol=1e-14)


@pytest.mark.parametrize("per_node", [False, True])
def test_user_stations(per_node):
    frac = np.linspace(0.2, 0.95, 7)
    width = np.full(7, 0.1)
    if per_node:
        frac = np.vstack([frac, frac * 0.99, frac * 1.01])
        width = np.vstack([width] * 3)
    prob = _run(radial_fractions=frac, width_fractions=width)
    R = prob.get_val("radius")[:, None]
    np.testing.assert_allclose(prob.get_val("radii"), np.broadcast_to(frac, (3, 7)) * R, rtol=1e-15)
    np.testing.assert_allclose(prob.get_val("dr"), np.broadcast_to(width, (3, 7)) * R, rtol=1e-15)


@pytest.mark.parametrize("user", [False, True])
def test_partials(user):
    options = dict(radial_fractions=np.linspace(0.2, 0.95, 7), width_fractions=np.full(7, 0.1)) if user else {}
    prob = _run(**options)
    assert_check_partials(prob.check_partials(method="cs", out_stream=None), atol=1e-12, rtol=1e-12)


def test_fraction_options_validated():
    with pytest.raises(ValueError, match="width_fractions"):
        _run(radial_fractions=np.linspace(0.2, 0.9, 7))
    with pytest.raises(ValueError, match="radial_fractions must have shape"):
        _run(radial_fractions=np.linspace(0.2, 0.9, 6), width_fractions=np.full(6, 0.1))
