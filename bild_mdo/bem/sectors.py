"""Azimuth sectors of the inclined-flow BEM: the sector angles and the index patterns of sector arrays.

The BEM of a rotor in inclined flow (:class:`~bild_mdo.bem.inclined_bem_group.InclinedBEMGroup`)
solves every blade station at ``num_sectors`` azimuth angles ``Lambda_k = 2 pi k / num_sectors``
(``k = 0 ... ns - 1``; ``Lambda = 0``: blade pointing up, as CCBlade's ``nSector``) and averages the
loads.  The sectors are extra stations of the same design: a sector array has shape
``(nn, ns * nr)``, sector-major (flat index ``i (ns nr) + k nr + j`` for design ``i``, sector ``k``,
station ``j``), so ``array.reshape(nn, ns, nr)`` separates them and every per-design input of the
blade-element components keeps its shape ``(nn,)``.
"""
from __future__ import annotations

import numpy as np


def declare_sector_option(options):
    """Declare ``num_sectors`` (int >= 1, default 1)."""
    options.declare("num_sectors", types=int, default=1, lower=1,
                    desc="number of azimuth sectors Lambda_k = 2 pi k / num_sectors averaged (CCBlade's nSector)")


def sector_azimuths(num_sectors):
    """Azimuth angles ``2 pi k / num_sectors`` (rad), shape ``(num_sectors,)``; ``[0.0]`` for one sector."""
    return 2.0 * np.pi * np.arange(num_sectors) / num_sectors


def sector_wrt_station(num_nodes, num_sectors, num_radial):
    """Rows and columns of a sector array ``(nn, ns*nr)`` with respect to a distribution ``(nn, nr)``.

    Row ``i (ns nr) + k nr + j`` depends on column ``i nr + j`` (the same design and station).
    """
    rows = np.arange(num_nodes * num_sectors * num_radial)
    node, rest = np.divmod(rows, num_sectors * num_radial)
    return rows, node * num_radial + rest % num_radial
