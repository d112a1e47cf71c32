"""The robust answer's rule and its early stop (``contactsep preload
--tolerance``; :mod:`contactsep.studies.preload.robust`).

A preload meets p_target when the upper end of the 95 % Wilson interval
of its p_open (n_open of the n samples that ran) is at most p_target:
the point estimate n_open / n would call 0 of 20 open "at most 1 %"
though 20 samples cannot tell 0 % from 16 %.  Even 0 of n has an upper
end z^2 / (n + z^2), so below :func:`samples_needed` samples no preload
can meet the target and the search is not run.

The samples of a preload run in fixed index blocks (:func:`block_stops`)
and after each block :func:`settled` asks whether the samples still to
run could change the decision; once they cannot, the rest are not run.
Whatever they would give, the decision is the one the full set of
samples gives (tests: every pattern of a few samples, random long ones),
and it depends only on the prefix run, not on the order runs finish.
"""

from __future__ import annotations

import math

from contactsep.studies.stats import Z95, wilson_interval

#: The first block of a preload's samples; each later block doubles the
#: samples run (10, 20, 40, ...), so a preload takes at most about
#: log2(samples / 10) + 1 batches, and one that many samples open stops
#: after the first.
FIRST_BLOCK = 10


def p_open_high(n_open: int, n: int) -> float:
    """The upper end of the 95 % Wilson interval of n_open of n (1: no
    sample ran, no evidence)."""
    return wilson_interval(n_open, n)[1] if n else 1.0


def meets(n_open: int, n: int, p_target: float) -> bool:
    """Whether n_open of n samples show p_open <= p_target at 95 %: the
    interval's upper end is within the target (never with n = 0)."""
    return n > 0 and p_open_high(n_open, n) <= p_target


def samples_needed(p_target: float) -> int | None:
    """The fewest samples with which a preload can meet ``p_target``:
    the smallest n whose 0 of n has its upper end z^2 / (n + z^2) within
    it (None for p_target 0, never met)."""
    if not p_target > 0.0:
        return None
    z2 = Z95 * Z95
    n = max(1, math.ceil(z2 * (1.0 - p_target) / p_target))
    # the closed form's round-off, settled by the interval itself
    while not meets(0, n, p_target):
        n += 1
    while n > 1 and meets(0, n - 1, p_target):
        n -= 1
    return n


def settled(n_open: int, n: int, remaining: int, p_target: float
            ) -> bool | None:
    """Whether a preload fails (True) or meets p_target (False) whatever
    its ``remaining`` samples give, from the n_open of n that ran so far
    (failed runs left out); None: they could still change it.

    The upper end of the interval grows with n_open at a fixed n and
    falls as n grows at a fixed n_open.  So the preload fails for sure
    when it fails even if every remaining sample runs and stays closed,
    and meets for sure when it meets with any j of them open and the
    rest failed (every j tried: no more is assumed of the bound)."""
    if not meets(n_open, n + remaining, p_target):
        return True
    if all(meets(n_open + j, n + j, p_target)
           for j in range(remaining, -1, -1)):
        return False
    return None


def block_stops(samples: int, first: int = FIRST_BLOCK) -> list[int]:
    """The prefix lengths after which a preload's decision is asked:
    first, 2 first, 4 first, ... and the whole set."""
    stops, stop = [], first
    while stop < samples:
        stops.append(stop)
        stop *= 2
    return [*stops, samples]
