"""available_cpus: the CPUs the process may run on, not the machine's (definition of the scheduler affinity)."""
import os

import pytest

from bild_mdo.utils.cpus import available_cpus


def test_counts_the_affinity_not_the_machine(monkeypatch):
    # A process pinned to CPUs 2 and 5 of a larger machine may use two of them.
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {2, 5}, raising=False)
    monkeypatch.setattr(os, "cpu_count", lambda: 64)
    assert available_cpus() == 2


def test_falls_back_to_the_cpu_count_without_affinity(monkeypatch):
    monkeypatch.delattr(os, "sched_getaffinity", raising=False)
    monkeypatch.setattr(os, "cpu_count", lambda: 8)
    assert available_cpus() == 8


@pytest.mark.parametrize("count", [None, 0])
def test_at_least_one(monkeypatch, count):
    # os.cpu_count() may return None ("undetermined"); a worker count is at least 1.
    monkeypatch.delattr(os, "sched_getaffinity", raising=False)
    monkeypatch.setattr(os, "cpu_count", lambda: count)
    assert available_cpus() == 1
