"""The tables a benchmark printed as text, read as tables.

Some committed runs (``benchmarks/results/NAME.md``) hold what a script
printed, not Markdown: columns aligned under a header line, such as ::

     sweep engine   k  seconds speed-up efficiency dask/local parent %
      eq23  local   1    32.62     1.00       1.00                   -
      eq23   dask   2    16.74     1.95       1.02       0.99      2.5

The ``datum`` role reads a cell of the K-th such table of a run as
``../benchmarks/results/NAME.md~K:COLUMN@KEY=VALUE`` (data_values.py),
so that a sentence quoting the run draws its figure from the file.

A printed table is a header line (no number among its words) and the
lines under it that read as its rows.  A row's word belongs to the
header word it overlaps whose end is nearest its own (the columns are
right-aligned under their names; left-aligned ones overlap one word);
several words under one header word form one cell ("robust  local"
under "search engine" in two cells, one a word).  A header word no row
fills joins the next one to its right, or the last ("yardstick s",
"parent %", "same answer").  A row has a number among its words, each
word overlaps a header word, and no header word holds more than one
word unless the table's first row has more there; the first line that does not read so ends the
table (a closing "load average ..." line, a blank line).  A cell
printed as "-" reads as NaN.
"""

from __future__ import annotations

import re
from pathlib import Path

from data_values import DatumError

_WORD = re.compile(r"\S+")


def _is_number(word: str) -> bool:
    try:
        float(word.replace(",", ""))
    except ValueError:
        return False
    return True


def header_words(line: str) -> list[tuple[str, int, int]]:
    """(word, start, end) of each word of a header line."""
    return [(m.group(), m.start(), m.end()) for m in _WORD.finditer(line)]


def row_cells(line: str, words: list[tuple[str, int, int]]):
    """The words of ``line`` under each header word (lists), or None
    where a word overlaps no header word."""
    cells = [[] for _ in words]
    for match in _WORD.finditer(line):
        hits = [k for k, (_, start, end) in enumerate(words)
                if min(end, match.end()) > max(start, match.start())]
        if not hits:
            return None
        nearest = min(hits, key=lambda k: abs(words[k][2] - match.end()))
        cells[nearest].append(match.group())
    return cells


def _cell(words: list[str]) -> str:
    """A cell's text: its words; a printed "-" (no value) is NaN, which
    the aggregates skip and a plain datum refuses."""
    text = " ".join(words)
    return "nan" if text == "-" else text


def _columns(words: list, rows: list[list[list[str]]]):
    """(names, the header word each column's cells come from): a header
    word that no row fills joins the next filled one, or the last."""
    filled = [any(row[k] for row in rows) for k in range(len(words))]
    names, sources, pending = [], [], []
    for k, (word, _, _) in enumerate(words):
        pending.append(word)
        if filled[k]:
            names.append(" ".join(pending))
            sources.append(k)
            pending = []
    if pending and names:
        names[-1] = " ".join([names[-1], *pending])
    return names, sources


def printed_tables(lines: list[str]) -> list[tuple[list[str], list[dict]]]:
    """The printed tables among ``lines``, each (column names, rows as
    {name: cell}), in order."""
    tables, i = [], 0
    while i < len(lines) - 1:
        words = header_words(lines[i])
        if not words or any(_is_number(w) for w, _, _ in words):
            i += 1
            continue
        rows, widths, j = [], None, i + 1
        while j < len(lines):
            cells = row_cells(lines[j], words)
            if cells is None or not any(_is_number(w) for c in cells
                                        for w in c):
                break
            counts = [len(c) for c in cells]
            if widths is None:
                widths = counts
            elif any(n > max(most, 1) for n, most in zip(counts, widths)):
                break
            rows.append(cells)
            j += 1
        if not rows:
            i += 1
            continue
        names, sources = _columns(words, rows)
        tables.append((names, [{name: _cell(row[k]) for name, k
                                in zip(names, sources)} for row in rows]))
        i = j
    return tables


def table_rows(path: Path, number: int,
               label: str) -> tuple[list[str], list[dict]]:
    """The header and rows of the ``number``-th printed table (from 1) of
    the run at ``path``, as data_values.read_rows gives a CSV's."""
    import benchmark_runs

    run = benchmark_runs.read_run(path)
    tables = []
    for part in run.parts:
        if part.kind == "text":
            tables.extend(printed_tables(list(part.lines)))
    if not 1 <= number <= len(tables):
        raise DatumError(f"{label}: the run has {len(tables)} printed "
                         f"tables, not a printed table {number}")
    return tables[number - 1]
