"""Fixtures for the driver tests.

OpenMDAO writes coloring files and other outputs under ``<cwd>/<problem>_out``;
every test here runs inside its own ``tmp_path`` so nothing lands in the repo.
"""
import pytest


@pytest.fixture(autouse=True)
def _run_in_tmp_path(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
