"""Run a vectorised batch once, and isolate the members that make it raise (the one bisection in bild-mdo).

A vectorised model fails as a whole when one member raises (an AnalysisError
of one design or operating point).  :func:`isolate_failures` runs the whole
batch once; only if that raises does it split the batch in halves, again and
again, until every failing member stands alone with its own error and every
other member has its result from a run that succeeded.
"""
import numpy as np


def isolate_failures(run, indices, errors):
    """Run ``run(indices)``; where it raises one of ``errors``, bisect down to the failing members.

    Parameters
    ----------
    run : callable
        ``run(part) -> result`` for an integer array ``part`` of member indices.
        It must return everything it computes (a reused model is overwritten by
        the next run).
    indices : array_like of int
        The members of the batch.
    errors : exception class or tuple of them
        What counts as a member's failure; anything else propagates.

    Returns
    -------
    successes : list of (ndarray, object)
        The index arrays of the runs that succeeded and their results; together
        with the failures they cover ``indices`` once.
    failures : list of (int, Exception)
        Each failing member and the error of its run alone.
    """
    successes, failures = [], []
    pending = [np.asarray(indices, dtype=int)]
    while pending:
        part = pending.pop()
        try:
            successes.append((part, run(part)))
        except errors as exc:
            if part.size == 1:
                failures.append((int(part[0]), exc))
            else:
                half = part.size // 2
                pending += [part[half:], part[:half]]
    return successes, failures
