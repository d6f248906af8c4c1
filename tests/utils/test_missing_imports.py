"""utils.missing_imports: an absent optional module is recorded as missing, a present one is left alone."""
import importlib
import sys

import pytest

from bild_mdo.utils.missing_imports import remember_missing


def test_an_absent_module_then_fails_to_import_at_once(monkeypatch):
    name = "bild_mdo_no_such_module_xyz"
    monkeypatch.delitem(sys.modules, name, raising=False)
    assert remember_missing((name,)) == (name,)
    assert sys.modules[name] is None
    # Python's own spelling of a missing module: the import raises ImportError (what OpenMDAO catches).
    with pytest.raises(ImportError):
        importlib.import_module(name)
    monkeypatch.delitem(sys.modules, name)


def test_an_installed_module_is_left_alone():
    # json is installed: it is not recorded, and importing it still works.
    saved = sys.modules.pop("json", None)
    try:
        assert remember_missing(("json",)) == ()
        assert "json" not in sys.modules or sys.modules["json"] is not None
        assert importlib.import_module("json").dumps([1]) == "[1]"
    finally:
        if saved is not None:
            sys.modules["json"] = saved
