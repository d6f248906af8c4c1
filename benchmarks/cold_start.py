"""Cold-start time of ``bild-mdo design`` against a bare ``import openmdao.api``, side by side.

Each measurement is a fresh Python process (wall time of ``subprocess.run``),
so it includes interpreter start-up and every import, as a user sees it.  The
three commands are interleaved within each repetition, so a busy machine
slows all of them alike, and the ratio uses the medians:

* ``python -c "import openmdao.api"`` (the reference),
* ``bild-mdo design`` with an empty polar cache (a temporary
  ``BILD_MDO_CACHE_DIR``, emptied before every run: the surrogate is built),
* ``bild-mdo design`` with a warm cache (the surrogate is loaded).

Three ratios are printed: of the medians, of the fastest runs (least
disturbed by other load) and the median of the per-repetition ratios.

Usage::

    .venv/bin/python benchmarks/cold_start.py [--repeat 7] [--importtime]

``--importtime`` also prints the slowest imports of ``bild_mdo.cli.main``
beyond those of ``openmdao.api`` (``python -X importtime``, self times).
"""
from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections import Counter

DESIGN = [sys.executable, "-m", "bild_mdo.cli.main", "design"]
OPENMDAO = [sys.executable, "-c", "import openmdao.api"]


def _timed(cmd, env):
    t0 = time.perf_counter()
    subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - t0


def _self_times(code, env):
    out = subprocess.run([sys.executable, "-X", "importtime", "-c", code], env=env, check=True,
                         capture_output=True, text=True).stderr
    times = {}
    for line in out.splitlines():
        if line.startswith("import time:") and "self [us]" not in line:
            parts = line.split("|")
            times[parts[2].strip()] = int(parts[0].split(":")[1])
    return times


def import_report(env, top=15):
    """Self import times (ms) of the modules ``bild_mdo.cli.main`` adds to ``openmdao.api``, by package."""
    base = _self_times("import openmdao.api", env)
    cli = _self_times("import bild_mdo.cli.main", env)
    extra = Counter()
    for name, us in cli.items():
        if name not in base:
            extra[".".join(name.split(".")[:2])] += us
    print(f"\nimports beyond openmdao.api: {sum(extra.values()) / 1e3:.0f} ms (self times, one run)")
    for name, us in extra.most_common(top):
        print(f"  {us / 1e3:7.1f} ms  {name}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7, help="repetitions of each command")
    parser.add_argument("--importtime", action="store_true", help="also list the slowest extra imports")
    args = parser.parse_args(argv)

    cache = tempfile.mkdtemp(prefix="bild_cold_start_")
    env = dict(os.environ, BILD_MDO_CACHE_DIR=cache)
    try:
        _timed(DESIGN, env)  # fills the cache, warms the OS file cache
        times = {"import openmdao.api": [], "design, warm cache": [], "design, empty cache": []}
        for _ in range(args.repeat):
            times["import openmdao.api"].append(_timed(OPENMDAO, env))
            times["design, warm cache"].append(_timed(DESIGN, env))
            empty = dict(env, BILD_MDO_CACHE_DIR=tempfile.mkdtemp(prefix="bild_cold_empty_", dir=cache))
            times["design, empty cache"].append(_timed(DESIGN, empty))
            shutil.rmtree(empty["BILD_MDO_CACHE_DIR"], ignore_errors=True)
        base = times["import openmdao.api"]
        ref = statistics.median(base)
        print(f"{'command':<24}{'median s':>10}{'min s':>8}{'max s':>8}{'ratio of':>10}{'ratio of':>10}"
              f"{'median of':>11}   ({args.repeat} runs, {os.cpu_count()} cores)")
        print(f"{'':<50}{'medians':>10}{'minima':>10}{'ratios':>11}")
        for name, values in times.items():
            med = statistics.median(values)
            paired = statistics.median(v / b for v, b in zip(values, base))
            print(f"{name:<24}{med:>10.2f}{min(values):>8.2f}{max(values):>8.2f}{med / ref:>10.2f}"
                  f"{min(values) / min(base):>10.2f}{paired:>11.2f}")
        if args.importtime:
            import_report(env)
    finally:
        shutil.rmtree(cache, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
