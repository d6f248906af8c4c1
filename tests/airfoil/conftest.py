"""Every airfoil test uses a polar cache in a temporary folder, never the user's."""
import pytest

from bild_mdo.airfoil.cache import CACHE_ENV


@pytest.fixture(scope="session")
def session_cache(tmp_path_factory):
    return tmp_path_factory.mktemp("polar_cache")


@pytest.fixture(autouse=True)
def polar_cache(session_cache, monkeypatch):
    """The session's cache folder in ``BILD_MDO_CACHE_DIR`` (built surrogates are shared by the tests)."""
    monkeypatch.setenv(CACHE_ENV, str(session_cache))
    return session_cache
