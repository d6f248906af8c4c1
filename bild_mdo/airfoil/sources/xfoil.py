"""Run Mark Drela's XFOIL to make airfoil polars.

XFOIL (Debian package ``xfoil``) opens a graphics window even in batch use,
so it is run under a virtual X server: ``xvfb-run -a xfoil`` (Debian package
``xvfb``).  XFOIL's own no-graphics switch ``PLOP G F`` crashes the Debian
build and is not used.

For every Reynolds number the requested angles are run in two sweeps that
both start next to alpha = 0, one upward and one downward, because each
viscous point starts from the previous boundary layer and attached flow near
zero lift is the easiest starting point.  The boundary layer is reset between
sweeps and Reynolds numbers.  A point that does not converge is missing from
XFOIL's polar file; it is dropped and counted.  If XFOIL crashes (it can
stop on a floating-point exception deep in stall), the points of the sweep
that crashed are dropped and XFOIL is restarted for the remaining sweeps.

Command line (writes one plain table per Reynolds number, the format read by
:func:`bild_mdo.airfoil.sources.readers.read_polar_table`; the ``# reynolds``,
``# mach``, ``# ncrit`` comment lines make it self-describing)::

    python -m bild_mdo.airfoil.sources.xfoil --airfoil 4412 --re 5e4 1e5 --alpha -10 20 0.25 --out DIR

Files are named ``<name>_re<Re>.txt``, e.g. ``naca4412_re100000.txt``, the
naming :func:`bild_mdo.airfoil.sources.readers.load_builtin_polars` expects.  The
reader refuses files with fewer than 10 points, so ask for at least 10 angles.
"""
from __future__ import annotations

import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

from bild_mdo.airfoil.sources.coordinates import parse_airfoil, read_coordinates
from bild_mdo.airfoil.sources.polar_data import PolarData
from bild_mdo.airfoil.sources.readers import parse_xfoil_file, write_polar_table

__all__ = ["main", "polar_file_name", "require_programs", "run_xfoil", "xfoil_version"]

INSTALL_HINT = "apt-get install xfoil xvfb"

# XFOIL prints alpha with three decimals in its polar file.
_ALPHA_DECIMALS = 3
_ALPHA_MATCH_TOL = 0.6 * 10.0 ** -_ALPHA_DECIMALS

_VERSION = re.compile(r"XFOIL\s+Version\s+([\w.]+)")


def require_programs():
    """Raise ``RuntimeError`` (with the install command) unless ``xfoil`` and ``xvfb-run`` are on PATH."""
    _require_programs()


def _require_programs():
    missing = [p for p in ("xfoil", "xvfb-run") if shutil.which(p) is None]
    if missing:
        raise RuntimeError(
            f"the XFOIL runner needs the programs 'xfoil' and 'xvfb-run' on PATH; missing: "
            f"{', '.join(missing)}. On Debian/Ubuntu install them with: {INSTALL_HINT}")


def _alpha_sweeps(alpha_deg):
    alpha = np.unique(np.round(np.asarray(alpha_deg, dtype=float).ravel(), _ALPHA_DECIMALS))
    if alpha.size == 0:
        raise ValueError("alpha_deg is empty")
    if not np.isfinite(alpha).all() or np.abs(alpha).max() > 90.0:
        raise ValueError("alpha_deg must be finite angles in degrees within [-90, 90]")
    return alpha[alpha >= 0.0], alpha[alpha < 0.0][::-1]


def _fmt(x):
    return f"{x:.{_ALPHA_DECIMALS}f}"


