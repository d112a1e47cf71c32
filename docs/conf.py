"""Sphinx configuration of the contactsep documentation site.

Build it (no network needed) with::

    pip install ".[docs]"
    sphinx-build -W -b html docs docs/_build/html

The gallery (``examples/plot_*.py``) is executed at every build and
written to ``docs/auto_examples/``; the API pages autosummary generates go
to ``docs/api/generated/``; both are build outputs, kept out of git.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")   # the gallery draws without a display

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE / "_ext"))
# the gallery's scripts read committed CSVs relative to the checkout
os.environ.setdefault("CONTACTSEP_ROOT", str(ROOT))



def _one_editable_finder() -> None:
    """Drop repeated meson-python editable finders from sys.meta_path.

    Some environments load the editable install's ``.pth`` twice; the two
    finders then share one ``lru_cache(maxsize=1)`` and evict each other,
    so every import of a contactsep name re-runs ninja (minutes of a
    build spent in ninja).  One finder is enough; a regular install has
    none and this does nothing.
    """
    seen, keep = set(), []
    for finder in sys.meta_path:
        key = (repr(finder) if type(finder).__name__ == "MesonpyMetaFinder"
               else id(finder))
        if key not in seen:
            seen.add(key)
            keep.append(finder)
    sys.meta_path[:] = keep


_one_editable_finder()

import contactsep  # after the path set-up above

#: Layers other work adds to the package: documented here once they are
#: importable (docs/api/later.rst is written at every build, git-ignored).
LATER_LAYERS = {
    "contactsep.preload": "The preload that keeps a design closed",
    "contactsep.modes": "Beam modes: Bernoulli-Euler, Timoshenko, supports",
}


def _write_later_layers() -> None:
    import importlib
    import inspect

    lines = ["Preload and beam modes", "======================", ""]
    for name, title in LATER_LAYERS.items():
        module, _, attribute = name.rpartition(".")
        try:
            value = getattr(importlib.import_module(module), attribute)
        except (ImportError, AttributeError):
            value = None
        lines += [f"``{name}``: {title}", "-" * (len(name) + len(title) + 6),
                  ""]
        if value is None:
            lines += [f"``{name}`` is not part of this version.", ""]
        elif inspect.ismodule(value):
            lines += [f".. automodule:: {name}", "   :members:", ""]
        elif inspect.isclass(value):
            lines += [f".. autoclass:: {name}", ""]
        else:
            lines += [f".. autofunction:: {name}", ""]
    text = "\n".join(lines)
    path = HERE / "api" / "later.rst"
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


_write_later_layers()

project = "contactsep"
author = "the contactsep authors"
copyright = "the contactsep authors, MIT licence"
version = release = contactsep.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "cli_reference",
    "data_values",
    "code_constants",
    "benchmark_runs",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store",
                    "auto_examples/*.ipynb", "auto_examples/*.py",
                    "auto_examples/*.zip", "auto_examples/*.json",
                    "auto_examples/*.md5"]
templates_path = ["_templates"]

# -- MyST: the Markdown pages stay Markdown --------------------------------
myst_enable_extensions = ["dollarmath", "colon_fence", "deflist"]
myst_heading_anchors = 3

# -- API reference ----------------------------------------------------------
autosummary_generate = True
autodoc_member_order = "bysource"
autodoc_typehints = "none"          # numpydoc's Parameters say the types
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

# -- Gallery ----------------------------------------------------------------
sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples"),
    "gallery_dirs": str(HERE / "auto_examples"),
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "matplotlib_animations": False,
    "show_memory": False,
    "plot_gallery": "True",
}

# -- HTML -------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = "contactsep"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
}
html_static_path: list[str] = []
html_show_sourcelink = False
