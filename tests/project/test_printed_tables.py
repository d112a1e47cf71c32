"""The tables a benchmark printed as text (docs/_ext/printed_tables.py),
read as tables for the ``datum`` role (``NAME.md~K``): a planted run in
the printed layouts the committed runs use, and every committed run,
each full row against its line split on spaces."""

from __future__ import annotations

import sys

import pytest

from conftest import ROOT

sys.path.insert(0, str(ROOT / "docs" / "_ext"))

import benchmark_runs  # noqa: E402
import data_values  # noqa: E402
import printed_tables  # noqa: E402

RUN = """<!-- python benchmarks/bench_scaling.py (printed output, copied) -->
run 2026-11-26 11:22 UTC, commit 5dc6b1c, load 1.7 (1-min avg), 2 cores

usable cores 2; load average 1.70 1.33 0.72 at the start
  k yardstick s speed-up
  1        0.49     1.00
  2        0.51     1.91

 sweep engine   k  seconds speed-up efficiency dask/local parent %
  eq23  local   1    32.62     1.00       1.00                   -
  eq23  local   2    16.54     1.97       1.03                 0.2
  eq23   dask   2    16.74     1.95       1.02       0.99      2.5
 hertz   dask  16     3.53    11.47       1.55       0.95      2.7
load average 1.74 1.44 0.88 at the end

search engine   k  seconds dask/local parent % same answer
robust  local   2     2.17                 2.6 yes
robust   dask   2     3.42       0.63      8.5 yes
"""


@pytest.fixture
def run_file(tmp_path):
    path = tmp_path / "run.md"
    path.write_text(RUN)
    return path


def test_the_planted_run_reads_as_three_tables(run_file):
    first, sweep, search = [printed_tables.table_rows(run_file, k, "run")
                            for k in (1, 2, 3)]
    assert first == (["k", "yardstick s", "speed-up"],
                     [{"k": "1", "yardstick s": "0.49", "speed-up": "1.00"},
                      {"k": "2", "yardstick s": "0.51", "speed-up": "1.91"}])
    names, rows = sweep
    assert names == ["sweep", "engine", "k", "seconds", "speed-up",
                     "efficiency", "dask/local", "parent %"]
    # the closing "load average" line is not a row; "-" is NaN; a column
    # empty on a row is an empty cell
    assert len(rows) == 4
    assert rows[0]["parent %"] == "nan" and rows[0]["dask/local"] == ""
    assert rows[3] == {"sweep": "hertz", "engine": "dask", "k": "16",
                       "seconds": "3.53", "speed-up": "11.47",
                       "efficiency": "1.55", "dask/local": "0.95",
                       "parent %": "2.7"}
    names, rows = search
    assert names == ["search", "engine", "k", "seconds", "dask/local",
                     "parent %", "same answer"]
    assert [row["same answer"] for row in rows] == ["yes", "yes"]
    assert rows[1]["dask/local"] == "0.63" and rows[0]["dask/local"] == ""


def test_a_datum_reads_a_printed_cell_and_aggregates_skip_nan(run_file):
    base = run_file.parent
    assert data_values.resolve("run.md~1:speed-up@k=2", base) == "1.91"
    assert data_values.resolve(
        "run.md~2:dask/local@sweep=eq23,engine=dask,k=2", base) == "0.99"
    assert data_values.resolve("run.md~2:max(parent %)", base) == "2.7"
    assert data_values.resolve("run.md~3:rows@same answer=yes", base) == "2"
    assert data_values.resolve(
        "=[run.md~2:seconds@engine=local,k=1] / "
        "[run.md~2:seconds@engine=local,k=2]:.2f", base) == "1.97"


@pytest.mark.parametrize("spec, words", [
    ("run.md~4:k", "the run has 3 printed tables, not a printed table 4"),
    ("run.md~x:k", "~x is not a table number"),
    ("data.csv~1:k", "~K selects a printed table of a benchmark run"),
    ("run.md~2:parent %@engine=local,k=1", "the value is nan"),
    ("run.md~2:dask/local@engine=local,k=1", "the cell is empty"),
])
def test_a_printed_datum_that_cannot_be_shown_is_one_line(run_file, spec,
                                                         words):
    (run_file.parent / "data.csv").write_text("k\n1\n")
    with pytest.raises(data_values.DatumError) as error:
        data_values.resolve(spec, run_file.parent)
    assert words in str(error.value) and "\n" not in str(error.value)


def _committed_runs():
    return sorted((ROOT / "benchmarks" / "results").glob("*.md"))


@pytest.mark.parametrize("path", _committed_runs(), ids=lambda p: p.stem)
def test_every_full_printed_row_is_its_line_split_on_spaces(path):
    """Independently of the column rule: a row with every cell one word
    holds its line's words in order."""
    run = benchmark_runs.read_run(path)
    lines = [line for part in run.parts if part.kind == "text"
             for line in part.lines]
    for part in run.parts:
        if part.kind != "text":
            continue
        for names, rows in printed_tables.printed_tables(list(part.lines)):
            for row in rows:
                cells = ["-" if row[n] == "nan" else row[n] for n in names]
                if all(cells) and all(len(c.split()) == 1 for c in cells):
                    assert " ".join(cells) in {" ".join(line.split())
                                               for line in lines}, row


def test_the_scaling_runs_hold_their_printed_tables():
    """The committed scaling runs, whose sentences on the pages draw from
    them: the tables and rows their printed text has (counted by eye
    in the files: 2 and 2 + 8 rows; 4 runs of 5 + 10, 5 + 20 rows)."""
    def tables(name):
        run = benchmark_runs.read_run(
            ROOT / "benchmarks" / "results" / f"{name}.md")
        return [len(rows) for part in run.parts if part.kind == "text"
                for _, rows in printed_tables.printed_tables(
                    list(part.lines))]
    assert tables("bench_scaling") == [2, 8]
    assert tables("bench_scaling_16cores") == [5, 10, 5, 20]
    assert tables("bench_scaling_budget") == [2, 8, 2, 2]
