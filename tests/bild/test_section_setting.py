"""The local section point is refused with the exact ideal loading, at every entry point, with one clear line.

Why (measured, bild_mdo/bild/local_section_point.py, check_section_setting): with each station's cd/cl following its
own load, the exact condition without the derivative of cd/cl with the load has several solutions at low Reynolds
numbers (an annulus unloaded at the Reynolds floor, or loaded), so designs depended on the batch they ran in.
"""
import openmdao.api as om
import pytest

from bild_mdo.bild import BILDGroup
from bild_mdo.bild.local_section_point import check_section_setting
from bild_mdo.results.design import design_rotor
from bild_mdo.verification.cases import SweepSpec
from tests.cli.runner import run

MESSAGE = r"^section_point='local' cannot be combined with ideal_loading='exact' \(at low Reynolds numbers"


@pytest.mark.parametrize("point, loading", [("reference", "paper"), ("reference", "exact"), ("local", "paper")])
def test_the_other_settings_are_accepted(point, loading):
    check_section_setting(point, loading)
    SweepSpec(levels=2, section_point=point, ideal_loading=loading)


def test_group_design_rotor_and_sweep_refuse_local_with_exact():
    prob = om.Problem(BILDGroup(num_nodes=2, num_radial=3, section_point="local", ideal_loading="exact"),
                      reports=False)
    with pytest.raises(ValueError, match=MESSAGE):
        prob.setup()
    with pytest.raises(ValueError, match=MESSAGE):
        design_rotor(v_axial=10.0, section_point="local", ideal_loading="exact")
    with pytest.raises(ValueError, match=MESSAGE):
        SweepSpec(section_point="local", ideal_loading="exact")


@pytest.mark.parametrize("command", [["design", "--v-axial", "10"], ["verify", "--levels", "2"]])
def test_cli_exits_2_with_one_line(capsys, tmp_path, command):
    code, out, err = run(capsys, *command, "--section-point", "local", "--ideal-loading", "exact",
                         *(["--db", str(tmp_path / "v.sqlite"), "--no-progress"] if command[0] == "verify" else []))
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "cannot be combined with" in lines[0] and "Traceback" not in err
    assert not (tmp_path / "v.sqlite").exists()
