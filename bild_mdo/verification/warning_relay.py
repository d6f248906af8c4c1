"""Warnings of a sweep shown once, as the user's warning display prints them, above the progress bar.

Every worker process has its own copy of the models, so a warning such as the
polar's Reynolds-number extrapolation (warned once per polar) would otherwise print
once per worker, with a source path, in the middle of the progress bar.  The
runner records the warnings of each case (:func:`recorded_warnings`), sends
them back with the result, and :class:`WarningRelay` re-issues each distinct
warning once through :mod:`warnings` (so filters and the ``bild-mdo``
command's one-line display apply), written above the bar with ``tqdm.write``.
"""
import contextlib
import io
import re
import warnings

# Warnings that differ only in their numbers (the Reynolds range one worker saw) are one warning.
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


@contextlib.contextmanager
def recorded_warnings():
    """Record the warnings raised inside the block into a list of picklable tuples.

    Yields
    ------
    list
        Filled on exit with ``(category, message, filename, lineno)``, one per
        distinct warning (numbers ignored), in order of appearance.
    """
    records = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            yield records
        finally:
            seen = set()
            for item in caught:
                key = warning_key(item.category, str(item.message))
                if key not in seen:
                    seen.add(key)
                    records.append((item.category, str(item.message), item.filename, item.lineno))


def warning_key(category, message):
    """What makes two warnings the same: category and text with every number replaced by '#'."""
    return getattr(category, "__name__", str(category)), _NUMBER.sub("#", message)


class WarningRelay:
    """Shows each distinct warning of a sweep once.

    Attributes
    ----------
    shown : list of str
        The messages shown so far, in order.
    """

    def __init__(self):
        self.shown = []
        self._seen = set()

    def show(self, records):
        """Re-issue the records not shown before.

        Parameters
        ----------
        records : iterable of tuple
            ``(category, message, filename, lineno)`` as :func:`recorded_warnings` gives.
        """
        for category, message, filename, lineno in records:
            key = warning_key(category, message)
            if key in self._seen:
                continue
            self._seen.add(key)
            self.shown.append(message)
            if not (isinstance(category, type) and issubclass(category, Warning)):
                category = UserWarning
            # No registry: the relay's own once-per-sweep rule replaces the per-module one.
            warnings.warn_explicit(message, category, filename, lineno, registry=None)

    @contextlib.contextmanager
    def above(self, bar):
        """While the block runs, warnings print above ``bar`` (a tqdm bar, or None for no bar)."""
        if bar is None:
            yield
            return
        previous = warnings.showwarning

        def show_above_bar(message, category, filename, lineno, file=None, line=None):
            buffer = io.StringIO()
            previous(message, category, filename, lineno, file=buffer, line=line)
            # tqdm.write (a class method, reached through the bar) clears the bar, prints and redraws it.
            bar.write(buffer.getvalue().rstrip("\n"), file=bar.fp)

        warnings.showwarning = show_above_bar
        try:
            yield
        finally:
            warnings.showwarning = previous
