"""The committed studies' comment lines name modules that exist: a CSV
written by an older layout (a module since moved) says where its
definitions live, and a reader following it finds nothing; the slow
regeneration tests would catch it, this catches it in every run."""

from __future__ import annotations

import importlib
import re

import pytest

from conftest import ROOT

#: ``(contactsep.some.module)`` in a ``#`` line of a committed CSV.
MODULE = re.compile(r"\((contactsep(?:\.[a-z_]+)+)\)")


def named_modules(text: str) -> set[str]:
    """The modules the ``#`` lines of a CSV's text name in parentheses."""
    return {name for line in text.splitlines() if line.startswith("#")
            for name in MODULE.findall(line)}


@pytest.mark.parametrize("path", sorted((ROOT / "docs" / "studies")
                                        .glob("*.csv")),
                         ids=lambda p: p.name)
def test_every_module_a_study_names_imports(path):
    for name in named_modules(path.read_text(encoding="utf-8")):
        importlib.import_module(name)


def test_the_checker_finds_a_moved_module():
    """The rule can fail: a planted comment naming a module that moved."""
    text = ("# status 9 unconverged (contactsep.studies.chatter_sweep)\n"
            "d_in,status\n0.25,0\n")
    names = named_modules(text)
    assert names == {"contactsep.studies.chatter_sweep"}
    with pytest.raises(ImportError):
        importlib.import_module(names.pop())
