"""Session-wide test settings.

The polar cache (built surrogates, XFOIL polars) goes to a folder of this test session, not the
user's cache: set before any test imports bild_mdo's cache module, and inherited by the
subprocesses that CLI and sweep tests start.
"""
import os
import tempfile

_CACHE = tempfile.TemporaryDirectory(prefix="bild-mdo-test-cache-")
os.environ["BILD_MDO_CACHE_DIR"] = _CACHE.name
