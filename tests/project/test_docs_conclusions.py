"""docs/circuit-opening.md's tables of the thesis's conclusions against circuit
opening ("The thesis's conclusions and circuit opening") quote the
committed studies (docs/studies/conclusion3|5|6|7.csv, `contactsep study
conclusionN --csv`), row for row: the datum roles that draw each row's
values from its study (the open time scaled to ms by the role's
expression).  Reads files only: the studies are three-beam searches of
minutes each."""

from __future__ import annotations

import csv
import math
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "circuit-opening.md"
STUDIES = ROOT / "docs" / "studies"

#: Each study's table: its header start, the column its rows are
#: selected by, and whether R is shown after it.
LEADING = {
    "conclusion5": ("| d (in) |", "d_in", False),
    "conclusion6": ("| γ2 (lb/in³) | R |", "gamma2_lb_in3", True),
    "conclusion7": ("| x3/L3 |", "r", False),
    "conclusion3": ("| e |", "e", False),
}


def rows(name: str) -> list[dict]:
    lines = [line for line in (STUDIES / f"{name}.csv").read_text()
             .splitlines() if not line.startswith("#")]
    return list(csv.DictReader(lines))


def rounded(row: dict) -> list[str]:
    """The page's rounding: y3 to 4 decimals, the gap to 3 digits, the
    open time in ms to 0.1, the preload to 4 digits."""
    return [f"{float(row['y3_max_in']):.4f}",
            f"{float(row['max_lower_gap_in']):.3g}",
            f"{1e3 * float(row['circuit_open_s']):.1f}", row["n_events"],
            f"{float(row['min_preload_lb']):.4g}"]


def cells(name: str, key: str, row: dict) -> list[str]:
    """A row's cells after its leading ones: the roles that show y3 to
    4 decimals, the gap to 3 digits, the events and the preload to 4
    digits, selected by the row's ``key``; the open time in ms to 0.1,
    the role's expression scaling the study's seconds."""
    where = f"{key}={float(row[key]):g}"

    def role(column, fmt=None):
        fmt = f":{fmt}" if fmt else ""
        return f"{{datum}}`studies/{name}.csv:{column}@{where}{fmt}`"

    open_ms = (f"{{datum}}`=1000 * [studies/{name}.csv:circuit_open_s@"
               f"{where}]:.1f`")
    return [role("y3_max_in", ".4f"), role("max_lower_gap_in", ".3g"),
            open_ms, role("n_events"), role("min_preload_lb", ".4g")]


def section() -> str:
    text = PAGE.read_text()
    start = text.index("## The thesis's conclusions and circuit opening")
    end = re.search(r"^## ", text[start + 3:], flags=re.MULTILINE)
    return text[start:start + 3 + end.start()]


@pytest.mark.parametrize("name", sorted(LEADING))
def test_the_conclusion_table_quotes_its_study(name):
    """Row for row, the study's key as text and the rest of its values
    the roles that select that row."""
    header, key, with_r = LEADING[name]
    text = section()
    lines = text[text.index(header + " eq. 23 max y3 (in)"):].splitlines()
    quoted = []
    for line in lines[2:]:
        if not line.startswith("|"):
            break
        quoted.append([c.strip() for c in line.strip("|").split("|")])
    def r_role(r):
        return (f"{{datum}}`studies/{name}.csv:R@{key}="
                f"{float(r[key]):g}:.2f`")

    expected = [[f"{float(r[key]):.1f}" if key == "r" else
                 f"{float(r[key]):g}"]
                + ([r_role(r)] if with_r else [])
                + cells(name, key, r) for r in rows(name)]
    assert quoted == expected


#: Each study's row that is the thesis rig itself (d = 0.25 in, the
#: rig's density, its tip contact point, the elastic contact).
THESIS_ROW = {"conclusion5": ("d_in", 0.25), "conclusion6": (
    "gamma2_lb_in3", 0.1), "conclusion7": ("r", 1.0), "conclusion3": (
    "e", 1.0)}


def test_every_study_has_the_thesis_rig_s_row_of_the_chart():
    """Four studies and the preload chart search the same design (the
    thesis rig, y_s = 0.5 in, elastic Hertz, N = 32, the chart's step
    and window) in separate runs: the same answer and figures."""
    chart = [r for r in rows("preload") if float(r["d_in"]) == 0.25
             and float(r["ys_in"]) == 0.5]
    assert len(chart) == 1 and int(chart[0]["n_modes"]) == 32
    found = []
    for name, (column, value) in THESIS_ROW.items():
        (row,) = [r for r in rows(name) if float(r[column]) == value]
        found.append(rounded(row)[1:])
    assert all(f == found[0] for f in found)
    assert found[0][-1] == f"{float(chart[0]['min_preload_lb']):.4g}"


