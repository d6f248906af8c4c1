"""Every public name of bild_mdo and of its subpackages' __all__ has an API page, linked from the index."""
import html as html_lib
import importlib
import pkgutil
import re

import bild_mdo


def _public_names():
    packages = {"bild_mdo": bild_mdo.__all__}
    for info in pkgutil.walk_packages(bild_mdo.__path__, "bild_mdo."):
        if info.ispkg:
            module = importlib.import_module(info.name)
            if hasattr(module, "__all__"):
                packages[info.name] = module.__all__
    return {f"{package}.{name}" for package, names in packages.items() for name in names}


def _ids(text):
    return set(re.findall(r'<dt class="sig sig-object py" id="([^"]+)"', text))


def test_api_index_matches_the_all_lists(docs_site):
    api = docs_site[0] / "api"
    index = (api / "index.html").read_text(encoding="utf-8")
    linked = {html_lib.unescape(m) for m in re.findall(r'href="(bild_mdo[^"#]*)\.html"', index)}
    expected = _public_names()
    assert len(expected) > 150
    assert linked == expected
    for name in sorted(expected):
        page = (api / f"{name}.html").read_text(encoding="utf-8")
        if name in _ids(page):
            continue
        # A re-export: its page names the page that documents the same object.
        target = re.search(r'is the same \w+ as <a class="reference internal" href="([^"#]+)\.html#([^"]+)"', page)
        assert target, f"{name}: no documentation on its page"
        assert target.group(2) in _ids((api / f"{target.group(1)}.html").read_text(encoding="utf-8"))
        package, _, short = name.rpartition(".")
        other_package, _, other_short = target.group(2).rpartition(".")
        assert getattr(importlib.import_module(package), short) is getattr(importlib.import_module(other_package), other_short)