def _session_script(geometry_cmds, sweeps, mach, ncrit, max_iter):
    """XFOIL keystrokes for a list of sweeps ``(reynolds, alphas, polar_file)``."""
    lines = list(geometry_cmds) + [
        "PANE",
        "OPER",
        f"ITER {int(max_iter)}",
        f"MACH {mach:.6g}",
        f"VISC {sweeps[0][0]:.6g}",
        "VPAR",
        f"N {ncrit:.6g}",
        "",
    ]
    current_re = sweeps[0][0]
    for k, (reynolds, alphas, polar_file) in enumerate(sweeps):
        if k > 0:
            # INIT toggles XFOIL's "BL initialised" flag, which is set after the
            # previous sweep solved a point, so this forces a fresh BL.
            lines.append("INIT")
        if reynolds != current_re:
            lines.append(f"RE {reynolds:.6g}")
            current_re = reynolds
        lines += ["PACC", polar_file, ""]
        lines += [f"ALFA {_fmt(a)}" for a in alphas]
        # XFOIL keeps at most 12 polars in memory and aborts on the 13th;
        # the file already holds the points, so drop the stored copy.
        lines += ["PACC", "PDEL 1"]
    lines += ["", "QUIT", ""]
    return "\n".join(lines)


def _run_session(script, workdir, timeout):
    """Run one XFOIL process; return (stdout text, problem or None)."""
    cmd = ["xvfb-run", "-a", "xfoil"]
    proc = subprocess.Popen(cmd, cwd=workdir, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True, start_new_session=True)
    try:
        out, _ = proc.communicate(script, timeout=timeout)
    except subprocess.TimeoutExpired:
        # xvfb-run starts Xvfb and xfoil as children: end the whole group.
        os.killpg(proc.pid, signal.SIGKILL)
        out, _ = proc.communicate()
        return out or "", f"timed out after {timeout:g} s"
    if proc.returncode != 0 or "Floating point exception" in out or "Program received signal" in out:
        return out, f"exited with status {proc.returncode}"
    return out, None


def xfoil_version():
    """The version string XFOIL prints at start-up, e.g. ``'6.99'``."""
    _require_programs()
    with tempfile.TemporaryDirectory(prefix="bild_xfoil_") as tmp:
        out, _ = _run_session("QUIT\n", tmp, 60.0)
    m = _VERSION.search(out)
    if not m:
        raise RuntimeError(f"could not read the XFOIL version from its output:\n{out[-2000:]}")
    return m.group(1)


