"""Numbers on the pages, drawn from the committed data at build time.

The inline role ``datum`` puts one value of a committed CSV into the
text, so that a page and the data it quotes cannot disagree::

    {datum}`studies/preload.csv:min_preload_lb@d_in=0.25,ys_in=0.5:.4g`

The role's text is ``FILE:COLUMN[@KEY=VALUE,...][:FORMAT]``:

``FILE``
    a CSV file, relative to ``docs/``; its lines that start with ``#``
    (the comments every CSV the package writes carries) are skipped.
    Or a committed JSON object (a command's ``--json`` output): one row
    whose columns are its leaves, named by their paths (``n``,
    ``inputs.seed``, ``p_exceed_ci95[0]``).
    Or a committed benchmark run, ``../benchmarks/results/NAME.md#K``:
    the K-th Markdown table of the run (benchmark_runs.py; 1 without
    ``#K``); ``NAME.md~K``: the K-th table it printed as text
    (printed_tables.py).
``COLUMN``
    the column whose value is shown, or an aggregate over the rows the
    filters select: ``max(col)``, ``min(col)``, ``sum(col)`` (NaN cells
    skipped, as pandas does) or ``rows`` (how many rows match).
``KEY=VALUE,...``
    the filters: a row matches when each ``KEY`` column equals its
    ``VALUE``, compared as numbers when both parse as numbers
    (``0.25`` matches ``0.250``), else as text.  A plain ``COLUMN``
    needs exactly one matching row.
``FORMAT``
    a Python format spec (``.2f``, ``.4g``, ``,d``), or ``.Psci``: the
    ``.Pe`` form with the exponent as the pages write it, neither a
    plus nor leading zeros (``4e-5``, ``1.2e6``); without one the cell
    is shown as written in the file.

Or ``=EXPR[:FORMAT]``, arithmetic on such values, each written
``[FILE:COLUMN@...]`` (data_expressions.py): a ratio, a difference, a
change of unit.

:func:`resolve` is the whole lookup, a pure function without Sphinx, so
the tests run it on every use in the pages; every way it can fail
raises :class:`DatumError` with one printable line naming the file,
column and filters.  The role reports that line as an error at the
role's source line, so ``sphinx-build -W`` stops on it.
"""

from __future__ import annotations

import csv
import math
import re
from dataclasses import dataclass
from pathlib import Path

#: The aggregates COLUMN may be, besides a plain column name.
AGGREGATES = ("max", "min", "sum")
_AGGREGATE = re.compile(rf"^({'|'.join(AGGREGATES)})\((.*)\)$")
#: Format types that take an integer only (a float with no fraction is
#: shown as one).
_INTEGER_TYPES = set("bcdoxX")


#: Separators written with a backslash inside a name or value (a table
#: row label "hertz N=16, summary only"), hidden while the text is split.
_ESCAPES = {"\\,": "\ue000", "\\:": "\ue001", "\\@": "\ue002"}


class DatumError(ValueError):
    """A ``datum`` that cannot be shown; its message is one line."""


@dataclass(frozen=True)
class Datum:
    """A parsed ``FILE:COLUMN[@KEY=VALUE,...][:FORMAT]``."""

    file: str
    column: str                  # as written: "x", "max(x)", "rows"
    filters: tuple[tuple[str, str], ...]
    fmt: str | None

    def where(self) -> str:
        """The datum's file, column and filters, for a message."""
        text = f"{self.file}: {self.column}"
        if self.filters:
            text += " where " + ", ".join(f"{k}={v}"
                                         for k, v in self.filters)
        return text


def one_line(text: str) -> str:
    """``text`` with white space runs as one space and any other
    unprintable character escaped, so a message stays one line."""
    text = " ".join(str(text).split())
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)