# The committed studies themselves (`contactsep study conclusionN
# --csv`, 6-18 min each on one core, once regenerated here in the slow
# set): tests/project/test_committed_searches.py simulates again the
# runs that decide each row's preload, one row's no-preload run, and
# every row's eq. 23 by the other backend.


# the physical separator's (`--separator physical`): "With the physical
# separator (issue 27)"

def physical_section() -> str:
    """The preload page's last section: the physical separator's chart
    and conclusions."""
    text = (ROOT / "docs" / "preload-family.md").read_text()
    start = text.index("### With the physical separator")
    end = re.search(r"^## ", text[start:], flags=re.MULTILINE)
    return text[start:start + end.start() if end else len(text)]


def quoted_table(text: str, header: str) -> list[list[str]]:
    lines = text[text.index(header):].splitlines()
    out = [[c.strip() for c in lines[0].strip("|").split("|")]]
    for line in lines[2:]:
        if not line.startswith("|"):
            break
        out.append([c.strip() for c in line.strip("|").split("|")])
    return out


def datum(name: str, d: float, ys: float) -> str:
    """The datum role that shows chart ``name``'s answer at (d, y_s)."""
    return (f"{{datum}}`studies/{name}.csv:min_preload_lb@d_in={d:g},"
            f"ys_in={ys:g}:.3g`")


def test_the_physical_chart_quotes_both_charts():
    """Each cell: the physical chart's answer and the clamped one's in
    parentheses ("none" where the clamped chart has none), the roles
    that select the cell's row of each; every row of both charts."""
    physical = {(float(r["d_in"]), float(r["ys_in"])): float(
        r["min_preload_lb"]) for r in rows("preload_physical")}
    rigid = {(float(r["d_in"]), float(r["ys_in"])): float(
        r["min_preload_lb"]) for r in rows("preload")}
    table = quoted_table(physical_section(), "| y_s (in) | d = 0.125 |")
    ds = (0.125, 0.25, 0.35, 0.5, 0.75)
    assert len(table) == 4
    assert {(d, float(c[0])) for c in table[1:] for d in ds} == \
        set(physical) == set(rigid)
    assert not any(math.isnan(v) for v in physical.values())
    for cells in table[1:]:
        ys = float(cells[0])
        assert cells[1:] == [
            f"{datum('preload_physical', d, ys)} ("
            + ("none" if math.isnan(rigid[d, ys]) else
               datum("preload", d, ys)) + ")" for d in ds], ys


def test_the_physical_conclusion_5_table_quotes_its_study():
    """Row for row, the d as text, the gap, events and preload the roles
    that select the row."""
    table = quoted_table(physical_section(),
                         "| d (in) | max lower gap (in) |")
    name = "conclusion5_physical"
    assert table[1:] == [
        [f"{float(r['d_in']):g}"] + [
            c for i, c in enumerate(cells(name, "d_in", r)) if i != 0]
        for r in rows(name)]


@pytest.mark.parametrize("name, header, column", [
    ("conclusion6_physical", "| conclusion 6: γ2 (lb/in³) |",
     "gamma2_lb_in3"),
    ("conclusion7_physical", "| conclusion 7: x3/L3 |", "r"),
    ("conclusion3_physical", "| conclusion 3: e |", "e")])
def test_the_physical_conclusion_rows_quote_their_study(name, header,
                                                        column):
    """The study's values in the header row as text; the gap and the
    preload (each study has one for every value) the roles that select
    their column's row."""
    table = quoted_table(physical_section(), header)
    found = rows(name)
    values = [float(v) for v in table[0][1:]]
    assert values == [float(r[column]) for r in found]
    assert not any(math.isnan(float(r["min_preload_lb"])) for r in found)

    def role(key, fmt, r):
        return (f"{{datum}}`studies/{name}.csv:{key}@{column}="
                f"{float(r[column]):g}:{fmt}`")

    assert table[1] == ["max lower gap (in)"] + [
        role("max_lower_gap_in", ".3g", r) for r in found]
    assert table[2] == ["min preload (lb)"] + [
        role("min_preload_lb", ".3g", r) for r in found]
