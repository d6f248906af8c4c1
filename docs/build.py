"""Build the documentation site: ``python docs/build.py [OUTDIR]`` (default ``docs/_build``).

The sources are copied to ``OUTDIR/source`` first, so the pages the build generates (the API
reference) and the executed notebooks never touch the repository; the site goes to ``OUTDIR/html``
and the warnings to ``OUTDIR/warnings.txt``.  Sphinx runs with ``-W --keep-going -n``: any
warning, broken cross-reference or failing example makes the build fail (exit status 1).
"""
import os
import pathlib
import shutil
import subprocess
import sys
import time

DOCS = pathlib.Path(__file__).resolve().parent
REPO = DOCS.parent


def start(outdir, jobs="2", quiet=False, log=None):
    """Start building the site into ``outdir`` in a subprocess; :func:`finish` waits for it.  With ``log`` (a
    path) the build's own output goes to that file, not to this process's terminal."""
    outdir = pathlib.Path(outdir).resolve()
    source = outdir / "source"
    if source.exists():
        shutil.rmtree(source)
    shutil.copytree(DOCS, source, ignore=shutil.ignore_patterns("_build", "__pycache__", "*.pyc"))
    # Project files the pages include (from the repository root, outside docs/).
    shutil.copy(REPO / "CHANGELOG.md", source / "changelog_source.md")
    shutil.copy(REPO / "CITATION.cff", source / "citation_source.cff")
    warnings = outdir / "warnings.txt"
    env = dict(os.environ, BILD_MDO_REPO=str(REPO), BILD_MDO_DOCS_SOURCE=str(source))
    cmd = [sys.executable, "-m", "sphinx", "-b", "html", "-E", "-W", "--keep-going", "-n", "-j", str(jobs),
           "-w", str(warnings), "-d", str(outdir / "doctrees"), str(source), str(outdir / "html")]
    if quiet:
        cmd.insert(3, "-q")
    if log is None:
        return subprocess.Popen(cmd, env=env, cwd=outdir), warnings, time.perf_counter(), None
    with open(log, "w") as stream:  # the child keeps its own copy of the file
        proc = subprocess.Popen(cmd, env=env, cwd=outdir, stdout=stream, stderr=subprocess.STDOUT)
    return proc, warnings, time.perf_counter(), pathlib.Path(log)


def finish(started):
    """``(returncode, warnings text, seconds)`` of a build begun by :func:`start`, once it has ended; a failed
    build with a ``log`` adds the end of its output to the warnings text."""
    proc, warnings, begun, log = started
    code = proc.wait()
    seconds = time.perf_counter() - begun
    text = warnings.read_text() if warnings.exists() else ""
    if code != 0 and log is not None and log.exists():
        text += "\n--- the build's output (end) ---\n" + log.read_text()[-4000:]
    return code, text, seconds


def build(outdir, jobs="2", quiet=False):
    """Build the site into ``outdir``; return ``(returncode, warnings text, seconds)``."""
    return finish(start(outdir, jobs, quiet))


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    outdir = pathlib.Path(argv[0]) if argv else DOCS / "_build"
    outdir.mkdir(parents=True, exist_ok=True)
    code, text, seconds = build(outdir)
    count = sum(1 for line in text.splitlines() if "WARNING" in line or "ERROR" in line)
    status = "built" if code == 0 else f"FAILED (exit {code})"
    print(f"docs: {status}: {outdir / 'html' / 'index.html'} in {seconds:.0f} s, {count} warnings")
    return code


if __name__ == "__main__":
    sys.exit(main())
