"""Size options and the shared variable catalogue."""
import numpy as np
import openmdao.api as om
import pytest

from bild_mdo.utils.options import DEFAULT_NUM_RADIAL, VARIABLES, add_inputs, add_outputs, declare_size_options, sizes


class _Comp(om.ExplicitComponent):
    def initialize(self):
        declare_size_options(self.options)

    def setup(self):
        add_inputs(self, ("v_axial", "radii"), radii=2.0)
        add_outputs(self, ("u_axial",))


class _NodeComp(om.ExplicitComponent):
    def initialize(self):
        declare_size_options(self.options, radial=False)


def test_shapes_units_and_overrides():
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("comp", _Comp(num_nodes=3, num_radial=5))
    prob.setup()
    meta = {m["prom_name"]: m for m in prob.model.get_io_metadata(metadata_keys=["shape", "units"]).values()}
    assert meta["comp.v_axial"]["shape"] == (3,) and meta["comp.v_axial"]["units"] == VARIABLES["v_axial"][2]
    assert meta["comp.radii"]["shape"] == (3, 5)
    assert meta["comp.u_axial"]["shape"] == (3, 5)
    np.testing.assert_array_equal(prob.get_val("comp.radii"), 2.0)


def test_defaults_and_radial_flag():
    comp = _Comp()
    assert comp.options["num_nodes"] == 1 and comp.options["num_radial"] == DEFAULT_NUM_RADIAL == 20
    assert sizes(_Comp(num_nodes=2, num_radial=4).options) == {"num_nodes": 2, "num_radial": 4}
    node = _NodeComp()
    assert "num_radial" not in node.options
    with pytest.raises(KeyError):
        _NodeComp(num_radial=3)
