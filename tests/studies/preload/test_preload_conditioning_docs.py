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


def test_the_table_is_the_study():
    quoted = table(section(TITLE), HEADER)
    expected = []
    for window, path in STUDIES.items():
        for name, runs in by_design(path).items():
            big = largest(runs)
            expected.append(
                [name, window, runs[0]["n_modes"],
                 g4(runs[0]["min_preload_lb"]),
                 *[pct(r["change_from_unperturbed"]) for r in runs[1:]],
                 "—" if big is None else f"{100 * big:.2f} %"])
    assert quoted == expected


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
