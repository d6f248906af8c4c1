"""Index patterns for the sparse partials of ``(num_nodes, num_radial)`` components.

Every component in bild-mdo stores per-design scalars with shape ``(nn,)`` and
radial distributions with shape ``(nn, nr)`` (row-major, so the flat index of
station ``j`` of node ``i`` is ``i * nr + j``).  These helpers return the
``rows``/``cols`` arrays for ``declare_partials`` so that no component writes
the patterns out by hand.
"""
import numpy as np


def diag(n):
    """rows = cols for an elementwise partial of ``n`` entries."""
    ar = np.arange(n)
    return ar, ar


def dist_wrt_dist(num_nodes, num_radial):
    """Elementwise partial of a ``(nn, nr)`` output with respect to a ``(nn, nr)`` input."""
    return diag(num_nodes * num_radial)


def dist_wrt_node(num_nodes, num_radial):
    """Partial of a ``(nn, nr)`` output with respect to a per-node ``(nn,)`` input."""
    rows = np.arange(num_nodes * num_radial)
    cols = np.repeat(np.arange(num_nodes), num_radial)
    return rows, cols


def node_wrt_dist(num_nodes, num_radial):
    """Partial of a per-node ``(nn,)`` output with respect to a ``(nn, nr)`` input (e.g. an integral)."""
    rows = np.repeat(np.arange(num_nodes), num_radial)
    cols = np.arange(num_nodes * num_radial)
    return rows, cols


def node_wrt_node(num_nodes):
    """Elementwise partial of a ``(nn,)`` output with respect to a ``(nn,)`` input."""
    return diag(num_nodes)


def dist_wrt_station(num_nodes, num_radial):
    """Partial of a ``(nn, nr)`` output with respect to a ``(nr,)`` input shared by all nodes."""
    rows = np.arange(num_nodes * num_radial)
    cols = np.tile(np.arange(num_radial), num_nodes)
    return rows, cols
