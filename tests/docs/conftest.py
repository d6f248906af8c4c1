"""The documentation site, built once per test session into a temporary folder (never into the repo)."""
import importlib.util
import pathlib

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def _docs_build_module():
    spec = importlib.util.spec_from_file_location("docs_build", REPO / "docs" / "build.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="session")
def docs_site(tmp_path_factory):
    """``(html folder, return code, warnings text, seconds)`` of one full build of the site."""
    outdir = tmp_path_factory.mktemp("docs")
    code, warnings, seconds = _docs_build_module().build(outdir, quiet=True)
    return outdir / "html", code, warnings, seconds