def parse(spec: str) -> Datum:
    """Split the role's text into its parts.

    Parameters
    ----------
    spec : str
        ``FILE:COLUMN[@KEY=VALUE,...][:FORMAT]``.

    Returns
    -------
    Datum

    Raises
    ------
    DatumError
        If a part is missing or a filter is not ``KEY=VALUE``.
    """
    text = one_line(spec).strip()
    for escaped, hidden in _ESCAPES.items():
        text = text.replace(escaped, hidden)
    file, sep, rest = text.partition(":")
    if not sep or not file.strip() or not rest.strip():
        raise DatumError(f"datum {_shown(text)!r}: expected "
                         "FILE:COLUMN[@KEY=VALUE,...][:FORMAT]")
    selector, sep, fmt = rest.partition(":")
    column, _, filter_text = selector.partition("@")
    column = column.strip()
    file = file.strip()
    filters = []
    for item in filter_text.split(",") if filter_text.strip() else ():
        key, eq, value = item.partition("=")
        if not eq or not key.strip():
            raise DatumError(f"{_shown(file)}: {_shown(column)}: filter "
                             f"{_shown(item.strip())!r} "
                             "is not KEY=VALUE")
        filters.append((_shown(key.strip()), _shown(value.strip())))
    if not column:
        raise DatumError(f"{file}: no column in datum {_shown(text)!r}")
    return Datum(_shown(file), _shown(column), tuple(filters),
                 fmt.strip() if sep else None)


def _shown(text: str) -> str:
    """``text`` with each escaped separator back as itself."""
    for escaped, hidden in _ESCAPES.items():
        text = text.replace(hidden, escaped[1])
    return text


def _column(name: str, header: list[str]) -> str:
    """The column ``name`` names: itself, or ``$K`` the K-th (from 1)."""
    if name.startswith("$") and name[1:].isdigit() and \
            1 <= int(name[1:]) <= len(header):
        return header[int(name[1:]) - 1]
    return name


def _number(text: str):
    """``text`` as an int or a float, or None if it is neither."""
    try:
        return int(text)
    except ValueError:
        pass
    try:
        return float(text)
    except ValueError:
        return None


def read_rows(path: Path, label: str) -> tuple[list[str], list[dict]]:
    """The header and rows of a CSV file, its ``#`` lines skipped.

    Parameters
    ----------
    path : pathlib.Path
        The file.
    label : str
        What a message names first (the file as the page names it,
        the column and the filters).

    Returns
    -------
    (list of str, list of dict)
        The column names and one dict a row (column -> cell text).
    """
    try:
        with open(path, encoding="utf-8", newline="") as handle:
            lines = [line for line in handle
                     if not line.startswith("#") and line.strip()]
    except FileNotFoundError:
        raise DatumError(f"{label}: no such file") from None
    except (OSError, UnicodeDecodeError) as error:
        raise DatumError(f"{label}: cannot read it "
                         f"({one_line(error)})") from None
    try:
        table = list(csv.reader(lines))
    except csv.Error as error:
        raise DatumError(f"{label}: not a CSV table "
                         f"({one_line(error)})") from None
    if not table:
        raise DatumError(f"{label}: no header line")
    header = [name.strip() for name in table[0]]
    rows = []
    for number, cells in enumerate(table[1:], start=2):
        if len(cells) != len(header):
            raise DatumError(f"{label}: data row {number - 1} has "
                             f"{len(cells)} cells, the header "
                             f"{len(header)}")
        rows.append(dict(zip(header, (c.strip() for c in cells))))
    return header, rows


def _flat(value, prefix: str, row: dict) -> None:
    """The leaves of a JSON value as ``row``'s cells, each named by its
    path: ``key.inner`` through objects, ``key[0]`` through arrays."""
    if isinstance(value, dict):
        for key, inner in value.items():
            _flat(inner, f"{prefix}.{key}" if prefix else str(key), row)
    elif isinstance(value, list):
        for index, inner in enumerate(value):
            _flat(inner, f"{prefix}[{index}]", row)
    elif value is None:
        row[prefix] = ""
    elif isinstance(value, bool):
        row[prefix] = "1" if value else "0"
    else:
        row[prefix] = str(value)     # a float's shortest exact repr


