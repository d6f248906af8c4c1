"""The input checks shared by the Python API and the command line: one clear line per mistake."""
import numpy as np
import pytest

from bild_mdo import validation


@pytest.mark.parametrize("call, message", [
    # Strings and booleans are not numbers, although NumPy would convert them.
    (lambda: validation.positive("radius", "1.5", units="m"),
     "radius must be a positive finite number in m, got '1.5'"),
    (lambda: validation.positive("rpm", True, units="rpm"), "rpm must be a positive finite number in rpm, got True"),
    (lambda: validation.positive("radius", [1.0, True]), "radius must be a positive finite number, got [1.0, True]"),
    (lambda: validation.positive("radius", np.array([True])), "radius must be a positive finite number, got array"),
    (lambda: validation.positive("radius", None), "radius must be a positive finite number, got None"),
    (lambda: validation.positive("radius", 1j), "radius must be a positive finite number, got 1j"),
    # Values: the first bad entry of a batch, with its position.
    (lambda: validation.positive("radius", [1.0, 0.0], units="m"),
     "radius must be a positive finite number in m, got 0 (design 1)"),
    (lambda: validation.positive("radius", np.inf), "radius must be a positive finite number, got inf"),
    (lambda: validation.non_negative("v_axial", -2.0, units="m/s", hint="0 is hover"),
     "v_axial must be a finite number >= 0 in m/s (0 is hover), got -2"),
    (lambda: validation.positive("chord", [[0.1, 0.2], [0.1, -0.2]], ndim=(2,)),
     "chord must be a positive finite number, got -0.2 (design 1, station 1)"),
    (lambda: validation.positive("chord", [0.1, -0.2], axes=("station",)),
     "chord must be a positive finite number, got -0.2 (station 1)"),
    (lambda: validation.in_range("hub_radius_ratio", 1.0, 0.0, 1.0, open_low=True, open_high=True),
     "hub_radius_ratio must be a finite number within (0, 1), got 1"),
    (lambda: validation.in_range("altitude", 12000.0, 0.0, 11000.0, units="m"),
     "altitude must be a finite number in m within [0, 11000], got 12000"),
    (lambda: validation.positive("radius", [[1.0]]),
     "radius must be a scalar or a 1-D list of values, got shape (1, 1)"),
    (lambda: validation.smaller("hub_radius", [0.1, 0.5], "radius", 0.5),
     "hub_radius must be smaller than radius, got 0.5 >= 0.5 (design 1)"),
    # Integers: whole numbers only, never booleans.
    (lambda: validation.integer("num_blades", True), "num_blades must be an integer >= 1, got True"),
    (lambda: validation.integer("num_radial", 2.5), "num_radial must be an integer >= 1, got 2.5"),
    (lambda: validation.integer("num_radial", "3"), "num_radial must be an integer >= 1, got '3'"),
    (lambda: validation.integer("num_radial", 0), "num_radial must be an integer >= 1, got 0"),
    (lambda: validation.choice("loss_model", "prandtl", ("tip_hub", "tip", "none")),
     "loss_model must be one of tip_hub, tip, none, got 'prandtl'"),
    (lambda: validation.batch_size({"rpm": 2, "ref_chord": 3}),
     "batch sizes disagree: batched arguments need equal lengths (or are scalars), got rpm: 2, ref_chord: 3"),
    (lambda: validation.batch_size({"rpm": 0}), "batch arguments are empty"),
])
def test_one_line_messages(call, message):
    with pytest.raises(ValueError) as info:
        call()
    text = str(info.value)
    assert text.startswith(message) and "\n" not in text


def test_valid_values_pass_through():
    np.testing.assert_array_equal(validation.positive("rpm", [800, 900.0]), [800.0, 900.0])
    assert validation.positive("radius", np.float32(1.5)).dtype == float
    assert validation.non_negative("v_axial", 0.0) == 0.0
    assert validation.in_range("altitude", 11000.0, 0.0, 11000.0) == 11000.0
    assert validation.integer("num_blades", np.int64(4)) == 4
    assert validation.integer("num_radial", 30.0) == 30  # a whole float, as a command line gives it
    assert validation.choice("loss_model", "tip", ("tip_hub", "tip")) == "tip"
    assert validation.batch_size({}) == 1 and validation.batch_size({"rpm": 3, "radius": 3}) == 3
    validation.smaller("hub_radius", [0.1, 0.2], "radius", 0.5)


def test_memory_bound_gives_the_estimate():
    # 1e9 points x 6 stations x 3 kB (the measured peak per point and station, rounded up) = 18 TB.
    with pytest.raises(ValueError) as info:
        validation.memory_bound("--advance-ratio N", 10**9, 6, limit=8e9, hint="use fewer points")
    assert str(info.value) == ("--advance-ratio N = 1000000000 with 6 stations would need about 18 TB of memory "
                               "(estimated 3 kB per point and station); the limit is 8 GB: use fewer points")
    validation.memory_bound("designs", 10_000, 30, limit=8e9)  # 0.9 GB: the batches of 10,000 fit
    assert validation.format_bytes(999) == "999 B" and validation.format_bytes(4.3e9) == "4.3 GB"
