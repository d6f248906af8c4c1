"""Helpers of the executed pages: tables from the committed results files in ``docs/data/``.

A number from a long run (the 10,000-case sweep, the benchmarks) is never typed into a page: the
page calls :func:`results_table`, which reads it from ``docs/data/NAME.json`` (written with the
command that produced it) and shows the command beside the table.
"""
import json
import os
import pathlib

from IPython.display import Markdown

DATA = pathlib.Path(os.environ.get("BILD_MDO_DOCS_DATA", pathlib.Path(__file__).resolve().parents[1] / "data"))


def load(name):
    """The results file ``docs/data/NAME.json`` as a dict."""
    return json.loads((DATA / f"{name}.json").read_text(encoding="utf-8"))


def results_table(name, key):
    """One table of a results file as Markdown, with its command and where its numbers come from."""
    data = load(name)
    table = data[key]
    lines = [f"**{table['title']}**", "", f"Command: `{table['command']}`"
             + (f" (wall time {table['wall_time']})" if "wall_time" in table else ""), "",
             "| " + " | ".join(table["columns"]) + " |", "|" + "---|" * len(table["columns"])]
    lines += ["| " + " | ".join(row) + " |" for row in table["rows"]]
    lines += [""] + [f"- {text}" for text in table.get("notes", {}).values()]
    lines += ["", f"*Source: `docs/data/{name}.json`. {data['provenance']}*"]
    return Markdown("\n".join(lines))


def note(name, key, item):
    """One sentence of a results file's notes (a number measured with the table's command)."""
    return load(name)[key]["notes"][item]
