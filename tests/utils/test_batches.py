"""The one batch bisection: every member is either in a successful run or fails alone."""
import numpy as np
import pytest

from bild_mdo.utils.batches import isolate_failures


def test_failing_members_are_isolated_and_the_rest_computed_once():
    failing = {2, 5}
    runs = []

    def run(part):
        runs.append(part.tolist())
        if failing & set(part.tolist()):
            raise ArithmeticError(f"member {sorted(failing & set(part.tolist()))[0]}")
        return part * 10

    successes, failures = isolate_failures(run, np.arange(8), ArithmeticError)
    assert sorted(i for i, _ in failures) == [2, 5]
    assert all(str(exc) == f"member {i}" for i, exc in failures)
    done = np.concatenate([part for part, _ in successes])
    assert sorted(done.tolist()) == [0, 1, 3, 4, 6, 7]          # each other member exactly once
    assert all(np.array_equal(result, part * 10) for part, result in successes)
    assert runs[0] == list(range(8))                            # the whole batch is tried first


def test_a_clean_batch_runs_once_and_other_errors_propagate():
    calls = []
    successes, failures = isolate_failures(lambda part: calls.append(part) or part.sum(), np.arange(4), ValueError)
    assert len(calls) == 1 and failures == [] and successes[0][1] == 6
    with pytest.raises(KeyError):
        isolate_failures(lambda part: {}["x"], np.arange(4), ValueError)
