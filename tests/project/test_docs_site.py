"""The documentation site builds with no warning (issue 30, item 1):
``sphinx-build -W -b html docs`` into a scratch directory, its gallery
executed, its API and command line references generated (about 20 s:
every gallery example runs; the ``test`` extra has what it needs).  It
builds from a copy of what the pages read: docs/, the gallery's
examples and the committed benchmark runs the performance pages show."""

from __future__ import annotations

import shutil
import subprocess
import sys

import pytest

from conftest import ROOT


def test_the_site_builds_without_a_warning(tmp_path):
    for module in ("sphinx", "myst_parser", "numpydoc", "sphinx_gallery",
                   "pydata_sphinx_theme"):
        pytest.importorskip(module)
    # the build writes the gallery and the API stubs into docs/ (both
    # git-ignored): build from a copy so that a run leaves the checkout
    # as it was and runs beside others
    source = tmp_path / "src"
    shutil.copytree(ROOT / "docs", source / "docs",
                    ignore=shutil.ignore_patterns("_build", "auto_examples",
                                                  "generated"))
    shutil.copytree(ROOT / "examples", source / "examples")
    # the performance pages show and quote the committed benchmark runs
    shutil.copytree(ROOT / "benchmarks" / "results",
                    source / "benchmarks" / "results")
    out = tmp_path / "html"
    done = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-b", "html",
         "-q", str(source / "docs"), str(out)],
        capture_output=True, text=True, timeout=1800)
    assert done.returncode == 0, done.stderr[-4000:]
    assert "WARNING" not in done.stderr, done.stderr[-4000:]
    pages = {p.relative_to(out).as_posix() for p in out.rglob("*.html")}
    for page in ("index.html", "tutorial.html", "cli.html",
                 "api/index.html", "auto_examples/index.html",
                 "api/generated/contactsep.evaluate.html",
                 "api/generated/contactsep.chatter.simulate.html"):
        assert page in pages, page
    examples = sorted(p for p in pages
                      if p.startswith("auto_examples/plot_"))
    assert len(examples) >= 8, examples
    # each example ran and drew (sphinx-gallery's images), and can be
    # downloaded as a script and as a notebook
    images = list((out / "_images").glob("sphx_glr_plot_*_001.png"))
    assert len(images) >= 8
    downloads = {p.name for p in (out / "_downloads").rglob("*")}
    assert sum(name.endswith(".ipynb") for name in downloads) >= 8
    # every subcommand is in the command line reference
    from contactsep.cli import build_parser
    cli = (out / "cli.html").read_text()
    commands = build_parser()._subparsers._group_actions[0].choices
    for name in commands:
        assert f"contactsep {name}" in cli, name
