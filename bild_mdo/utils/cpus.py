"""How many CPUs this process may run on (for default worker counts)."""
from __future__ import annotations

import os


def available_cpus():
    """CPUs this process may use: its scheduler affinity where the OS has one, else ``os.cpu_count()``, at least 1.

    ``os.cpu_count()`` counts the machine's CPUs, also those a container, a batch
    scheduler or ``taskset`` keeps the process off; default worker counts from it
    oversubscribe the CPUs the process has.
    """
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)
