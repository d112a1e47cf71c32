"""The committed preload searches (issue 45, item 5): the preload charts
(docs/studies/preload.csv, preload_physical.csv) and the conclusion
studies (conclusion3|5|6|7.csv) are checked fast, not regenerated.  Their
regeneration is minutes of three-beam searches (thousands of
simulations); the slow set ran it through the docs' shell commands and
test_docs_conclusions.  Here, for every row, the two runs that decide
its answer are simulated again at the committed settings:

* the answer itself has no event (it is a tested preload, closed);
* the tested preload just below it has one: the answer is the upper end
  of the search's last bracket, whose lower end had an event.  An answer
  the bisection gave lies on its tree, 2^(j/128) lb (a grid value 2^(k/4)
  halved five times to within 1 %), and the lower end is one step of
  2^(1/128) below; one the fine band gave lies on the fine grid
  FINE_RATIO^j lb, and the lower end is the fine value below.  Which one
  a row's answer is, is read from the number itself (an answer on
  neither is a failure);
* a row with no answer (NaN) has an event at the highest preload the
  search tried, the one its '#' line names.

A converged row (``converged`` 1) also has no event 2 % above its answer
at its ``check_n_modes`` and half its step (the check's half that does
not need a search).  The conclusion studies' other columns: eq. 23's
max y3 of every row by the other backend (numpy; the study used the
compiled one), and the no-preload run of one row, chosen by the study's
name, simulated again.  The '#' lines say what settings these are
(pinned as text: a change of the search's rule shows here), the columns
are the ones named with their units, and the page that documents each
study names the command that regenerates it.
"""

from __future__ import annotations

import csv
import math
import re
import zlib

import numpy as np
import pytest

from conftest import ROOT

STUDIES = ROOT / "docs" / "studies"
#: The search's fine grid and the bisection's last step (search.py).
FINE_RATIO = 1.0099
TREE = 128
#: The notes of every chart and study searched by the chart's rule.
RULE = ("an event: the circuit open (both gaps above 1e-6 in) for at "
        "least 1e-05 s")
CHART_RULE = (
    "min_preload_lb: the smallest tested preload above which every "
    "tested preload has no event; scan 2^(k/4) lb upward from 1/16 lb "
    "until an octave above the last event is closed, bisection to 1%, "
    "then every 0.99% step from 0.7 to 2 times the answer simulated, "
    "closed above it")
CHART_COLUMNS = ["model", "n_modes", "d_in", "ys_in", "min_preload_lb"]
#: chart -> (its design's fields beside the thesis rig, its page, the
#: command there that regenerates it, its columns).
CHARTS = {
    "preload": ({}, "preload-family.md",
                "contactsep study preload --converge --csv "
                "docs/studies/preload.csv",
                CHART_COLUMNS + ["dt_s", "check_n_modes", "converged"]),
    "preload_physical": ({"beam2": "timoshenko", "kr2": 21900.0},
                         "preload-family.md",
                         "contactsep study preload --separator physical "
                         "--csv docs/studies/preload_physical.csv",
                         CHART_COLUMNS),
}
#: study -> (its field, the column that holds the field's value, its
#: leading columns, the Hertz contact's damping).
CONCLUSIONS = {
    "conclusion3": ("e", "e", ["e"], "flores"),
    "conclusion5": ("h2", "d_in", ["d_in"], "none"),
    "conclusion6": ("gamma2", "gamma2_lb_in3", ["R", "gamma2_lb_in3"],
                    "none"),
    "conclusion7": ("x3", "x3_in", ["r", "x3_in"], "none"),
}
CONCLUSION_COLUMNS = ["y3_max_in", "max_lower_gap_in", "circuit_open_s",
                      "n_events", "min_preload_lb"]
PHYSICAL = "separator (member 2) beam physics: beam2 = timoshenko"


def read(name: str) -> tuple[list[str], list[str], list[dict]]:
    """A committed CSV's '#' lines (without '# '), header and rows."""
    lines = (STUDIES / f"{name}.csv").read_text(encoding="utf-8") \
        .splitlines()
    notes = [line[2:] for line in lines if line.startswith("# ")]
    table = [line for line in lines if not line.startswith("#")]
    return notes, table[0].split(","), list(csv.DictReader(table))


def below(answer: float) -> float:
    """The tested preload just below an answer: the last bracket's lower
    end (module docstring)."""
    tree = TREE * math.log2(answer)
    if abs(tree - round(tree)) < 1e-6:
        return 2.0 ** ((round(tree) - 1) / TREE)
    fine = math.log(answer) / math.log(FINE_RATIO)
    assert abs(fine - round(fine)) < 1e-6, (
        f"{answer!r} lb is on neither the bisection's tree nor the fine "
        f"grid")
    return FINE_RATIO ** (round(fine) - 1)


def event(design, preload: float, dt: float, damping: str) -> bool:
    """Whether the search's run (the chart's settings) has an event."""
    from contactsep.constants import LISTING_TAU_S
    from contactsep.studies.preload.chart import _simulate_event
    from contactsep.studies.preload.runs import PreloadRun
    settings = {"damping": damping, "dt": dt, "t_end": LISTING_TAU_S}
    return _simulate_event(PreloadRun(design, "hertz", settings, preload))


def decide(design, row: dict, notes: list[str], where: str, dt: float,
           damping: str) -> None:
    """The runs that decide a row's min_preload_lb (module docstring)."""
    answer = float(row["min_preload_lb"])
    if math.isnan(answer):
        (note,) = [n for n in notes if n.startswith(f"no answer at {where}")]
        top = float(re.search(r"an event at ([\d.]+) lb", note).group(1))
        assert event(design, top, dt, damping), (where, top)
        return
    assert not event(design, answer, dt, damping), (where, answer)
    assert event(design, below(answer), dt, damping), (where, answer)


