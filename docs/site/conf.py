"""Sphinx configuration of tyrelab's documentation site (``make docs`` -> build/docs/index.html).

Sphinx with numpydoc and autodoc (the Python API from the docstrings), MyST (the pages are
Markdown, as ``docs/*.md`` that the report ships), sphinx-argparse (the command line from
:func:`tyrelab.cli.build_parser`), sphinxcontrib-programoutput (the commands of the tutorials run
while the pages are built, their output shown) and sphinx.ext.doctest (the Python examples run by
``sphinx-build -b doctest``). ``_ext/tyrelab_reference.py`` writes the scenario-key and warehouse
references from the schemas and the stages' declarations; ``_ext/tyrelab_outputs.py`` checks that
every output shown in the README and ``docs/*.md`` is what its command prints.
"""

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

import tyrelab  # noqa: E402

project = "tyrelab"
author = "tyrelab maintainers"
copyright = "tyrelab maintainers"
version = release = tyrelab.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.doctest",
    "numpydoc",
    "sphinxarg.ext",
    "sphinxcontrib.programoutput",
    "tyrelab_reference",
    "tyrelab_outputs",
]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
exclude_patterns = ["_build", "_ext"]
myst_enable_extensions = ["colon_fence"]
myst_heading_anchors = 3

# The API reference: numpydoc renders the docstrings' sections; no autosummary stubs.
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
autodoc_typehints = "none"
autodoc_member_order = "bysource"

# Only the pages' {doctest} blocks are run here; the docstrings' examples are run by
# pytest --doctest-modules (make test), in their modules' namespaces.
doctest_test_doctest_blocks = ""
doctest_global_setup = "import os, tyrelab\nos.chdir(os.environ.get('TYRELAB_DOCS_WORK', '.'))"

# The commands of the tutorials run in the work folder make docs prepares (TYRELAB_DOCS_WORK).
programoutput_use_ansi = False

# Explanation pages include docs/*.md, written for GitHub and the report: their headings need
# not start at level 1 and may skip levels.
suppress_warnings = ["myst.header"]

html_theme = "alabaster"
html_title = f"tyrelab {release}"
html_theme_options = {"page_width": "1100px", "sidebar_width": "240px"}
html_static_path = []
