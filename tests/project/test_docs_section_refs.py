"""Every pointer from the code and the tests into a page's section,
``docs/PAGE.md, "Section"``, names a page that exists and a section it
has (a heading, or a bold lead-in of a list item, starting with those
words): a section that moves to another page takes its pointers along."""

from __future__ import annotations

import re
from pathlib import Path

from conftest import ROOT

#: ``docs/page.md, "Words`` in a docstring, a comment (wrapped over
#: ``#:`` lines) or a message (``\"`` inside a string).
POINTER = re.compile(r'docs/([\w/-]+\.md),? +\\?"([^"\\]{3,200})')
#: A section's title: a Markdown heading or a list item's bold lead-in.
TITLE = re.compile(r"^(?:#+ +|\* +\*\*)(.*?)(?:\*\*.*)?$")


def _words(text: str) -> str:
    return " ".join(re.sub(r"\n\s*#:?", " ", text).split()).lower()


def titles(page: Path) -> list[str]:
    """The section titles of ``page``, lower case, spaces collapsed."""
    found = []
    for line in page.read_text(encoding="utf-8").splitlines():
        match = TITLE.match(line)
        if match:
            found.append(_words(match.group(1)).rstrip("."))
    return found


def broken_pointers(sources: list[Path], docs: Path) -> list[tuple]:
    """(source, page, words) of every pointer whose page is missing or
    has no section starting with its words (or that its words start
    with: a pointer may quote past a title's end)."""
    broken = []
    for source in sources:
        text = source.read_text(encoding="utf-8")
        for match in POINTER.finditer(text):
            page, words = docs / match.group(1), _words(match.group(2))
            if not page.is_file():
                broken.append((source.name, match.group(1), words))
                continue
            if not any(title.startswith(words) or words.startswith(title)
                       for title in titles(page)):
                broken.append((source.name, match.group(1), words))
    return broken


def _sources() -> list[Path]:
    return sorted(p for folder in ("python", "tests", "benchmarks")
                  for p in (ROOT / folder).rglob("*.py")
                  if p.resolve() != Path(__file__).resolve())


def test_every_section_pointer_names_a_section_of_its_page():
    assert broken_pointers(_sources(), ROOT / "docs") == []


def test_the_checker_sees_a_moved_section(tmp_path):
    """The rule can fail: pointers planted at a missing page, at a
    section the page lacks, and at sections it has (a heading, wrapped
    over comment lines, a bold lead-in, a message's escaped quote)."""
    docs = tmp_path / "docs"
    docs.mkdir()
    (docs / "page.md").write_text(
        "# Page\n\n## The default N\n\n* **The unit problem of eq. 13.**  "
        "Text.\n")
    source = tmp_path / "code.py"
    source.write_text(
        '#: see docs/page.md, "The\n#: default N")\n'
        '"""docs/page.md, "The unit problem of eq. 13")."""\n'
        'message = "(docs/page.md, \\"The default N\\")"\n'
        '# docs/page.md, "Contact laws"\n'
        '# docs/gone.md, "The default N"\n')
    assert broken_pointers([source], docs) == [
        ("code.py", "page.md", "contact laws"),
        ("code.py", "gone.md", "the default n")]
