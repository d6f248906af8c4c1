"""The on-disk polar cache: keyed by the source, atomic writes, rebuilt when the source changes."""
import threading
import warnings

import numpy as np
import pytest

from bild_mdo.airfoil import cache
from bild_mdo.airfoil.sources.readers import load_builtin_polars
from bild_mdo.airfoil.surrogate import TabulatedPolar


def _two_polars():
    # Two Reynolds numbers of the shipped NACA 4412 data: a small, real surrogate to build.
    return [p for p in load_builtin_polars("naca4412") if p.reynolds in (5e5, 1e6)]


def test_cache_dir_follows_the_environment_variable(tmp_path, monkeypatch):
    monkeypatch.setenv(cache.CACHE_ENV, str(tmp_path / "elsewhere"))
    assert cache.cache_dir().parent == tmp_path / "elsewhere"
    monkeypatch.delenv(cache.CACHE_ENV)
    import platformdirs
    assert cache.cache_dir().parent == __import__("pathlib").Path(platformdirs.user_cache_dir("bild-mdo"))


def test_hash_key_separates_types_and_values():
    assert cache.hash_key(1) != cache.hash_key("1") != cache.hash_key(1.0)
    assert cache.hash_key(np.arange(3.0)) == cache.hash_key(np.arange(3.0))
    assert cache.hash_key(np.arange(3.0)) != cache.hash_key(np.arange(3))
    assert cache.hash_key({"a": 1, "b": 2}) == cache.hash_key({"b": 2, "a": 1})


def test_store_and_load_round_trip_without_pickle(polar_cache):
    key = cache.hash_key("round trip")
    arrays = {"x": np.linspace(0, 1, 5), "name": np.array("naca2412")}
    path = cache.store_arrays("test", "demo", key, arrays)
    assert path.parent.parent == polar_cache / "v1"
    loaded = cache.load_arrays("test", "demo", key)
    np.testing.assert_array_equal(loaded["x"], arrays["x"])
    assert str(loaded["name"]) == "naca2412"
    assert cache.load_arrays("test", "demo", cache.hash_key("other")) is None
    # A damaged entry counts as missing.
    path.write_bytes(b"not a zip file")
    assert cache.load_arrays("test", "demo", key) is None


def test_cached_surrogate_is_the_built_one_bit_for_bit():
    # The cache stores the spline coefficients themselves, so a load gives the
    # numbers of a fresh fit exactly (the built-in NACA 4412 stays unchanged).
    polars = _two_polars()
    built = TabulatedPolar(polars, name="pair")
    first = TabulatedPolar.cached(polars, name="pair")
    loaded = TabulatedPolar.cached(polars, name="pair")
    alpha = np.radians(np.linspace(-180.0, 180.0, 2001))
    reynolds = np.geomspace(5e5, 1e6, 2001)
    for polar in (first, loaded):
        for got, want in zip(polar.evaluate(alpha, reynolds), built.evaluate(alpha, reynolds)):
            np.testing.assert_array_equal(got, want)
        for got, want in zip(polar.second_derivatives(alpha, reynolds), built.second_derivatives(alpha, reynolds)):
            np.testing.assert_array_equal(got, want)
        assert polar.alpha_scan_range == built.alpha_scan_range
        assert polar.name == "pair"


def test_a_changed_source_or_setting_gets_a_new_key(polar_cache):
    polars = _two_polars()
    key = TabulatedPolar.cache_key(polars)
    data = polars[0]
    edited = type(data)(data.reynolds, data.mach, data.alpha_deg, data.cl + 1e-4, data.cd, data.source)
    assert TabulatedPolar.cache_key([edited, polars[1]]) != key
    assert TabulatedPolar.cache_key(polars, cd_max=1.5) != key
    assert TabulatedPolar.cache_key(polars, name="other") == key


def test_unwritable_cache_warns_once_and_still_builds(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("a file where the cache folder should be")
    monkeypatch.setenv(cache.CACHE_ENV, str(blocker))
    with pytest.warns(RuntimeWarning, match="polar cache disabled"):
        assert cache.store_arrays("test", "x", "k" * 64, {"a": np.zeros(2)}) is None
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert cache.store_arrays("test", "x", "k" * 64, {"a": np.zeros(2)}) is None


def test_concurrent_writers_leave_a_complete_entry():
    key = cache.hash_key("concurrent")
    arrays = {"x": np.arange(200_000.0)}
    threads = [threading.Thread(target=cache.store_arrays, args=("test", "busy", key, arrays)) for _ in range(6)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    np.testing.assert_array_equal(cache.load_arrays("test", "busy", key)["x"], arrays["x"])
    assert not list(cache.cache_dir().joinpath("test").glob("*.tmp"))


def test_clear_cache_removes_the_folder(tmp_path, monkeypatch):
    monkeypatch.setenv(cache.CACHE_ENV, str(tmp_path))
    cache.store_arrays("test", "gone", cache.hash_key("gone"), {"a": np.zeros(1)})
    folder = cache.clear_cache()
    assert not folder.exists()