def json_row(path: Path, label: str) -> tuple[list[str], list[dict]]:
    """A committed JSON object (a command's ``--json`` output) as a table
    of one row, its leaves the columns (:func:`_flat`)."""
    import json
    try:
        with open(path, encoding="utf-8") as handle:
            value = json.load(handle)
    except FileNotFoundError:
        raise DatumError(f"{label}: no such file") from None
    except (OSError, UnicodeDecodeError, ValueError) as error:
        raise DatumError(f"{label}: not a JSON file "
                         f"({one_line(error)})") from None
    if not isinstance(value, dict):
        raise DatumError(f"{label}: not a JSON object")
    row = {}
    _flat(value, "", row)
    return list(row), [row]


def _rows(base: Path, datum: Datum) -> tuple[list[str], list[dict]]:
    """The header and rows ``datum.file`` names: a CSV, or the K-th
    table of a committed benchmark run, ``NAME.md#K``
    (benchmark_runs.py)."""
    if "~" in datum.file:           # a table the run printed as text
        file, _, table = datum.file.partition("~")
        if not file.endswith(".md"):
            raise DatumError(f"{datum.where()}: ~K selects a printed table "
                             "of a benchmark run (.md), not of a CSV")
        try:
            number = int(table)
        except ValueError:
            raise DatumError(f"{datum.where()}: ~{table} is not a table "
                             "number") from None
        import printed_tables
        return printed_tables.table_rows(base / file, number,
                                         datum.where())
    file, hash_, table = datum.file.partition("#")
    if file.endswith(".json") and not hash_:
        return json_row(base / file, datum.where())
    if not file.endswith(".md"):
        if hash_:
            raise DatumError(f"{datum.where()}: #K selects a table of a "
                             "benchmark run (.md), not of a CSV")
        return read_rows(base / file, datum.where())
    import benchmark_runs

    try:
        number = int(table) if hash_ else 1
    except ValueError:
        raise DatumError(f"{datum.where()}: #{table} is not a table "
                         "number") from None
    return benchmark_runs.table_rows(base / file, number, datum.where())


def _matches(cell: str, wanted: str) -> bool:
    a, b = _number(cell), _number(wanted)
    if a is not None and b is not None:
        return a == b
    return cell == wanted


def _pages_exponent(text: str) -> str:
    """``4e-05`` as the pages write it, ``4e-5`` (``1.2e+06``: ``1.2e6``)."""
    mantissa, _, exponent = text.partition("e")
    return f"{mantissa}e{int(exponent)}"


def _format(value, datum: Datum) -> str:
    fmt = datum.fmt
    if fmt is None:
        return str(value)
    number = _number(value) if isinstance(value, str) else value
    if number is None:
        raise DatumError(f"{datum.where()}: {value!r} is not a number, "
                         f"for format {fmt!r}")
    if fmt[-1:] in _INTEGER_TYPES and isinstance(number, float):
        if not number.is_integer():
            raise DatumError(f"{datum.where()}: {value} is not an "
                             f"integer, for format {fmt!r}")
        number = int(number)
    try:
        if fmt.endswith("sci"):
            return _pages_exponent(format(number, fmt[:-3] + "e"))
        return format(number, fmt)
    except (ValueError, TypeError) as error:
        raise DatumError(f"{datum.where()}: bad format {fmt!r} "
                         f"({one_line(error)})") from None


