"""Fuzzing the command line: random good and bad argument lists end with exit code 0 or 2, never a traceback.

Property of ``main(argv)``: the exit code is 0 or 2; stderr holds only lines starting ``bild-mdo``; on exit
code 2 exactly one of them is the error (the others are warnings), and no output file exists that was asked
for by a run that failed.
"""
import contextlib
import io
import os
import shutil
import tempfile
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from bild_mdo.cli.main import main
from tests.fuzz.samples import geometry_texts

SCALE = int(os.environ.get("BILD_MDO_FUZZ_SCALE", "1"))
FUZZ = settings(max_examples=40 * SCALE, deadline=None, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])

NUMBERS = ["0", "-1", "nan", "inf", "-inf", "1e400", "abc", "", "True", "1,5", "0x3", "1e-300", "3", "2.5", "1e12"]
FLUIDS = ["water", "seawater", "Air", "lava", "", "1000,1e-3,1480", "1000,1e-3", "1,-2,3", "a,b,c"]
GOOD = {"--rpm": ["800", "1200"], "--radius": ["1.5", "0.5"], "--hub-radius-ratio": ["0.2", "0.3"],
        "--ref-radius-ratio": ["0.5", "0.7"], "--ref-chord": ["0.15", "0.05"], "--altitude": ["0", "3000", "11000"],
        "--v-axial": ["0", "10"], "--advance-ratio": ["0.5", "1.0"], "--thrust": ["1500", "800"]}
AIRFOILS = ["analytic", "naca4412", "NACA4412", "foo", "", "naca44", "../x", "neuralfoil:", "analytic ", "{tmp}/blade.csv"]
CHOICES = {"--loss-model": ["tip_hub", "tip", "none", "prandtl"], "--chord-form": ["thrust", "torque", "x"]}
GEOMETRIES = ["blade.csv", "blade.json", "blade.prop", "missing.csv", "folder", "garbage.csv", "garbage.json",
              "garbage.prop", "empty.csv"]
TARGETS = ["{tmp}/out.csv", "{tmp}/folder", "{tmp}/missing/out.csv", "{tmp}/blade.csv/x.csv", "", "{tmp}/folder/"]
PLOTS = ["{tmp}/folder", "{tmp}/missing/p.png", "{tmp}/p.xyz", "{tmp}/blade.csv/p.png"]


def _value(option, clean):
    return st.sampled_from(GOOD.get(option, []) + ([] if clean else NUMBERS))


@st.composite
def design_argv(draw):
    # Half of the lists hold only valid values, so that runs which succeed are searched as well.
    clean = draw(st.booleans())
    argv = ["design", "--airfoil", draw(st.sampled_from(AIRFOILS[:2] if clean else AIRFOILS)),
            "--num-radial", draw(st.sampled_from(["4", "6"] + ([] if clean else ["1", "0", "2.5", "x", "100000000"])))]
    options = sorted(set(GOOD) - {"--advance-ratio", "--thrust"}) if clean else sorted(GOOD)
    for option in draw(st.lists(st.sampled_from(options), max_size=3, unique=True)):
        argv += [option] + draw(st.lists(_value(option, clean), min_size=1 if clean else 0, max_size=1 if clean else 3))
    for option, values in CHOICES.items():
        if draw(st.booleans()):
            argv += [option, draw(st.sampled_from(values[:2] if clean else values))]
    if draw(st.booleans()):
        argv += ["--num-blades", draw(st.sampled_from(["2", "3", "0", "-1", "2.5", "x", "True"]))]
    if draw(st.booleans()):
        argv += ["--root-chord-correction", draw(st.sampled_from(["0.5", "2"] + NUMBERS))]
    if draw(st.booleans()):
        argv += ["--fluid", draw(st.sampled_from(FLUIDS[:2] if clean else FLUIDS))]
    for option in draw(st.lists(st.sampled_from(["--csv", "--json", "--qprop", "--plot"]), max_size=2, unique=True)):
        argv += [option, draw(st.sampled_from(PLOTS if option == "--plot" else TARGETS))]
    return argv


