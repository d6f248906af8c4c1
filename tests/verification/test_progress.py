import io

from bild_mdo.verification.progress import ProgressBar, format_duration


class FakeClock:
    def __init__(self):
        self.now = 100.0

    def __call__(self):
        return self.now


def test_terminal_bar_shows_count_percent_rate_eta_and_is_throttled():
    clock, stream = FakeClock(), io.StringIO()
    bar = ProgressBar(200, label="optimise", stream=stream, force=True, min_interval=0.5, width=10, clock=clock)
    clock.now += 10.0
    bar.update(50)
    # 50 of 200 in 10 s: 25 %, 5 items/s, 150 left -> 30 s.
    assert stream.getvalue() == "\roptimise [##........] 50/200  25.0% 5.00/s ETA 30s"
    clock.now += 0.1
    bar.update(1)
    assert stream.getvalue().count("\r") == 1  # within min_interval: not redrawn
    clock.now += 1.0
    bar.update(149)
    bar.close()
    bar.close()
    assert stream.getvalue().count("\n") == 1  # closed once
    # 200 items in 11.1 s: 18.02/s.
    assert stream.getvalue().rstrip("\n").endswith("200/200 100.0% 18.02/s ETA 0s")


def test_plain_lines_when_not_a_terminal():
    clock, stream = FakeClock(), io.StringIO()
    bar = ProgressBar(1000, stream=stream, plain_interval=30.0, clock=clock)
    assert not bar.tty  # StringIO is not a TTY
    for _ in range(100):
        clock.now += 1.0
        bar.update()
    # One line per 30 s of the 100 s, no carriage returns and no bar.
    lines = stream.getvalue().splitlines()
    assert len(lines) == 3 and "\r" not in stream.getvalue() and "[" not in lines[0]
    assert lines[0] == "30/1000   3.0% 1.00/s ETA 16m10s"


def test_format_duration():
    assert [format_duration(s) for s in (None, float("nan"), 42.4, 185, 7620)] == ["?", "?", "42s", "3m05s", "2h07m"]
