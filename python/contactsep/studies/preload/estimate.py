"""How long a preload search will take, said before its first
simulation (``contactsep preload``'s progress line).

The search's runs are the design's simulation at preloads from the
ceiling down: most keep the lower contact pressed for most of the
window, and a pressed step is a fixed step, so a run costs about its
window over its step, in steps, each at about the cost of a step of the
run at no preload that the command makes first to check the design (the
probe: its flight and fixed steps, timed).  Measured on the family at
N = 16 and 32 (benchmarks/preload_estimate.py), a preloaded run took
0.43-0.89 of this estimate at the ceiling and 0.18-0.92 at half or a
tenth of it: the probe's mean step carries the run's setup, and a run
with events has fewer fixed steps than its window holds.  So it errs
long, by up to about 2 for runs near the ceiling and up to about 5 for
light ones; it is the search at N and its check at twice the modes and
half the step (probed the same way), divided over the workers, and the
runs it counts are :func:`~contactsep.studies.preload.verify.
expected_runs`'s.  The robust answer's runs, a convergence check beyond
2N and a search again where the check fails are not in it: the progress
bar's total grows when they are planned.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from contactsep.studies.preload.verdict import duration_text


def step_seconds(result, seconds: float) -> float:
    """The measured seconds a step of a simulation ``result`` that took
    ``seconds`` (its flight and fixed steps where the stepper counts
    them, else its window over its step)."""
    work = getattr(result, "work", None) or {}
    steps = work.get("flight_steps", 0) + work.get("fixed_steps", 0)
    if steps <= 0:
        steps = _window_steps(result)
    return max(seconds, 0.0) / max(steps, 1)


def _window_steps(result) -> float:
    """A run's window over its step, in steps (at least 1)."""
    dt = getattr(result, "dt", 0.0) or 0.0
    if not (dt > 0.0 and math.isfinite(dt)):
        return 1.0
    return max(result.t_end_s / dt, 1.0)


def run_seconds(result, seconds: float) -> float:
    """The estimated seconds of one run like ``result`` (the same window
    and step) kept pressed the whole window: every step of the window at
    the cost a step measured on ``result``."""
    return _window_steps(result) * step_seconds(result, seconds)


@dataclass(frozen=True)
class SearchEstimate:
    """The search's runs and their estimated wall time.

    Attributes
    ----------
    runs : int
        The simulations counted (the search at N and its check).
    seconds : float
        Their estimated wall time (s) on ``workers``, to a factor of
        about two (module docstring).
    workers : int
        The workers the runs are shared by.
    """

    runs: int
    seconds: float
    workers: int

    def line(self) -> str:
        """The one line shown before the first run."""
        workers = f"{self.workers} worker" + ("s" if self.workers > 1
                                              else "")
        return (f"preload: about {self.runs} simulations, estimated "
                f"{duration_text(self.seconds)} on {workers} (more if a "
                f"check fails or tolerances are given)")


def search_estimate(search_runs: int, run_s: float, check_runs: int = 0,
                    check_run_s: float = 0.0,
                    workers: int = 1) -> SearchEstimate:
    """The estimate of ``search_runs`` runs of ``run_s`` seconds at N
    and ``check_runs`` of ``check_run_s`` at 2N, on ``workers``."""
    workers = max(int(workers), 1)
    total = search_runs * run_s + check_runs * check_run_s
    return SearchEstimate(runs=search_runs + check_runs,
                          seconds=total / workers, workers=workers)
