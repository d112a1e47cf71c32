"""What docs/preload-family.md says of how well-posed the smallest preload is
(issue 25; "How well-posed the answer is") against the committed studies
docs/studies/preload_conditioning.csv (each design's own step and
window) and preload_conditioning_chart.csv (the thesis rigs at the
preload chart's 0.06 s window and 5e-8 s step), written by
benchmarks/preload_conditioning.py: each design's whole search on
copies whose y_s differs by 1e-9 and 1e-6 of itself.  Reads files only;
tests/studies/preload/test_preload_perturbation.py confirms the steel relay's
ill-conditioning by direct runs."""

from __future__ import annotations

import csv
import sys
from pathlib import Path

import pytest
from design_family import FAMILY
from test_preload_docs import section, table

ROOT = Path(__file__).resolve().parents[3]
STUDIES = {"own": ROOT / "docs" / "studies" / "preload_conditioning.csv",
           "0.06 s, 5e-8 s":
               ROOT / "docs" / "studies" / "preload_conditioning_chart.csv"}
FAMILY_STUDY = ROOT / "docs" / "studies" / "preload_family.csv"
TITLE = "### How well-posed the answer is"
HEADER = "| design | window, step | N | min preload (lb) |"
CHANGES = [0.0, 1e-9, -1e-9, 1e-6, -1e-6]


def rows(path) -> list[dict]:
    body = [line for line in path.read_text().splitlines()
            if not line.startswith("#")]
    return list(csv.DictReader(body))


def by_design(path) -> dict:
    found = {}
    for r in rows(path):
        found.setdefault(r["design"], []).append(r)
    return found


def largest(runs) -> float | None:
    """The largest |change| of the perturbed copies (None: no answer)."""
    changes = [abs(float(r["change_from_unperturbed"])) for r in runs[1:]
               if r["change_from_unperturbed"] not in ("", "nan")]
    return max(changes) if changes else None


def g4(text: str) -> str:
    return "—" if text in ("", "nan") else f"{float(text):.4g}"


def pct(text: str) -> str:
    return "—" if text in ("", "nan") else f"{100 * float(text):+.2f} %"


@pytest.mark.parametrize("path", STUDIES.values(), ids=list(STUDIES))
def test_the_study_perturbs_ys_alone_as_it_says(path):
    lines = path.read_text().splitlines()
    assert all(line.startswith("#") for line in lines[:3])
    for name, runs in by_design(path).items():
        assert [float(r["ys_change"]) for r in runs] == CHANGES
        for r in runs:
            ys = FAMILY[name].ys * (1.0 + float(r["ys_change"]))
            assert float(r["ys_in"]) == pytest.approx(ys, rel=1e-15)
            assert r["n_modes"] == "32"


#: The perturbed copies' ys_change, in the table's column order.
COPIES = ("1e-09", "-1e-09", "1e-06", "-1e-06")


def datum(path, column: str, design: str, change: str = "0",
          fmt: str | None = None) -> str:
    """The role that shows ``column`` of ``design``'s copy ``change``."""
    return (f"{{datum}}`studies/{path.name}:{column}@design={design},"
            f"ys_change={change}" + (f":{fmt}`" if fmt else "`"))


def largest_role(path, design: str) -> str:
    """The role that shows, in per cent, the largest |change| of the
    design's four perturbed copies."""
    values = ", ".join(
        "abs([studies/" + path.name + ":change_from_unperturbed@design="
        + design + ",ys_change=" + c + "])" for c in COPIES)
    return "{datum}`=100 * max(" + values + "):.2f`"


def resolved(role: str) -> str:
    """What the page shows for ``role`` (docs/_ext/data_values.py)."""
    sys.path.insert(0, str(ROOT / "docs" / "_ext"))
    from data_values import resolve
    return resolve(role.removeprefix("{datum}`").removesuffix("`"),
                   ROOT / "docs")

