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