def resolve(spec: str, base: str | Path) -> str:
    """The text the role ``{datum}`spec``` shows.

    Parameters
    ----------
    spec : str
        ``FILE:COLUMN[@KEY=VALUE,...][:FORMAT]`` (see the module).
    base : str or os.PathLike
        The directory ``FILE`` is relative to (``docs/``).

    Returns
    -------
    str
        The value, formatted.

    Raises
    ------
    DatumError
        A missing file, column or filter column; no matching row, or
        more than one for a plain column; an empty cell or a NaN; a
        value that is not a number where one is needed; a bad format.  One printable line
        naming the file, column and filters.
    """
    if one_line(spec).strip().startswith("="):
        return _expression(spec, base)
    datum = parse(spec)
    if Path(datum.file).is_absolute():
        raise DatumError(f"{datum.file}: FILE must be relative to docs/")
    header, rows = _rows(Path(base), datum)
    datum = Datum(datum.file, datum.column,
                  tuple((_column(k, header), v) for k, v in datum.filters),
                  datum.fmt)
    aggregate = _AGGREGATE.match(datum.column)
    name = aggregate.group(2).strip() if aggregate else datum.column
    name = _column(name, header)
    needed = [k for k, _ in datum.filters]
    if datum.column != "rows":
        needed.append(name)
    for column in needed:
        if column not in header:
            raise DatumError(f"{datum.where()}: no column {column!r} "
                             f"(the file has {', '.join(header)})")
    chosen = [row for row in rows
              if all(_matches(row[k], v) for k, v in datum.filters)]
    if datum.column == "rows":
        return _format(len(chosen), datum)
    if not chosen:
        raise DatumError(f"{datum.where()}: no row matches")
    if aggregate is None:
        if len(chosen) > 1:
            raise DatumError(f"{datum.where()}: {len(chosen)} rows match, "
                             "one is needed (add a filter or use "
                             "max(), min(), sum(), rows)")
        cell = chosen[0][name]
        if not cell:
            raise DatumError(f"{datum.where()}: the cell is empty")
        if isinstance(_number(cell), float) and math.isnan(_number(cell)):
            raise DatumError(f"{datum.where()}: the value is {cell}")
        return _format(cell, datum)
    numbers = []
    for row in chosen:
        number = _number(row[name])
        if number is None:
            raise DatumError(f"{datum.where()}: {row[name]!r} is not a "
                             "number")
        if not (isinstance(number, float) and math.isnan(number)):
            numbers.append(number)
    if not numbers:
        raise DatumError(f"{datum.where()}: every matching value is NaN")
    kind = aggregate.group(1)
    if kind == "sum":
        return _format(sum(numbers), datum)
    best = (max if kind == "max" else min)(numbers)
    if datum.fmt is None:    # as written in the file
        return next(row[name] for row in chosen
                    if _number(row[name]) == best)
    return _format(best, datum)


def _expression(spec: str, base: str | Path) -> str:
    """The text of an expression ``=EXPR[:FORMAT]`` (data_expressions)."""
    import data_expressions

    def value(inner: str):
        text = resolve(inner, base)
        number = _number(text.replace(",", ""))
        if number is None:
            raise DatumError(f"{inner}: {text!r} is not a number")
        return number

    number = data_expressions.evaluate(spec, value)
    fmt = data_expressions.split(spec)[2]
    return _format(number, Datum(one_line(spec).strip(), "=", (), fmt))


def files(spec: str) -> list[str]:
    """The files (relative to docs/) a use of the role reads."""
    if one_line(spec).strip().startswith("="):
        import data_expressions

        return [parse(inner).file.partition("#")[0]
                for inner in data_expressions.split(spec)[1]]
    return [parse(spec).file.partition("#")[0]]


def source_line(source: str, text: str, lineno: int) -> int:
    """The line of ``source`` (a file) where the role's ``text`` is,
    the first at or after ``lineno``; ``lineno`` if it is not found.

    MyST gives an inline role the line its paragraph starts on; an error
    points at the role's own line instead."""
    try:
        lines = Path(source).read_text(encoding="utf-8").splitlines(True)
    except (OSError, UnicodeDecodeError, ValueError):
        return lineno
    start = sum(len(line) for line in lines[:max(lineno - 1, 0)])
    whole = "".join(lines)
    at = whole.find(f"`{text}`", start)
    return lineno if at < 0 else whole.count("\n", 0, at) + 1


def datum_role(name, rawtext, text, lineno, inliner, options=None,
               content=None):
    """The ``datum`` role: the value as text, or an error at ``lineno``."""
    from docutils import nodes

    document = inliner.document
    env = getattr(document.settings, "env", None)
    base = Path(env.srcdir) if env is not None else Path(__file__).parents[1]
    try:
        if env is not None:      # a changed CSV rebuilds the page
            for file in files(text):
                env.note_dependency(str(base / file))
        value = resolve(text, base)
    except DatumError as error:
        line = source_line(document.get("source", ""), text, lineno)
        message = inliner.reporter.error(f"datum: {error}", line=line)
        problem = inliner.problematic(rawtext, rawtext, message)
        return [problem], [message]
    return [nodes.Text(value)], []


def setup(app):
    """Register the ``datum`` role."""
    app.add_role("datum", datum_role)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
