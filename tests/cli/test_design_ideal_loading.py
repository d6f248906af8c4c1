"""bild-mdo design --ideal-loading."""
import pytest

from bild_mdo.results.design import design_rotor
from tests.cli.runner import run


def test_design_ideal_loading_exact(capsys):
    code, out, err = run(capsys, "design", "--ideal-loading", "exact", "--num-radial", "12", "--v-axial", "10")
    assert code == 0, err
    exact = design_rotor(v_axial=10.0, num_radial=12, ideal_loading="exact")
    thrust_line = next(line for line in out.splitlines() if line.strip().startswith("thrust T"))
    assert float(thrust_line.split()[-2]) == pytest.approx(exact.thrust, rel=1e-5)
    code, _, err = run(capsys, "design", "--ideal-loading", "optimal")
    assert code == 2
    assert "--ideal-loading" in err


def test_design_local_point_with_exact_loading(capsys):
    # The Reynolds-aware exact loading from the CLI: the same design as design_rotor gives.
    code, out, err = run(capsys, "design", "--section-point", "local", "--ideal-loading", "exact", "--num-radial",
                         "10", "--v-axial", "10")
    assert code == 0, err
    aware = design_rotor(v_axial=10.0, num_radial=10, section_point="local", ideal_loading="exact")
    thrust_line = next(line for line in out.splitlines() if line.strip().startswith("thrust T"))
    assert float(thrust_line.split()[-2]) == pytest.approx(aware.thrust, rel=1e-5)
