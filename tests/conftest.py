"""Session-wide test settings.

The polar cache (built surrogates, XFOIL polars) goes to a folder of this test session, not the
user's cache: set before any test imports bild_mdo's cache module, and inherited by the
subprocesses that CLI and sweep tests start.

Where the session collects the documentation tests (``tests/docs``), the site's build (about two
minutes, most of it on one core) starts in a subprocess as soon as collection ends, and those tests
run last: the build uses the core the other tests leave idle (``tests/docs/conftest.py`` waits for it).
"""
import os
import pathlib
import tempfile

import pytest

_CACHE = tempfile.TemporaryDirectory(prefix="bild-mdo-test-cache-")
os.environ["BILD_MDO_CACHE_DIR"] = _CACHE.name

_DOCS_TESTS = pathlib.Path(__file__).resolve().parent / "docs"
#: The background build of the site, under "build": ``(build module, started build, output folder)``.
DOCS_BUILD = {}


@pytest.hookimpl(trylast=True)  # after -k / -m have deselected what they deselect
def pytest_collection_modifyitems(session, config, items):
    docs = [item for item in items if _DOCS_TESTS in pathlib.Path(str(item.path)).parents]
    if not docs or config.option.collectonly:
        return
    items[:] = [item for item in items if item not in docs] + docs
    from tests.docs.conftest import docs_build_module

    module = docs_build_module()
    folder = tempfile.TemporaryDirectory(prefix="bild-mdo-test-docs-")
    log = pathlib.Path(folder.name) / "build-output.txt"  # not the terminal, where pytest reports
    DOCS_BUILD["build"] = (module, module.start(folder.name, quiet=True, log=log), folder)


def pytest_unconfigure(config):
    started = DOCS_BUILD.pop("build", None)
    if started is not None:
        proc = started[1][0]
        if proc.poll() is None:  # the session ended before the docs tests waited for it
            proc.terminate()
            proc.wait()
        started[2].cleanup()
