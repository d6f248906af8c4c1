"""The site builds with zero warnings and every example on it runs (make docs, as in CI)."""
import pathlib
import re

REPO = pathlib.Path(__file__).resolve().parents[2]
DOCS = REPO / "docs"


def test_site_builds_without_a_warning(docs_site):
    html, code, warnings, seconds = docs_site
    assert warnings.strip() == "", warnings
    assert code == 0
    assert (html / "index.html").exists()
    print(f"docs build: {seconds:.0f} s")


def _pages_with_code():
    for path in sorted(DOCS.rglob("*.md")):
        if "_build" in path.parts or path.name == "README.md":
            continue
        text = path.read_text(encoding="utf-8")
        if "```{code-cell}" in text:
            yield path.relative_to(DOCS).with_suffix(".html"), text.count("```{code-cell}")


def test_every_executed_page_shows_its_outputs(docs_site):
    html = docs_site[0]
    pages = list(_pages_with_code())
    assert len(pages) >= 12
    for page, cells in pages:
        text = (html / page).read_text(encoding="utf-8")
        # myst-nb writes one "cell docutils container" per code cell; an error would have failed the build.
        assert len(re.findall(r'class="cell(?: tag_[^ "]+)* docutils container"', text)) == cells, page
        assert "cell_output" in text, f"{page}: no output at all"
        assert "Traceback" not in text, page


def test_cli_reference_lists_every_subcommand(docs_site):
    text = (docs_site[0] / "cli.html").read_text(encoding="utf-8")
    for command in ("demo", "design", "analyze", "verify"):
        assert f'id="bild-mdo-{command}"' in text


def test_build_writes_nothing_into_the_repository(docs_site):
    # The API pages are generated into the build's own copy of the sources.
    assert not (DOCS / "api").exists()
    assert not any(p.suffix == ".ipynb" for p in DOCS.rglob("*") if "_build" not in p.parts)
