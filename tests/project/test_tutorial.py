"""docs/tutorial.md shows what its commands print (issue 30, items 3
and 8): every command block followed by an output block is run, in
order, in a scratch directory, and the output shown is compared with
what it prints; the committed CSVs of its slow steps
(docs/studies/tutorial_*.csv) are what the code computes, and the
page's summary numbers are what those rows give.

Numbers are compared to 2e-5 of their value: the commands print six
significant digits, so a platform's last-bit difference may move the
last printed digit by one, and nothing more.
"""

from __future__ import annotations

import csv
import io
import math
import re
import sys

import numpy as np
import pytest

from conftest import ROOT

sys.path.insert(0, str(ROOT / "docs" / "_ext"))
import tutorial_outputs as tutorial  # noqa: E402

NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)(e[-+]?\d+)?[,;:)]?$", re.I)
#: Lines whose numbers are the machine's, not the model's.
VOLATILE = ("elapsed_s",)


def numbers_agree(a: str, b: str) -> bool:
    """To the page's digits (2e-5); a zero to round-off (Wilson's lower
    end at p = 0 computes as 3e-18)."""
    x, y = float(a.rstrip(",;:)")), float(b.rstrip(",;:)"))
    return x == y or abs(x - y) <= max(2e-5 * max(abs(x), abs(y)), 1e-15)


#: What a failure says: the page is regenerated, not edited by hand.
REGENERATE = ("docs/tutorial.md differs from what the code prints; if the "
              "code's change is intended, run python "
              "docs/_ext/tutorial_outputs.py and read the diff")


def assert_same_output(shown: str, printed: str, what: str) -> None:
    what = f"{what}: {REGENERATE}"
    expected = tutorial.shown(printed).splitlines()
    lines = shown.splitlines()
    assert len(lines) == len(expected), (what, lines[-1:], expected[-1:])
    for old, new in zip(lines, expected):
        if any(word in old for word in VOLATILE):
            assert old.split("=")[0] == new.split("=")[0], (what, old, new)
            continue
        old_words, new_words = old.split(), new.split()
        assert len(old_words) == len(new_words), (what, old, new)
        for a, b in zip(old_words, new_words):
            if NUMBER.match(a) and NUMBER.match(b):
                assert numbers_agree(a, b), (what, old, new)
            else:
                assert a == b, (what, old, new)


def test_the_page_has_its_steps():
    steps = tutorial.steps()
    assert len(steps) >= 6
    assert all(step.shown.strip() for step in steps), "an empty output"
    assert len(tutorial.setup_steps()) == 1
    assert "my_relay.json" in tutorial.setup_steps()[0].code


def test_quick_outputs_are_what_the_commands_print(tmp_path):
    for step in tutorial.setup_steps():
        tutorial.run(step, tmp_path, {})
    for step in tutorial.steps():
        if step.slow:
            continue
        assert_same_output(step.shown, tutorial.run(step, tmp_path, {}),
                           step.command)


def parse_csv(text: str) -> tuple[list[str], list[str], list[list[str]]]:
    lines = text.splitlines()
    comments = [line for line in lines if line.startswith("#")]
    header, *rows = list(csv.reader(io.StringIO("\n".join(
        line for line in lines if not line.startswith("#")))))
    return comments, header, rows


def assert_same_csv(committed: str, fresh: str, what: str) -> None:
    """Comments, header and text exactly; numbers to 1e-10 of their
    column's largest magnitude (12 significant digits are written)."""
    old_comments, old_header, old_rows = parse_csv(committed)
    new_comments, new_header, new_rows = parse_csv(fresh)
    assert old_comments == new_comments, what
    assert old_header == new_header, what
    assert len(old_rows) == len(new_rows), what
    for k, column in enumerate(old_header):
        old = [row[k] for row in old_rows]
        new = [row[k] for row in new_rows]
        try:
            a, b = np.array(old, dtype=float), np.array(new, dtype=float)
        except ValueError:
            assert old == new, (what, column)
            continue
        assert np.array_equal(np.isnan(a), np.isnan(b)), (what, column)
        ok = ~np.isnan(a)
        scale = np.max(np.abs(b[ok]), initial=0.0)
        assert np.all(np.abs(a[ok] - b[ok]) <= 1e-10 * scale), (what, column)


