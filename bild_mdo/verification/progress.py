"""A dependency-free progress report for long sweeps.

On a terminal it redraws one line (bar, count, percent, rate, ETA) at most
every ``min_interval`` seconds; when the stream is not a terminal (a log file,
CI) it writes a plain line every ``plain_interval`` seconds instead, so logs
stay short.
"""
import sys
import time


def format_duration(seconds):
    """Format seconds as ``'42s'``, ``'3m05s'`` or ``'2h07m'``; ``'?'`` when unknown."""
    if seconds is None or seconds != seconds or seconds == float("inf"):
        return "?"
    seconds = int(round(seconds))
    if seconds < 60:
        return f"{seconds}s"
    if seconds < 3600:
        return f"{seconds // 60}m{seconds % 60:02d}s"
    return f"{seconds // 3600}h{(seconds % 3600) // 60:02d}m"


class ProgressBar:
    """Progress of ``total`` work items, written to a stream (stderr by default).

    Parameters
    ----------
    total : int
        Number of items expected.
    label : str
        Text before the bar.
    stream : file-like, optional
        Where to write; ``sys.stderr`` when omitted.
    force : bool, optional
        True draws the redrawn bar even when the stream is not a terminal,
        False always writes plain lines; None decides by ``stream.isatty()``.
    min_interval : float
        Minimum seconds between redraws of the terminal bar.
    plain_interval : float
        Seconds between plain lines when not drawing a bar.
    width : int
        Characters of the bar itself.
    clock : callable
        Returns the time in seconds (injectable for tests).
    """

    def __init__(self, total, label="", stream=None, force=None, min_interval=0.1, plain_interval=30.0, width=30,
                 clock=time.monotonic):
        self.total = max(int(total), 0)
        self.label = label
        self.stream = sys.stderr if stream is None else stream
        if force is None:
            isatty = getattr(self.stream, "isatty", None)
            force = bool(isatty and isatty())
        self.tty = force
        self.min_interval = min_interval
        self.plain_interval = plain_interval
        self.width = width
        self.clock = clock
        self.count = 0
        self.start = clock()
        self._last_write = None
        self._closed = False
        self._last_len = 0

    def rate(self):
        """Items per second so far (0 before the first item)."""
        elapsed = self.clock() - self.start
        return self.count / elapsed if elapsed > 0 else 0.0

    def eta(self):
        """Estimated seconds to finish, or None while no rate is known."""
        rate = self.rate()
        if rate <= 0:
            return None
        return max(self.total - self.count, 0) / rate

    def line(self):
        """The current status line (without line ending)."""
        pct = 100.0 * self.count / self.total if self.total else 100.0
        text = f"{self.count}/{self.total} {pct:5.1f}% {self.rate():.2f}/s ETA {format_duration(self.eta())}"
        if self.tty:
            filled = int(self.width * self.count / self.total) if self.total else self.width
            text = f"[{'#' * filled}{'.' * (self.width - filled)}] {text}"
        return f"{self.label} {text}" if self.label else text

    def update(self, n=1):
        """Add ``n`` finished items and write if the throttle allows."""
        self.count += n
        now = self.clock()
        interval = self.min_interval if self.tty else self.plain_interval
        if self._last_write is None and not self.tty:
            # A plain log gets its first line only after one interval, so short runs stay quiet.
            self._last_write = self.start
        if self._last_write is None or now - self._last_write >= interval:
            self._write()
            self._last_write = now

    def _write(self, final=False):
        if self.tty:
            text = self.line()
            # Blank out the rest of a longer previous line.
            padding = " " * max(self._last_len - len(text), 0)
            self._last_len = len(text)
            self.stream.write("\r" + text + padding + ("\n" if final else ""))
        else:
            self.stream.write(self.line() + "\n")
        self.stream.flush()

    def close(self):
        """Write the final state once (idempotent)."""
        if not self._closed:
            self._closed = True
            self._write(final=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False
