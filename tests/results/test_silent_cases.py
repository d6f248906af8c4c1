"""Inputs that used to be accepted silently (issue 24) now say what is wrong, in one line or one warning.

Sources: physical bounds stated beside each case (a helical tip Mach number far past 1, where blade-element
polars and momentum theory fail; a blade needs stations from hub to tip) and the definition of an unloaded
station (zero chord: the ideal loading carries nothing there).
"""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.bild import BILDGroup
from bild_mdo.results.design import MAX_TIP_MACH, UnloadedStationsWarning, design_rotor


def test_a_tip_far_past_sonic_is_refused():
    # 1e12 rpm on a 1.5 m rotor: Omega R / a = 1e12 * 2 pi / 60 * 1.5 / 340.3 = 4.6e8.
    with pytest.raises(ValueError, match=r"tip Mach number 4.62e\+08 .*refuses above 3"):
        design_rotor(rpm=1e12)
    # Just below the bound it is designed (and flagged by the supersonic-tip warning).
    rpm = 0.99 * MAX_TIP_MACH * 340.294 / (1.5 * 2.0 * np.pi / 60.0)
    with pytest.warns(UserWarning, match="tip Mach number"):
        design_rotor(rpm=rpm, on_infeasible="skip", bem_analysis=False)


def test_a_design_with_unloaded_stations_warns():
    # The Reynolds-aware exact loading leaves hub annuli of fast propellers with small c_ref unloaded (in 24 of
    # the 81 cases of the verification's levels 3, README): J = 1.5, R = 1 m, c_ref = 0.1 m is one.
    options = dict(advance_ratio=1.5, ref_chord=0.1, radius=1.0, section_point="local", ideal_loading="exact",
                   bem_analysis=False)
    with pytest.warns(UnloadedStationsWarning, match=r"the design leaves \d+ of 30 stations at r/R .* unloaded"):
        design = design_rotor(**options)
    unloaded = int(np.sum(design.chord <= 0.0))
    assert unloaded > 0
    assert f"{unloaded} unloaded station(s) (zero chord)" in design.summary()
    with pytest.warns(UnloadedStationsWarning, match=r"1 design\(s\) leave stations unloaded \(zero chord\), "
                                                     r"design 1: \d+ of 30"):
        design_rotor(**{**options, "advance_ratio": [0.5, 1.5]})


@pytest.mark.parametrize("options, message", [
    (dict(num_nodes=0), "Value \\(0\\) of option 'num_nodes' is less than minimum allowed value of 1"),
    (dict(num_radial=1), "num_radial must be at least 2"),
])
def test_bild_group_sizes_are_checked(options, message):
    with pytest.raises(ValueError, match=message):
        om.Problem(BILDGroup(**options), reports=False).setup()
