"""Sphinx configuration of the bild-mdo documentation site.

Toolchain (why): Sphinx with autodoc + numpydoc renders the numpydoc docstrings the package already
has (shapes, units, equation numbers) into an API page per public name, as SciPy, NumPy, OpenMDAO's
API docs and OpenAeroStruct do; myst-nb reads the pages as MyST Markdown notebooks (plain text, easy
to review and diff) and executes every code cell on every build, as OpenMDAO's and Dymos's Jupyter
Book pages are, so a stale example fails the build instead of going out of date.  sphinx-argparse
renders the CLI reference from ``bild_mdo.cli.main.build_parser``.  furo is a light theme with a
search box on every page.  The build runs with ``-W --keep-going -n`` (``docs/build.py``): any
warning, broken cross-reference or failing example fails it.
"""
import os
import pathlib
import sys

DOCS = pathlib.Path(os.environ.get("BILD_MDO_DOCS_SOURCE", pathlib.Path(__file__).resolve().parent))
REPO = pathlib.Path(os.environ.get("BILD_MDO_REPO", DOCS.parent))
sys.path.insert(0, str(DOCS / "_ext"))
sys.path.insert(0, str(REPO))
# The executed pages' kernels import the small page helpers (docs/_ext/docs_helpers.py) and read the
# committed results files (docs/data/) from the source tree.
os.environ["PYTHONPATH"] = os.pathsep.join([str(DOCS / "_ext"), str(REPO), os.environ.get("PYTHONPATH", "")])
os.environ["BILD_MDO_DOCS_DATA"] = str(REPO / "docs" / "data")

import bild_mdo  # noqa: E402

project = "bild-mdo"
author = "bild-mdo developers"
copyright = "2026, bild-mdo developers"
release = version = bild_mdo.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "numpydoc",
    "myst_nb",
    "sphinxarg.ext",
    "bild_api",
]

source_suffix = {".rst": "restructuredtext", ".md": "myst-nb"}
exclude_patterns = ["_build", "README.md", "data", "_ext", "changelog_source.md", "**.ipynb_checkpoints"]
root_doc = "index"

# Cross-references: every broken one is an error (-n -W).  Names outside bild_mdo (numpy, OpenMDAO,
# the standard library) are not linked (the build is offline, no intersphinx); bild_api resolves
# references by the real module path of a re-exported object (see docs/_ext/bild_api.py).
nitpicky = True
# Cross-references in docstrings whose path is wrong (the object lives elsewhere or was renamed).
# Each needs a docstring fix in bild_mdo/ (listed in docs/README.md); until then it is not linked.
nitpick_ignore = [
    ("py:func", "bild_mdo.bild.variants.local_point.load_path_model.trial"),    # local_point/kernels.py
    ("py:func", "bild_mdo.bild.variants.local_point.kernels.paper_trial_one"),  # local_point/sheet_solve.py
    ("py:data", "bild_mdo.optimization.problem.THRUST_TOLERANCE"),              # verification/optimality.py
]

# autodoc + numpydoc: members in source order; OpenMDAO's framework methods of components are not
# part of a component's interface (its Options/Inputs/Outputs are, in its docstring).
autodoc_member_order = "bysource"
autodoc_typehints = "none"
autodoc_inherit_docstrings = False
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks = set()

# myst-nb: execute every page on every build (no cache in the tree), fail on an error.
nb_execution_mode = "force"
nb_execution_raise_on_error = True
nb_execution_timeout = 300
nb_execution_in_temp = True
nb_execution_show_tb = True
nb_merge_streams = True
nb_render_markdown_format = "myst"  # Markdown outputs (the results tables) with tables
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
suppress_warnings = ["mystnb.unknown_mime_type"]

html_theme = "furo"
html_title = f"bild-mdo {release}"
html_static_path = []
html_show_sourcelink = False

# Docstrings write |sin phi| for an absolute value; in reStructuredText that is a substitution.
rst_epilog = "\n".join(f".. |{text}| replace:: \\|{text}\\|" for text in ("sin", "sin phi", "sin(phi)"))
