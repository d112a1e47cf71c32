"""The project's own files (issue 19, item 9): the licence pyproject
declares, a citation of the software and of the thesis, a changelog."""

from __future__ import annotations

import re

import contactsep
from conftest import ROOT


def words(text: str) -> str:
    return " ".join(re.sub(r"[^a-z ]", " ", text.lower()).split())


def test_license_is_the_one_pyproject_declares():
    pyproject = (ROOT / "pyproject.toml").read_text()
    assert 'license = { text = "MIT" }' in pyproject
    text = (ROOT / "LICENSE").read_text()
    assert text.startswith("MIT License\n")
    assert "Permission is hereby granted, free of charge" in text


def test_citation_names_this_software_and_the_thesis():
    cff = (ROOT / "CITATION.cff").read_text()
    assert cff.startswith("cff-version: 1.2.0\n")
    assert f"\nversion: {contactsep.__version__}\n" in cff
    assert "\nlicense: MIT\n" in cff and "\ntype: software\n" in cff
    thesis = cff.split("- type: thesis", 1)[1]
    title = thesis.split("title: >-", 1)[1].split("authors:", 1)[0]
    # the title the README gives the thesis (as the thesis text has it)
    readme = (ROOT / "README.md").read_text()
    stated = re.search(r"^\*(.*?)\*", readme, flags=re.S | re.M).group(1)
    assert words(title) == words(stated)
    assert "appendix g" in words(thesis)


def test_changelog_has_this_version():
    changelog = (ROOT / "CHANGELOG.md").read_text()
    assert changelog.startswith("# Changelog\n")
    assert f"\n## {contactsep.__version__} (" in changelog
