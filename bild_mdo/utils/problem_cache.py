"""A small least-recently-used cache of set-up OpenMDAO problems, keyed by configuration and polar.

Setting up a problem costs far more than running it, so the plain-Python entry points keep a few set-up
problems by configuration and reuse them.  The polar is part of the key by identity; since ``id()`` can be
reused after an object dies, the cache keeps the polar beside the problem and compares it on every hit.
"""
from __future__ import annotations

import collections


class ProblemCache:
    """Up to ``size`` set-up problems, least recently used evicted first."""

    def __init__(self, size):
        self.size = int(size)
        self._entries = collections.OrderedDict()

    def get(self, key, polar, make):
        """The cached problem of ``(key, polar)``, or ``make()`` set up and stored for it."""
        full = (key, id(polar))
        hit = self._entries.get(full)
        if hit is not None and hit[0] is polar:
            self._entries.move_to_end(full)
            return hit[1]
        prob = make()
        self._entries[full] = (polar, prob)
        while len(self._entries) > self.size:
            self._entries.popitem(last=False)
        return prob

    def clear(self):
        """Forget every cached problem (frees their memory)."""
        self._entries.clear()
