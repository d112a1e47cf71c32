"""What docs/preload-family.md says of the preload chart against the committed
chart (docs/studies/preload.csv, issue 25 item 5): the table of "The
preload chart", the headline row, the convergence table of
"Convergence of the answer" (each row's N, step and check at 2N and
half the step, its verdict, the first answer of a row searched again)
and the PNG beside it.  Reads files
only: the numbers' own checks are the slow tests of test_preload.py and
benchmarks/preload_study.py."""

from __future__ import annotations

import csv
import math
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
PAGE = ROOT / "docs" / "preload-family.md"
CHART = ROOT / "docs" / "studies" / "preload.csv"


def chart():
    lines = CHART.read_text().splitlines()
    body = [line for line in lines if not line.startswith("#")]
    rows = list(csv.DictReader(body))
    return {(float(r["d_in"]), float(r["ys_in"])): float(r["min_preload_lb"])
            for r in rows}, rows


def section(title: str) -> str:
    text = PAGE.read_text()
    start = text.index(title)
    end = re.search(r"^#{2,3} ", text[start + len(title):], flags=re.MULTILINE)
    return text[start:start + len(title) + (end.start() if end else
                                            len(text))]


def table(text: str, header: str) -> list[list[str]]:
    lines = text[text.index(header):].splitlines()
    rows = []
    for line in lines[2:]:
        if not line.startswith("|"):
            break
        rows.append([cell.strip() for cell in line.strip("|").split("|")])
    return rows


def same(quoted: str, value: float) -> bool:
    """The page's figure is the chart's to its 4 significant digits."""
    if math.isnan(value):
        return quoted in ("—", "-")
    return quoted == f"{value:.4g}"


def test_the_chart_table_shows_every_row_of_the_committed_chart():
    """One table row a chart row; its answer (a dash where the chart
    has none) and N are the roles that select that row."""
    answers, rows = chart()
    quoted = table(section("## The preload chart"),
                   "| d (in) | y_s (in) | min preload (lb) |")
    assert len(quoted) == len(rows) == 15
    assert {(float(c[0]), float(c[1])) for c in quoted} == set(answers)
    for cells in quoted:
        d, ys = float(cells[0]), float(cells[1])
        assert cells[2] == ("—" if math.isnan(answers[(d, ys)]) else
                            datum("min_preload_lb", d, ys)), cells
        assert cells[3] == datum("n_modes", d, ys, None), cells


def datum(column: str, d: float, ys: float, fmt: str | None = ".4g") \
        -> str:
    """The role that shows the chart's ``column`` at (d, y_s)."""
    return (f"{{datum}}`studies/preload.csv:{column}@d_in={d:g},"
            f"ys_in={ys:g}" + (f":{fmt}`" if fmt else "`"))


def test_the_headline_row_is_the_committed_one():
    """The headline's number is the role that selects the row the
    sentence names (the role's resolution is held elsewhere), and that
    row of the chart has an answer, converged."""
    answers, rows = chart()
    text = " ".join(section("## The preload chart").split())
    assert ("**At y_s = 0.5 in and d = 0.25 in, at least "
            + datum("min_preload_lb", 0.25, 0.5) + " lb**") in text
    [row] = [r for r in rows
             if (float(r["d_in"]), float(r["ys_in"])) == (0.25, 0.5)]
    assert not math.isnan(answers[(0.25, 0.5)]) and row["converged"] == "1"


def convergence_rows():
    return table(section("### Convergence of the answer"),
                 "| d (in) | y_s (in) | answer (lb) | N |")


def searched_again():
    """(d, y_s) -> the first search's "answer at N = n", from the
    chart's notes ("searched again: a lb at N = n, ...")."""
    found = {}
    for line in CHART.read_text().splitlines():
        m = re.match(r"# d = ([\d.]+) in, y_s = ([\d.]+) in: searched "
                     r"again: ([\d.]+) lb at N = (\d+)", line)
        if m:
            found[(float(m[1]), float(m[2]))] = f"{m[3]} at N = {m[4]}"
    return found


def test_the_convergence_table_quotes_every_answer_and_its_check():
    """Every row with an answer: its answer, N, step and check the
    roles that select that row of the committed chart, the verdict its
    ``converged`` column, and the first answer of a row searched again
    the chart's note."""
    answers, rows = chart()
    by_key = {(float(r["d_in"]), float(r["ys_in"])): r for r in rows}
    quoted = convergence_rows()
    with_answer = {k for k, v in answers.items() if not math.isnan(v)}
    assert {(float(c[0]), float(c[1])) for c in quoted} == with_answer
    again = searched_again()
    for cells in quoted:
        key = d, ys = (float(cells[0]), float(cells[1]))
        row = by_key[key]
        assert cells[2:6] == [datum("min_preload_lb", d, ys),
                              datum("n_modes", d, ys, None),
                              datum("dt_s", d, ys, "g"),
                              datum("check_n_modes", d, ys, None)], key
        assert cells[6] == ("yes" if row["converged"] == "1" else "NO"), key
        assert cells[7] == again.get(key, "—"), key


def test_the_page_counts_the_converged_rows_as_the_chart_does():
    """The page says "all" of the rows with an answer are converged,
    their number the role that counts the converged rows: so every row
    of the chart with an answer is converged, and only those."""
    _, rows = chart()
    with_answer = [r for r in rows if r["min_preload_lb"] != "nan"]
    converged = [r for r in rows if r["converged"] == "1"]
    assert converged == with_answer
    count = "{datum}`studies/preload.csv:rows@converged=1`"
    text = " ".join(section("### Convergence of the answer").split())
    chart_text = " ".join(section("## The preload chart").split())
    assert f"**All {count} rows with an answer are converged to 2 %" in text
    assert f"as are all {count} rows with an answer" in chart_text


def test_the_png_is_committed_beside_the_csv():
    png = CHART.with_suffix(".png")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "![The preload chart](studies/preload.png)" in PAGE.read_text()
