"""The package's cache folder on disk (polars, load-path tables, compiled kernels).

Its entries are described where they are written: :mod:`bild_mdo.airfoil.cache` (arrays keyed by a hash of
what made them) and :mod:`bild_mdo.utils.compiled` (numba's compiled functions).
"""
from __future__ import annotations

import os
from pathlib import Path

#: Environment variable that overrides the cache folder.
CACHE_ENV = "BILD_MDO_CACHE_DIR"

# Layout version of the cache folder itself (bump to abandon every old entry).
_LAYOUT = "v1"


def cache_dir():
    """The cache folder (not created here).

    Returns
    -------
    Path
        ``$BILD_MDO_CACHE_DIR`` if set and not empty, else
        ``platformdirs.user_cache_dir("bild-mdo")``, with the layout version
        appended.
    """
    override = os.environ.get(CACHE_ENV, "").strip()
    if override:
        base = Path(override).expanduser()
    else:
        import platformdirs  # a few ms; only needed when no override is set
        base = Path(platformdirs.user_cache_dir("bild-mdo"))
    return base / _LAYOUT
