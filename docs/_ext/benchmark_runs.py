"""Committed benchmark runs on the pages, at build time.

A benchmark run with ``--save`` writes what it printed to
``benchmarks/results/NAME.md``: an HTML comment with its command, a
provenance line (``run DATE, commit HASH, load L, C cores``), then
its parts: each Markdown table, and each run of other lines between
blank lines and tables.  The
pages show those parts from the file, never a copy:

.. code-block:: markdown

    ```{benchmark-run} bench_model
    :parts: 2
    ```

shows the run's second part (a table as a table, text as a literal
block); without ``:parts:`` every part, and ``:parts: 1-3,5`` a
selection.  The inline role ``{benchmark-provenance}`NAME``` gives the
run's provenance line without its leading "run ", for the sentence that
introduces it.  The ``datum`` role (data_values.py) reads a table cell
of a run as ``../benchmarks/results/NAME.md#K:COLUMN@KEY=VALUE``: the
K-th table of the file.

:func:`read_run` is the whole parse, without Sphinx, so the tests run
it on every committed run; every way it can fail raises
data_values.DatumError with one printable line.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from data_values import DatumError, one_line

#: Where the committed runs are, relative to docs/.
RESULTS = Path("..") / "benchmarks" / "results"


@dataclass(frozen=True)
class Part:
    """One part of a run: a table, or lines of text."""

    kind: str                    # "table" or "text"
    lines: tuple[str, ...]


@dataclass(frozen=True)
class Run:
    """A committed benchmark run: its command, provenance and parts."""

    command: str
    provenance: str              # the "run ..." line, "run " left out
    parts: tuple[Part, ...]

    def tables(self) -> list[Part]:
        """The run's table parts, in order."""
        return [part for part in self.parts if part.kind == "table"]


def read_run(path: Path) -> Run:
    """The run saved at ``path``.

    Raises
    ------
    DatumError
        No such file, unreadable, or not a saved run (no command
        comment and provenance line first).
    """
    label = Path(path).name
    try:
        lines = Path(path).read_text(encoding="utf-8").splitlines()
    except FileNotFoundError:
        raise DatumError(f"{label}: no such benchmark run") from None
    except (OSError, UnicodeDecodeError) as error:
        raise DatumError(f"{label}: cannot read it "
                         f"({one_line(error)})") from None
    if len(lines) < 2 or not lines[0].startswith("<!--") or \
            not lines[1].startswith("run "):
        raise DatumError(f"{label}: not a saved benchmark run (expected "
                         "a command comment, then a 'run ...' line)")
    command = lines[0].removeprefix("<!--").removesuffix("-->").strip()
    parts, block, kind = [], [], None
    for line in [*lines[2:], ""]:
        this = None
        if line.strip():
            this = "table" if line.lstrip().startswith("|") else "text"
        if block and this != kind:
            parts.append(Part(kind, tuple(block)))
            block = []
        if this is not None:
            block.append(line.rstrip())
        kind = this
    return Run(command, lines[1].removeprefix("run ").strip(), tuple(parts))


def cells(line: str) -> list[str]:
    """The cells of one Markdown table line."""
    return [cell.strip() for cell in line.strip().strip("|").split("|")]


def table_rows(path: Path, number: int,
               label: str) -> tuple[list[str], list[dict]]:
    """The header and rows of the ``number``-th table (from 1) of the
    run at ``path``, as data_values.read_rows gives a CSV's."""
    run = read_run(path)
    tables = run.tables()
    if not 1 <= number <= len(tables):
        raise DatumError(f"{label}: the run has {len(tables)} tables, "
                         f"not a table {number}")
    header, _rule, *body = tables[number - 1].lines
    names = cells(header)
    rows = []
    for line in body:
        row = cells(line)
        if len(row) != len(names):
            raise DatumError(f"{label}: a row of table {number} has "
                             f"{len(row)} cells, the header {len(names)}")
        rows.append(dict(zip(names, row)))
    return names, rows


def selected(spec: str | None, count: int, label: str) -> list[int]:
    """The part numbers (from 1) that ``:parts:`` names: ``2``,
    ``1-3,5``; None: every part."""
    if spec is None or not spec.strip():
        return list(range(1, count + 1))
    chosen = []
    for item in spec.split(","):
        first, dash, last = item.strip().partition("-")
        try:
            low = int(first)
            high = int(last) if dash else low
        except ValueError:
            raise DatumError(f"{label}: parts {spec.strip()!r}: expected "
                             "numbers such as 2 or 1-3,5") from None
        if not 1 <= low <= high <= count:
            raise DatumError(f"{label}: parts {item.strip()!r}: the run "
                             f"has parts 1 to {count}")
        chosen.extend(range(low, high + 1))
    return chosen


def _directive():
    """The ``benchmark-run`` directive class (Sphinx imported here, so
    the parse above imports without it)."""
    from docutils import nodes
    from docutils.parsers.rst import directives
    from docutils.statemachine import StringList
    from sphinx.util.docutils import SphinxDirective

    class BenchmarkRun(SphinxDirective):
        """Show parts of a committed benchmark run."""

        required_arguments = 1
        option_spec = {"parts": directives.unchanged}

        def run(self) -> list:
            name = self.arguments[0]
            path = Path(self.env.srcdir) / RESULTS / f"{name}.md"
            self.env.note_dependency(str(path))
            try:
                run = read_run(path)
                numbers = selected(self.options.get("parts"),
                                   len(run.parts), f"{name}.md")
            except DatumError as error:
                raise self.error(f"benchmark-run: {error}") from None
            shown = []
            for number in numbers:
                part = run.parts[number - 1]
                if part.kind == "text":
                    text = "\n".join(part.lines)
                    block = nodes.literal_block(text, text)
                    block["language"] = "text"
                    shown.append(block)
                    continue
                holder = nodes.container()
                self.state.nested_parse(StringList(list(part.lines),
                                                   str(path)),
                                        self.content_offset, holder)
                shown.extend(holder.children)
            return shown

    return BenchmarkRun


def provenance_role(name, rawtext, text, lineno, inliner, options=None,
                    content=None):
    """``{benchmark-provenance}`NAME```: the run's provenance line."""
    from docutils import nodes

    env = getattr(inliner.document.settings, "env", None)
    base = Path(env.srcdir) if env is not None else Path(__file__).parents[1]
    path = base / RESULTS / f"{text.strip()}.md"
    try:
        if env is not None:
            env.note_dependency(str(path))
        value = read_run(path).provenance
    except DatumError as error:
        message = inliner.reporter.error(f"benchmark-provenance: {error}",
                                         line=lineno)
        return [inliner.problematic(rawtext, rawtext, message)], [message]
    return [nodes.Text(value)], []


def setup(app):
    """Register the ``benchmark-run`` directive and the
    ``benchmark-provenance`` role."""
    app.add_directive("benchmark-run", _directive())
    app.add_role("benchmark-provenance", provenance_role)
    return {"parallel_read_safe": True}
