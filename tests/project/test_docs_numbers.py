"""Numbers the docs quote from studies too slow for the pages' own
examples are re-run here (issue 30, item 8): docs/performance.md's p_open
of the benchmark's tolerance sweep with a 20 lb preload (seed 1, the
designs of benchmarks/results/bench_chatter_sweep.md).  Slow: 40 Hertz
simulations with a preload, each over the design's own window (about
2 s of CPU each)."""

from __future__ import annotations

import re

import pytest

from conftest import ROOT

CLAIM = re.compile(r"every one of the (\d+) preloaded designs opens "
                   r"\(p_open (\d); 95 % Wilson interval \[([\d.]+), "
                   r"(\d)\]")


def quoted() -> tuple[int, float, float, float]:
    text = " ".join((ROOT / "docs" / "performance-parallel.md").read_text()
                    .split() + (ROOT / "docs" / "performance-contact.md")
                    .read_text().split() + (ROOT / "docs" /
                                            "performance.md").read_text()
                    .split())
    found = CLAIM.search(text)
    assert found, "performance.md no longer quotes the sweep's p_open"
    return (int(found.group(1)),
            *(float(found.group(k)) for k in (2, 3, 4)))


def test_the_page_quotes_the_draw():
    designs, p_open, low, high = quoted()
    assert designs > 0 and low <= p_open <= high


def test_performance_p_open_is_what_the_sweep_gives():
    from contactsep.studies.sweep import run as runner
    from contactsep.studies.sweep import spec as sweep
    designs, p_open, low, high = quoted()
    spec = sweep.make_spec(sample=["d=normal(0.25,0.01)",
                                   "ys=uniform(0.45,0.55)"],
                           samples=designs, seed=1, base={"n_modes": 16},
                           model="hertz", settings={"preload": 20.0})
    summary = runner.run_sweep(spec)
    assert round(summary["p_open"], 3) == p_open
    assert [round(x, 3) for x in summary["p_open_ci95"]] == [low, high]
