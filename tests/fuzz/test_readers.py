"""Fuzzing the file readers: random bytes and garbled good files give the geometry or one ValueError line.

Property: a reader either returns values that are all finite (a geometry, a polar table) or raises
ValueError whose message is one line naming the file; never another exception type, never a NaN.
"""
import atexit
import os
import shutil
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from bild_mdo.airfoil.sources.readers import read_polar_file
from bild_mdo.io.csv import read_csv
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

