"""Warnings of a sweep: one line each, once, written above the progress bar."""
import io
import warnings

from tqdm import tqdm

from bild_mdo.verification.warning_relay import WarningRelay, recorded_warnings, warning_key


def _one_line(message, category, filename, lineno, file=None, line=None):
    # The display a command installs (bild-mdo prints "bild-mdo: warning: <message>").
    print(f"warning: {message}", file=file)


def test_same_warning_with_other_numbers_is_one_warning():
    assert warning_key(UserWarning, "clamped (seen 3.47e+04..1.172e+05)") == \
        warning_key(UserWarning, "clamped (seen 4.955e+04..2.253e+05)")
    assert warning_key(UserWarning, "a") != warning_key(RuntimeWarning, "a")


def test_recorded_once_and_shown_once_above_the_bar(monkeypatch):
    with recorded_warnings() as first:
        for k in range(3):
            warnings.warn(f"clamped (seen {k}..{k + 1})", UserWarning)
    with recorded_warnings() as second:
        warnings.warn("clamped (seen 7..8)", UserWarning)
        warnings.warn("another thing", RuntimeWarning)
    assert [r[1] for r in first] == ["clamped (seen 0..1)"]

    stream = io.StringIO()
    monkeypatch.setattr(warnings, "showwarning", _one_line)
    relay = WarningRelay()
    bar = tqdm(total=2, file=stream, ascii=True, mininterval=0)
    with warnings.catch_warnings():
        warnings.simplefilter("always")
        with relay.above(bar):
            bar.update()
            relay.show(first)
            relay.show(second)
            bar.update()
    bar.close()
    assert relay.shown == ["clamped (seen 0..1)", "another thing"]
    lines = stream.getvalue().replace("\r", "\n").splitlines()
    # Each warning on a line of its own, never inside a bar line, and no source path.
    assert lines.count("warning: clamped (seen 0..1)") == 1 and lines.count("warning: another thing") == 1
    assert not any(".py" in line for line in lines)
    assert warnings.showwarning is _one_line
