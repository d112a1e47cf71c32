"""What docs/preload-family.md says of the preload command on the design family
(issue 25, items 2 and 6; "The preload command on the family") against
the committed study docs/studies/preload_family.csv, written by
benchmarks/preload_family.py (``contactsep.preload(design,
converge=True)`` on each relay of tests/design_family.py).  Reads files
only; the study is a convergence study (each answer against its own
searches at 2N, dt/2 and, where it moved more than 2 %, its check at
4N at dt/4 or the work budget's finest step), and the test at the end
simulates again the runs that decide its cheapest row."""

from __future__ import annotations

import csv
import math
from pathlib import Path

from test_preload_docs import section, table

ROOT = Path(__file__).resolve().parents[3]
STUDY = ROOT / "docs" / "studies" / "preload_family.csv"
TITLE = "### The preload command on the family"
HEADER = "| design | N | dt (s) | min preload (lb) | at 2N, dt/2 (lb) |"


def rows() -> list[dict]:
    body = [line for line in STUDY.read_text().splitlines()
            if not line.startswith("#")]
    return list(csv.DictReader(body))


def g4(text: str) -> str:
    return "none" if text in ("", "nan") else f"{float(text):.4g}"


def test_every_comment_is_one_line_and_every_row_is_a_relay():
    from design_family import FAMILY
    lines = STUDY.read_text().splitlines()
    assert all(line.startswith("#") for line in lines[:4])
    names = [r["design"] for r in rows()]
    assert sorted(names) == sorted(n for n in FAMILY
                                   if not n.startswith("thesis"))


def role(design: str, column: str, fmt: str | None = None) -> str:
    """The datum role that shows ``column`` of the relay's row."""
    fmt = f":{fmt}" if fmt else ""
    return (f"{{datum}}`studies/preload_family.csv:{column}@design="
            f"{design}{fmt}`")


def test_the_table_is_the_study():
    """Row for row: the study's values the roles that select the relay's
    row (every relay has an answer, so no "none"), the change as a
    percentage, and the verdict as text."""
    quoted = table(section(TITLE), HEADER)
    assert len(quoted) == len(rows())
    for cells, r in zip(quoted, rows()):
        d = r["design"]
        assert g4(r["min_preload_lb"]) != "none"
        held = {"1": "yes", "0": "no"}[r["converged"]]
        assert cells == [
            d, role(d, "n_modes"), role(d, "dt_s", ".3g"),
            role(d, "min_preload_lb", ".4g"),
            role(d, "verify_min_preload_lb", ".4g"),
            role(d, "min_preload_change", "+.2%"),
            role(d, "converged_min_preload_lb", ".4g"),
            role(d, "converged_n_modes"),
            role(d, "converged_check_n_modes"), held,
            role(d, "simulations"), role(d, "wall_s", ".0f")], d


def test_a_converged_row_is_within_two_percent_at_its_check():
    """The study's own consistency: a row converged at its N moved at
    most 2 % at 2N; one converged at 2N moved more (it was checked)."""
    for r in rows():
        change = float(r["min_preload_change"])
        if r["converged"] == "1" and r["converged_n_modes"] == r["n_modes"]:
            assert abs(change) <= 0.02, r["design"]
            assert r["converged_min_preload_lb"] == r["min_preload_lb"]
        elif r["converged"] == "1":
            assert abs(change) > 0.02, r["design"]
            assert int(r["converged_check_n_modes"]) == \
                2 * int(r["converged_n_modes"])


def test_every_relay_s_answer_held_its_check():
    """What the page claims: on every relay the converged answer held
    its check at twice its N (within 2 % there), so the command's
    default (one check at 4N) converges each of them; the two whose
    answer moved more than 2 % at 2N were checked at 4N = 128."""
    text = section(TITLE)
    assert "On every relay of the family\n  `converged_min_preload_lb` " \
        "then held its check at 4N" in text
    for r in rows():
        assert r["converged"] == "1", r["design"]
        assert int(r["converged_check_n_modes"]) == \
            2 * int(r["converged_n_modes"]) <= 4 * int(r["n_modes"])
    moved = {r["design"] for r in rows()
             if abs(float(r["min_preload_change"])) > 0.02}
    assert moved == {"steel_relay", "becu_light"}


def search_rows(path):
    body = [line for line in path.read_text().splitlines()
            if not line.startswith("#")]
    return [(float(r["preload_lb"]), r["event"] == "1")
            for r in csv.DictReader(body)]