def run_xfoil(airfoil, reynolds_list, alpha_deg, mach=0.0, ncrit=9.0, max_iter=200, timeout=None):
    """Compute viscous polars with XFOIL at several Reynolds numbers.

    Parameters
    ----------
    airfoil : str or os.PathLike
        NACA 4-digit designation (``"NACA 4412"``, ``"naca4412"``, ``"4412"``)
        or the path of a Selig-format coordinates file.  The geometry is
        re-panelled with XFOIL's ``PANE`` in both cases.
    reynolds_list : sequence of float
        Chord Reynolds numbers (> 0).
    alpha_deg : array_like
        Angles of attack (deg), any order; rounded to 0.001 deg (XFOIL's
        output precision), duplicates removed.
    mach : float
        Free-stream Mach number, 0 <= mach < 1.
    ncrit : float
        e^N transition amplification factor (9: average wind tunnel).
    max_iter : int
        XFOIL viscous iteration limit per point (``ITER``).
    timeout : float, optional
        Limit in seconds for one XFOIL process.  Default: 60 s plus 2 s per
        requested point.

    Returns
    -------
    polars : list of PolarData
        One per Reynolds number, in the order of ``reynolds_list``; only the
        converged points, sorted by alpha.
    report : dict
        ``{reynolds: number of requested angles dropped}`` (not converged, or
        lost in a crash).

    Raises
    ------
    RuntimeError
        ``xfoil`` or ``xvfb-run`` is not installed (the message gives the
        install command), or no angle converged at some Reynolds number.
    ValueError
        Invalid airfoil, Reynolds numbers, angles or settings.
    """
    kind, spec = parse_airfoil(airfoil)
    reynolds = [float(r) for r in np.atleast_1d(np.asarray(reynolds_list, dtype=float))]
    if not reynolds or not all(np.isfinite(r) and r > 0.0 for r in reynolds):
        raise ValueError(f"reynolds_list must hold finite Reynolds numbers > 0, got {reynolds_list!r}")
    if len(set(reynolds)) != len(reynolds):
        raise ValueError(f"reynolds_list has duplicates: {reynolds_list!r}")
    if not (np.isfinite(mach) and 0.0 <= mach < 1.0):
        raise ValueError(f"mach must be in [0, 1), got {mach!r}")
    if not (np.isfinite(ncrit) and ncrit > 0.0):
        raise ValueError(f"ncrit must be > 0, got {ncrit!r}")
    if int(max_iter) < 1:
        raise ValueError(f"max_iter must be >= 1, got {max_iter!r}")
    up, down = _alpha_sweeps(alpha_deg)
    n_alpha = up.size + down.size
    if timeout is None:
        timeout = 60.0 + 2.0 * n_alpha * len(reynolds)
    _require_programs()

    if kind == "naca":
        label = f"NACA {spec}"
    else:
        name, xy = read_coordinates(spec)
        label = name or spec.stem

    # Each sweep: (Re index, alphas, polar file name); XFOIL is happiest with
    # short relative file names, so everything lives in a temporary folder.
    sweeps = []
    for i, r in enumerate(reynolds):
        for tag, alphas in (("up", up), ("down", down)):
            if alphas.size:
                sweeps.append((i, alphas, f"polar_{i}_{tag}.txt"))

    rows = {i: [] for i in range(len(reynolds))}
    version = None
    with tempfile.TemporaryDirectory(prefix="bild_xfoil_") as tmp:
        if kind == "naca":
            geometry = [f"NACA {spec}"]
        else:
            coords = ["airfoil"] + [f"{x: .7f} {y: .7f}" for x, y in xy]
            Path(tmp, "airfoil.dat").write_text("\n".join(coords) + "\n", encoding="ascii")
            geometry = ["LOAD airfoil.dat"]
        start = 0
        while start < len(sweeps):
            todo = sweeps[start:]
            script = _session_script(geometry, [(reynolds[i], a, f) for i, a, f in todo],
                                     mach, ncrit, max_iter)
            out, problem = _run_session(script, tmp, timeout)
            if version is None and (m := _VERSION.search(out)):
                version = m.group(1)
            done = [k for k, (_, _, f) in enumerate(todo) if Path(tmp, f).exists()]
            if problem is None:
                start = len(sweeps)
            else:
                # The last sweep that opened its polar file is where XFOIL
                # stopped; its missing points count as dropped.
                last = done[-1] if done else 0
                i_re, alphas, _ = todo[last]
                warnings.warn(f"XFOIL {problem} during the {'up' if alphas[0] >= 0 else 'down'}ward "
                              f"sweep at Re = {reynolds[i_re]:g}; restarting XFOIL for the remaining "
                              f"sweeps. Last output:\n{out[-1500:]}", RuntimeWarning, stacklevel=2)
                start += last + 1
            for k in done:
                i_re, _, fname = todo[k]
                _, _, _, _, file_rows = parse_xfoil_file(Path(tmp, fname), lenient=True)
                rows[i_re].extend((a, cl, cd) for _, a, cl, cd in file_rows)

    requested = np.concatenate([down[::-1], up])
    polars, report = [], {}
    for i, r in enumerate(reynolds):
        data = np.array(rows[i], dtype=float).reshape(-1, 3)
        keep = []
        for a in requested:
            hit = np.flatnonzero(np.abs(data[:, 0] - a) < _ALPHA_MATCH_TOL)
            if hit.size:
                keep.append(hit[0])
        report[r] = int(requested.size - len(keep))
        if not keep:
            raise RuntimeError(f"XFOIL converged at no angle of attack for {label} at Re = {r:g} "
                               f"(dropped per Re: {report}); try other angles, a larger max_iter, or "
                               f"check the airfoil geometry")
        data = data[keep]
        polars.append(PolarData(
            reynolds=r, mach=mach, alpha_deg=data[:, 0], cl=data[:, 1], cd=data[:, 2], ncrit=ncrit,
            source=f"XFOIL {version or '(version unknown)'} {label} Re={r:g} Mach={mach:g} "
                   f"Ncrit={ncrit:g} ITER={int(max_iter)} (bild_mdo.airfoil.sources.xfoil)"))
    return polars, report


