"""The results file: one true message per unusable path, and one writer at a time."""
import os

import pytest

from bild_mdo.verification.cases import SweepSpec
from bild_mdo.verification.store import ResultsStore
from bild_mdo.verification.store_file import StoreBusyError, StoreError, check_store_path

SPEC = SweepSpec(levels=2)


def test_missing_folder(tmp_path):
    with pytest.raises(StoreError, match=r"the folder '.*missing' of the results store .* does not exist; create it"):
        ResultsStore(tmp_path / "missing" / "s.sqlite", SPEC)
    assert not (tmp_path / "missing").exists()


def test_folder_given_for_the_file(tmp_path):
    with pytest.raises(StoreError, match=r"is a folder; the results store \(--db\) is a file, for example"):
        ResultsStore(tmp_path, SPEC)


def test_file_given_for_the_folder(tmp_path):
    (tmp_path / "plain").write_text("x")
    with pytest.raises(StoreError, match="is a file, not a folder"):
        check_store_path(str(tmp_path / "plain" / "s.sqlite"))


def test_not_writable(tmp_path, monkeypatch):
    # Permission bits do not bind root (the test may run as root): the access check itself is replaced.
    (tmp_path / "s.sqlite").write_bytes(b"")
    monkeypatch.setattr(os, "access", lambda path, mode: os.path.isdir(path))
    with pytest.raises(StoreError, match=r"is not writable \(permissions\); make it writable"):
        check_store_path(str(tmp_path / "s.sqlite"))
    monkeypatch.setattr(os, "access", lambda path, mode: not os.path.isdir(path))
    with pytest.raises(StoreError, match=r"the folder .* is not writable \(permissions\)"):
        check_store_path(str(tmp_path / "new.sqlite"))


def test_one_writer_at_a_time(tmp_path):
    path = tmp_path / "s.sqlite"
    with ResultsStore(path, SPEC) as first:
        with pytest.raises(StoreBusyError, match=f"another sweep is writing to '{path}'"):
            ResultsStore(path, SPEC)
        # Reading while a sweep writes is fine.
        with ResultsStore(path, SPEC, writer=False) as reader:
            assert reader.count() == 0
        first.write({"case_id": 0, "bild_converged": True, "converged": True})
    # The lock goes with the writer.
    with ResultsStore(path, SPEC) as second:
        assert second.done_ids() == {0}
