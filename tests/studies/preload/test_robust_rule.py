"""The robust answer's rule (studies.preload.robust_rule): p_target met on the
upper end of the 95 % Wilson interval, the samples that rule needs, and
the early stop, whose decision must be the full set's exactly."""

from __future__ import annotations

import itertools
import random

import pytest
from scipy.optimize import brentq
from scipy.stats import norm

from contactsep.studies.preload import robust_rule
from contactsep.studies.preload.robust_rule import (
    block_stops,
    meets,
    p_open_high,
    samples_needed,
    settled,
)

#: Outcomes of one sample: closed, open (an event), failed (not run).
CLOSED, OPEN, FAILED = 0, 1, 2


def scipy_upper(k: int, n: int) -> float:
    """The Wilson score interval's upper end from its definition, by a
    root finder: the p > k/n with (k - n p)^2 = z^2 n p (1 - p)."""
    z = norm.ppf(0.975)
    if k == n:
        return 1.0
    return brentq(lambda p: (k - n * p) ** 2 - z * z * n * p * (1 - p),
                  k / n + 1e-15, 1.0 - 1e-15, xtol=1e-14)


@pytest.mark.parametrize("k, n", [(0, 1), (0, 20), (1, 20), (3, 50),
                                  (0, 381), (7, 400), (19, 20)])
def test_the_upper_end_is_wilsons(k, n):
    assert p_open_high(k, n) == pytest.approx(scipy_upper(k, n), rel=1e-9)


def test_no_sample_that_ran_is_no_evidence():
    assert p_open_high(0, 0) == 1.0 and not meets(0, 0, 0.5)


@pytest.mark.parametrize("p_target", [0.01, 0.05, 0.1, 0.2, 0.5, 0.9,
                                      0.001])
def test_samples_needed_is_the_smallest_n_by_brute_force(p_target):
    """The smallest n (searched one by one, the root finder's bound)
    whose 0 of n meets the target; 0.01 needs 381."""
    n = 1
    while scipy_upper(0, n) > p_target:
        n += 1
    assert samples_needed(p_target) == n
    if p_target == 0.01:
        assert n == 381


def test_p_target_zero_is_never_met():
    assert samples_needed(0.0) is None


def test_the_bound_moves_as_the_early_stop_assumes():
    """Up with n_open at a fixed n, down with n at a fixed n_open."""
    for n in range(1, 120):
        ups = [p_open_high(k, n) for k in range(n + 1)]
        assert ups == sorted(ups)
    for k in range(0, 30):
        downs = [p_open_high(k, n) for n in range(max(k, 1), 300)]
        assert downs == sorted(downs, reverse=True)


def full_decision(outcomes, p_target) -> bool:
    """Fails (True) on the whole set of samples."""
    n = sum(o != FAILED for o in outcomes)
    return not meets(outcomes.count(OPEN), n, p_target)


def early_decision(outcomes, p_target, first) -> tuple[bool, int]:
    """(fails, samples run) deciding after each block from its prefix."""
    for stop in block_stops(len(outcomes), first):
        prefix = outcomes[:stop]
        verdict = settled(prefix.count(OPEN),
                          sum(o != FAILED for o in prefix),
                          len(outcomes) - stop, p_target)
        if verdict is not None:
            return verdict, stop
    raise AssertionError("the whole set must decide")


@pytest.mark.parametrize("p_target", [0.1, 0.3, 0.5, 0.8])
def test_every_pattern_of_few_samples_stops_with_the_full_decision(
        p_target):
    for size in range(1, 9):
        for outcomes in itertools.product((CLOSED, OPEN, FAILED),
                                          repeat=size):
            outcomes = list(outcomes)
            for first in (1, 2, 3):
                fails, _ = early_decision(outcomes, p_target, first)
                assert fails == full_decision(outcomes, p_target), \
                    (outcomes, first)


def test_random_long_patterns_stop_with_the_full_decision_and_save():
    """400 samples at p_target 0.01 (and others): every early decision is
    the full set's; where samples open often the preload stops early."""
    rng = random.Random(45)
    saved, often = 0, []
    for trial in range(3000):
        size = rng.choice([20, 100, 381, 400, 1000])
        p_target = rng.choice([0.01, 0.05, 0.2])
        p_open = rng.choice([0.0, 0.001, 0.005, 0.01, 0.03, 0.3, 1.0])
        p_fail = rng.choice([0.0, 0.0, 0.02])
        outcomes = [FAILED if rng.random() < p_fail else
                    OPEN if rng.random() < p_open else CLOSED
                    for _ in range(size)]
        fails, ran = early_decision(outcomes, p_target,
                                    robust_rule.FIRST_BLOCK)
        assert fails == full_decision(outcomes, p_target)
        if p_open >= 0.3 and p_target == 0.01 and size >= 381:
            often.append(ran)
        saved += size - ran
    # at 381 or more samples one open sample fails p_target 0.01
    assert saved > 0 and len(often) > 50
    assert sum(often) / len(often) < 1.5 * robust_rule.FIRST_BLOCK


def test_block_stops_double_from_the_first_block():
    assert block_stops(400) == [10, 20, 40, 80, 160, 320, 400]
    assert block_stops(10) == [10] and block_stops(3) == [3]
    assert block_stops(20, first=10) == [10, 20]
