"""The BILD family: one interface, one folder per member, BILDGroup picks the member its options name."""
import openmdao.api as om
import pytest

from bild_mdo.bild import BILDGroup
from bild_mdo.bild.variants import SECTION_POINTS, VARIANTS
from bild_mdo.bild.variants.base import BILDVariant

FOLDERS = {("paper", "reference"): "paper", ("exact", "reference"): "exact", ("paper", "local"): "local_paper",
           ("exact", "local"): "reynolds_exact"}


def test_every_pair_of_options_has_one_member_in_its_own_folder():
    assert set(VARIANTS) == {(loading, point) for loading in ("paper", "exact") for point in SECTION_POINTS}
    for key, member in VARIANTS.items():
        assert issubclass(member, BILDVariant)
        assert (member.ideal_loading, member.section_point) == key
        assert member.__module__ == f"bild_mdo.bild.variants.{FOLDERS[key]}.variant"


@pytest.mark.parametrize("key", sorted(VARIANTS))
def test_bild_group_builds_the_member_its_options_name(key):
    ideal_loading, section_point = key
    prob = om.Problem(BILDGroup(num_nodes=2, num_radial=3, ideal_loading=ideal_loading, section_point=section_point),
                      reports=False)
    prob.setup()
    assert type(prob.model.variant) is VARIANTS[key]
    assert prob.model.variant.per_station == (section_point == "local")