def _alpha_grid(start, stop, step):
    if step <= 0.0 or stop < start:
        raise ValueError(f"--alpha START STOP STEP needs STOP >= START and STEP > 0, "
                         f"got {start} {stop} {step}")
    n = int(round((stop - start) / step))
    if not np.isclose(start + n * step, stop, atol=1e-9):
        raise ValueError(f"--alpha: (STOP - START) / STEP must be a whole number, got {start} {stop} {step}")
    return np.round(start + step * np.arange(n + 1), _ALPHA_DECIMALS)


def polar_file_name(name, reynolds, mach=None):
    """File name ``<name>_re<Re>.txt`` (with ``mach``: ``<name>_re<Re>_mach<M>.txt``) used by the CLI and the built-in data."""
    suffix = "" if mach is None else f"_mach{mach:g}"
    return f"{name}_re{int(round(reynolds))}{suffix}.txt"


def main(argv=None):
    """Command-line entry point; see the module docstring."""
    parser = argparse.ArgumentParser(
        prog="python -m bild_mdo.airfoil.sources.xfoil",
        description="Run XFOIL (under xvfb-run) and write one polar table per Reynolds (and Mach) number.")
    parser.add_argument("--airfoil", required=True,
                        help="NACA 4- or 5-digit designation ('4412', 'NACA 23012') or a Selig coordinates file")
    parser.add_argument("--re", required=True, nargs="+", type=float, metavar="RE",
                        help="chord Reynolds numbers")
    parser.add_argument("--alpha", required=True, nargs=3, type=float, metavar=("START", "STOP", "STEP"),
                        help="angle-of-attack grid in degrees, STOP included")
    parser.add_argument("--out", required=True, type=Path, help="output folder (created if missing)")
    parser.add_argument("--mach", type=float, nargs="+", default=[0.0], metavar="M",
                        help="Mach number(s) (default 0); several write one table per Reynolds and Mach "
                             "number, named <name>_re<Re>_mach<M>.txt (a Mach-dependent polar set)")
    parser.add_argument("--ncrit", type=float, default=9.0, help="e^N amplification factor (default 9)")
    parser.add_argument("--max-iter", type=int, default=200, help="XFOIL iteration limit per point")
    parser.add_argument("--name", default=None,
                        help="file name prefix (default: naca<digits> or the coordinates file stem)")
    args = parser.parse_args(argv)

    try:
        kind, spec = parse_airfoil(args.airfoil)
        alpha = _alpha_grid(*args.alpha)
    except ValueError as exc:
        parser.error(str(exc))
    name = args.name or (f"naca{spec}" if kind == "naca" else spec.stem.lower())
    several = len(args.mach) > 1
    for mach in args.mach:
        t0 = time.perf_counter()
        try:
            polars, report = run_xfoil(args.airfoil, args.re, alpha, mach=mach, ncrit=args.ncrit,
                                       max_iter=args.max_iter)
        except ValueError as exc:
            parser.error(str(exc))
        elapsed = time.perf_counter() - t0
        args.out.mkdir(parents=True, exist_ok=True)
        print(f"XFOIL {xfoil_version()}, {name}, {alpha.size} angles {alpha[0]:g}..{alpha[-1]:g} deg, "
              f"Mach {mach:g}, Ncrit {args.ncrit:g}, {elapsed:.1f} s")
        print(f"{'Re':>10} {'points':>6} {'dropped':>7} {'max L/D':>8} {'at alpha':>8}")
        for polar in polars:
            path = args.out / polar_file_name(name, polar.reynolds, mach if several else None)
            write_polar_table(path, polar)
            ld = polar.lift_to_drag
            k = int(np.argmax(ld))
            print(f"{polar.reynolds:>10g} {polar.alpha_deg.size:>6d} {report[polar.reynolds]:>7d} "
                  f"{ld[k]:>8.1f} {polar.alpha_deg[k]:>8.2f}  -> {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
