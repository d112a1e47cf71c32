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


ISSUE = re.compile(r"\bissues? #?\d+", re.I)
TEST_FILE = re.compile(r"\btests/\S+\.py\b|\btest_\w+\.py\b")


def body_lines(page):
    """The page's lines outside fenced code blocks, with their numbers."""
    fenced = False
    for number, line in enumerate(page.read_text().splitlines(), 1):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        if not fenced:
            yield number, line


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_no_body_text_names_an_issue_or_a_test_file(page):
    """A reader cannot look an issue number up and does not care which
    test file holds a claim: the main pages name the check's subject.
    Dated history, with its issue numbers, lives in docs/records/."""
    named = [f"{page.name}:{number}: {line.strip()[:100]}"
             for number, line in body_lines(page)
             if ISSUE.search(line) or TEST_FILE.search(line)]
    assert not named, "\n".join(named)


#: How the project's own work was organised ("this session", "the
#: previous session"): history, not something a reader can use.
SESSION = re.compile(r"\bsessions?\b", re.I)


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_no_body_text_tells_the_projects_session_history(page):
    told = [f"{page.name}:{number}: {line.strip()[:100]}"
            for number, line in body_lines(page) if SESSION.search(line)]
    assert not told, "\n".join(told)
