"""One verdict line for an answer: the number to use and how converged
it is, or what moved, by how much, and the rerun that would settle it
with its cost (``contactsep preload``, ``contactsep chatter --verify``).

A verdict has a text, the same in the text output and the JSON, and the
estimated seconds of its rerun (None: no rerun to make), which only the
text output gives: it comes from this run's measured times, and the
JSON of a run is reproducible (a resumed search's equals an
uninterrupted one's).  The estimate is the measured wall time of the
runs made, scaled to the rerun: each doubling of N, with the step
halved as the checks halve it, multiplies a run's cost by the measured
ratio of a run at 2N and half the step to one at N (preload: the repeat
at 2N against the search at N), or, where none was measured, by
COST_PER_DOUBLING.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

#: A run at twice the modes and half the step against one at N, where
#: this run measured none: twice the steps, and each step's cost about
#: linear in N.  docs/performance.md measured 2.5-5.0 on the family at
#: N = 32 (the check run of `chatter --verify` against the run).
COST_PER_DOUBLING = 4.0
#: The largest relative change of the answer (and of the chatter
#: quantities the project claims converged) that counts as converged.
PRELOAD_TOLERANCE = 0.02
CHATTER_TOLERANCE = 0.01
#: The quantities of `chatter --verify` that converge (to 1 % at the
#: default N: docs/numerics.md, "The default N"), and those documented
#: as not converging (the largest lower gap over the window, the
#: longest opening, the number of events: a chaotic rattle), which no
#: verdict rests on.
CHECKED = (("first_impact_change", "first impact"),
           ("first_impulse_change", "first impulse"),
           ("circuit_open_change", "total open time"),
           ("first_lift_change", "first lift"))
NOT_CHECKED = ("max lower gap", "longest opening", "events")


@dataclass(frozen=True)
class Verdict:
    """The verdict's words and its rerun's estimated seconds."""

    text: str
    rerun_s: float | None = None

    def line(self) -> str:
        """The text output's line: the words, the rerun's time."""
        if self.rerun_s is None:
            return self.text
        return f"{self.text} (about {duration_text(self.rerun_s)})"


def duration_text(seconds: float) -> str:
    """'40 s', '12 min', '3.4 h' (two significant digits)."""
    if seconds < 60.0:
        return f"{max(seconds, 1.0):.2g} s".replace("e+0", "e")
    if seconds < 3600.0:
        return f"{seconds / 60.0:.2g} min"
    return f"{seconds / 3600.0:.2g} h" if seconds < 360000.0 else \
        f"{seconds / 3600.0:,.0f} h"


def _percent(change: float) -> str:
    """A relative change as a percentage, two significant digits."""
    return f"{abs(change) * 100:.2g} %"


def _lb(value) -> str:
    """A force in lb, as the unit system shown writes it ('0.226 lb',
    '1.005 N' under ``--units si``)."""
    from contactsep.model.names import shown_text
    if value is None or not math.isfinite(value):
        return "none"
    return shown_text(value, "lb", 4)


def cost_ratio(answer) -> float:
    """The measured cost of a run at 2N and half the step against one at
    N: the repeat at 2N's mean run time over the search's (fallback
    COST_PER_DOUBLING)."""
    timing = getattr(answer, "timing", None) or {}
    (n1, s1), (n2, s2) = timing.get("search", (0, 0.0)), \
        timing.get("verify", (0, 0.0))
    if n1 and n2 and s1 > 0.0 and s2 > 0.0:
        return (s2 / n2) / (s1 / n1)
    return COST_PER_DOUBLING


def _scaled(answer, seconds: float, doublings: int) -> float | None:
    if not seconds > 0.0:
        return None
    return seconds * cost_ratio(answer) ** max(doublings, 0)


def _rerun_seconds(answer, doublings: int) -> float | None:
    """A nominal rerun at 2^doublings N: this run's search at N again at
    the finer N and step (each doubling one cost_ratio), then its check
    at twice that N, a few preloads (_CHECK_PRELOADS) 2 % either side of
    the answer, as a check that holds costs (not the whole search a
    failing one falls back to)."""
    timing = getattr(answer, "timing", None) or {}
    runs, seconds = timing.get("search", (0, 0.0))
    if not (runs and seconds > 0.0):
        return None
    ratio, k = cost_ratio(answer), max(doublings, 0)
    return seconds * ratio**k + _CHECK_PRELOADS * seconds / runs \
        * ratio**(k + 1)


def _doublings(n_from, n_to) -> int:
    return round(math.log2(n_to / n_from)) if n_from and n_to else 1


def preload_verdict(answer) -> Verdict:
    """The verdict of a PreloadAnswer: its robust answer's where
    tolerances were given (the answer a designer specifies), else the
    nominal one's."""
    if answer.robust is not None:
        return _robust_verdict(answer, answer.robust)
    return _nominal_verdict(answer)


