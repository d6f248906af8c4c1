"""Fuzzing the file readers: random bytes and garbled good files give the geometry or one ValueError line.

Property: a reader either returns values that are all finite (a geometry, a polar table) or raises
ValueError whose message is one line naming the file; never another exception type, never a NaN.
Files that would lie are refused, whatever the draw: stations cut from either end (of a file with station
widths, format 2, and of one without, format 1), a format version newer than the reader, a twist in rad
that is in degrees; a byte-order mark changes nothing; a binary polar file is named as not text.
"""
import atexit
import json
import os
import re
import shutil
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from bild_mdo.airfoil.sources.readers import read_polar_file
from bild_mdo.io.airfoil import resolve_airfoil
from bild_mdo.io.csv import read_csv
from bild_mdo.io.geometry import FORMAT_VERSION
from bild_mdo.io.json import read_json
from bild_mdo.io.qprop import read_qprop
from tests.fuzz.samples import POLAR_TABLE, XFOIL_POLAR, geometry_texts

# BILD_MDO_FUZZ_SCALE=50 runs 50 times as many examples (a longer search by hand; the suite keeps ~5 s).
SCALE = int(os.environ.get("BILD_MDO_FUZZ_SCALE", "1"))
FUZZ = settings(max_examples=60 * SCALE, deadline=None, database=None, suppress_health_check=[HealthCheck.too_slow])
READERS = {".csv": read_csv, ".json": read_json, ".prop": read_qprop}
_FOLDER = Path(tempfile.mkdtemp(prefix="bild-mdo-fuzz-"))
atexit.register(shutil.rmtree, _FOLDER, ignore_errors=True)
SEEDS = {**geometry_texts(_FOLDER), ".xfoil": XFOIL_POLAR, ".table": POLAR_TABLE}

# Tokens that break numbers, lists and lines: empty, non-finite, huge, negative, other types, separators.
BAD_TOKENS = ["", "nan", "NaN", "inf", "-inf", "1e999", "-1", "0", "-0", "1e-320", "abc", "\x00", ",", ";", "[",
              "]", "{", "}", '"', "'", "#", "!", "true", "null", "[]", "{}", "3.5", "1,2", " ", "\t", "é", "\ufeff",
              "9" * 400, "[[[[[[[[", "0x10", "1_000"]


@st.composite
def garbled(draw, text):
    """``text`` with some tokens replaced, lines deleted or repeated, or cut short."""
    lines = text.splitlines(keepends=True)
    for _ in range(draw(st.integers(1, 4))):
        if not lines:
            break
        action = draw(st.sampled_from(["token", "token", "delete", "repeat", "cut", "swap"]))
        i = draw(st.integers(0, len(lines) - 1))
        if action == "token":
            tokens = lines[i].replace(",", " , ").split(" ")
            j = draw(st.integers(0, len(tokens) - 1))
            tokens[j] = draw(st.sampled_from(BAD_TOKENS) | st.text(max_size=6))
            lines[i] = " ".join(tokens)
        elif action == "delete":
            del lines[i]
        elif action == "repeat":
            lines.insert(i, lines[i])
        elif action == "swap":
            j = draw(st.integers(0, len(lines) - 1))
            lines[i], lines[j] = lines[j], lines[i]
        else:
            lines[i] = lines[i][:draw(st.integers(0, len(lines[i])))]
    return "".join(lines)


def _finite(values):
    return all(np.all(np.isfinite(np.asarray(v, dtype=float))) for v in values)


def _check_geometry(geometry):
    assert _finite([geometry.radii, geometry.chord, geometry.twist, geometry.radius, geometry.hub_radius,
                    list(geometry.design_point.values())])
    if geometry.polar_coefficients:
        assert _finite(list(geometry.polar_coefficients.values()))


def _check_polar(data):
    assert _finite([data.alpha_deg, data.cl, data.cd, data.reynolds, data.mach])


def _read(path, suffix):
    """Read ``path`` with the reader of ``suffix``; the property holds for its result or its error."""
    try:
        if suffix in READERS:
            _check_geometry(READERS[suffix](path))
        else:
            _check_polar(read_polar_file(path))
    except ValueError as err:
        message = str(err)
        assert "\n" not in message, message
        assert str(path) in message, message


def _write(name, content):
    path = Path(tempfile.mkdtemp(dir=_FOLDER)) / name
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content, encoding="utf-8")
    return path


@pytest.mark.parametrize("suffix", [".csv", ".json", ".prop", ".xfoil", ".table"])
def test_good_seed_files_read_finite_values(suffix):
    _read(_write(f"seed{suffix}", SEEDS[suffix]), suffix)


@pytest.mark.parametrize("suffix", [".csv", ".json", ".prop", ".xfoil", ".table"])
@FUZZ
@given(data=st.data())
def test_garbled_files_give_values_or_one_line(suffix, data):
    text = data.draw(garbled(SEEDS[suffix]))
    _read(_write(f"blade{suffix}", text), suffix)


@pytest.mark.parametrize("suffix", [".csv", ".json", ".prop", ".xfoil"])
@settings(max_examples=25 * SCALE, deadline=None, database=None)
@given(content=st.binary(max_size=300))
def test_random_bytes_give_one_line(suffix, content):
    _read(_write(f"random{suffix}", content), suffix)


def test_deeply_nested_json_is_one_line():
    path = _write("nested.json", '{"format": "bild-mdo rotor geometry", "designs": ' + "[" * 100_000 + "]" * 100_000
                  + "}")
    _read(path, ".json")