def shown_value(step, name: str) -> str:
    line, = [line for line in step.shown.splitlines()
             if line.split("=")[0].strip() == name]
    return line.split("=", 1)[1].strip()


def test_the_pages_tolerance_numbers_are_the_committed_rows():
    """p_open, its Wilson interval and n_open on the page are what the
    committed rows give (counted here, the interval by its formula)."""
    step, = [s for s in tutorial.steps() if "tolerance.csv" in s.code]
    _, header, rows = parse_csv(tutorial.TOLERANCE_CSV.read_text())
    status = np.array([int(r[header.index("status")]) for r in rows])
    events = np.array([int(r[header.index("n_events")]) for r in rows])
    n, opened = int(np.sum(status == 0)), int(np.sum(events[status == 0] > 0))
    assert int(shown_value(step, "n")) == n == 100
    assert int(shown_value(step, "n_open")) == opened
    assert numbers_agree(shown_value(step, "p_open"), repr(opened / n))
    # Wilson's interval, z = 1.959964 (95 %), from its formula
    z = 1.959963984540054
    p = opened / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z / (1 + z * z / n) * math.sqrt(p * (1 - p) / n
                                           + z * z / (4 * n * n))
    low, high = shown_value(step, "p_open_ci95").split(", ")
    assert numbers_agree(low, repr(centre - half))
    assert numbers_agree(high, repr(centre + half))


def test_the_pages_preload_is_the_committed_search():
    step, = [s for s in tutorial.steps() if "min_preloads" in s.code]
    comments, header, rows = parse_csv(tutorial.PRELOAD_CSV.read_text())
    # the columns of contactsep preload --csv: one layout for both
    from contactsep.studies.preload_answer import CSV_COLUMNS
    assert header == list(CSV_COLUMNS)
    rows = [dict(zip(header, r)) for r in rows]
    assert {(r["search"], r["n"], r["n_failed"], r["n_modes"], r["dt_s"])
            for r in rows} == {("nominal", "1", "0", "8", "")}
    assert all(r["n_open"] == r["event"] for r in rows)
    smallest = float([c for c in comments if "min_preload_lb" in c][0]
                     .split(" = ")[1])
    printed = re.search(r"no event: (\S+) lb", step.shown).group(1)
    assert numbers_agree(printed, f"{smallest:.4g}")
    # the answer is a simulated preload with no event, and no preload
    # above it gave one
    preloads = np.array([float(r["preload_lb"]) for r in rows])
    event = np.array([r["event"] == "1" for r in rows])
    assert smallest in preloads and not event[preloads == smallest][0]
    assert not np.any(event[preloads >= smallest])
    assert np.any(event[preloads < smallest])


@pytest.mark.slow
def test_the_preload_search_is_what_the_code_computes(tmp_path):
    """The page's Python step (about 90 s): its output, and the
    committed CSV of every preload it simulated."""
    step, = [s for s in tutorial.steps() if "min_preloads" in s.code]
    namespace: dict = {}
    assert_same_output(step.shown, tutorial.run(step, tmp_path, namespace),
                       "min_preloads")
    assert_same_csv(tutorial.PRELOAD_CSV.read_text(),
                    tutorial.preload_csv_text(namespace["search"],
                                              namespace["relay"]),
                    "tutorial_preload.csv")


@pytest.mark.slow
def test_the_tolerance_study_is_what_the_code_computes(tmp_path):
    """The page's sweep (100 Hertz simulations with a preload, about
    two minutes): its output and its rows."""
    for step in tutorial.setup_steps():
        tutorial.run(step, tmp_path, {})
    step, = [s for s in tutorial.steps() if "tolerance.csv" in s.code]
    assert_same_output(step.shown, tutorial.run(step, tmp_path, {}),
                       "sweep")
    assert_same_csv(tutorial.TOLERANCE_CSV.read_text(),
                    (tmp_path / "tolerance.csv").read_text(),
                    "tutorial_tolerance.csv")
