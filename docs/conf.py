"""Sphinx configuration of the cummins documentation site.

Build it (warnings are errors, every gallery example is run):

    pip install -e ".[docs]"
    python -m sphinx -W -b html docs docs/_build/html

The pages: the user guide and the theory (``docs/guide``, ``docs/theory``), the notes
``docs/*.md`` as they are (MyST, not copied), the API reference from the docstrings
(``docs/reference``) and the gallery, made by running ``examples/*.py``
(sphinx-gallery) on the bundled tanker and S-175.
"""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(DOCS))  # gallery_scraper
if (ROOT / "src" / "cummins").is_dir():
    sys.path.insert(0, str(ROOT / "src"))

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("MPLBACKEND", "agg")

from gallery_scraper import figure_scraper  # noqa: E402

import cummins  # noqa: E402

project = "cummins"
author = "cummins developers"
copyright = "cummins developers, MIT licence"
release = cummins.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    # MathJax served from the site itself (_static/mathjax), not from a CDN: the
    # equations render on a machine without network, as the site is read offline
    "sphinx-mathjax-offline",
    "sphinx.ext.viewcode",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
templates_path = ["_templates"]
exclude_patterns = [
    "_build",
    "**/README.md",
    "**/*.inc.md",
    "auto_examples/*.ipynb",
    "auto_examples/*.zip",
]
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3

# the API from the SciPy-style docstrings
autosummary_generate = True
autodoc_typehints = "none"  # the docstrings say the types, with their units
autodoc_member_order = "bysource"
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
napoleon_use_ivar = True  # dataclass attributes as fields, not a second description
# a name re-exported by a package (FitError in cummins.radiation.fit) is documented where
# it is defined and where it is exported: a cross-reference finds both; the gallery's
# configuration holds its image scraper, a function, which Sphinx does not cache
suppress_warnings = ["ref.python", "config.cache"]


def escape_bars(app, what, name, obj, options, lines) -> None:
    """``|K|``, ``|RAO|`` in the docstrings are absolute values, not reST substitutions:
    escape the bars outside literals (a line block or a grid table is left alone)."""
    for k, line in enumerate(lines):
        if "|" in line and not line.lstrip().startswith(("| ", "+-", "+=")):
            parts = re.split(r"(``.*?``)", line)
            lines[k] = "".join(
                part if part.startswith("``") else part.replace("|", "\\|") for part in parts
            )


sphinx_gallery_conf = {
    "examples_dirs": [str(ROOT / "examples")],
    "gallery_dirs": ["auto_examples"],
    "filename_pattern": r"/\d\d_",  # every numbered example is run
    "within_subsection_order": "FileNameSortKey",
    "image_scrapers": (figure_scraper, "matplotlib"),
    "remove_config_comments": True,
    "download_all_examples": False,
    "plot_gallery": "True",
    "abort_on_example_error": True,
    "show_memory": False,
    "min_reported_time": 1,
}

html_theme = "alabaster"
html_title = f"cummins {release}"
html_static_path = ["_static"]
html_css_files = ["cummins.css"]
html_theme_options = {
    "description": "Frequency-domain hydrodynamics to time-domain vessel models",
    "fixed_sidebar": True,
    "page_width": "1200px",
    "sidebar_width": "240px",
}
html_show_sourcelink = False


def write_command_help(app) -> None:
    """``guide/commands.inc.md``: the ``--help`` of every command, as the command line
    prints it (included by ``guide/command_line.md``; generated, not in the repository)."""
    from click.testing import CliRunner

    from cummins.cli import main
    from cummins.cli.app import COMMANDS

    runner = CliRunner()
    parts = []
    for name in ["", *COMMANDS]:
        args = [name, "--help"] if name else ["--help"]
        text = runner.invoke(main, args, prog_name="cummins", terminal_width=88).output
        title = f"cummins {name}" if name else "cummins"
        parts.append(f"### `{title}`\n\n```text\n{text.rstrip()}\n```\n")
    (DOCS / "guide" / "commands.inc.md").write_text("\n".join(parts), encoding="utf-8")


def setup(app):
    app.connect("builder-inited", write_command_help)
    app.connect("autodoc-process-docstring", escape_bars)
