"""benchmarks/bench_scaling.py runs as the one script a session lent a
many-core machine would run: the yardstick, both sweeps on both engines
at every worker count, and the robust search on both engines with the
same answer, all in one call (here at the smallest budget, two
workers).  Its timings are not checked: only that every row it promises
is printed."""

from __future__ import annotations

import os
import re
import subprocess
import sys

import pytest

from conftest import ROOT

pytest.importorskip("distributed")


def test_the_script_prints_every_configuration_within_its_budget(tmp_path):
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    done = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "bench_scaling.py"),
         "--minutes", "0.05", "--max-workers", "2", "--robust-samples",
         "3"], check=False, cwd=tmp_path, env=env, capture_output=True,
        text=True,
        timeout=900)
    assert done.returncode == 0, done.stderr[-2000:]
    rows = [line.split() for line in done.stdout.splitlines()]
    # the budget's plan before the runs: each sweep's size is at least
    # its smallest (a shorter sweep says nothing of scaling), and above
    # it no more than its share of the budget (0.4 of 0.05 min) over
    # one design's time on one worker, shared by the two engines'
    # configurations at least (which sizes bind depends on the machine)
    for name, smallest in (("eq23", 100_000), ("hertz", 16)):
        plan = re.search(rf"^{name}: (\S+) us a design on one worker; "
                         rf"([\d,]+) designs fit (\d+) s$", done.stdout,
                         flags=re.M)
        assert plan, (name, done.stdout[:2000])
        each_s, size = float(plan.group(1)) * 1e-6, int(
            plan.group(2).replace(",", ""))
        assert size >= smallest
        if size > smallest:
            assert size <= 0.4 * 60 * 0.05 / (2 * each_s) * 1.01
    for sweep in ("eq23", "hertz"):
        for engine in ("local", "dask"):
            for k in ("1", "2"):
                assert [sweep, engine, k] in [r[:3] for r in rows], \
                    (sweep, engine, k)
    robust = [r for r in rows if r[:1] == ["robust"]]
    assert [r[1:3] for r in robust] == [["local", "2"], ["dask", "2"]]
    # the two engines found the same answer
    assert all(r[-1] == "yes" for r in robust), robust
    assert done.stdout.rstrip().endswith(" s in all")