def _refused(path, suffix, pattern):
    """Reading ``path`` raises one ValueError line that names the file and matches ``pattern``."""
    with pytest.raises(ValueError) as info:
        READERS[suffix](path)
    message = str(info.value)
    assert "\n" not in message and str(path) in message, message
    assert re.search(pattern, message), message


def _format_1(suffix, text):
    """The seed as format 1 wrote it: no station widths, version 1."""
    if suffix == ".csv":
        lines = text.replace("format 2", "format 1").splitlines()
        return "\n".join(line if line.startswith("#") else line.rsplit(",", 1)[0] for line in lines) + "\n"
    if suffix == ".json":
        doc = json.loads(text)
        doc["version"] = 1
        for entry in doc["designs"]:
            del entry["dr [m]"]
        return json.dumps(doc)
    return "\n".join(line.replace("format = 2", "format = 1") for line in text.splitlines()
                     if not line.startswith("# bild-mdo: dr [m]")) + "\n"


def _cut(suffix, text, count, from_tip):
    """The text with ``count`` station rows cut from the tip end (or the hub end)."""
    if suffix == ".json":
        doc = json.loads(text)
        entry = doc["designs"][0]
        for key in ("r [m]", "chord [m]", "twist [deg]", "dr [m]"):
            if key in entry:
                entry[key] = entry[key][:-count] if from_tip else entry[key][count:]
        return json.dumps(doc)
    lines = text.splitlines()
    if suffix == ".csv":
        rows = [i for i, line in enumerate(lines) if line and not line.startswith("#")][1:]
    else:
        rows = [i for i, line in enumerate(lines) if line.strip() and not line.lstrip().startswith("#")][8:]
    drop = set(rows[-count:] if from_tip else rows[:count])
    return "\n".join(line for i, line in enumerate(lines) if i not in drop) + "\n"


@pytest.mark.parametrize("suffix", [".csv", ".json", ".prop"])
@pytest.mark.parametrize("version", [1, 2])
@settings(max_examples=8 * SCALE, deadline=None, database=None)
@given(count=st.integers(1, 2), from_tip=st.booleans())
def test_cut_files_are_refused(suffix, version, count, from_tip):
    # The seed blade has 4 stations (QPROP: 6 rows with the hub and tip rows); cutting 1 or 2 from either end
    # leaves a span its stations do not tile: the widths no longer add up (format 2), or an end station lies
    # 1.5 spacings or more from the hub or tip (format 1).
    text = SEEDS[suffix] if version == 2 else _format_1(suffix, SEEDS[suffix])
    path = _write(f"cut{suffix}", _cut(suffix, text, count, from_tip))
    _refused(path, suffix, r"stations are missing|stations but \d+ widths|at least 2 stations")


@pytest.mark.parametrize("suffix", [".csv", ".json", ".prop"])
@settings(max_examples=8 * SCALE, deadline=None, database=None)
@given(version=st.integers(FORMAT_VERSION + 1, 10**6))
def test_newer_files_are_refused(suffix, version):
    text = SEEDS[suffix]
    text = (text.replace("format 2", f"format {version}") if suffix == ".csv" else
            text.replace('"version": 2', f'"version": {version}') if suffix == ".json" else
            text.replace("format = 2", f"format = {version}"))
    _refused(_write(f"new{suffix}", text), suffix, rf"format version {version} is newer than this bild-mdo reads")


@pytest.mark.parametrize("suffix", [".csv", ".json"])
@settings(max_examples=10 * SCALE, deadline=None, database=None)
@given(twist=st.lists(st.floats(6.3, 360.0), min_size=4, max_size=4))
def test_twist_in_degrees_declared_rad_is_named(suffix, twist):
    if suffix == ".csv":
        lines = SEEDS[suffix].replace("twist [deg]", "twist [rad]").splitlines()
        header = next(i for i, line in enumerate(lines) if line.startswith("r [m]"))
        for k, value in enumerate(twist):
            cells = lines[header + 1 + k].split(",")
            cells[2] = repr(value)
            lines[header + 1 + k] = ",".join(cells)
        text = "\n".join(lines) + "\n"
    else:
        doc = json.loads(SEEDS[suffix])
        entry = doc["designs"][0]
        del entry["twist [deg]"]
        entry["twist [rad]"] = twist
        text = json.dumps(doc)
    _refused(_write(f"deg{suffix}", text), suffix, r"the values look like degrees, but the file gives them in rad")


@pytest.mark.parametrize("suffix", [".csv", ".json", ".prop"])
def test_byte_order_mark_changes_nothing(suffix):
    plain, marked = _write(f"plain{suffix}", SEEDS[suffix]), _write(f"bom{suffix}", "\ufeff" + SEEDS[suffix])
    a, b = READERS[suffix](plain), READERS[suffix](marked)
    for name in ("radii", "chord", "twist", "dr"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    assert (a.radius, a.hub_radius, a.num_blades, a.design_point) == (b.radius, b.hub_radius, b.num_blades,
                                                                      b.design_point)


@settings(max_examples=25 * SCALE, deadline=None, database=None)
@given(head=st.binary(max_size=100), control=st.sampled_from([bytes([c]) for c in [*range(9), *range(14, 32), 127]]),
       tail=st.binary(max_size=100))
def test_binary_polar_files_are_named_not_text(head, control, tail):
    path = _write("polar.dat", head + control + tail)
    with pytest.raises(ValueError) as info:
        resolve_airfoil(str(path))
    message = str(info.value)
    assert "\n" not in message and message.startswith(f"{path}: "), message
    assert "not a text polar file" in message or "UTF-16 text; save it as UTF-8" in message, message