def page_names(page: str, command: str) -> bool:
    text = (ROOT / "docs" / page).read_text(encoding="utf-8")
    return command in text.replace("\\\n", " ")


def test_an_answer_s_lower_end_is_found_or_refused():
    """The rule can fail: an answer on neither grid is refused."""
    assert below(2.0 ** (507 / TREE)) == pytest.approx(2.0 ** (506 / TREE))
    assert below(FINE_RATIO ** 35) == pytest.approx(FINE_RATIO ** 34)
    with pytest.raises(AssertionError):
        below(15.5)


@pytest.mark.parametrize("name", sorted(CHARTS))
def test_the_chart_s_answers_are_its_deciding_runs(name):
    from contactsep.studies.study import thesis_study_design
    fields, page, command, columns = CHARTS[name]
    notes, header, rows = read(name)
    assert header == columns
    assert page_names(page, command), command
    assert notes[0] == ("The smallest lower-contact preload with no "
                        "discontinuity event in the window")
    assert notes[1].startswith("model hertz, damping none, N = 32 modes "
                               "per member, the adaptive stepper at dt "
                               "5e-08 s, window 0-0.06 s from the "
                               "release; ") and notes[1].endswith(RULE)
    assert notes[2] == CHART_RULE
    assert (PHYSICAL in "\n".join(notes)) == bool(fields)
    assert [(float(r["d_in"]), float(r["ys_in"])) for r in rows] == [
        (d, ys) for d in (0.125, 0.25, 0.35, 0.5, 0.75)
        for ys in (0.25, 0.5, 0.75)]
    for row in rows:
        d, ys, n = float(row["d_in"]), float(row["ys_in"]), \
            int(row["n_modes"])
        dt = float(row.get("dt_s", 5e-8))
        assert row["model"] == "hertz" and (n, dt) in {(32, 5e-8),
                                                       (64, 2.5e-8)}
        design = thesis_study_design(d=d, ys=ys, n_modes=n, **fields)
        where = f"d = {d:g} in, y_s = {ys:g} in" + (
            f" (N = {n})" if n != 32 else "")
        decide(design, row, notes, where, dt, "none")
        if row.get("converged") == "1":
            check = int(row["check_n_modes"])
            assert check == 2 * n
            twice = thesis_study_design(d=d, ys=ys, n_modes=check, **fields)
            assert not event(twice, 1.02 * float(row["min_preload_lb"]),
                             dt / 2, "none"), (where, "check")


@pytest.mark.parametrize("name", sorted(CONCLUSIONS))
def test_the_conclusion_s_rows_are_its_deciding_runs(name):
    from contactsep.chatter import simulate
    from contactsep.constants import LISTING_TAU_S
    from contactsep.model import evaluate
    from contactsep.model.fields import column_name
    from contactsep.studies.study import thesis_study_design
    field, column, leading, damping = CONCLUSIONS[name]
    notes, header, rows = read(name)
    assert header == leading + CONCLUSION_COLUMNS
    assert page_names("circuit-opening.md", f"contactsep study {name}")
    assert notes[1].startswith(f"the thesis (conclusion {name[-1]}): ")
    law = ("Hertz contact, Flores damping calibrated to e"
           if damping == "flores" else "Hertz contact, elastic")
    assert notes[2] == (
        f"y3_max_in: eq. 23 as printed, N = 32; the rest: the three "
        f"beams, {law}, N = 32, the adaptive stepper at dt 5e-08 s, "
        f"window 0-0.06 s from the release")
    assert notes[3].startswith("max_lower_gap_in, circuit_open_s, "
                               "n_events: no preload; min_preload_lb: ")
    base = thesis_study_design(n_modes=32)
    values = np.array([float(r[column]) for r in rows])
    designs = [base.replace(**{field: float(v)}) for v in values]
    y3 = evaluate(base.replace(**{field: values}), backend="numpy").y3_max
    np.testing.assert_allclose(
        y3, [float(r["y3_max_in"]) for r in rows], rtol=1e-9)
    for row, value, design in zip(rows, values, designs):
        where = f"{column_name(field)} = {value:g}"
        decide(design, row, notes, where, 5e-8, damping)
    # one row's no-preload run, the row chosen by the study's name
    k = zlib.crc32(name.encode()) % len(rows)
    settings = {"dt": 5e-8, "t_end": LISTING_TAU_S}
    if damping == "flores":
        settings["damping"] = "flores"
    r = simulate(designs[k], model="hertz", samples=1,
                 single_impulse=False, **settings)
    row = rows[k]
    assert int(row["n_events"]) == r.n_events
    for column_name_, value in (("max_lower_gap_in", r.max_lower_gap_in),
                                ("circuit_open_s", r.circuit_open_s)):
        assert float(row[column_name_]) == pytest.approx(value, rel=1e-9,
                                                         abs=1e-15)


def test_a_planted_answer_is_refused():
    """The check can fail: the thesis row's answer moved one step of the
    bisection down (to the run with an event) is refused."""
    from contactsep.studies.study import thesis_study_design
    notes, _, rows = read("preload")
    (row,) = [r for r in rows if (r["d_in"], r["ys_in"]) == ("0.25", "0.5")]
    planted = {**row, "min_preload_lb": repr(below(float(
        row["min_preload_lb"])))}
    design = thesis_study_design(d=0.25, ys=0.5, n_modes=32)
    with pytest.raises(AssertionError):
        decide(design, planted, notes, "d = 0.25 in, y_s = 0.5 in", 5e-8,
               "none")