def test_the_table_is_the_study():
    """Row for row: N, the answer and each copy's change the roles that
    select the design's copy (a dash where the study has no answer);
    the largest change the role that takes the largest |change| of the
    four copies (its value the one derived here: test_data_values
    resolves it)."""
    quoted = table(section(TITLE), HEADER)
    expected = []
    for window, path in STUDIES.items():
        for name, runs in by_design(path).items():
            big = largest(runs)
            if big is not None:
                assert resolved(largest_role(path, name)) == \
                    f"{100 * big:.2f}", name
            assert [float(r["ys_change"]) for r in runs[1:]] == \
                [float(c) for c in COPIES]
            expected.append(
                [name, window, datum(path, "n_modes", name),
                 "—" if g4(runs[0]["min_preload_lb"]) == "—" else
                 datum(path, "min_preload_lb", name, fmt=".4g"),
                 *["—" if pct(r["change_from_unperturbed"]) == "—" else
                   datum(path, "change_from_unperturbed", name, c, "+.2%")
                   for r, c in zip(runs[1:], COPIES)],
                 "—" if big is None else largest_role(path, name) + "%"])
    assert quoted == expected


def test_the_readings_quote_the_study():
    """The readings below the table: the steel relay's change at a part
    per billion, the beryllium-copper relay's at ±1e-6, the thesis rigs'
    answers at the chart's window: the roles that select those rows."""
    own, chart = STUDIES["own"], STUDIES["0.06 s, 5e-8 s"]
    text = " ".join(section(TITLE).split())
    change = "change_from_unperturbed"
    for claim in (
            "**The steel relay moves by "
            + datum(own, change, "steel_relay", "1e-09", ".1%")
            + " for a part per billion**",
            "moves by " + datum(own, change, "becu_light", "1e-06", ".1%")
            + " and " + datum(own, change, "becu_light", "-1e-06", ".1%")
            + " at ±1e-6**",
            "(rows of the chart: " + ", ".join(
                datum(chart, "min_preload_lb", d, fmt=".4g")
                for d in ("thesis", "thesis_thin")) + " and "
            + datum(chart, "min_preload_lb", "thesis_thick", fmt=".4g")
            + " lb)"):
        assert claim in text, claim


def test_the_chart_rigs_do_not_move_and_match_the_preload_chart():
    """The data behind "the thesis rigs at the chart's window and step
    do not move at all": every copy's answer is the unperturbed one,
    and the thesis rig's is the preload chart's at d = 0.25, y_s = 0.5
    (a separate run of the same search)."""
    chart = by_design(STUDIES["0.06 s, 5e-8 s"])
    for name, runs in chart.items():
        assert all(float(r["change_from_unperturbed"]) == 0.0
                   for r in runs[1:]), name
    preload = rows(ROOT / "docs" / "studies" / "preload.csv")
    (rig,) = [r for r in preload if float(r["d_in"]) == 0.25
              and float(r["ys_in"]) == 0.5]
    assert f"{float(chart['thesis'][0]['min_preload_lb']):.4g}" == \
        f"{float(rig['min_preload_lb']):.4g}"


def test_the_relays_that_would_not_settle_with_n():
    """The page's reading: the relays whose answer moved more than 2 %
    at 2N (steel_relay, becu_light) are the ones a change of y_s by
    1e-9 or 1e-6 of itself moves by more than 2 % (the steel relay by
    more than its change at 2N); those whose answer held within 2 % at
    2N move by at most one fine step (0.99 %)."""
    family = {r["design"]: float(r["min_preload_change"])
              for r in rows(FAMILY_STUDY)}
    own = by_design(STUDIES["own"])
    for name, change in family.items():
        assert (largest(own[name]) > 0.02) == (abs(change) > 0.02), name
        if abs(change) <= 0.02:
            assert largest(own[name]) <= 0.0099, name
    steel = own["steel_relay"]
    at_ppb = max(abs(float(r["change_from_unperturbed"])) for r in steel
                 if abs(float(r["ys_change"])) == 1e-9)
    assert at_ppb > abs(family["steel_relay"])