def search_at_128(name):
    """The whole search at N = 128 (docs/studies/preload_family_<short>
    128.csv): its tried preloads, their highest event, the answer
    recomputed from them as the search defines it (the smallest tried
    preload above which every tried one is closed; the file's own
    comment must say the same), and the family row's N = 64 answer,
    which held its check at N = 128."""
    short = {"becu_light": "becu", "steel_relay": "steel"}[name]
    path = ROOT / "docs" / "studies" / f"preload_family_{short}128.csv"
    tried = sorted(search_rows(path))
    last_event = max(p for p, event in tried if event)
    answer = min(p for p, event in tried if p > last_event)
    assert f"# answer: {answer:.6g} lb" in path.read_text()
    row = next(r for r in rows() if r["design"] == name)
    assert (row["converged"], row["converged_check_n_modes"]) == (
        "1", "128")
    return tried, last_event, answer, float(row["converged_min_preload_lb"])


def test_becu_light_s_search_at_128_finds_a_window_the_check_missed():
    """docs/studies/preload_family_becu128.csv (the whole search at
    N = 128): its answer, recomputed here from the tried preloads as the
    search defines it (the smallest tried preload above which every tried
    one is closed), is 4.7 % above the N = 64 answer the check let hold,
    because of an event 3.6 % above that answer (beyond the check's 2 %)
    and none within 2 % above it."""
    tried, last_event, answer, at_64 = search_at_128("becu_light")
    assert round(100 * (answer / at_64 - 1), 1) == 4.7
    assert round(100 * (last_event / at_64 - 1), 1) == 3.6
    assert not any(event for p, event in tried
                   if at_64 < p <= 1.02 * at_64)
    text = section(TITLE)
    assert "answers\n  0.04625 lb, 4.7 % above the N = 64 answer" in text


def test_steel_relay_s_search_at_128_is_4_percent_below_its_checked_answer():
    """docs/studies/preload_family_steel128.csv (the whole search at
    N = 128, half its own step): the answer recomputed from the tried
    preloads is 3.9 % below the N = 64 answer that held its check (at
    twice that step), and the preload 2 % below that answer is closed
    there: the check's verdict depends on the step."""
    tried, _, answer, at_64 = search_at_128("steel_relay")
    assert round(100 * (answer / at_64 - 1), 1) == -3.9
    below = [event for p, event in tried
             if 0.975 * at_64 <= p <= 0.985 * at_64]
    assert below and not any(below)
    assert "answers 0.1616 lb, 3.9 % below" in section(TITLE)


def _on_the_grid(printed: str) -> tuple[float, float]:
    """(the answer, the tested preload just below it) from its six
    printed digits: an answer lies on the bisection's tree 2^(j/128) lb
    or on the fine grid 1.0099^j lb (tests/project/
    test_committed_searches.py, whose rule this is), and six digits
    name the point (1e-4 of a step)."""
    value = float(printed)
    for ratio in (2.0 ** (1 / 128), 1.0099):
        j = math.log(value) / math.log(ratio)
        if abs(j - round(j)) < 1e-3:
            answer = ratio ** round(j)
            assert math.isclose(answer, value, rel_tol=1e-5)
            return answer, ratio ** (round(j) - 1)
    raise AssertionError(f"{printed} lb is on neither grid")


def test_the_cheapest_row_is_its_deciding_runs():
    """steel_thick (its whole search, two minutes on two cores, was
    regenerated in the slow set; benchmarks/preload_family.py writes
    the study): the runs that decide its committed answer, simulated
    again as contactsep.preload runs them (elastic Hertz, the design's
    own step and window): the answer closed, the tested preload below
    it with an event, its step the committed one, and, the row being
    converged at N, the check's run at 2N and half the step 2 % above
    the answer closed."""
    from design_family import FAMILY

    from contactsep.chatter import simulate
    from contactsep.studies.preload.chart import (DEFAULT_MODES,
                                                  _simulate_event)
    from contactsep.studies.preload.runs import PreloadRun
    row = next(r for r in rows() if r["design"] == "steel_thick")
    design = FAMILY["steel_thick"].replace(n_modes=DEFAULT_MODES)
    assert int(row["n_modes"]) == DEFAULT_MODES

    def event(design, load, settings=None):
        return _simulate_event(PreloadRun(design, "hertz", settings or {},
                                          load))

    answer, lower = _on_the_grid(row["min_preload_lb"])
    assert not event(design, answer)
    assert event(design, lower)
    dt = simulate(design, model="hertz", samples=1,
                  single_impulse=False, t_end=1e-4).dt
    assert math.isclose(dt, float(row["dt_s"]), rel_tol=1e-5)
    assert row["converged"] == "1" and row["converged_n_modes"] == \
        row["n_modes"]
    check = int(row["converged_check_n_modes"])
    assert check == 2 * DEFAULT_MODES
    assert not event(design.replace(n_modes=check), 1.02 * answer,
                     {"dt": dt / 2})
