"""Remember that PETSc's Python binding is not installed, so OpenMDAO does not search for it on every call.

OpenMDAO (3.45) tries ``from petsc4py import PETSc`` in every ``compute_totals``
of a serial run (``_TotalJacInfo._compute_jac_scatters``).  Python caches a
successful import, but not a failed one: without petsc4py each call searches
the whole ``sys.path`` again, about 0.35 ms (7 % of the reverse totals of one
Reynolds-aware BILD design).  Where :func:`importlib.util.find_spec` finds no
petsc4py when bild-mdo is imported, :func:`remember_missing` records the
absence the way Python itself spells it (``sys.modules[name] = None``: the
import then raises ``ImportError`` at once, which is what OpenMDAO expects).
Nothing changes where petsc4py is installed, or where the caller has already
imported or blocked it.
"""
from __future__ import annotations

import importlib.util
import sys

#: Optional packages OpenMDAO imports on a hot path and handles the absence of.
OPTIONAL_MODULES = ("petsc4py",)


def remember_missing(names=OPTIONAL_MODULES):
    """Record each module of ``names`` that is not installed as missing (module docstring); returns those names."""
    missing = []
    for name in names:
        if name in sys.modules:
            continue
        try:
            found = importlib.util.find_spec(name) is not None
        except (ImportError, ValueError):
            found = False
        if not found:
            sys.modules[name] = None
            missing.append(name)
    return tuple(missing)
