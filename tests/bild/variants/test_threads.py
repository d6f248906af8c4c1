"""The local-point solves on several threads: the same stations, bit for bit, as on one.

Source: the invariant that a design in a batch equals the design alone (each design's stations are solved in
order, and nothing passes from one design to the next), so chunks of whole designs solved on separate threads
must give exactly the single-threaded result; and the contract of ``BILD_MDO_NUM_THREADS``.
"""
import numpy as np
import pytest

from bild_mdo.airfoil.load_path_table import load_path_table
from bild_mdo.bild.variants.local_paper.solve import solve_stations as solve_paper
from bild_mdo.bild.variants.local_point.kernels import design_starts
from bild_mdo.bild.variants.local_point.load_path_model import StationFlow
from bild_mdo.bild.variants.reference_point.reference_airfoil import default_polar
from bild_mdo.bild.variants.reynolds_exact.solve import solve_stations
from bild_mdo.utils import compiled
from bild_mdo.utils.compiled import MIN_CHUNK, num_threads, run_in_threads

NUM_RADIAL = 30


def _designs(count, seed=3):
    """``count`` rotors of NUM_RADIAL stations each, hub to tip (R 0.5 ... 1.5 m, hover and forward flight)."""
    rng = np.random.default_rng(seed)
    radius = np.repeat(rng.uniform(0.5, 1.5, count), NUM_RADIAL)
    r = radius * np.tile(np.linspace(0.22, 0.985, NUM_RADIAL), count)
    v_axial = np.repeat(np.where(rng.random(count) < 0.3, 0.0, rng.uniform(2.0, 40.0, count)), NUM_RADIAL)
    rpm = np.repeat(rng.uniform(600.0, 1.6e3, count), NUM_RADIAL) * 2.0 * np.pi / 60.0
    return StationFlow(lam=np.repeat(rng.uniform(4.0, 20.0, count), NUM_RADIAL), v_axial=v_axial,
                       v_theta=rpm * r, r=r, radius=radius, hub_radius=0.2 * radius, rho=np.full(r.size, 1.1),
                       mu=np.full(r.size, 1.8e-5), num_blades=3, loss_model="tip_hub", chord_form="thrust")


def _same(a, b):
    for name in ("x0", "label", "status", "values"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)


@pytest.fixture(scope="module")
def table():
    return load_path_table(default_polar())


@pytest.mark.parametrize("solve", [solve_stations, solve_paper], ids=["exact", "paper"])
def test_threads_give_the_single_threaded_stations(solve, table, monkeypatch):
    flow = _designs(3 * MIN_CHUNK // NUM_RADIAL + 7)  # three chunks, none ending on a multiple of the chunk size
    monkeypatch.setenv("BILD_MDO_NUM_THREADS", "1")
    one = solve(table, flow)
    calls = []
    original = run_in_threads

    def spy(call, starts, count):
        original(lambda begin, end: (calls.append((begin, end)), call(begin, end)), starts, count)

    module = solve.__module__
    monkeypatch.setattr("bild_mdo.utils.compiled.run_in_threads", spy)
    monkeypatch.setenv("BILD_MDO_NUM_THREADS", "3")
    several = solve(table, flow)
    assert len(calls) == 3, module  # the solve did run in three chunks
    assert all(begin % NUM_RADIAL == 0 for begin, _ in calls)  # each a run of whole designs
    assert (one.status == 0).mean() > 0.9  # mostly loaded stations: the comparison means something
    _same(one, several)


def test_a_warm_started_batch_on_threads_is_the_one_on_one_thread(table, monkeypatch):
    flow = _designs(2 * MIN_CHUNK // NUM_RADIAL + 3, seed=8)
    cold = solve_stations(table, flow)
    moved = flow._replace(lam=flow.lam * (1.0 + 1e-4))
    runs = []
    for threads in ("1", "2"):
        monkeypatch.setenv("BILD_MDO_NUM_THREADS", threads)
        runs.append(solve_stations(table, moved, start=cold.phi, first_label=cold.label))
    _same(*runs)


def test_chunks_begin_at_the_first_station_of_a_design(monkeypatch):
    flow = _designs(5)
    rows = np.stack([np.asarray(getattr(flow, name), dtype=float) for name in StationFlow._fields[:8]])
    np.testing.assert_array_equal(design_starts(rows), np.arange(5) * NUM_RADIAL)
    count = 10 * MIN_CHUNK
    starts = np.arange(0, count, 997)  # designs of 997 stations
    monkeypatch.setenv("BILD_MDO_NUM_THREADS", "4")
    chunks = []
    run_in_threads(lambda begin, end: chunks.append((begin, end)), starts, count)
    chunks.sort()
    assert len(chunks) == 4 and chunks[0][0] == 0 and chunks[-1][1] == count
    assert all(a[1] == b[0] for a, b in zip(chunks, chunks[1:]))  # every station once
    assert all(begin in set(starts) for begin, _ in chunks)
    chunks.clear()
    run_in_threads(lambda begin, end: chunks.append((begin, end)), starts, 2 * MIN_CHUNK - 1)
    assert chunks == [(0, 2 * MIN_CHUNK - 1)]  # too few stations for two chunks: the calling thread


def test_the_thread_setting(monkeypatch):
    monkeypatch.setenv("BILD_MDO_NUM_THREADS", "2")
    assert num_threads() == 2
    monkeypatch.delenv("BILD_MDO_NUM_THREADS")
    assert 1 <= num_threads() <= 8
    monkeypatch.setenv("OMPI_COMM_WORLD_LOCAL_SIZE", "64")  # 64 MPI ranks on this machine: one thread each
    assert num_threads() == 1
    monkeypatch.delenv("OMPI_COMM_WORLD_LOCAL_SIZE")
    for bad in ("0", "two", "-1"):
        monkeypatch.setenv("BILD_MDO_NUM_THREADS", bad)
        with pytest.raises(ValueError, match="BILD_MDO_NUM_THREADS must be a whole number >= 1"):
            compiled.num_threads()


def test_a_bad_thread_setting_is_one_line_of_the_cli(capsys, monkeypatch):
    from tests.cli.runner import run

    monkeypatch.setenv("BILD_MDO_NUM_THREADS", "two")
    code, out, err = run(capsys, "design", "--section-point", "local", "--radius", "1.5", "--ref-chord", "0.1")
    assert code == 2 and "Traceback" not in err
    assert "BILD_MDO_NUM_THREADS must be a whole number >= 1, not 'two'" in err and len(err.strip().splitlines()) == 1