def _nominal_seconds(answer) -> float:
    timing = getattr(answer, "timing", None) or {}
    return timing.get("nominal", (0, 0.0))[1]


def _nominal_verdict(answer) -> Verdict:
    n = answer.n_modes
    if not math.isfinite(answer.min_preload_lb):
        return Verdict(f"no answer: an event up to the largest preload "
                       f"the design takes ({_lb(answer.ceiling_lb)})")
    change = answer.min_preload_change
    if answer.converged:
        a = answer.converged_min_preload_lb
        if answer.converged_n_modes == n and change is not None:
            return Verdict(f"answer: {_lb(a)} (converged: N = {n} within "
                           f"{_percent(change)})")
        return Verdict(f"answer: {_lb(a)} (converged: N = "
                       f"{answer.converged_n_modes}, held within 2 % at "
                       f"N = {answer.converged_check_n_modes})")
    if answer.converged is None:
        if change is None:
            return Verdict(f"answer: {_lb(answer.min_preload_lb)} at N = "
                           f"{n} (convergence not checked)")
        if abs(change) <= PRELOAD_TOLERANCE:
            return Verdict(f"answer: {_lb(answer.min_preload_lb)} "
                           f"(converged: N = {n} within "
                           f"{_percent(change)})")
        if isinstance(n, int):
            at, rerun = f"N = {2 * n}", f"--n-modes {2 * n}"
        else:       # an N a member: the options of each member's N
            at, rerun = "twice each member's N", "twice each member's N"
        return Verdict(
            f"not converged: the answer moved {change:+.1%} from N = {n} "
            f"({_lb(answer.min_preload_lb)}) to {at} "
            f"({_lb(answer.verify_min_preload_lb)}); rerun with {rerun}",
            _rerun_seconds(answer, 1))
    history = answer.converge_history
    moved = ""
    if len(history) >= 2:
        (n0, a0), (n1, a1) = history[-2], history[-1]
        if math.isfinite(a0) and math.isfinite(a1) and a0 > 0:
            moved = (f"the answer moved {a1 / a0 - 1:+.1%} from N = {n0} "
                     f"({_lb(a0)}) to N = {n1} ({_lb(a1)})")
        else:
            moved = f"no answer at N = {n1}" if not math.isfinite(a1) \
                else f"no answer at N = {n0}"
    checked = answer.converged_check_n_modes
    if checked is not None and checked > answer.converged_n_modes:
        return Verdict(
            f"not converged: {moved}, and its check at N = {checked} "
            f"failed; rerun with --n-modes {checked}",
            _rerun_seconds(answer, _doublings(n, checked)))
    return Verdict(f"not converged: {moved}; no check at N = "
                   f"{2 * (checked or n)} fits the simulation's work "
                   f"budget")


