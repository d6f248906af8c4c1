"""The documentation site, built once per test session into a temporary folder (never into the repo).

Where the whole session collected these tests, the build began in the background when collection
ended (``tests/conftest.py``); the fixture waits for it.
"""
import importlib.util
import pathlib

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def docs_build_module():
    spec = importlib.util.spec_from_file_location("docs_build", REPO / "docs" / "build.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="session")
def docs_site(tmp_path_factory):
    """``(html folder, return code, warnings text, seconds)`` of one full build of the site."""
    from tests.conftest import DOCS_BUILD

    if "build" in DOCS_BUILD:
        module, started, folder = DOCS_BUILD["build"]
        outdir = pathlib.Path(folder.name)
        code, warnings, seconds = module.finish(started)
    else:
        outdir = tmp_path_factory.mktemp("docs")
        code, warnings, seconds = docs_build_module().build(outdir, quiet=True)
    return outdir / "html", code, warnings, seconds
