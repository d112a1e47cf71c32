"""The site's four parts: no page in their toctrees over 600 lines, and the
records (dated studies, benchmark history) stay outside those toctrees."""
import re

from conftest import ROOT

DOCS = ROOT / "docs"
LIMIT = 600


def toctree_entries(page):
    text = (DOCS / page).read_text()
    base = page.rsplit("/", 1)[0] + "/" if "/" in page else ""
    for block in re.findall(r"^```\{toctree\}\n(.*?)^```", text,
                            flags=re.S | re.M):
        for line in block.splitlines():
            line = line.strip()
            if line and not line.startswith(":"):
                yield base + line + ".md"


def main_pages():
    seen, todo = [], ["index.md"]
    while todo:
        page = todo.pop()
        for entry in toctree_entries(page):
            if (DOCS / entry).exists() and entry not in seen:
                seen.append(entry)
                todo.append(entry)
    return seen


def test_the_toctrees_reach_the_how_to_pages():
    pages = main_pages()
    assert "howto/index.md" in pages
    assert "howto/batch-cluster.md" in pages
    assert "tutorial.md" in pages


def test_no_page_in_the_four_parts_is_over_600_lines():
    over = {p for p in main_pages()
            if len((DOCS / p).read_text().splitlines()) > LIMIT}
    assert over == set(), sorted(over)


def test_no_records_page_is_in_the_main_toctrees():
    assert not [p for p in main_pages() if p.startswith("records/")]
    assert (DOCS / "records" / "index.md").exists()
