"""Where a benchmark's run is kept: ``--save`` writes what the benchmark
printed to ``benchmarks/results/NAME.md``, after a line saying when,
on which commit and under what load it ran.  docs/performance.md quotes
these files, and tests/project/test_performance_page.py holds every
table row the page quotes equal to the file's."""

from __future__ import annotations

import datetime
import os
import subprocess
from pathlib import Path

#: The committed results of the benchmarks.
RESULTS = Path(__file__).resolve().parent / "results"


def provenance() -> str:
    """'run 2026-11-26 05:30 UTC, commit abc1234, load 1.9 (1-min avg),
    2 cores'."""
    when = datetime.datetime.now(datetime.timezone.utc)
    try:
        commit = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"], capture_output=True,
            text=True, check=True,
            cwd=Path(__file__).resolve().parent).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        commit = "unknown"
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    return (f"run {when:%Y-%m-%d %H:%M} UTC, commit {commit}, load "
            f"{load:.1f} (1-min avg), {os.cpu_count()} cores")


class Report:
    """Prints each line, and keeps it for :meth:`save`."""

    def __init__(self) -> None:
        self.lines: list[str] = []

    def __call__(self, text: str = "") -> None:
        print(text, flush=True)
        self.lines.extend(text.split("\n"))

    def save(self, name: str, command: str) -> Path:
        """Write benchmarks/results/NAME.md: the command, provenance(),
        then every line printed."""
        RESULTS.mkdir(exist_ok=True)
        path = RESULTS / f"{name}.md"
        path.write_text("\n".join([f"<!-- {command} -->", provenance(), "",
                                   *self.lines]) + "\n")
        return path
