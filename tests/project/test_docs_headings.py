"""The main pages' headings name what a section is about, never a work
item of the project's history ("(issue 25)"): a reader cannot look an
issue number up.  Dated history lives in docs/records/ and CHANGELOG.md."""

from __future__ import annotations

import re

import pytest

from conftest import ROOT

PAGES = sorted((ROOT / "docs").glob("*.md"))


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_no_heading_names_an_issue(page):
    headings = [line for line in page.read_text().splitlines()
                if line.startswith("#")]
    assert headings, page.name
    named = [h for h in headings if re.search(r"\bissues? \d+", h, re.I)]
    assert not named, named