def _robust_verdict(answer, r) -> Verdict:
    from contactsep.studies.preload.robust_rule import p_open_high

    if not r.shown:
        needed = r.samples_needed
        if needed is None:
            return Verdict("not shown at any sample count: p_target 0")
        return Verdict(
            f"not shown at this sample count: needs >= {needed} samples "
            f"(p_target {r.p_target:g} on p_open's 95 % upper bound; "
            f"{r.samples} give at best {p_open_high(0, r.samples):.3g}); "
            f"rerun with --samples {needed}", _samples_rerun(answer, r))
    if not math.isfinite(r.min_preload_lb):
        return Verdict(f"no robust answer: p_open's 95 % upper bound "
                       f"above {r.p_target:g} up to the largest preload "
                       f"the design takes ({_lb(answer.ceiling_lb)})")
    said = (f"{_lb(r.min_preload_lb)} robust (p_open <= {r.p_target:g} "
            f"on its 95 % upper bound {r.p_open_ci95_high:.3g}: "
            f"{r.n_open} of {r.n} open")
    if r.converged:
        return Verdict(f"answer: {said}; held within 2 % at N = "
                       f"{r.check_n_modes})")
    if r.converged is None:
        return Verdict(f"answer: {said}; convergence not checked)")
    n = answer.n_modes
    return Verdict(
        f"not converged: the robust answer {_lb(r.min_preload_lb)} at "
        f"N = {n} does not hold at N = {r.check_n_modes} (p_target "
        f"failed within 2 % above it, or met within 2 % below); "
        f"rerun with --n-modes {r.check_n_modes}",
        _scaled(answer, _nominal_seconds(answer) + r.seconds,
                _doublings(n, r.check_n_modes)))


#: Preloads the robust answer's check at 2N runs.
_CHECK_PRELOADS = 5


def _samples_rerun(answer, r) -> float | None:
    """The rerun at ``samples_needed``: this run's nominal part again,
    and a robust search of the nominal search's count of preloads, each
    of samples_needed runs at the search's mean run time (at most: a
    failing preload stops early), and its check at 2N."""
    timing = getattr(answer, "timing", None) or {}
    runs, seconds = timing.get("search", (0, 0.0))
    if not (runs and seconds > 0.0):
        return None
    per_run = seconds / runs
    robust = len(answer.tested) * r.samples_needed * per_run
    if r.check_n_modes is not None:
        robust += _CHECK_PRELOADS * r.samples_needed * per_run * \
            cost_ratio(answer)
    return _nominal_seconds(answer) + robust


def chatter_verdict(result, seconds: float | None) -> Verdict | None:
    """The verdict of a `chatter --verify` run (None: not verified) from
    its *_change fields against CHATTER_TOLERANCE, those documented as
    not converging not checked; ``seconds``: the measured wall time of
    the run and its check, for the rerun's estimate."""
    changes = result.changes
    if not changes:
        return None
    n, fine = result.n_modes, changes["verify_n_modes"]
    unchecked = ", ".join(NOT_CHECKED)
    if changes.get("verify_status", 0) != 0:
        moved = (f"the check at N = {fine} and half the step ended with "
                 f"status {changes['verify_status']}")
    else:
        off = [(label, changes[key]) for key, label in CHECKED
               if key in changes and not changes[key] <= CHATTER_TOLERANCE]
        if not off:
            worst = max((changes[key] for key, _ in CHECKED
                         if key in changes), default=0.0)
            return Verdict(f"answer: converged: N = {n} within "
                           f"{_percent(worst)} at N = {fine} and half the "
                           f"step (first impact, first impulse, total open "
                           f"time, first lift; not checked: {unchecked})")
        moved = ", ".join(
            f"{label} "
            f"{'undefined in one run' if math.isnan(c) else _percent(c)}"
            for label, c in off) + f" at N = {fine} and half the step"
    rerun = None if seconds is None else seconds * COST_PER_DOUBLING
    return Verdict(f"not converged: {moved} (above "
                   f"{_percent(CHATTER_TOLERANCE)}; not checked: "
                   f"{unchecked}); rerun with --n-modes {fine} --verify",
                   rerun)