@st.composite
def analyze_argv(draw):
    clean = draw(st.booleans())
    argv = ["analyze", "{tmp}/" + draw(st.sampled_from(GEOMETRIES[:3] if clean else GEOMETRIES))]
    sweep = draw(st.sampled_from(["--advance-ratio", "--rpm"] + ([] if clean else [None, "--collective-pitch"])))
    if clean:
        good = ["0", "0.4", "1.2"] if sweep == "--advance-ratio" else ["600", "1000", "1400"]
        argv += [sweep] + draw(st.lists(st.sampled_from(good), min_size=2, max_size=2)) + [
            draw(st.sampled_from(["1", "3", "5"]))]
        return argv + draw(st.sampled_from([[], ["--altitude", "2000"], ["--loss-model", "tip"],
                                            ["--csv", "{tmp}/out.csv"], ["--airfoil", "naca4412"]]))
    if sweep:
        good = {"--advance-ratio": ["0", "1.2"], "--rpm": ["600", "1000"], "--collective-pitch": ["-2", "3"]}[sweep]
        argv += [sweep] + draw(st.lists(st.sampled_from(good + NUMBERS + ["3", "1e9", "100000000"]), min_size=0,
                                        max_size=4))
    for option in draw(st.lists(st.sampled_from(["--at-rpm", "--v-axial", "--altitude", "--design", "--thrust"]),
                                max_size=2, unique=True)):
        argv += [option] + draw(st.lists(st.sampled_from(["1000", "5", "0", "1"] + NUMBERS), min_size=1,
                                         max_size=3 if option == "--v-axial" else 1))
    if draw(st.booleans()):
        argv += ["--trim", draw(st.sampled_from(["collective_pitch", "rpm", "pitch"]))]
    if draw(st.booleans()):
        argv += ["--fluid", draw(st.sampled_from(FLUIDS))]
    if draw(st.booleans()):
        argv += ["--airfoil", draw(st.sampled_from(AIRFOILS))]
    if draw(st.booleans()):
        argv += ["--loss-model", draw(st.sampled_from(CHOICES["--loss-model"]))]
    if draw(st.booleans()):
        argv += ["--csv", draw(st.sampled_from(TARGETS))]
    if draw(st.booleans()):
        argv += ["--plot", draw(st.sampled_from(PLOTS))]
    return argv


@st.composite
def compare_argv(draw):
    files = draw(st.lists(st.sampled_from(["{tmp}/" + name for name in GEOMETRIES]), min_size=0, max_size=3))
    argv = ["compare"] + files
    if draw(st.booleans()):
        argv += ["--plot", draw(st.sampled_from(PLOTS + ["{tmp}/c.png"]))]
    return argv


JUNK = st.lists(st.sampled_from(["design", "analyze", "demo", "--help", "-x", "--", "--rpm", "3", "",
                                 "bogus", "--version", "--csv", "--output-dir"]), max_size=4)


def _run(argv):
    tmp = Path(tempfile.mkdtemp(prefix="bild-mdo-cli-fuzz-"))
    try:
        (tmp / "folder").mkdir()
        texts = geometry_texts(tmp)
        for suffix, text in texts.items():
            (tmp / f"garbage{suffix}").write_text(text[: len(text) // 3] + "\x00 1e999 [")
        (tmp / "empty.csv").write_text("")
        argv = [arg.replace("{tmp}", str(tmp)) for arg in argv]
        before = set(tmp.rglob("*"))
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(argv)
        created = set(tmp.rglob("*")) - before
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    text = err.getvalue()
    assert code in (0, 2), (argv, code, text)
    assert "Traceback" not in text + out.getvalue(), (argv, text)
    lines = text.strip().splitlines()
    assert all(line.startswith("bild-mdo") for line in lines), (argv, text)
    if code == 2:
        errors = [line for line in lines if not line.startswith("bild-mdo: warning:")]
        assert len(errors) == 1 and " error: " in errors[0], (argv, text)
        assert not created, (argv, created)  # a failed run leaves no file behind


@FUZZ
@given(argv=design_argv())
def test_design_arguments(argv):
    _run(argv)


@FUZZ
@given(argv=analyze_argv())
def test_analyze_arguments(argv):
    _run(argv)


@FUZZ
@given(argv=compare_argv())
def test_compare_arguments(argv):
    _run(argv)


@settings(max_examples=30 * SCALE, deadline=None, database=None)
@given(argv=JUNK)
def test_junk_arguments(argv):
    if "demo" in argv and "--help" not in argv and "--version" not in argv:
        argv = argv + ["--output-dir", "{tmp}/blade.csv"]  # keep the demo from running: its folder is a file
    _run(argv)
